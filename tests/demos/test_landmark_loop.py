"""The landmark-loop demo: every control reruns the lap with its setting, moving in time only
redraws, the picture shows the step, every corner of the controls stays finite, the dropout
toggle acts at the step shown, and a student's own step drives it (or is named when it breaks).
Chapter 10's "Try this" prompts are in test_prompts_ch10.py."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.check.localization_checks import _variants
from kfcourse.demos.landmark_loop import COLUMN_WIDTH, FIRST_FRAME, GATE, IMAGE_WIDTH, YOURS
from kfcourse.filters.gaussian import ellipse_axes
from kfcourse.plots.loop import position_errors, strip_limit
from tests.demos.layout import readout, widgets_in

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


def make(seed=0, filter=None):
    return kf.demos.landmark_loop(seed=seed, filter=filter)


def reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Chapter 10's step written out: predict with R = W M W^T, then gate and update reading by reading."""
    W = kf.unicycle_control_jacobian(mu, u, dt)
    mu, Sig = kf.ekf_predict(
        mu, Sig, u, lambda x, c: kf.unicycle(x, c, dt), lambda x, c: kf.unicycle_jacobian(x, c, dt), W @ M @ W.T
    )
    used = np.zeros(len(z), dtype=bool)
    for j, (zj, m) in enumerate(zip(z, landmarks, strict=True)):
        H = kf.range_bearing_jacobian(mu, m)
        nu = kf.models.range_bearing_residual(zj, kf.range_bearing(mu, m))
        if nu @ np.linalg.solve(H @ Sig @ H.T + Q, nu) <= gate**2:
            h, Hf = (lambda x, m=m: kf.range_bearing(x, m)), (lambda x, m=m: kf.range_bearing_jacobian(x, m))
            mu, Sig = kf.ekf_update(mu, Sig, zj, h, Hf, Q, kf.models.range_bearing_residual)
            mu[2] = kf.wrap_angle(mu[2])
            used[j] = True
    return mu, Sig, used


def views(demo):
    """The map's artists and the strips' artists, in the order the demo hands them to its renderer."""
    dynamic = demo.renderer.dynamic
    return dynamic[:10], dynamic[10:]


def tick_values(ax) -> list[float]:
    """The y tick labels of a strip, read as numbers."""
    return [float(label.get_text().strip("\u2007").replace("\u2212", "-")) for label in ax.get_yticklabels()]


def expected_run(model):
    return kf.sim.landmark_loop(
        model.seed,
        filter=model.filter,
        dropout=model.blind,
        one_back=True,
        motion_noise=model.motion_noise,
        sensor_noise=model.sensor_noise,
        filter_motion_noise=model.motion_noise * np.sqrt(model.trust_motion),
        filter_sensor_noise=model.sensor_noise * np.sqrt(model.trust_sensor),
        kidnap=model.kidnap,
        gate=GATE,
    )


# --------------------------------------------------------------------------- controls
@pytest.mark.fact
def test_first_frame_is_a_normal_lap_mid_way():
    demo = make()
    m = demo.model
    assert m.frame == FIRST_FRAME == demo.controls["frame"].value == 60  # chapter 10: "opens at step 60"
    assert GATE == 4.0
    assert demo.controls["frame"].max == m.run.t.size - 1
    assert (m.filter, m.motion_noise, m.sensor_noise, m.blind, m.kidnap) == ("ekf", 1.0, 1.0, None, None)
    assert (m.trust_motion, m.trust_sensor) == (1.0, 1.0)
    assert m.run.gate == GATE and m.run.dropout is None
    assert m.run.used[m.frame].sum() == 2 and "uses 2 readings" in readout(demo)  # two beams in the first picture
    assert "run 0" in readout(demo) and "<b>honest</b>" in readout(demo)
    assert demo.controls["kidnap"].description == "Kidnap"
    assert demo.controls["filter"].options == ("EKF", "UKF")


def test_sliders_rerun_the_lap_once_where_they_are_let_go():
    demo = make()
    for key in ("motion", "sensor", "trust_motion", "trust_sensor"):
        assert demo.controls[key].continuous_update is False, key  # a rerun per dragged pixel would queue up
    assert demo.controls["frame"].continuous_update is True  # stepping only redraws: follows the drag


@pytest.mark.fact
@pytest.mark.parametrize(
    ("key", "value", "attr"),
    [
        ("motion", 3.0, "motion_noise"),
        ("sensor", 0.2, "sensor_noise"),
        ("trust_motion", 0.1, "trust_motion"),
        ("trust_sensor", 10.0, "trust_sensor"),
        ("filter", "UKF", "filter"),
    ],
)
@pytest.mark.pixels
def test_each_control_reruns_the_lap_with_its_setting(key, value, attr):
    demo = make()
    m = demo.model
    run, picture = m.run, bytes(demo.image.value)
    demo.controls[key].value = value
    assert getattr(m, attr) == (value.lower() if key == "filter" else pytest.approx(value))
    assert m.run is not run and bytes(demo.image.value) != picture
    np.testing.assert_array_equal(m.run.mu, expected_run(m).mu)
    assert m.frame == FIRST_FRAME  # the step shown stays


@pytest.mark.fact
def test_the_world_and_the_filters_trust_are_apart():
    demo = make()
    m = demo.model
    demo.controls["sensor"].value = 3.0  # the world's sensor: the filter still told the truth
    assert m.run.sensor_noise == pytest.approx(3.0) and m.run.filter_sensor_noise == pytest.approx(3.0)
    demo.controls["trust_sensor"].value = 0.01  # Q the filter assumes: 0.01 times the true one
    assert m.run.sensor_noise == pytest.approx(3.0) and m.run.filter_sensor_noise == pytest.approx(0.3)
    assert "over-confident" in readout(demo)
    world = kf.sim.landmark_loop(0, sensor_noise=3.0, gate=GATE)
    np.testing.assert_array_equal(m.run.z, world.z)  # the world did not change with the trust


@pytest.mark.fact
def test_dropout_acts_at_the_step_shown():
    demo = make()
    m = demo.model
    demo.controls["frame"].value = 20
    demo.controls["dropout"].value = True  # blind from here on
    assert m.blind == (20, m.run.t.size) and m.run.dropout == (20, m.run.t.size)
    assert not m.run.used[20:].any() and m.run.used[19].any()
    demo.controls["frame"].value = 50
    assert "sensor blind" in readout(demo)
    demo.controls["frame"].value = 90
    demo.controls["dropout"].value = False  # sight back here, one landmark first
    assert m.blind == (20, 90) and m.run.dropout == (20, 90) and m.run.one_back
    assert m.run.used[90].sum() == 1 and "(sight back: the nearest landmark only)" in readout(demo)
    demo.controls["frame"].value = 10
    demo.controls["dropout"].value = True
    assert m.blind == (10, m.run.t.size)  # a new stretch from here
    demo.controls["dropout"].value = False  # off where it began: nothing blind
    assert m.blind is None and m.run.dropout is None


@pytest.mark.fact
def test_new_run_draws_new_noise_and_keeps_the_settings():
    demo = make()
    m = demo.model
    demo.controls["motion"].value = 2.0
    run = m.run
    demo.controls["new"].click()
    assert m.seed == 1 and "run 1" in readout(demo) and m.motion_noise == pytest.approx(2.0)
    assert not np.array_equal(m.run.odometry, run.odometry)
    np.testing.assert_array_equal(m.run.mu, expected_run(m).mu)


def test_moving_in_time_never_reruns():
    demo = make()
    run = demo.model.run
    for k in (0, 5, 40, demo.controls["frame"].max):
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
    np.testing.assert_array_equal(m.run.mu, expected_run(m).mu)
    demo.controls["frame"].value = 50
    demo.controls["kidnap"].click()
    assert m.kidnap is None and m.run.kidnap is None and demo.controls["kidnap"].description == "Kidnap"


def test_the_column_fits_a_laptop():
    """Picture and column side by side in a laptop's 848 px; every row of the column within its 340 px."""
    demo = make(filter=reference_step)
    assert IMAGE_WIDTH + COLUMN_WIDTH <= 848
    column = demo.children[1].children[1]
    for row in column.children:
        parts = row.children if hasattr(row, "children") and row.children else [row]
        widths = [int(str(w.layout.width).removesuffix("px")) for w in parts if w.layout.width]
        assert sum(widths) <= COLUMN_WIDTH, [w.description for w in parts]
    assert len(column.children) == 8  # Run/step, two world sliders, two trust sliders, the buttons, filter, readout


def picture_checks(demo, run, k, parts):
    (truth_before, truth_after, beams, rejected, trail, truth_robot, robot, prior_ring, ring, note), strips = parts
    error, bound = position_errors(run)
    assert len(truth_before.get_xydata()) == run.kidnap and len(truth_after.get_xydata()) == run.t.size - run.kidnap
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
    past_x, past_y = strips[4], strips[10]  # per axis: blind, band, kidnap, future, past, cursor
    np.testing.assert_allclose(past_x.get_xydata()[-1], [run.t[k], error[k, 0]])  # in metres
    np.testing.assert_allclose(past_y.get_xydata()[-1], [run.t[k], error[k, 1]])
    assert strips[5].get_xdata()[0] == pytest.approx(run.t[k])
    band = strips[1].get_paths()[0].vertices
    assert band[:, 1].max() == pytest.approx(bound[:, 0].max())  # +2 sqrt(Sig_xx) at its widest
    return note


def test_picture_shows_the_step():
    demo = make()
    m = demo.model
    demo.controls["frame"].value = 40
    demo.controls["dropout"].value = True
    demo.controls["frame"].value = 70
    demo.controls["dropout"].value = False
    demo.controls["frame"].value = 20
    demo.controls["kidnap"].click()  # kidnapped at step 20: some readings get rejected later
    run = m.run
    top = strip_limit(run)
    notes = {}
    for k in (0, 45, 70, 75, 121):
        demo.controls["frame"].value = k
        note = picture_checks(demo, run, k, views(demo))
        notes[k] = note.get_text()
        for ax in demo.renderer.fig.axes[1:]:
            assert ax.get_ylim() == (-top, top) and tick_values(ax) == [-top, 0.0, top]
    assert notes[45] == "sensor blind" and notes[70] == "sight back: one landmark first"
    assert top >= np.abs(position_errors(run)[0]).max()  # the strips hold the whole kidnapped run


@pytest.mark.fact
@pytest.mark.parametrize(
    ("motion", "sensor", "filter"), list(itertools.product((0.1, 10.0), (0.1, 10.0), ("ekf", "ukf")))
)
def test_every_corner_stays_finite(motion, sensor, filter):
    demo = make()
    demo.controls["motion"].value = motion
    demo.controls["sensor"].value = sensor
    demo.controls["filter"].value = filter.upper()
    for dropout, kidnap in itertools.product((False, True), (False, True)):
        trust = 0.01 if dropout == kidnap else 100.0  # each end of the filter's trust, with and without each
        demo.controls["trust_motion"].value = trust
        demo.controls["trust_sensor"].value = 1e4 / (trust * 100)  # the other end
        demo.controls["frame"].value = 30
        demo.controls["dropout"].value = dropout
        if kidnap != (demo.model.kidnap is not None):
            demo.controls["kidnap"].click()
        run = demo.model.run
        assert demo.model.failure is None
        assert (run.motion_noise, run.sensor_noise, run.filter) == pytest.approx((motion, sensor, filter))
        for name in ("mu", "Sig", "mu_bar", "Sig_bar", "area", "error", "nees"):
            assert np.isfinite(getattr(run, name)).all(), name
        for k in (0, 70, demo.controls["frame"].max):
            demo.controls["frame"].value = k
            text = readout(demo).lower()
            assert "nan" not in text and "inf" not in text
            for artist in demo.renderer.dynamic:
                data = artist.get_xydata() if hasattr(artist, "get_xydata") else None
                if data is not None:
                    assert np.isfinite(np.asarray(data, float)).all()
            assert bytes(demo.image.value[:3]) == b"\xff\xd8\xff"  # a JPEG


# --------------------------------------------------------------------------- the student's own step
# A fact: the written-out step and the course's EKF round apart, and a reading on the gate would split them.
@pytest.mark.fact
def test_your_step_drives_the_demo():
    demo = make(filter=reference_step)
    m = demo.model
    assert demo.controls["filter"].options == (YOURS, "EKF", "UKF") and m.filter == YOURS
    assert m.failure is None and m.run.filter == "reference_step"
    ekf = kf.sim.landmark_loop(0, gate=GATE, one_back=True)
    np.testing.assert_allclose(m.run.mu, ekf.mu, atol=1e-9)  # the same algorithm as the course's EKF
    np.testing.assert_array_equal(m.run.used, ekf.used)
    demo.controls["filter"].value = "UKF"
    assert m.run.filter == "ukf"
    demo.controls["filter"].value = YOURS
    assert m.run.filter == "reference_step"


def not_written(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    raise NotImplementedError("write my_step")


def nan_mean(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
    return mu * np.nan, Sig, used


def flat_mean(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
    return mu[:2], Sig, used


def negative_covariance(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
    return mu, Sig if len(z) == 0 else Sig - np.eye(3), used


def two_outputs(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    return reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)[:2]


def markup(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    return {}["<b>"]  # a KeyError whose message reads like HTML


def lopsided(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
    return mu, Sig + np.triu(np.full((3, 3), 0.01), 1), used


def square_mean(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
    return np.diag(mu), Sig, used


@pytest.mark.fact
@pytest.mark.parametrize(
    ("step", "said"),
    [
        (not_written, "not_written at step 0 (0 readings) raised NotImplementedError: write my_step"),
        (nan_mean, "nan_mean at step 0 (0 readings) returned mu must be finite"),
        (flat_mean, "flat_mean at step 0 (0 readings) returned mu must"),
        (negative_covariance, "negative_covariance at step 0 (2 readings) returned Sig must be positive semi-definite"),
        (two_outputs, "two_outputs at step 0 (0 readings) must return (mu, Sig, used)"),
        (markup, "markup at step 0 (0 readings) raised KeyError: &#x27;&lt;b&gt;&#x27;"),  # shown as text
        (lopsided, "lopsided at step 0 (0 readings) returned Sig must be a symmetric covariance matrix, got [["),
        (square_mean, "square_mean at step 0 (0 readings) returned mu must be a 1-D vector, got shape (3, 3)"),
    ],
)
def test_a_broken_step_is_named_in_the_readout_never_raised(step, said):
    demo = make(filter=step)
    m = demo.model
    text = readout(demo)
    assert "Your filter failed" in text and said in text, text
    assert m.failure and m.run.filter == "ekf"  # the course's EKF is shown meanwhile
    assert "Shown: the course's EKF" in text
    demo.controls["motion"].value = 2.0  # still alive: every control works
    assert "Your filter failed" in readout(demo)
    demo.controls["filter"].value = "EKF"
    assert "Your filter failed" not in readout(demo) and m.failure is None


@pytest.mark.fact
def test_a_flat_ellipse_reads_as_unboundedly_over_confident():
    def certain(mu, Sig, u, z, landmarks, dt, M, Q, gate):
        mu, _, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
        return mu, np.zeros((3, 3)), used

    text = readout(make(filter=certain))
    assert "<b>over-confident</b>: mean NEES unbounded" in text and "truth <b>outside</b>" in text
    assert "nan" not in text.lower() and "inf" not in text.lower()


@pytest.mark.fact
@pytest.mark.parametrize("variant", _variants(), ids=lambda v: v.mistake)
def test_every_mistake_the_checker_knows_drives_the_demo_or_is_named(variant):
    """The usual wrong steps of chapter 10's exercise, handed to the demo: it runs them or says how they
    broke, never raises, and its readout stays finite at every setting a prompt uses."""

    def my_step(mu, Sig, u, z, landmarks, dt, M, Q, gate):
        return variant.fn(mu, Sig, u, z, landmarks, dt, M, Q, gate)

    demo = make(filter=my_step)
    for key, value in (("motion", 10.0), ("sensor", 10.0), ("sensor", 0.1), ("trust_sensor", 0.01)):
        demo.controls[key].value = value
        for k in (0, 90, demo.controls["frame"].max):
            demo.controls["frame"].value = k
            text = readout(demo)
            assert demo.model.failure is None or "Your filter failed" in text
            shown = text.split("Shown: the course's EKF.")[-1].lower()  # the run on the picture
            assert "nan" not in shown and "inf" not in shown


def test_the_demo_widgets_are_found():
    demo = make(filter=reference_step)
    assert len([w for w in widgets_in(demo) if "kf-readout" in w._dom_classes]) == 1


def test_the_filter_argument_is_a_step_function():
    with pytest.raises(ValueError, match=r"^filter must be your step function"):
        make(filter="ekf")
