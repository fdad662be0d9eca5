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
import pytest

import kfcourse as kf
from kfcourse.demos._base import shown
from kfcourse.plots import palette
from tests.demos.layout import readout, widgets_in
from tests.demos.test_tracker import readout_lines

SENTENCE_END = re.compile(r"[.!?](?=\s|$)")
NOT_A_NUMBER = re.compile(r"\b(nan|inf|infinity)\b", re.IGNORECASE)
SEEDS = (0, 1, 2)
# The demo modules that write slider values (importlib: ``kfcourse.demos.tracker`` is also the demo function).
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


def shown_on_page(control: widgets.Widget) -> str:
    """The text a slider's readout shows: its value in d3-format's ``readout_format`` (an IntSlider: the integer).

    Written apart from the demos' own ``shown``: Python's alternate form of "g" keeps the trailing zeros as
    JavaScript's toPrecision does; its exponent loses the leading zero and a whole number its trailing point.
    """
    if isinstance(control, widgets.IntSlider):
        return str(control.value)
    fmt = control.readout_format
    text = format(control.value, fmt.replace(".", "#.") if fmt.endswith("g") else fmt)
    text = re.sub(r"e([+-])0*(\d)", r"e\1\2", text).removesuffix(".")
    if float(text) == 0:
        text = text.lstrip("-")
    return text.replace("-", "\u2212") if text.startswith("-") else text


def said(demo) -> str:
    """The demo's description, checked: one or two sentences, every number finite."""
    text = demo.description.text
    assert text and not NOT_A_NUMBER.search(text), text
    assert 1 <= len(SENTENCE_END.findall(text)) <= 2, text
    return text


def move(demo, name: str, value) -> str:
    """Set a control, and return the new description, which must differ from the one before and, for a
    slider, name the value its readout shows."""
    before = said(demo)
    control = demo.controls[name]
    control.value = value
    after = said(demo)
    assert after != before, (name, value, after)
    if isinstance(control, widgets.IntSlider | widgets.FloatSlider | widgets.FloatLogSlider):
        assert shown_on_page(control) in after, (name, shown_on_page(control), after)
    return after


def press(demo, name: str) -> str:
    """Click a button, and return the new description, which must differ from the one before."""
    before = said(demo)
    demo.controls[name].click()
    after = said(demo)
    assert after != before, (name, after)
    return after


def slider_ends(control: widgets.Widget) -> tuple:
    """A slider's two ends as values (a log slider: its base to the power of its ends)."""
    if isinstance(control, widgets.FloatLogSlider):
        return control.base**control.min, control.base**control.max
    return control.min, control.max


def at_the_ends(demo, names, then=()) -> list[str]:
    """Each slider of ``names`` at its minimum and its maximum, each followed by the presses ``then``: every
    description on the way is checked, and names the slider's readout."""
    texts = []
    for name in names:
        control = demo.controls[name]
        for end in slider_ends(control):
            control.value = end
            assert shown_on_page(control) in said(demo), (name, end, said(demo))
            texts.append(said(demo))
            for button in then:
                demo.controls[button].click()
                texts.append(said(demo))
    return texts


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


# --------------------------------------------------------------------------- chapter 1


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


def test_hallway_names_the_cells_where_a_mirrored_belief_peaks():
    demo = kf.demos.hallway(seed=0)
    peaks = [i for i, p in enumerate(demo.model.belief) if p == pytest.approx(demo.model.belief.max())]
    assert len(peaks) == 2 and f"2 cells ({peaks[0]}, {peaks[1]})" in said(demo)


# --------------------------------------------------------------------------- chapter 2


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


# --------------------------------------------------------------------------- chapter 6


@pytest.mark.parametrize("seed", SEEDS)
def test_tracker_says_the_step_the_settings_and_where_the_truth_is(seed):
    demo = kf.demos.tracker(seed=seed)
    assert f"Run {seed}, step {demo.model.frame} " in said(demo)
    move(demo, "frame", 40)
    move(demo, "sigma", 2.5)
    move(demo, "Q", 10**2.5)
    move(demo, "R", 10**-1.5)
    assert f"Run {seed + 1}," in press(demo, "new")
    at_the_ends(demo, ["frame", "sigma", "Q", "R"])


def test_tracker_description_keeps_to_one_line_at_the_sliders_corners():
    """The picture, the readout and the controls fit a laptop's screen with one line of description."""
    demo = kf.demos.tracker(seed=0)
    c = demo.controls
    for q, r, k in itertools.product(slider_ends(c["Q"]), slider_ends(c["R"]), (0, c["frame"].max)):
        c["sigma"].value, c["Q"].value, c["R"].value, c["frame"].value = 5.0, q, r, k
        assert readout_lines(said(demo)) == 1, said(demo)


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
