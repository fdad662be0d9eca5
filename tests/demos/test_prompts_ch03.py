"""Chapter 3's "Try this" prompts, each driven through the step-through demo's
controls exactly as the chapter says, asserting what the chapter promises.

Time steps: the k-th Predict moves the robot to time step k; an Update reads
the sensor at that time step (3.6 m at step 1, 4.7 m at step 2, then seeded
readings of a robot at 2 + k metres).
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots import palette

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def demo():
    return kf.demos.step_through(seed=0)


def press(d, *keys):
    for key in keys:
        d.controls[key].click()


def slide_to_max(d, key):
    control = d.controls[key]
    d.controls[key].value = control.base**control.max if isinstance(control, widgets.FloatLogSlider) else control.max


def table_html(d) -> str:
    (table,) = [w for w in d.children if isinstance(w, widgets.HTML) and "kf-caption" not in w._dom_classes]
    return table.value


def visible_curve(d, colour):
    """The y-values of the one visible curve of a role's colour, drawn in the role's line style."""
    (ax,) = d.renderer.fig.axes
    found = [
        line.get_ydata()
        for line in ax.get_lines()
        if line.get_visible()
        and line.get_color() == colour
        and line.get_linestyle() == palette.line_style(colour)
        and len(line.get_xdata()) > 2
    ]
    assert len(found) == 1, f"{len(found)} visible curves of colour {colour}"
    return np.asarray(found[0], float)


def status_text(d) -> str:
    (ax,) = d.renderer.fig.axes
    return "\n".join(t.get_text() for t in ax.texts if t.get_visible())


# The six "Try this" prompts are done in order on one demo, as a student does them: each starts
# where the one before left the demo (presses and sliders).


def try_1_predict_update_predict_update_reproduces_cycles_1_and_2(d):
    """Try this 1: Predict, Update, Predict, Update; the table reproduces cycles 1 and 2."""
    press(d, "predict", "update", "predict", "update")
    assert_cycles_1_and_2(d)


def assert_cycles_1_and_2(d):
    c1 = kf.kf_1d_cycle(2.0, 0.40, u=1.0, z=3.6, R=0.20, Q=0.10)
    c2 = kf.kf_1d_cycle(c1.mu, c1.var, u=1.0, z=4.7, R=0.20, Q=0.10)
    assert len(d.model.rows) == 2
    for row, k, z, cyc in zip(d.model.rows, (1, 2), (3.6, 4.7), (c1, c2), strict=True):
        assert row[0] == k
        assert row[1:] == pytest.approx((cyc.mu_bar, cyc.var_bar, z, cyc.innovation, cyc.K, cyc.mu, cyc.var))
    html = table_html(d)
    for number in ("3.000", "0.600", "3.600", "0.857", "3.514", "0.086", "4.700", "0.741", "4.652", "0.074"):
        assert number in html, number


def try_2_reset_then_predict_three_times_and_update_uses_the_step_3_reading(d):
    """Try this 2: Reset, then Predict three times and Update once; the Update uses step 3's
    reading (not 3.6, step 1's), so the belief stays with the robot near 5 m."""
    press(d, "reset", "predict", "predict", "predict")
    assert (d.model.mu, d.model.var) == pytest.approx((5.0, 1.0))  # step 3: 2 + 3 m, 0.4 + 3 x 0.2
    press(d, "update")
    assert d.model.z != 3.6  # step 1's reading belongs to step 1
    # the belief moves forward with the robot; step 1's reading would drag it back to 3.73 m
    assert d.model.mu > 4.5
    (row,) = d.model.rows
    z3 = d.model.reading(3)
    assert row[0] == 3 and row[3] == d.model.z == z3
    assert abs(z3 - 5.0) < 1.0  # a reading of the robot at step 3, 2 + 3 m
    assert min(5.0, z3) <= d.model.mu <= max(5.0, z3)  # between the prediction and the reading


def try_3_predict_several_times_widens_the_curve(d):
    """Try this 3: Predict several times in a row; the purple curve keeps widening and
    flattening, its variance growing by R every step."""
    peaks, variances = [], []
    for _ in range(5):
        press(d, "predict")
        variances.append(d.model.var)
        peaks.append(visible_curve(d, palette.PREDICTION).max())
    assert np.diff(variances) == pytest.approx([0.20] * 4)  # every Predict adds R
    assert np.all(np.diff(peaks) < 0)  # and flattens the curve further
    assert peaks[-1] == pytest.approx(1 / np.sqrt(2 * np.pi * variances[-1]), rel=0.01)


def try_4_update_twice_in_a_row_is_refused(d):
    """Try this 4: Update twice in a row; the second press is refused and the belief does not
    change (each time step has one reading; using it twice would count it twice)."""
    press(d, "update")
    before = (d.model.mu, d.model.var, list(d.model.rows))
    picture = bytes(d.image.value)
    press(d, "update")
    assert (d.model.mu, d.model.var, d.model.rows) == before
    assert "already used" in status_text(d)
    assert bytes(d.image.value) != picture  # the refusal is shown


def try_5_reset_large_Q_makes_K_small_and_teal_hugs_purple(d):
    """Try this 5: Reset, Q to its largest value, then Predict, Update; K drops below 0.1 and the
    teal curve hugs the purple one."""
    press(d, "reset")
    slide_to_max(d, "Q")
    assert d.model.Q == pytest.approx(10.0)
    press(d, "predict", "update")
    assert d.model.K < 0.1
    purple, teal = visible_curve(d, palette.PREDICTION), visible_curve(d, palette.ESTIMATE)
    assert np.max(np.abs(teal - purple)) < 0.1 * purple.max()


def try_6_Q_back_reset_two_cycles_then_large_R_gives_K_near_1(d):
    """Try this 6: Q back to 0.1, Reset, Predict, Update, Predict, Update (cycles 1 and 2 again),
    then R to its largest value; both rows are replayed, the gains rise close to 1 and each
    estimate sits almost on its reading."""
    d.controls["Q"].value = 0.1
    press(d, "reset", "predict", "update", "predict", "update")
    assert_cycles_1_and_2(d)
    slide_to_max(d, "R")
    assert [row[0] for row in d.model.rows] == [1, 2]
    for row in d.model.rows:
        assert row[5] > 0.98
        assert row[6] == pytest.approx(row[3], abs=0.02)
    assert "0.99" in table_html(d)


PROMPTS = (
    try_1_predict_update_predict_update_reproduces_cycles_1_and_2,
    try_2_reset_then_predict_three_times_and_update_uses_the_step_3_reading,
    try_3_predict_several_times_widens_the_curve,
    try_4_update_twice_in_a_row_is_refused,
    try_5_reset_large_Q_makes_K_small_and_teal_hugs_purple,
    try_6_Q_back_reset_two_cycles_then_large_R_gives_K_near_1,
)


@pytest.mark.pixels
def test_try_this_1_to_6_in_order_on_one_demo():
    """The chapter's six prompts, one after the other on the same demo, each asserting what it promises."""
    d = demo()
    for prompt in PROMPTS:
        prompt(d)


def test_update_before_any_predict_is_refused():
    """The text: before the first Predict there is no reading yet (the robot is at step 0)."""
    d = demo()
    press(d, "update")
    assert (d.model.mu, d.model.var, d.model.rows) == (2.0, 0.40, [])
    assert "press Predict" in status_text(d)


def test_reset_keeps_the_sliders():
    """Reset clears the presses, not the sliders: prompts 5 and 6 say so and move Q themselves."""
    d = demo()
    d.controls["Q"].value = 10.0
    press(d, "predict", "reset")
    assert d.model.Q == pytest.approx(10.0) and d.controls["Q"].value == pytest.approx(10.0)
    press(d, "predict", "update")
    assert d.model.K == pytest.approx(0.6 / 10.6)


def test_reset_goes_back_to_the_prior():
    """Reset (used in try-this 2) goes back to the prior N(2.0, 0.40) at step 0."""
    d = demo()
    first = bytes(d.image.value)
    press(d, "predict", "update", "predict", "reset")
    assert (d.model.mu, d.model.var, d.model.rows, d.model.phase) == (2.0, 0.40, [], "prior")
    assert bytes(d.image.value) == first


def assert_density_label_not_clipped(d, what: str) -> None:
    """The y axis label and tick labels, as a full redraw places them with the layout found
    once, lie inside the picture."""
    d.renderer.png()
    fig = d.renderer.fig
    renderer = fig.canvas.get_renderer()
    (ax,) = fig.axes
    for text in [ax.yaxis.label, *ax.get_yticklabels()]:
        if text.get_visible() and text.get_text():
            box = text.get_window_extent(renderer)
            assert box.x0 >= 0 and box.x1 <= fig.bbox.x1, f"after {what}: {text.get_text()!r} at {box}"


@pytest.mark.pixels
def test_the_density_label_is_never_cut_off():
    """Tall and flat curves change the y tick labels ("0.5", "1.75", "12.5", "0.0125"); the layout is
    found once, so none of them may push the "density" label off the picture."""
    d = demo()
    assert_density_label_not_clipped(d, "start")
    for keys in (("predict",), ("update",), ("predict", "update"), ("reset",)):
        press(d, *keys)
        assert_density_label_not_clipped(d, " ".join(keys))
    d.controls["Q"].value = 0.001  # a razor-sharp sensor: tall curves
    press(d, "predict", "update")
    assert_density_label_not_clipped(d, "Q = 0.001")
    d.controls["R"].value = 0.001
    assert_density_label_not_clipped(d, "R = Q = 0.001")
    d.controls["R"].value, d.controls["Q"].value = 10.0, 10.0
    press(d, *["predict"] * 30)  # a very flat prediction: small densities
    assert_density_label_not_clipped(d, "30 predicts at R = 10")
