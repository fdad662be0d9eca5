"""The 2-D tracker: every control does what the caption says (the world's noise apart from the
filter's belief), the readout says what the run record holds, and the failure modes show on
the run record.  The chapter's "Try this" prompts are tested in test_prompts_ch06.py."""

from __future__ import annotations

import html
import io
import itertools
import re

import numpy as np
import pytest
from matplotlib import font_manager
from PIL import Image, ImageFont

import kfcourse as kf
from kfcourse.filters.gaussian import ellipse_axes
from kfcourse.sim.target import START_STEPS, filter_target, process_noise
from tests.demos.layout import readout, widgets_in

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.

# A 1280x800 laptop: the whole demo (its folded caption, picture, description and controls) within 680 px, in an
# output 848 px wide (what tests/browser/test_notebooks_in_lab.py measures in JupyterLab).
LAPTOP_PX, OUTPUT_PX = 680, 848
ROW_PX = 34  # a row of sliders, buttons or toggles: 28 px high with its margins, rounded up
READOUT_FONT_PX, READOUT_LINE = 13, 1.5  # the readouts' font size and line height, rounded up
READOUT_MARGIN_PX = 4
DESCRIPTION_LINE, DESCRIPTION_MARGIN_PX = 1.4, 6  # the description under the picture: one line (describe.css)
CAPTION_PX = READOUT_FONT_PX * DESCRIPTION_LINE  # the caption folded under its title: one line


def make(seed=0):
    return kf.demos.tracker(seed=seed)


def lag_in_turns(model) -> float:
    """Mean distance (m) of the estimate from the truth while the target turns."""
    run, est = model.run, model.est
    d = np.linalg.norm(est.mu[:, :2] - run.truth[:, :2], axis=1)
    return float(d[run.turning].mean())


def roughness(xy) -> float:
    """Mean size of the step-to-step change of direction once tracking: |p_{k+1} - 2 p_k + p_{k-1}| (m)."""
    return float(np.linalg.norm(np.diff(xy[START_STEPS:], 2, axis=0), axis=1).mean())


def slider_to(demo, key, value):
    demo.controls[key].value = value
    assert demo.controls[key].value == pytest.approx(value)


# --------------------------------------------------------------------------- controls
@pytest.mark.pixels
@pytest.mark.fact
def test_filter_sliders_retune_the_filter_not_the_world():
    demo = make()
    m = demo.model
    truth, z = m.run.truth, m.run.z
    picture = bytes(demo.image.value)
    slider_to(demo, "Q", 100.0)
    assert m.q_factor == pytest.approx(100.0) and m.q_var == pytest.approx(100.0)  # x the true 1 m^2
    np.testing.assert_allclose(m.est.Q, 100.0 * np.eye(2))
    assert bytes(demo.image.value) != picture
    slider_to(demo, "R", 0.1)
    assert m.accel_var == pytest.approx(0.1)
    np.testing.assert_allclose(m.est.R, process_noise(m.run.dt, 0.1))
    assert m.run.truth is truth and m.run.z is z  # the same target, the same readings
    expected = filter_target(m.run, process_noise(m.run.dt, 0.1), 100.0 * np.eye(2))
    np.testing.assert_allclose(m.est.mu, expected.mu)


def test_sensor_slider_changes_the_world_and_the_filter_is_told_the_truth():
    demo = make()
    m = demo.model
    e = m.run.z - m.run.truth[:, :2]
    slider_to(demo, "sigma", 2.5)
    assert m.run.sensor_std == 2.5
    np.testing.assert_allclose(m.run.z - m.run.truth[:, :2], 2.5 * e)  # the same noise draw, spread wider
    np.testing.assert_allclose(m.est.Q, 6.25 * np.eye(2))  # Q follows the world's ...
    slider_to(demo, "Q", 0.1)
    np.testing.assert_allclose(m.est.Q, 0.625 * np.eye(2))  # ... times the mistuning
    slider_to(demo, "sigma", 1.0)
    np.testing.assert_allclose(m.est.Q, 0.1 * np.eye(2))
    assert "filter's Q = 0.1 m², true 1 m²" in readout(demo)


@pytest.mark.pixels
@pytest.mark.fact
def test_new_run_draws_new_noise_and_keeps_the_settings():
    demo = make()
    m = demo.model
    slider_to(demo, "sigma", 2.0)
    slider_to(demo, "R", 100.0)
    z, picture = m.run.z, bytes(demo.image.value)
    demo.controls["new"].click()
    assert m.seed == 1 and m.run.seed == 1 and not np.allclose(m.run.z, z)
    assert m.run.sensor_std == 2.0 and m.accel_var == 100.0 and m.frame == 95
    np.testing.assert_allclose(m.est.R, process_noise(m.run.dt, 100.0))
    assert bytes(demo.image.value) != picture and "run 1" in readout(demo)


def test_readout_says_the_honesty_test_and_the_ellipse_reach():
    demo = make()
    m = demo.model
    for settings in ({}, {"Q": 1e4}, {"Q": 1.0, "R": 1e-3}):
        for key, value in settings.items():
            slider_to(demo, key, value)
        h = m.est.honesty()
        text = readout(demo)
        assert f"<b>{h.verdict}</b>" in text and f"run {h.mean_nees:.3g}" in text
        assert f"honest from {h.low:.2f} to {h.high:.2f}" in text
        assert f" the 2σ ellipse ({m.est.ellipse_radius(m.frame):.2f} m" in text
        assert f"estimate {m.est.position_error()[m.frame]:.2f} m off" in text


def test_picture_shows_the_frame_estimate_ellipse_and_velocities():
    demo = make()
    m = demo.model
    v = demo.view
    pings, trail, ahead, truth_vel, truth_dot, est_vel, est_dot, ring = (
        v.readings,
        v.trail,
        v.ahead,
        v.truth_velocity,
        v.truth_dot,
        v.velocity,
        v.dot,
        v.ring,
    )
    assert set(demo.renderer.dynamic) == {pings, trail, ahead, truth_vel, truth_dot, est_vel, est_dot, ring}
    for k in (0, 37, 120):
        demo.controls["frame"].value = k
        assert m.frame == k
        assert len(pings.get_offsets()) == k + 1  # orange: the readings so far
        np.testing.assert_allclose(pings.get_offsets()[-1], m.run.z[k])
        np.testing.assert_allclose(trail.get_xydata()[-1], m.est.mu[k, :2])  # teal trail ends at the estimate
        np.testing.assert_allclose(ahead.get_xydata(), m.est.mu[k:, :2])  # dotted: the rest of the run
        np.testing.assert_allclose(est_dot.get_xydata()[0], m.est.mu[k, :2])
        np.testing.assert_allclose(truth_dot.get_xydata()[0], m.run.truth[k, :2])  # grey dot: the truth now
        np.testing.assert_allclose(ring.get_center(), m.est.mu[k, :2])
        w, h, _ = ellipse_axes(m.est.Sig[k, :2, :2], 2.0)  # the 2-sigma ellipse of the position block
        assert (ring.get_width(), ring.get_height()) == pytest.approx((w, h))
        v_est, v_true = m.velocities()
        np.testing.assert_allclose(np.diff(est_vel.get_xydata(), axis=0)[0], v_est, atol=1e-9)  # 1 s of velocity
        np.testing.assert_allclose(np.diff(truth_vel.get_xydata(), axis=0)[0], v_true, atol=1e-9)
        text = readout(demo)
        assert f"estimated ({v_est[0]:+.2f}, {v_est[1]:+.2f})" in text
        assert f"true ({v_true[0]:+.2f}, {v_true[1]:+.2f})" in text
        assert m.regime() in text
        assert (f"K = {m.gain():.3f}" in text) if k > 0 else ("K =" not in text)  # step 0: no gain yet


def test_time_and_retuning_never_redraw_the_map():
    """The map's limits are the true path's: a step, Run or a retune moves only the filter's artists."""
    demo = make()
    ax = demo.renderer.fig.axes[0]
    limits = ax.get_xlim(), ax.get_ylim()
    draws = demo.renderer.full_draws
    for k in (0, 1, demo.controls["frame"].max, 50):
        demo.controls["frame"].value = k
    slider_to(demo, "Q", 1e4)
    slider_to(demo, "R", 1e-3)
    assert demo.step(3)  # what Run does
    assert demo.renderer.full_draws == draws
    assert (ax.get_xlim(), ax.get_ylim()) == limits
    lo, hi = demo.model.run.truth[:, :2].min(axis=0), demo.model.run.truth[:, :2].max(axis=0)
    assert limits[0][0] < lo[0] and hi[0] < limits[0][1] and limits[1][0] < lo[1] and hi[1] < limits[1][1]


@pytest.mark.pixels
@pytest.mark.fact
def test_first_frame_is_useful_and_seeded():
    a, b, c = make(0), make(0), make(1)
    assert a.model.frame > 20 and "balanced" in a.model.regime()
    assert bytes(a.image.value) == bytes(b.image.value)
    assert bytes(a.image.value) != bytes(c.image.value)  # another seed, other readings


@pytest.mark.fact
@pytest.mark.parametrize("sigma", [0.1, 5.0])
@pytest.mark.parametrize(("q", "r"), [(1e-3, 1e-3), (1e-3, 1e7), (1e4, 1e-3), (1e4, 1e7)])
def test_slider_corners_stay_finite(q, r, sigma):
    demo = make()
    slider_to(demo, "sigma", sigma)
    slider_to(demo, "Q", q)
    slider_to(demo, "R", r)
    m = demo.model
    assert np.isfinite(m.est.mu).all() and np.isfinite(m.est.Sig).all() and np.isfinite(m.est.K).all()
    for k in (0, 1, demo.controls["frame"].max):
        demo.controls["frame"].value = k
        text = readout(demo).lower()
        assert "nan" not in text and "inf" not in text


# --------------------------------------------------------------------------- failure modes
@pytest.mark.fact
def test_lag_on_turns_grows_with_Q():
    demo = make()
    tuned = lag_in_turns(demo.model)
    slider_to(demo, "Q", 1e4)
    assert lag_in_turns(demo.model) > 4 * tuned
    slider_to(demo, "Q", 1e2)
    assert tuned < lag_in_turns(demo.model) < 4 * tuned  # on the way: it grows with Q


@pytest.mark.fact
def test_jitter_grows_with_R_and_K_goes_to_1():
    demo = make()
    m = demo.model
    demo.controls["frame"].value = demo.controls["frame"].max
    rough, K = [], []
    for r in (10.0, 1e3, 1e5, 1e7):
        slider_to(demo, "R", r)
        rough.append(roughness(m.est.mu[:, :2]))
        K.append(m.gain())
    assert rough == sorted(rough) and K == sorted(K)
    assert K[-1] > 0.99 and rough[-1] > 5 * rough[0]
    assert rough[-1] == pytest.approx(roughness(m.run.z), rel=0.05)  # as rough as the readings


# --------------------------------------------------------------------------- fits a laptop
def readout_lines(text: str) -> int:
    """How many lines the readout takes in the output: its lines, each measured in DejaVu Sans (wider than the
    notebook's fonts, so the estimate errs on the tall side) and wrapped at the output's width."""
    font = ImageFont.truetype(font_manager.findfont("DejaVu Sans"), READOUT_FONT_PX)
    plain = html.unescape(re.sub(r"<[^>]+>", "", text.replace("<br>", "\n")))
    return sum(int(font.getlength(line) // OUTPUT_PX) + 1 for line in plain.split("\n"))


def estimated_height(demo, lines: int) -> float:
    """The whole demo (CSS px): its folded caption, the picture at the demo's width and its own shape,
    its one-line description, a readout of ``lines`` lines, and one ROW_PX per row of controls."""
    width, height = Image.open(io.BytesIO(bytes(demo.image.value))).size
    rows = [c for c in demo.children[2:] if c is not demo.description and "kf-readout" not in c._dom_classes]
    readout_px = lines * READOUT_FONT_PX * READOUT_LINE + READOUT_MARGIN_PX
    description_px = READOUT_FONT_PX * DESCRIPTION_LINE + DESCRIPTION_MARGIN_PX
    picture_px = min(demo.display_width, OUTPUT_PX) * height / width
    return CAPTION_PX + picture_px + description_px + readout_px + len(rows) * ROW_PX


def rows_fit_the_output(demo) -> bool:
    """Every row of controls is no wider than the output (the widths the controls ask for)."""
    for row in demo.children[2:]:
        widths = [int(str(w.layout.width).removesuffix("px")) for w in widgets_in(row) if w.layout.width]
        if sum(widths) > OUTPUT_PX:
            return False
    return True


@pytest.mark.pixels
@pytest.mark.fact
def test_picture_and_controls_fit_a_laptop_at_every_corner_of_the_sliders():
    demo = make()
    c = demo.controls
    lines = 0
    for sigma, q, r, k in itertools.product([0.1, 5.0], [1e-3, 1.0, 1e4], [1e-3, 10.0, 1e7], [0, 95, 159]):
        c["sigma"].value, c["Q"].value, c["R"].value, c["frame"].value = sigma, q, r, k
        lines = max(lines, readout_lines(readout(demo)))
    assert lines == 4  # no line of the readout wraps
    assert demo.display_width == OUTPUT_PX and rows_fit_the_output(demo)
    assert estimated_height(demo, lines) <= LAPTOP_PX
