"""Chapters 0 to 6: every demo says in words what its picture shows.

For each demo: moving a control changes the description, and the description names the new
value as the student sees it (a slider's readout text, a choice's word, a button's effect);
at every slider's ends the description is one or two sentences with no "nan" or "inf" in it.
The readouts under the pictures write coloured text in the palette's text shades, and every
group of choice buttons has a name (its label, or a tooltip).
"""

from __future__ import annotations

import itertools
import re

import ipywidgets as widgets
import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos._base import shown
from kfcourse.plots import palette
from tests.demos.describing import at_the_ends, move, press, said, shown_on_page, slider_ends
from tests.demos.layout import readout, widgets_in
from tests.demos.test_tracker import readout_lines

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.

SEEDS = (0, 1, 2)
TEXT_SHADES = {palette.PREDICTION_TEXT, palette.MEASUREMENT_TEXT, palette.ESTIMATE_TEXT, palette.TRUTH_TEXT}

# What the page's readouts show (d3-format 3 in the browser, as JavaScript's toFixed and toPrecision write it).
D3_SHOWS = [
    (0.2, ".3g", "0.200"),
    (10**-0.7, ".3g", "0.200"),
    (0.001, ".3g", "0.00100"),
    (10.0, ".3g", "10.0"),
    (0.5, ".2g", "0.50"),
    (0.01, ".2g", "0.010"),
    (100.0, ".2g", "1.0e+2"),
    (100.0, ".3g", "100"),
    (99.99, ".3g", "100"),
    (1e4, ".3g", "1.00e+4"),
    (1e7, ".3g", "1.00e+7"),
    (10**2.5, ".3g", "316"),
    (10**-0.5, ".3f", "0.316"),
    (-0.6, ".2f", "\u22120.60"),
    (-1e-17, ".2f", "0.00"),
    (-4.0, ".2f", "\u22124.00"),
    (2.5, ".1f", "2.5"),
]


# --------------------------------------------------------------------------- how the page writes numbers


@pytest.mark.parametrize(("value", "fmt", "text"), D3_SHOWS)
def test_the_demos_write_numbers_as_the_readouts_show_them(value, fmt, text):
    assert shown(value, fmt) == text
    control = widgets.FloatSlider(value=value, min=-1e8, max=1e8, readout_format=fmt)
    assert shown_on_page(control) == text


def test_a_format_the_readouts_do_not_use_is_refused():
    with pytest.raises(ValueError, match="fmt"):
        shown(1.0, "%.2f")


# --------------------------------------------------------------------------- chapter 0


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_raw_vs_filtered_says_the_step_the_noise_and_each_error(seed):
    demo = kf.demos.raw_vs_filtered(seed=seed)
    m = demo.model
    text = said(demo)
    raw, dead, filtered = (f"{100 * e:.0f} cm" for e in m.rms_errors_all())
    assert f"step {m.frame}" in text and raw in text and dead in text and filtered in text
    move(demo, "sensor_noise", 1.25)
    move(demo, "frame", 60)
    assert f"Run {seed + 1}," in press(demo, "new_noise")
    at_the_ends(demo, ["sensor_noise", "frame"])


def closest_on_the_line(demo) -> list[str]:
    """The names of the estimates whose RMS error, in whole cm as the description says it, is the smallest."""
    raw, dead, filtered = (round(100 * e) for e in demo.model.rms_errors_all())
    errors = {"the filter": filtered, "the raw pings": raw, "dead reckoning": dead}
    return [name for name, cm in errors.items() if cm == min(errors.values())]


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_raw_vs_filtered_always_says_which_estimate_is_the_closest(seed):
    """Prompt 2 (sensor noise 3 m: dead reckoning beats the filter over 150 steps) and prompt 4 (New noise twice:
    dead reckoning is lucky) as well as the opening, where the filter is the closest, at every step."""
    demo = kf.demos.raw_vs_filtered(seed=seed)
    for sensor in (0.05, 0.4, 3.0):
        demo.controls["sensor_noise"].value = sensor
        for frame in (0, 1, 30, 149):
            demo.controls["frame"].value = frame
            closest, text = closest_on_the_line(demo), said(demo)
            if len(closest) == 1:
                assert text.endswith(f", so {closest[0]} is the closest."), text
            else:
                assert text.endswith(f" and {closest[-1]} are equally close."), text
                assert all(name in text.split(", so ")[-1] for name in closest), text


@pytest.mark.fact
def test_raw_vs_filtered_says_when_dead_reckoning_wins():
    demo = kf.demos.raw_vs_filtered(seed=0)
    assert said(demo).endswith("so the filter is the closest.")
    assert move(demo, "sensor_noise", 3.0).endswith("so dead reckoning is the closest.")  # 34 cm against 37 cm
    demo.controls["sensor_noise"].value = 0.4
    press(demo, "new_noise")
    assert press(demo, "new_noise").endswith("so dead reckoning is the closest.")  # run 2: 11 cm against 12 cm


# --------------------------------------------------------------------------- chapter 1


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_hallway_says_what_each_step_did_and_where_the_belief_peaks(seed):
    demo = kf.demos.hallway(seed=seed)
    m = demo.model
    assert said(demo).startswith("After Update")
    assert press(demo, "predict").startswith("After Predict (1 move since Reset")
    assert f"truly at cell {m.true_cell}" in said(demo)
    assert press(demo, "update").startswith("After Update")
    move(demo, "motion_reliability", 0.73)
    assert "from the next Update on" in move(demo, "sensor_reliability", 0.61)
    assert "ends: wall" in move(demo, "boundary", "wall")
    assert "ends: wrap" in move(demo, "boundary", "wrap")
    press(demo, "predict")
    press(demo, "reset")
    at_the_ends(demo, ["motion_reliability", "sensor_reliability"], then=("predict", "update"))


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_hallway_says_a_coin_flip_sensor_leaves_the_belief_unchanged(seed):
    """Prompt 3: sensor reliability 0.5 and Update: the likelihood is flat and the belief does not change."""
    demo = kf.demos.hallway(seed=seed)
    m = demo.model
    for _ in range(3):
        press(demo, "predict")
        assert "coin-flip" not in press(demo, "update")
    before = m.belief.copy()
    assert "coin-flip" not in move(demo, "sensor_reliability", 0.5)  # not used until the next Update
    text = press(demo, "update")
    np.testing.assert_allclose(m.belief, before, rtol=1e-12)
    assert "; a coin-flip sensor: the likelihood is flat, the belief unchanged), the belief still peaks at " in text
    assert f"still peaks at {m.belief.max():.2f} on " in text
    assert "coin-flip" not in press(demo, "predict")
    demo.controls["sensor_reliability"].value = 0.51
    assert "coin-flip" not in press(demo, "update") and "still" not in said(demo)


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_hallway_says_where_the_last_cell_goes_at_each_end(seed):
    """Prompt 5: on the loop cell 11's probability moves on to cell 0; prompt 6: at a wall it piles up in cell 11."""
    demo = kf.demos.hallway(seed=seed)
    m = demo.model
    last = len(m.belief) - 1
    for _ in range(4):
        before = m.belief.copy()
        text = press(demo, "predict")
        p = m.motion_reliability
        assert m.belief[0] == pytest.approx(p * before[last] + (1 - p) * before[0])  # cell 11's share arrived
        assert f"cell {last}'s share carried round the loop to cell 0, which now holds {m.belief[0]:.2f})" in text
        press(demo, "update")
    demo.controls["boundary"].value = "wall"
    press(demo, "reset")
    for _ in range(10):
        text = press(demo, "predict")
        assert f"cell {last} keeping its share at the wall, now holding {m.belief[last]:.2f})" in text
    assert f"the belief peaks at {m.belief.max():.2f} on cell {last};" in text


def test_hallway_sets_the_step_off_with_a_comma():
    demo = kf.demos.hallway(seed=0)
    for name in ("predict", "update", "predict"):
        text = press(demo, name)
        assert "), the belief " in text and ") the belief" not in text


@pytest.mark.fact
def test_hallway_names_the_cells_where_a_mirrored_belief_peaks():
    demo = kf.demos.hallway(seed=0)
    peaks = [i for i, p in enumerate(demo.model.belief) if p == pytest.approx(demo.model.belief.max())]
    assert len(peaks) == 2 and f"2 cells ({peaks[0]}, {peaks[1]})" in said(demo)


# --------------------------------------------------------------------------- chapter 2


@pytest.mark.fact
def test_covariance_says_how_sigma_stretches_and_tilts_the_ellipses():
    demo = kf.demos.covariance_ellipse(seed=0)
    assert "above the x axis" in said(demo)  # rho = 0.6: the long axis rises to the right
    move(demo, "var_x", 3.3)
    assert "below the x axis" in move(demo, "rho", -0.35)
    assert "along the x axis" in move(demo, "rho", 0.0)
    assert "along the y axis" in move(demo, "var_y", 3.9)
    move(demo, "var_y", 3.3)
    assert "are circles" in said(demo)
    at_the_ends(demo, ["var_x", "var_y", "rho"])


# --------------------------------------------------------------------------- chapter 3


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_step_through_says_what_each_press_did(seed):
    demo = kf.demos.step_through(seed=seed)
    assert said(demo).startswith("Step 0, the prior")
    assert press(demo, "update").startswith("Update refused (no reading at step 0)")
    assert press(demo, "predict").startswith("Predict to step 1")
    text = press(demo, "update")
    assert text.startswith("Update with step 1's reading z = 3.60: K = 0.857")
    assert "already used" in press(demo, "update")
    press(demo, "predict")
    press(demo, "predict")
    assert press(demo, "update").startswith("Update with step 3's reading")
    assert "R = 0.0316" in move(demo, "R", 10**-1.5)
    assert "Q = 2.00" in move(demo, "Q", 10**0.3)
    press(demo, "reset")
    at_the_ends(demo, ["R", "Q"], then=("predict", "update"))


# --------------------------------------------------------------------------- chapter 4


def test_trust_says_the_gain_as_a_share_of_the_way():
    demo = kf.demos.trust_slider(seed=0)
    m = demo.model
    text = said(demo)
    assert f"K = {m.K:.3f}" in text and f"{100 * m.K:.0f} % of the way" in text
    assert "\u22121.00" in text and "measurement (z = 1.50, variance 0.316, the surer one)" in text
    move(demo, "mu_pred", -2.3)
    move(demo, "z", 0.7)
    assert "prediction (mean \u22122.30, variance 0.063, the surer one)" in move(demo, "var_pred", 10**-1.2)
    move(demo, "var_meas", 10**0.5)
    at_the_ends(demo, ["mu_pred", "z", "var_pred", "var_meas"])
    for var_pred, var_meas in itertools.product(slider_ends(demo.controls["var_pred"]), repeat=2):
        demo.controls["var_pred"].value, demo.controls["var_meas"].value = var_pred, var_meas
        assert " 0 % " not in said(demo) and "100 %" not in said(demo)


def test_trust_writes_the_fused_variance_as_the_variance_sliders_do():
    demo = kf.demos.trust_slider(seed=0)
    m = demo.model
    assert "its variance 0.240 is narrower than both." in said(demo)  # 1 × 0.316 / 1.316
    demo.controls["var_meas"].value = 10.0
    assert "its variance 5.000 is narrower than both." in move(demo, "var_pred", 10.0)
    for var_pred, var_meas in itertools.product([10**-2, 10**-0.5, 10**0.3, 10**1], repeat=2):
        demo.controls["var_pred"].value, demo.controls["var_meas"].value = var_pred, var_meas
        assert f"its variance {shown(m.fused()[1], demo.controls['var_pred'].readout_format)} is " in said(demo)
    demo.controls["var_pred"].value = 0.01  # the fused 0.00999 shows as 0.010, like the surer one
    assert "its variance 0.010 is only just narrower than both." in said(demo)


# --------------------------------------------------------------------------- chapter 6


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_tracker_says_the_step_the_settings_and_where_the_truth_is(seed):
    demo = kf.demos.tracker(seed=seed)
    assert said(demo).startswith(f"Step {demo.model.frame}, σ 1.0 m, Q × 1.00, σₐ² 10.0: ")
    move(demo, "frame", 40)
    move(demo, "sigma", 2.5)
    move(demo, "Q", 10**2.5)
    move(demo, "R", 10**-1.5)
    press(demo, "new")
    assert demo.model.seed == seed + 1
    at_the_ends(demo, ["frame", "sigma", "Q", "R"])


def tracker_says(demo) -> str:
    """The tracker's description, checked against the readout: the mode, K, the error, the ellipse and the
    verdict it says are the readout's, and where the truth is (inside or outside the 2σ ellipse) is right."""
    m, text, shown_below = demo.model, said(demo), readout(demo)
    k = m.frame
    error, radius = f"{m.est.position_error()[k]:.2f}", f"{m.est.ellipse_radius(k):.2f}"
    verdict = m.est.honesty().verdict
    gain = f", K = {m.gain():.3f}" if k > 0 else ""
    assert f": {m.mode()}{gain}; {error} m off, " in text, text
    assert f"K = {m.gain():.3f}" in shown_below and m.mode() in m.regime() and m.regime() in shown_below
    assert text.endswith(f" the 2σ ellipse ({radius} m); {verdict}.") and f"<b>{verdict}</b>" in shown_below, text
    off = m.run.truth[k, :2] - m.est.mu[k, :2]
    inside = off @ np.linalg.solve(m.est.Sig[k, :2, :2], off) <= 4  # within 2σ: a squared Mahalanobis distance ≤ 2²
    assert f" m off, {'inside' if inside else 'outside'} the 2σ ellipse (" in text, text
    where = "inside" if inside else "<b>outside</b>"
    assert f"estimate {error} m off, {where} the 2σ ellipse ({radius} m" in shown_below, shown_below
    return text


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS)
def test_tracker_says_what_the_prompts_ask_the_student_to_notice(seed):
    """Chapter 6's five prompts, driven as they say: the mode, K, the error against the ellipse, the verdict."""
    demo = kf.demos.tracker(seed=seed)
    assert "balanced, K = 0.222;" in tracker_says(demo)
    # 1. From step 0: the starting guess (no gain yet), start-up for 2 s, then balanced; honest.
    assert ": starting guess; " in move(demo, "frame", 0) and "K =" not in said(demo)
    assert ": start-up, K = " in move(demo, "frame", 10)
    assert ": balanced, K = 0.222; " in move(demo, "frame", demo.controls["frame"].max)
    assert tracker_says(demo).endswith("; honest.")
    # 2. sensor σ 3 m: K falls from 0.222 to 0.135 and the ellipse grows from 0.94 m to 2.21 m.
    demo.controls["frame"].value = 95
    assert "K = 0.222;" in said(demo) and "(0.94 m)" in said(demo)
    text = move(demo, "sigma", 3.0)
    assert ": balanced, K = 0.135; " in tracker_says(demo) and "ellipse (2.21 m); " in text
    demo.controls["sigma"].value = 1.0
    # 3. Huge Q: coasting; at step 90 the estimate is metres off, but inside an ellipse of 20.5 m.
    demo.controls["Q"].value = 10**4
    assert ": coasting, K = " in move(demo, "frame", 29) and demo.model.gain() < 0.05
    text = move(demo, "frame", 90)
    assert ": coasting, K = " in tracker_says(demo) and " m off, inside the 2σ ellipse (20.50 m); " in text
    assert 3.0 < demo.model.est.position_error()[90] < 15.0
    # 4. Huge σₐ²: jittery, K = 0.997, honest.
    demo.controls["Q"].value = 1.0
    text = move(demo, "R", 10**7)
    assert ": jittery, K = 0.997; " in tracker_says(demo) and text.endswith("; honest.")
    # 5. Tiny σₐ²: coasting at step 100, K = 0.040, outside an ellipse of 0.40 m, over-confident in every run.
    demo.controls["R"].value = 10**-3
    text = move(demo, "frame", 100)
    assert ": coasting, K = 0.040; " in tracker_says(demo)
    assert text.endswith(" m off, outside the 2σ ellipse (0.40 m); over-confident.")


@pytest.mark.fact
def test_tracker_says_the_verdict_of_a_timid_filter():
    demo = kf.demos.tracker(seed=0)
    demo.controls["Q"].value = 10**4
    assert tracker_says(demo).endswith("; timid.")  # prompt 3: timid in most runs, this one among them


@pytest.mark.fact
def test_tracker_description_keeps_to_one_line_at_the_sliders_corners():
    """The picture, the readout and the controls fit a laptop's screen with one line of description: at every
    corner of the sliders, in the middle of each range, at the first, a start-up and the last steps."""
    for seed in SEEDS:
        demo = kf.demos.tracker(seed=seed)
        m, c = demo.model, demo.controls
        sigmas, qs, rs = (0.1, 2.0, 5.0), (*slider_ends(c["Q"]), 1.0), (*slider_ends(c["R"]), 10.0)
        for sigma, q, r in itertools.product(sigmas, qs, rs):  # the model alone: no picture to draw
            m.set_sensor_std(sigma)
            m.set_q_factor(q)
            m.set_accel_var(r)
            for k in (0, 10, 50, 95, 141, c["frame"].max):
                m.frame = k
                assert readout_lines(m.describe()) == 1, m.describe()


def nees_says(demo) -> str:
    """The NEES panel's description, checked against the model: the mean against 4 and the shares of the
    steps below, inside and above the band, in that order."""
    m, text = demo.model, said(demo)
    below, inside, above = (f"{100 * share:.0f} %" for share in m.fractions())
    assert f"has a mean of {m.avg_nees.mean():.2f} (4 expected)" in text, text
    assert f"is below, inside and above the 95 % band at {below}, {inside} and {above} of the steps." in text, text
    assert text.endswith(f"The filter is {m.verdict()}.")
    return text


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS[:2])
def test_nees_says_whether_the_curve_is_below_or_above_the_band(seed):
    """Prompts 1 to 3: honest at factor 1; Q × 0.1 above the band at every step, Q × 10 below; R the same way."""
    demo = kf.demos.nees_panel(seed=seed)
    assert "The filter is honest" in nees_says(demo)
    demo.controls["factor"].value = 0.1
    assert "band at 0 %, 0 % and 100 % of the steps. The filter is over-confident" in nees_says(demo)
    demo.controls["factor"].value = 10.0
    assert "band at 100 %, 0 % and 0 % of the steps. The filter is timid" in nees_says(demo)
    demo.controls["which"].value = "R"
    assert "The filter is timid" in nees_says(demo)
    demo.controls["factor"].value = 0.1
    assert "The filter is over-confident" in nees_says(demo)


@pytest.mark.fact
@pytest.mark.parametrize("seed", SEEDS[:2])
def test_nees_says_the_mistuning_where_the_curve_lies_and_the_verdict(seed):
    demo = kf.demos.nees_panel(seed=seed)
    assert "honest" in said(demo)
    assert "the true R (process noise)" in move(demo, "which", "R")
    assert "over-confident" in move(demo, "factor", 0.01)
    assert "the true Q (measurement noise)" in move(demo, "which", "Q")
    move(demo, "factor", 10**1.3)
    assert f"(run {seed + 1})" in press(demo, "new")
    for which in ("R", "Q"):
        demo.controls["which"].value = which
        at_the_ends(demo, ["factor"])


# --------------------------------------------------------------------------- colours and names


DEMOS = ["raw_vs_filtered", "hallway", "covariance_ellipse", "step_through", "trust_slider", "tracker", "nees_panel"]


@pytest.mark.parametrize("name", DEMOS)
def test_coloured_text_uses_the_text_shades_and_choices_have_a_name(name):
    demo = getattr(kf.demos, name)(seed=0)
    for w in widgets_in(demo):
        if isinstance(w, widgets.HTML):
            for colour in re.findall(r"color:\s*(#[0-9a-fA-F]{6})", w.value):
                assert colour in TEXT_SHADES or colour == palette.INK, (name, colour)
        if isinstance(w, widgets.ToggleButtons):
            assert w.description or w.tooltip, name


def test_the_tracker_readout_writes_the_estimate_in_its_text_shade():
    assert f"color:{palette.ESTIMATE_TEXT}" in readout(kf.demos.tracker(seed=0))
