"""The 2-D tracker: every control does what the caption says, the two failure modes
show on the run record, and every "Try this" of chapter 6 keeps its promise."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.filters.gaussian import ellipse_axes
from kfcourse.sim.target import START_STEPS, filter_target, process_noise

TUNED = {"Q": 1.0, "R": 10.0}


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
def test_sliders_retune_the_filter_not_the_world():
    demo = make()
    m = demo.model
    truth, z = m.run.truth, m.run.z
    picture = bytes(demo.image.value)
    slider_to(demo, "Q", 100.0)
    assert m.q_var == pytest.approx(100.0)
    np.testing.assert_allclose(m.est.Q, 100.0 * np.eye(2))
    assert bytes(demo.image.value) != picture
    slider_to(demo, "R", 0.1)
    assert m.accel_var == pytest.approx(0.1)
    np.testing.assert_allclose(m.est.R, process_noise(m.run.dt, 0.1))
    assert m.run.truth is truth and m.run.z is z  # the same target, the same readings
    expected = filter_target(m.run, process_noise(m.run.dt, 0.1), 100.0 * np.eye(2))
    np.testing.assert_allclose(m.est.mu, expected.mu)


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
        text = demo.children[2].value  # the readout under the picture
        assert f"estimated ({v_est[0]:+.2f}, {v_est[1]:+.2f})" in text
        assert f"true ({v_true[0]:+.2f}, {v_true[1]:+.2f})" in text
        assert m.regime() in text and f"K = {m.gain():.3f}" in text


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


def test_first_frame_is_useful_and_seeded():
    a, b, c = make(0), make(0), make(1)
    assert a.model.frame > 20 and "balanced" in a.model.regime()
    assert bytes(a.image.value) == bytes(b.image.value)
    assert bytes(a.image.value) != bytes(c.image.value)  # another seed, other readings


@pytest.mark.parametrize(("q", "r"), [(1e-3, 1e-3), (1e-3, 1e7), (1e4, 1e-3), (1e4, 1e7)])
def test_slider_corners_stay_finite(q, r):
    demo = make()
    slider_to(demo, "Q", q)
    slider_to(demo, "R", r)
    m = demo.model
    assert np.isfinite(m.est.mu).all() and np.isfinite(m.est.Sig).all() and np.isfinite(m.est.K).all()
    for k in (0, 1, demo.controls["frame"].max):
        demo.controls["frame"].value = k
        assert "nan" not in demo.children[2].value.lower()


# --------------------------------------------------------------------------- failure modes
def test_lag_on_turns_grows_with_Q():
    demo = make()
    tuned = lag_in_turns(demo.model)
    slider_to(demo, "Q", 1e4)
    assert lag_in_turns(demo.model) > 4 * tuned
    slider_to(demo, "Q", 1e2)
    assert tuned < lag_in_turns(demo.model) < 4 * tuned  # on the way: it grows with Q


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


# --------------------------------------------------------------------------- Try this (chapter 6)
def try_1_run_from_step_0_starts_up_then_stays_balanced_and_beats_the_readings(demo):
    m = demo.model
    demo.controls["frame"].value = 0  # "drag step to 0"
    assert m.regime().startswith("starting guess")
    demo.controls["play"].value = True  # "press Run": plays from the step shown
    demo.controls["play"].value = False
    assert demo.controls["frame"].value <= 1  # Run started at step 0, not at the opening step 95
    demo.controls["frame"].value = 0
    regimes = []
    while demo.step():
        regimes.append(m.regime().split(":")[0])
    assert regimes == ["start-up"] * (START_STEPS - 1) + ["balanced"] * (m.run.t.size - START_STEPS)
    assert m.run.t[START_STEPS] == pytest.approx(2.0)  # "for the first 2 s"
    est, raw = m.errors()
    assert est < 0.6 * raw  # about half
    assert est == pytest.approx(0.64, abs=0.01) and raw == pytest.approx(1.28, abs=0.01)


def try_2_huge_Q_sails_on_along_its_old_velocity(demo):
    m = demo.model
    demo.controls["frame"].value = 90
    tuned_error = m.errors()[0]  # "against 0.6 m when tuned" (prompt 1 left the start settings)
    assert tuned_error == pytest.approx(0.6, abs=0.05)
    slider_to(demo, "Q", demo.controls["Q"].base ** demo.controls["Q"].max)
    assert m.q_var == pytest.approx(1e4)
    # step 29, the end of the first straight: on the target, at the right 2 m/s, but coasting
    demo.controls["frame"].value = 29
    assert m.run.t[29] == pytest.approx(2.9) and not m.run.turning[29] and m.run.turning[30]
    assert np.linalg.norm(m.est.mu[29, :2] - m.run.truth[29, :2]) < 1.0
    v_est, v_true = m.velocities()
    assert np.linalg.norm(v_est - v_true) < 0.3
    assert m.gain() < 0.05 and m.regime().startswith("K → 0: coasting")
    # step 49, the end of the first turn: grey points up, teal still along x
    demo.controls["frame"].value = 49
    assert m.run.turning[49] and not m.run.turning[50]
    v_est, v_true = m.velocities()
    assert v_true[1] > 1.9 and abs(v_true[0]) < 0.1
    assert v_est[0] > 1.9 and abs(v_est[1]) < 0.5
    # step 90, in the U-turn: 8 m from the target, the mean distance so far past 3 m
    demo.controls["frame"].value = 90
    assert m.run.turning[90]
    assert np.linalg.norm(m.est.mu[90, :2] - m.run.truth[90, :2]) == pytest.approx(8.0, abs=0.5)
    assert m.errors()[0] > 3.0 > 4 * tuned_error
    assert lag_in_turns(m) > 4 * lag_in_turns(make().model)  # late in every turn
    assert roughness(m.est.mu[:, :2]) < roughness(make().model.est.mu[:, :2]) / 4  # and smooth


def try_3_huge_sigma_a_is_jittery_and_the_velocity_line_stays_in_view(demo):
    m = demo.model
    slider_to(demo, "Q", 1.0)
    slider_to(demo, "R", demo.controls["R"].base ** demo.controls["R"].max)
    assert m.accel_var == pytest.approx(1e7)
    demo.controls["frame"].value = 90
    assert round(m.gain(), 3) == 0.997 and m.regime().startswith("K → 1: jittery")
    assert roughness(m.est.mu[:, :2]) > 0.95 * roughness(m.run.z)  # copies the orange dots
    v_err = m.est.mu[START_STEPS:, 2:] - m.run.truth[START_STEPS:, 2:]  # once tracking
    assert 160.0 < np.abs(v_err).max() < 200.0 and 50.0 < v_err.std() < 70.0  # "up to about ±180", "near 60"
    ax = demo.renderer.fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    est_vel = demo.view.velocity
    for k in range(demo.controls["frame"].max + 1):
        demo.controls["frame"].value = k
        start, (x, y) = est_vel.get_xydata()
        if x0 <= start[0] <= x1 and y0 <= start[1] <= y1:
            assert x0 - 1e-9 <= x <= x1 + 1e-9 and y0 - 1e-9 <= y <= y1 + 1e-9
        else:  # an estimate off the picture draws no line into it
            np.testing.assert_allclose((x, y), start)


def try_4_tiny_sigma_a_coasts_too_and_only_the_ratio_matters(demo):
    m = demo.model
    tuned = lag_in_turns(make().model)
    slider_to(demo, "R", 10.0)  # "put sigma_a^2 back to 10"
    slider_to(demo, "R", demo.controls["R"].base ** demo.controls["R"].min)
    K = [m.est.K[k, 0, 0] for k in range(START_STEPS, m.run.t.size)]
    assert np.all(np.diff(K) < 0)  # ever more confident: K keeps falling
    assert [round(m.est.K[k, 0, 0], 3) for k in (20, 50)] == [0.177, 0.076]
    demo.controls["frame"].value = 100
    assert round(m.gain(), 3) == 0.040 and m.regime().startswith("K → 0: coasting")
    assert lag_in_turns(m) > 2 * tuned
    gains = []
    for q, r in [(1.0, 10.0), (10.0, 100.0), (0.1, 1.0)]:  # the same ratio of sigma_a^2 to Q
        slider_to(demo, "Q", q)
        slider_to(demo, "R", r)
        gains.append(m.est.K[-1])
    assert round(gains[0][0, 0], 3) == 0.222
    np.testing.assert_allclose(gains[1], gains[0], rtol=1e-6)
    np.testing.assert_allclose(gains[2], gains[0], rtol=1e-6)


def test_try_prompts_in_order_on_one_demo():
    """Chapter 6's four prompts, one after the other, on the demo as it opens."""
    demo = make()
    try_1_run_from_step_0_starts_up_then_stays_balanced_and_beats_the_readings(demo)
    try_2_huge_Q_sails_on_along_its_old_velocity(demo)
    try_3_huge_sigma_a_is_jittery_and_the_velocity_line_stays_in_view(demo)
    try_4_tiny_sigma_a_coasts_too_and_only_the_ratio_matters(demo)
