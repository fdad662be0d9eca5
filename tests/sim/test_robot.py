"""The seeded robot: reproducible, immutable, exact without noise, honest with it."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from kfcourse.models import range_bearing, range_bearing_residual, unicycle
from kfcourse.sim import DEFAULT_LANDMARKS, RobotRun, loop_controls, simulate_robot

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

ARRAYS = ["t", "u", "odometry", "start", "truth", "landmarks", "visible", "z"]
NO_NOISE = {"v_std": 0.0, "omega_std": 0.0, "range_std": 0.0, "bearing_std": 0.0}


def test_same_seed_same_record_other_seed_other_noise():
    a, b = simulate_robot(seed=3), simulate_robot(seed=3)
    for field in dataclasses.fields(RobotRun):
        x, y = getattr(a, field.name), getattr(b, field.name)
        assert np.array_equal(x, y), field.name
    c = simulate_robot(seed=4)
    assert not np.array_equal(a.odometry, c.odometry)
    assert np.array_equal(a.truth, c.truth)  # the robot does what it is told whatever the seed


def test_shapes_and_types():
    run = simulate_robot()
    T, L = len(run.u), len(DEFAULT_LANDMARKS)
    assert run.t.shape == (T,) and np.allclose(run.t, run.dt * np.arange(1, T + 1))
    assert run.u.shape == run.odometry.shape == (T, 2)
    assert run.truth.shape == (T, 3) and run.start.shape == (3,)
    assert run.landmarks.shape == (L, 2) and np.array_equal(run.landmarks, DEFAULT_LANDMARKS)
    assert run.visible.shape == (T, L) and run.visible.dtype == bool
    assert run.z.shape == (T, L, 2)
    assert all(np.all(np.isfinite(getattr(run, name))) for name in ARRAYS)
    assert np.all(run.z[~run.visible] == 0.0)  # zeros, never NaN, where nothing is seen


def test_record_and_its_arrays_are_read_only():
    run = simulate_robot()
    for name in ARRAYS:
        with pytest.raises(ValueError, match="read-only"):
            getattr(run, name)[0] = 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        run.seed = 1
    assert not DEFAULT_LANDMARKS.flags.writeable


def test_inputs_are_copied_not_shared():
    u = loop_controls()
    m = np.array([[0.0, -1.0], [1.0, 3.0]])
    run = simulate_robot(u, landmarks=m)
    u[:] = 0.0
    m[:] = 9.0
    assert run.u[0, 0] == 1.0 and run.landmarks[0, 1] == -1.0


def test_without_noise_truth_follows_the_unicycle_exactly():
    u = loop_controls(laps=2)
    run = simulate_robot(u, dt=0.2, start=(1.0, -2.0, 0.4), **NO_NOISE)
    pose = np.array([1.0, -2.0, 0.4])
    for k in range(len(u)):
        pose = unicycle(pose, u[k], 0.2)
        assert np.array_equal(run.truth[k], pose), k
    assert np.array_equal(run.odometry, run.u)


def test_without_noise_readings_are_range_bearing_exactly():
    run = simulate_robot(**NO_NOISE)
    assert run.visible.any()
    for k, j in zip(*np.nonzero(run.visible), strict=True):
        assert np.array_equal(run.z[k, j], range_bearing(run.truth[k], run.landmarks[j]))


def test_default_loop_closes_and_always_sees_a_landmark():
    run = simulate_robot(**NO_NOISE)
    assert np.allclose(run.truth[-1], run.start, atol=1e-9)
    assert run.truth[:, 0].min() == pytest.approx(-4.0, abs=0.1) and run.truth[:, 0].max() == pytest.approx(
        4.0, abs=0.1
    )
    assert run.truth[:, 1].max() == pytest.approx(5.0, abs=0.1)
    assert run.visible.any(axis=1).all()


def test_a_circle_closes_too():
    u = loop_controls(length=4.0, width=4.0, radius=2.0, speed=0.5, dt=0.1)
    assert np.all(u[:, 1] == u[0, 1]) and u[0, 1] > 0  # one constant left turn
    run = simulate_robot(u, dt=0.1, **NO_NOISE)
    centre = np.array([0.0, run.u[0, 0] / run.u[0, 1]])  # radius V / omega, left of the start
    assert np.allclose(np.linalg.norm(run.truth[:, :2] - centre, axis=1), u[0, 0] / u[0, 1])
    assert np.allclose(run.truth[-1], run.start, atol=1e-9)


def test_sensor_range_is_respected():
    for sensor_range in (1.5, 3.0, 4.0, 20.0):
        run = simulate_robot(sensor_range=sensor_range, seed=1)
        true_range = np.linalg.norm(run.truth[:, None, :2] - run.landmarks[None, :, :], axis=2)  # (T, L)
        assert np.array_equal(run.visible, true_range <= sensor_range)
        assert np.all(run.z[~run.visible] == 0.0) and np.all(run.z[run.visible][:, 0] != 0.0)
    assert simulate_robot(sensor_range=20.0).visible.all()


def test_bearings_lie_in_the_half_open_interval_near_pi():
    # The robot stands still facing +x with a landmark straight behind it: the true
    # bearing is exactly pi, so the noise pushes readings over the edge both ways.
    T = 4000
    run = simulate_robot(np.zeros((T, 2)), start=(0.0, 0.0, 0.0), landmarks=[[-3.0, 0.0]], bearing_std=0.1, seed=5)
    assert run.visible.all()
    phi = run.z[:, 0, 1]
    assert np.all((phi > -math.pi) & (phi <= math.pi))
    assert (phi > 3.0).sum() > T // 4 and (phi < -3.0).sum() > T // 4  # wrapped, not left beyond pi
    err = range_bearing_residual(run.z[:, 0], range_bearing(run.truth, run.landmarks[0]))[:, 1]
    assert np.std(err) == pytest.approx(0.1, rel=0.05)
    assert np.all(np.abs(err) < 0.6)


def test_bearings_are_wrapped_along_the_default_loop():
    run = simulate_robot(bearing_std=0.5, seed=2)
    phi = run.z[run.visible][:, 1]
    assert np.all((phi > -math.pi) & (phi <= math.pi))


def test_noise_statistics_match_the_stds():
    T = 6000
    u = np.tile([[0.5, 0.0]], (T, 1))  # a straight drive past one landmark that stays in view
    stds = {"v_std": 0.2, "omega_std": 0.05, "range_std": 0.3, "bearing_std": 0.02}
    run = simulate_robot(u, dt=0.001, landmarks=[[1.5, 2.0]], sensor_range=10.0, seed=11, **stds)
    assert run.visible.all()
    odo = run.odometry - run.u
    z_err = range_bearing_residual(run.z[:, 0], range_bearing(run.truth, run.landmarks[0]))
    # sample std of n normal draws: relative standard error 1/sqrt(2n) ~ 0.9 %; allow 4.5 of them
    tol = 4.5 / math.sqrt(2 * T)
    for err, name in [(odo[:, 0], "v_std"), (odo[:, 1], "omega_std"), (z_err[:, 0], "range_std")]:
        assert np.std(err) == pytest.approx(stds[name], rel=tol), name
        assert abs(np.mean(err)) < 4.5 * stds[name] / math.sqrt(T), name
    assert np.std(z_err[:, 1]) == pytest.approx(stds["bearing_std"], rel=tol)
    assert abs(np.corrcoef(odo[:, 0], z_err[:, 0])[0, 1]) < 4.5 / math.sqrt(T)  # independent draws


def noise(run):
    """The noise each record drew: odometry minus command (T, 2), and reading minus
    true reading, bearing wrapped, for every visible pair (n, 2)."""
    k, j = np.nonzero(run.visible)
    true_z = np.stack([range_bearing(run.truth[a], run.landmarks[b]) for a, b in zip(k, j, strict=True)])
    return run.odometry - run.u, range_bearing_residual(run.z[k, j], true_z)


@pytest.mark.parametrize(
    ("name", "which", "column"), [("v_std", 0, 0), ("omega_std", 0, 1), ("range_std", 1, 0), ("bearing_std", 1, 1)]
)
def test_scaling_a_std_rescales_the_same_draws(name, which, column):
    base = {"v_std": 0.1, "omega_std": 0.02, "range_std": 0.1, "bearing_std": 0.01}
    a = simulate_robot(seed=7, **base)
    b = simulate_robot(seed=7, **(base | {name: 3 * base[name]}))
    assert np.array_equal(a.visible, b.visible)
    da, db = noise(a)[which], noise(b)[which]
    assert np.allclose(db[:, column], 3 * da[:, column], rtol=1e-9, atol=1e-12)
    assert np.allclose(db[:, 1 - column], da[:, 1 - column], rtol=1e-9, atol=1e-12)  # the other noise is untouched
    assert np.any(da[:, column] != 0.0)


def test_draws_depend_on_the_sizes_not_on_the_map_content():
    a = simulate_robot(landmarks=[[0.0, -1.0], [3.0, 3.0]], seed=9)
    b = simulate_robot(landmarks=[[1.0, -1.0], [-3.0, 3.0]], seed=9)
    assert np.array_equal(a.odometry, b.odometry)  # same sizes, same draws


def test_an_empty_map_sees_nothing():
    run = simulate_robot(landmarks=[])
    assert run.landmarks.shape == (0, 2) and run.visible.shape == (len(run.u), 0) and run.z.shape == (len(run.u), 0, 2)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"v_std": -0.1}, "v_std"),
        ({"omega_std": np.nan}, "omega_std"),
        ({"range_std": -1.0}, "range_std"),
        ({"bearing_std": "a lot"}, "bearing_std"),
        ({"sensor_range": 0.0}, "sensor_range"),
        ({"sensor_range": np.inf}, "sensor_range"),
        ({"dt": -0.1}, "dt"),
        ({"u": [[1.0, 0.0, 0.0]]}, "u"),
        ({"u": np.empty((0, 2))}, "u"),
        ({"u": [[1.0, np.nan]]}, "u"),
        ({"start": (0.0, 0.0)}, "start"),
        ({"landmarks": [[1.0, 2.0, 3.0]]}, "landmarks"),
        ({"landmarks": [[1.0, np.inf]]}, "landmarks"),
        ({"seed": -1}, "seed"),
        ({"seed": 1.5}, "seed"),
    ],
)
def test_bad_arguments_name_themselves(kwargs, name):
    with pytest.raises(ValueError, match=name):
        simulate_robot(**kwargs)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"radius": 0.0}, "radius"),
        ({"length": 1.0}, "length"),
        ({"width": 1.9, "radius": 1.0}, "width"),
        ({"speed": 0.0}, "speed"),
        ({"dt": 0.0}, "dt"),
        ({"laps": 0}, "laps"),
    ],
)
def test_loop_controls_bad_arguments_name_themselves(kwargs, name):
    with pytest.raises(ValueError, match=name):
        loop_controls(**kwargs)


def test_loop_controls_laps_repeat_the_lap():
    one, three = loop_controls(), loop_controls(laps=3)
    assert np.array_equal(three, np.tile(one, (3, 1)))
    assert np.sum(one[:, 1]) * 0.2 == pytest.approx(2 * math.pi)  # one full turn per lap


def test_sight_comes_back_one_landmark_first_the_nearest():
    every = simulate_robot(seed=3, dropout=(40, 70))
    one = simulate_robot(seed=3, dropout=(40, 70), one_back=True)
    assert one.one_back and not every.one_back
    assert not one.visible[40:70].any() and one.visible[70].sum() == 1 < every.visible[70].sum()
    d = np.where(every.visible[70], np.linalg.norm(one.landmarks - one.truth[70, :2], axis=1), np.inf)
    assert one.visible[70, np.argmin(d)]
    np.testing.assert_array_equal(np.delete(one.visible, 70, axis=0), np.delete(every.visible, 70, axis=0))
    np.testing.assert_array_equal(one.z, every.z)  # the same draws
    assert simulate_robot(seed=3, one_back=True).visible.sum() == simulate_robot(seed=3).visible.sum()
    end = simulate_robot(seed=3, dropout=(40, 10_000), one_back=True)  # blind to the end: nothing comes back
    assert not end.visible[40:].any()
