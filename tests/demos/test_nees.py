"""The NEES panel: the controls mistune what the caption says, an honest filter stays in
the band, a filter off by 10x leaves it on the side chapter 6 says."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.nees import DOF, N_STEPS, N_TRACKS
from kfcourse.sim.target import filter_tracks, nees, nees_band


def make(seed=0):
    return kf.demos.nees_panel(seed=seed)


def set_mistune(demo, which, factor):
    demo.controls["which"].value = which
    demo.controls["factor"].value = factor
    assert demo.model.which == which and demo.model.factor == pytest.approx(factor)


def test_controls_mistune_the_named_noise_and_keep_the_world():
    demo = make()
    m = demo.model
    truth = m.batch.truth
    R, Q = m.batch.R, m.batch.Q
    assert [np.array_equal(a, b) for a, b in zip(m.assumed(), (R, Q), strict=True)] == [True, True]
    picture = bytes(demo.image.value)
    set_mistune(demo, "R", 0.1)
    R_used, Q_used = m.assumed()
    np.testing.assert_allclose(R_used, 0.1 * R)
    np.testing.assert_array_equal(Q_used, Q)
    assert bytes(demo.image.value) != picture
    set_mistune(demo, "Q", 10.0)
    R_used, Q_used = m.assumed()
    np.testing.assert_array_equal(R_used, R)
    np.testing.assert_allclose(Q_used, 10.0 * Q)
    assert m.batch.truth is truth
    mu, Sig = filter_tracks(m.batch, R_used, Q_used)  # the curve is the average NEES of that filter
    np.testing.assert_allclose(m.avg_nees, nees(m.batch.truth, mu, Sig).mean(axis=0))
    curve = demo.view.curve
    np.testing.assert_allclose(curve.get_ydata(), np.clip(m.avg_nees, 0.5, 500.0))
    np.testing.assert_allclose(curve.get_xdata(), m.batch.dt * np.arange(N_STEPS))
    assert f"{m.avg_nees.mean():.2f}" in demo.children[2].value


def test_factor_reruns_where_it_is_let_go_and_never_redraws_the_axes():
    """Each factor reruns every track: the slider reports the value it is let go at (and each key press),
    not every value on the way; the log axis and the band stay, only the curve moves."""
    demo = make()
    assert demo.controls["factor"].continuous_update is False
    draws = demo.renderer.full_draws
    for which, factor in (("R", 0.01), ("R", 100.0), ("Q", 0.3)):
        set_mistune(demo, which, factor)
    assert demo.renderer.full_draws == draws


def test_band_is_the_chi_square_band_for_the_number_of_tracks():
    m = make().model
    assert m.batch.truth.shape[:2] == (N_TRACKS, N_STEPS) and N_TRACKS >= 200
    assert m.band == nees_band(N_TRACKS, DOF, 0.95)
    low, high = m.band
    assert low < DOF < high and high - low < 1.0


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_honest_filter_stays_in_the_band(seed):
    m = make(seed).model
    below, inside, above = m.fractions()
    assert inside >= 0.8 and max(below, above) < 0.5
    assert m.verdict().startswith("honest")
    low, high = m.band
    assert low < m.avg_nees[N_STEPS // 2 :].mean() < high


# --------------------------------------------------------------------------- Try this (chapter 6)
@pytest.mark.parametrize(
    ("which", "factor", "side"),
    [("Q", 0.1, "above"), ("Q", 10.0, "below"), ("R", 0.1, "above"), ("R", 10.0, "below")],
)
def test_try_off_by_ten_leaves_the_band_on_the_promised_side(which, factor, side):
    demo = make()
    m = demo.model
    set_mistune(demo, which, factor)
    below, _, above = m.fractions()
    low, high = m.band
    if side == "above":  # told the noise is smaller than it is: Sigma too small, over-confident
        assert above > 0.7 and m.verdict().startswith("over-confident")
        assert m.avg_nees[N_STEPS // 2 :].mean() > high
    else:  # told the noise is larger than it is: Sigma too large, timid
        assert below > 0.7 and m.verdict().startswith("timid")
        assert m.avg_nees[N_STEPS // 2 :].mean() < low
    assert m.verdict() in demo.children[2].value


def test_try_factor_one_is_honest_again():
    demo = make()
    set_mistune(demo, "Q", 0.1)
    set_mistune(demo, "Q", 1.0)
    assert demo.model.verdict().startswith("honest")


def test_try_sensor_ten_times_better_than_it_is_gives_about_25():
    demo = make()
    set_mistune(demo, "Q", 0.1)
    assert 15 < demo.model.avg_nees[N_STEPS // 2 :].mean() < 35


@pytest.mark.parametrize("which", ["R", "Q"])
def test_factor_extremes_stay_finite_and_on_the_right_side(which):
    demo = make()
    m = demo.model
    for factor, verdict in ((0.01, "over-confident"), (100.0, "timid")):
        set_mistune(demo, which, factor)
        assert np.isfinite(m.avg_nees).all() and (m.avg_nees > 0).all()
        assert m.verdict().startswith(verdict)
        assert "nan" not in demo.children[2].value.lower()


def test_try_prompts_in_order_on_one_panel():
    demo = make()
    m = demo.model
    low, high = m.band
    text = lambda: demo.children[2].value  # noqa: E731  (the readout under the picture)
    # 1. At factor 1: inside the band at almost every step (93 % here: a 95 % band lets a few steps out).
    below, inside, above = m.fractions()
    assert m.factor == 1.0 and m.verdict().startswith("honest")
    assert round(inside, 2) == 0.93 and below + above > 0  # a few steps out, not none
    assert "93%" in text()
    # 2. Choose Q and drag factor to 0.1: far above the band, about 25. Then to 10: below the band.
    set_mistune(demo, "Q", 0.1)
    assert m.fractions()[2] == 1.0 and m.verdict().startswith("over-confident")
    assert round(m.avg_nees.mean()) == 25
    set_mistune(demo, "Q", 10.0)
    assert m.fractions()[0] == 1.0 and m.verdict().startswith("timid")
    # 3. Choose R and do the same: 0.1 lifts the curve above the band after about a second; 10 drops it below.
    set_mistune(demo, "R", 0.1)
    out = np.flatnonzero(m.avg_nees > high)
    first = out[0] * m.batch.dt
    assert 0.8 <= first <= 1.6  # after about a second ...
    assert np.array_equal(out, np.arange(out[0], N_STEPS))  # ... and above from then on
    assert (m.avg_nees[: out[0]] >= low).all()  # inside until then
    assert m.verdict().startswith("over-confident") and m.verdict() in text()
    set_mistune(demo, "R", 10.0)
    assert m.fractions()[0] > 0.7 and m.verdict().startswith("timid")
