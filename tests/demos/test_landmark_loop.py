"""The landmark-loop demo: every control reruns the lap with its setting, moving in time only
redraws, the picture shows the step, every corner of the controls stays finite, and every
"Try this" of chapter 10 keeps its promise."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.landmark_loop import DROPOUT, FIRST_FRAME, GATE
from kfcourse.filters.gaussian import ellipse_axes
from kfcourse.plots.loop import position_errors, strip_limit
from tests.demos.layout import readout


def make(seed=0):
    return kf.demos.landmark_loop(seed=seed)


def views(demo):
    """The map's artists and the strips' artists, in the order the demo hands them to its renderer."""
    dynamic = demo.renderer.dynamic
    return dynamic[:10], dynamic[10:]


def tick_values(ax) -> list[float]:
    """The y tick labels of a strip, read as numbers."""
    return [float(label.get_text().strip("\u2007").replace("\u2212", "-")) for label in ax.get_yticklabels()]


def bar_area(run, k) -> float:
    return float(np.pi * np.sqrt(np.linalg.det(run.Sig_bar[k, :2, :2])))


def expected_run(model):
    return kf.sim.landmark_loop(
        model.seed,
        filter=model.filter,
        dropout=DROPOUT if model.dropout else None,
        motion_noise=model.motion_noise,
        sensor_noise=model.sensor_noise,
        kidnap=model.kidnap,
        gate=GATE,
    )


# --------------------------------------------------------------------------- controls
def test_first_frame_is_a_normal_lap_mid_way():
    demo = make()
    m = demo.model
    assert m.frame == FIRST_FRAME == demo.controls["frame"].value == 60  # chapter 10: "opens at step 60"
    assert DROPOUT == (40, 70) and GATE == 4.0  # the window and the gate the chapter's prose and cells use
    assert demo.controls["frame"].max == m.run.t.size - 1
    assert (m.filter, m.motion_noise, m.sensor_noise, m.dropout, m.kidnap) == ("ekf", 1.0, 1.0, False, None)
    assert m.run.gate == GATE and m.run.dropout is None
    assert m.run.used[m.frame].sum() == 2 and "uses 2 readings" in readout(demo)  # two beams in the first picture
    assert demo.controls["kidnap"].description == "Kidnap"


def test_noise_sliders_rerun_the_lap_once_where_they_are_let_go():
    demo = make()
    assert demo.controls["motion"].continuous_update is False  # a rerun per dragged pixel would queue up
    assert demo.controls["sensor"].continuous_update is False
    assert demo.controls["frame"].continuous_update is True  # stepping only redraws: follows the drag


@pytest.mark.parametrize(
    ("key", "value", "attr"),
    [
        ("motion", 3.0, "motion_noise"),
        ("sensor", 0.2, "sensor_noise"),
        ("dropout", True, "dropout"),
        ("filter", "UKF", "filter"),
    ],
)
def test_each_control_reruns_the_lap_with_its_setting(key, value, attr):
    demo = make()
    m = demo.model
    run, picture = m.run, bytes(demo.image.value)
    demo.controls[key].value = value
    assert getattr(m, attr) == (value.lower() if key == "filter" else pytest.approx(value))
    assert m.run is not run and bytes(demo.image.value) != picture
    np.testing.assert_array_equal(m.run.mu, expected_run(m).mu)
    assert m.frame == FIRST_FRAME  # the step shown stays


def test_moving_in_time_never_reruns():
    demo = make()
    run = demo.model.run
    for k in (0, 5, DROPOUT[0], demo.controls["frame"].max):
        demo.controls["frame"].value = k
        assert demo.model.frame == k and demo.model.run is run
    demo.controls["frame"].value = 0
    while demo.step(7):
        assert demo.model.run is run


def test_kidnap_button_carries_the_robot_off_at_the_step_shown_and_undoes():
    demo = make()
    m = demo.model
    demo.controls["frame"].value = 30
    demo.controls["kidnap"].click()
    assert m.kidnap == 30 == m.run.kidnap and demo.controls["kidnap"].description == "Undo kidnap"
    assert "kidnapped</b> at step 30" in readout(demo)
    assert np.linalg.norm(m.run.truth[30, :2] - expected_run(m).truth[30, :2]) == 0.0
    np.testing.assert_array_equal(m.run.mu, expected_run(m).mu)
    demo.controls["frame"].value = 50
    demo.controls["kidnap"].click()
    assert m.kidnap is None and m.run.kidnap is None and demo.controls["kidnap"].description == "Kidnap"


def test_picture_shows_the_step():
    demo = make()
    m = demo.model
    (truth_before, truth_after, beams, rejected, trail, truth_robot, robot, prior_ring, ring, note), strips = views(
        demo
    )
    demo.controls["dropout"].value = True
    demo.controls["frame"].value = 20
    demo.controls["kidnap"].click()  # kidnapped at step 20: some readings get rejected later
    run = m.run
    error, bound = position_errors(run)
    top = strip_limit(run)
    for k in (0, 45, 75, 121):
        demo.controls["frame"].value = k
        np.testing.assert_allclose(trail.get_xydata()[-1], run.mu[k, :2])
        np.testing.assert_allclose(robot.get_xy()[:3].mean(axis=0), run.mu[k, :2], atol=1e-9)  # the centroid
        np.testing.assert_allclose(truth_robot.get_xy()[:3].mean(axis=0), run.truth[k, :2], atol=1e-9)
        np.testing.assert_allclose(ring.get_center(), run.mu[k, :2])
        np.testing.assert_allclose(prior_ring.get_center(), run.mu_bar[k, :2])
        w, h, _ = ellipse_axes(run.Sig[k, :2, :2], 2.0)
        assert (ring.get_width(), ring.get_height()) == pytest.approx((w, h))
        assert len(beams.get_segments()) == run.used[k].sum()
        assert len(rejected.get_segments()) == run.rejected[k].sum()
        for segment, j in zip(beams.get_segments(), np.flatnonzero(run.used[k]), strict=True):
            np.testing.assert_allclose(segment, [run.mu[k, :2], run.landmarks[j]])
        assert note.get_text() == ("sensor blind" if DROPOUT[0] <= k < DROPOUT[1] else note.get_text())
        assert len(truth_before.get_xydata()) == 20 and len(truth_after.get_xydata()) == run.t.size - 20
        past_x, past_y = strips[4], strips[10]  # per axis: blind, band, kidnap, future, past, cursor
        np.testing.assert_allclose(past_x.get_xydata()[-1], [run.t[k], error[k, 0]])  # in metres
        np.testing.assert_allclose(past_y.get_xydata()[-1], [run.t[k], error[k, 1]])
        assert strips[5].get_xdata()[0] == pytest.approx(run.t[k])
        band = strips[1].get_paths()[0].vertices
        assert band[:, 1].max() == pytest.approx(bound[:, 0].max())  # +2 sqrt(Sig_xx) at its widest
        for ax in demo.renderer.fig.axes[1:]:
            assert ax.get_ylim() == (-top, top) and tick_values(ax) == [-top, 0.0, top]
    assert top >= np.abs(error).max() and top >= bound.max()  # the strips hold the whole kidnapped run


@pytest.mark.parametrize(
    ("motion", "sensor", "filter"), list(itertools.product((0.1, 10.0), (0.1, 10.0), ("ekf", "ukf")))
)
def test_every_corner_stays_finite(motion, sensor, filter):
    demo = make()
    demo.controls["motion"].value = motion
    demo.controls["sensor"].value = sensor
    demo.controls["filter"].value = filter.upper()
    for dropout, kidnap in itertools.product((False, True), (False, True)):
        demo.controls["dropout"].value = dropout
        if kidnap != (demo.model.kidnap is not None):
            demo.controls["kidnap"].click()
        run = demo.model.run
        assert (run.motion_noise, run.sensor_noise, run.filter) == pytest.approx((motion, sensor, filter))
        for name in ("mu", "Sig", "mu_bar", "Sig_bar", "area", "error"):
            assert np.isfinite(getattr(run, name)).all(), name
        for k in (0, DROPOUT[1], demo.controls["frame"].max):
            demo.controls["frame"].value = k
            text = readout(demo).lower()
            assert "nan" not in text and "inf" not in text
            for artist in demo.renderer.dynamic:
                data = artist.get_xydata() if hasattr(artist, "get_xydata") else None
                if data is not None:
                    assert np.isfinite(np.asarray(data, float)).all()
            assert bytes(demo.image.value[:3]) == b"\xff\xd8\xff"  # a JPEG


# --------------------------------------------------------------------------- Try this (chapter 10)
def try_1_a_normal_lap_is_accurate_and_honest(demo):
    m = demo.model
    demo.controls["frame"].value = 0  # "drag step to 0 and press Run"
    errors, areas, beams = [], [], []
    while True:
        k = m.frame
        errors.append(m.run.error[k])
        areas.append(m.run.area[k])
        beams.append(int(m.run.used[k].sum()))
        assert m.run.rejected[k].sum() == 0  # never an orange beam
        if not demo.step():
            break
    assert len(errors) == m.run.t.size
    assert max(errors) < 0.15  # "never more than 15 cm"
    assert 0.001 <= min(areas) and max(areas) < 0.01  # "the 1-sigma area after the readings: 0.001 to 0.01 m²"
    assert round(bar_area(m.run, 0), 3) == 0.032  # "the readout's before starts higher, 0.032 m² at step 0"
    assert (min(beams), max(beams)) == (1, 3)  # "one to three beams"
    assert "(99% of steps so far)" in readout(demo)


def try_2_dropout_balloons_then_three_readings_cut_it_tenfold(demo):
    m = demo.model
    demo.controls["dropout"].value = True
    run = m.run
    demo.controls["frame"].value = DROPOUT[0] - 1
    start = m.areas()[1]
    for k in range(DROPOUT[0], DROPOUT[1]):
        demo.controls["frame"].value = k
        assert m.blind() and "sensor blind" in readout(demo) and run.used[k].sum() == 0
    assert round(start, 4) == 0.0033 and round(run.area[DROPOUT[1] - 1], 3) == 0.078  # "0.0033 at 39 to 0.078 at 69"
    assert (np.diff(run.area[DROPOUT[0] - 1 : DROPOUT[1]]) > 0).all()  # "grows at every step"
    assert run.area[DROPOUT[1] - 1] / start > 20  # "more than twenty times"
    demo.controls["frame"].value = DROPOUT[1]
    before, after = m.areas()
    assert (round(before, 3), round(after, 4)) == (0.083, 0.0082) and run.used[DROPOUT[1]].sum() == 3
    assert "(×0.10)" in readout(demo)
    assert run.error.max() < 0.15  # good odometry: the estimate barely wanders


def try_3_push_the_process_noise_until_it_breaks(demo):
    m = demo.model
    demo.controls["motion"].value = demo.controls["motion"].base ** demo.controls["motion"].max
    assert m.motion_noise == pytest.approx(10.0) and m.dropout
    run = m.run
    demo.controls["frame"].value = DROPOUT[1] - 1
    assert round(run.area[DROPOUT[1] - 2], 1) == 5.7 and round(run.area[DROPOUT[0] - 1], 3) == 0.017  # "5.7 by 68"
    assert run.area[DROPOUT[1] - 2] == run.area[DROPOUT[0] : DROPOUT[1]].max()  # its largest blind
    assert (np.diff(run.area[DROPOUT[0] - 1 : DROPOUT[1]]) < 0).any()  # "not quite at every step"
    assert round(run.error[DROPOUT[1] - 1], 1) == 1.7  # "by step 69 ... 1.7 m off"
    e = run.truth[:, :2] - run.mu[:, :2]
    d2 = np.einsum("ti,tij,tj->t", e, np.linalg.inv(run.Sig[:, :2, :2]), e)
    assert (d2[DROPOUT[0] : DROPOUT[1]] <= 4.0).all()  # "the grey robot stays inside the teal (2-sigma) ellipse"
    demo.controls["frame"].value = DROPOUT[1]
    before, after = m.areas()
    assert round(before, 1) == 5.8 and round(after, 3) == 0.013 and "(×0.0022)" in readout(demo)
    assert round(run.error[DROPOUT[1]], 2) == 0.39
    k = DROPOUT[1]
    assert (run.used[k].sum(), run.rejected[k].sum()) == (2, 1)  # "one beam turns orange"
    assert "uses 2 readings" in readout(demo) and "rejects 1" in readout(demo) and "<b>outside</b>" in readout(demo)
    assert not run.inside[k] and run.inside[k + 1]  # "outside the 3σ ellipse ... back inside" one step later
    assert round(np.linalg.norm(run.truth[k, :2] - run.mu_bar[k, :2]), 1) == 1.8  # "a tangent ... 1.8 m wrong"
    demo.controls["frame"].value = k + 1
    assert "uses 3 readings" in readout(demo) and "<b>outside</b>" not in readout(demo)


def try_4_precise_sensor_after_a_blind_stretch_ekf_against_ukf(demo):
    m = demo.model
    demo.controls["sensor"].value = demo.controls["sensor"].base ** demo.controls["sensor"].min
    assert m.sensor_noise == pytest.approx(0.1) and m.motion_noise == pytest.approx(10.0) and m.dropout
    demo.controls["frame"].value = DROPOUT[0] - 1
    assert "(57% of steps so far)" in readout(demo)  # "at step 39 ... inside at only 57 %"
    k = DROPOUT[1]
    demo.controls["frame"].value = k
    run = m.run
    assert m.filter == "ekf" and (run.used[k].sum(), run.rejected[k].sum()) == (1, 2)
    assert "rejects 2" in readout(demo) and "<b>outside</b>" in readout(demo)
    assert round(run.error[k], 2) == 1.31 and round(run.area[k], 3) == 0.027
    width, length = 2 * 2 * np.sqrt(np.linalg.eigvalsh(run.Sig[k, :2, :2]))  # the 2-sigma ellipse's axes
    assert (round(width, 2), round(length, 1)) == (0.04, 3.5)  # "a needle (4 cm by 3.5 m at 2σ)"
    assert run.error[k : k + 9].min() > 1.0 and not run.inside[k : k + 9].any()  # "over a metre off, outside"
    assert round(run.error[k + 9], 2) == 0.17  # "until step 79"
    demo.controls["filter"].value = "UKF"
    run = m.run
    assert (run.used[k].sum(), run.rejected[k].sum()) == (3, 0)
    assert round(run.error[k], 2) == 0.04
    assert round(run.area[k], 4) == 0.0005 and not run.inside[k]  # "1σ area 0.0005 m², outside its 3σ ellipse"
    assert "<b>outside</b>" in readout(demo)  # "and the readout says so"
    assert run.inside[k + 1]  # "back inside at step 71"


def try_5_kidnap_the_filter_stays_confidently_wrong(demo):
    m = demo.model
    demo.controls["motion"].value = 1.0
    demo.controls["sensor"].value = 1.0
    demo.controls["dropout"].value = False
    demo.controls["filter"].value = "EKF"
    demo.controls["frame"].value = 60
    demo.controls["kidnap"].click()
    run = m.run
    assert m.kidnap == 60
    assert np.linalg.norm(run.truth[60, :2] - run.mu[60, :2]) > 4.0  # the grey robot jumps to the far side
    after = slice(60, None)
    assert run.rejected[after].sum() > 2 * run.used[after].sum()  # "most beams turn orange"
    centre = int(np.flatnonzero((run.landmarks == [0.0, 2.5]).all(axis=1))[0])
    assert np.flatnonzero(run.used[after].any(axis=0)).tolist() == [centre]  # "one stays teal": the centre landmark
    mirror = 2 * np.array([0.0, 2.5]) - run.landmarks  # the map, turned half a turn about the centre landmark
    assert {tuple(p) for p in mirror.tolist()} == {tuple(p) for p in run.landmarks.tolist()}  # "symmetric"
    assert (round(run.error[after].min()), round(run.error[after].max())) == (5, 9)  # "5 to 9 m off"
    longest = 2 * 2 * np.sqrt(np.linalg.eigvalsh(run.Sig[after, :2, :2]).max())  # the 2-sigma ellipse's long axis
    assert longest < 1.0  # "its 2-sigma ellipse stays under a metre across"
    assert not run.inside[after].any()
    demo.controls["frame"].value = demo.controls["frame"].max
    assert "(48% of steps so far)" in readout(demo)
    ekf_error = run.error.copy()
    demo.controls["filter"].value = "UKF"
    assert np.abs(m.run.error - ekf_error).max() < 0.05  # "the UKF fares no better"
    assert not m.run.inside[after].any()
    demo.controls["kidnap"].click()  # Undo kidnap
    assert m.kidnap is None and m.run.inside.mean() > 0.95


def test_try_prompts_in_order_on_one_demo():
    """Chapter 10's five prompts, one after the other, on the demo as it opens."""
    demo = make()
    try_1_a_normal_lap_is_accurate_and_honest(demo)
    try_2_dropout_balloons_then_three_readings_cut_it_tenfold(demo)
    try_3_push_the_process_noise_until_it_breaks(demo)
    try_4_precise_sensor_after_a_blind_stretch_ekf_against_ukf(demo)
    try_5_kidnap_the_filter_stays_confidently_wrong(demo)
