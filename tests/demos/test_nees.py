"""The NEES panel: the controls mistune what the caption says, an honest filter stays in
the band, and the extremes stay finite.  The chapter's "Try this" prompts are tested in
test_prompts_ch06.py."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.nees import DOF, N_STEPS, N_TRACKS
from kfcourse.sim.scores import nees, nees_band
from kfcourse.sim.target import filter_tracks
from tests.demos.layout import readout
from tests.demos.test_tracker import LAPTOP_PX, OUTPUT_PX, estimated_height, readout_lines, rows_fit_the_output

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


def make(seed=0):
    return kf.demos.nees_panel(seed=seed)


def set_mistune(demo, which, factor):
    demo.controls["which"].value = which
    demo.controls["factor"].value = factor
    assert demo.model.which == which and demo.model.factor == pytest.approx(factor)


@pytest.mark.pixels
@pytest.mark.fact
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
    assert f"{m.avg_nees.mean():.2f}" in readout(demo)


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


@pytest.mark.fact
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_honest_filter_stays_in_the_band(seed):
    m = make(seed).model
    below, inside, above = m.fractions()
    assert inside >= 0.8 and max(below, above) < 0.5
    assert m.verdict().startswith("honest")
    low, high = m.band
    assert low < m.avg_nees[N_STEPS // 2 :].mean() < high


@pytest.mark.fact
@pytest.mark.parametrize("which", ["R", "Q"])
def test_factor_extremes_stay_finite_and_on_the_right_side(which):
    demo = make()
    m = demo.model
    for factor, verdict in ((0.01, "over-confident"), (100.0, "timid")):
        set_mistune(demo, which, factor)
        assert np.isfinite(m.avg_nees).all() and (m.avg_nees > 0).all()
        assert m.verdict().startswith(verdict)
        assert "nan" not in readout(demo).lower()


@pytest.mark.pixels
@pytest.mark.fact
def test_new_run_draws_new_tracks_and_keeps_the_mistuning():
    demo = make()
    m = demo.model
    set_mistune(demo, "R", 0.1)
    truth, picture = m.batch.truth, bytes(demo.image.value)
    demo.controls["new"].click()
    assert m.batch.seed == 1 and not np.allclose(m.batch.truth, truth)
    assert m.which == "R" and m.factor == pytest.approx(0.1)
    mu, Sig = filter_tracks(m.batch, *m.assumed())
    np.testing.assert_allclose(m.avg_nees, nees(m.batch.truth, mu, Sig).mean(axis=0))
    assert bytes(demo.image.value) != picture and "run 1:" in readout(demo)


@pytest.mark.pixels
@pytest.mark.fact
def test_picture_and_controls_fit_a_laptop():
    demo = make()
    lines = 0
    for which in ("R", "Q"):
        for factor in (0.01, 1.0, 100.0):
            set_mistune(demo, which, factor)
            lines = max(lines, readout_lines(readout(demo)))
    assert lines == 3  # no line of the readout wraps
    assert demo.display_width == OUTPUT_PX and rows_fit_the_output(demo)
    assert estimated_height(demo, lines) <= LAPTOP_PX
