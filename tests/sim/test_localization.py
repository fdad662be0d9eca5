"""The landmark localization loop (chapters 8-10): its data, its switches and its honesty."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.capstone_world import SIG0, loop_world
from kfcourse.sim.landmark_lap import _steps_in_common

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


@pytest.fixture(scope="module")
def ekf_run():
    return kf.sim.landmark_loop(0)


def test_data_are_simulate_robots_step_for_step(ekf_run):
    robot = kf.sim.simulate_robot(seed=0)
    np.testing.assert_allclose(ekf_run.truth, robot.truth, atol=1e-12)
    np.testing.assert_array_equal(ekf_run.odometry, robot.odometry)
    np.testing.assert_array_equal(ekf_run.z, robot.z)
    np.testing.assert_array_equal(ekf_run.used, robot.visible)  # no dropout, no gate: every reading in range
    assert not ekf_run.rejected.any()


@pytest.mark.fact
def test_both_filters_see_the_same_world_and_end_near_the_truth(ekf_run):
    ukf_run = kf.sim.landmark_loop(0, filter="ukf")
    for name in ("truth", "odometry", "z", "used"):
        np.testing.assert_array_equal(getattr(ukf_run, name), getattr(ekf_run, name))
    for run in (ekf_run, ukf_run):
        assert run.error.max() < 0.3
        assert run.share_inside >= 0.95
    assert not np.array_equal(ukf_run.mu, ekf_run.mu)  # two filters, not one twice


def test_record_is_read_only_and_consistent(ekf_run):
    T, L = ekf_run.t.size, ekf_run.landmarks.shape[0]
    assert ekf_run.mu.shape == ekf_run.mu_bar.shape == (T, 3)
    assert ekf_run.Sig.shape == ekf_run.Sig_bar.shape == (T, 3, 3)
    assert ekf_run.used.shape == ekf_run.rejected.shape == (T, L)
    with pytest.raises(ValueError):
        ekf_run.mu[0, 0] = 1.0
    np.testing.assert_array_equal(ekf_run.Sig0, SIG0)
    e = np.linalg.norm(ekf_run.truth[:, :2] - ekf_run.mu[:, :2], axis=1)
    np.testing.assert_allclose(ekf_run.error, e)
    Sxy = ekf_run.Sig[:, :2, :2]
    np.testing.assert_allclose(ekf_run.area, np.pi * np.sqrt(np.linalg.det(Sxy)))
    # an update never makes the filter less sure: det Sig <= det Sig_bar at every step
    assert np.all(np.linalg.det(ekf_run.Sig) <= np.linalg.det(ekf_run.Sig_bar) * (1 + 1e-9))


@pytest.mark.fact
def test_dropout_blinds_exactly_its_window():
    run = kf.sim.landmark_loop(0, dropout=(40, 80))
    assert not run.used[40:80].any()
    assert run.used[:40].any(axis=1).all() and run.used[80:].any(axis=1).all()
    free = kf.sim.landmark_loop(0)
    np.testing.assert_array_equal(run.mu[:40], free.mu[:40])  # before the window nothing differs


def test_noise_scales_the_world_and_by_default_the_filter():
    base, loud = kf.sim.landmark_loop(0), kf.sim.landmark_loop(0, motion_noise=2.0, sensor_noise=3.0)
    loop = kf.sim.loop_controls(dt=base.dt)
    np.testing.assert_allclose(loud.odometry - loop, 2.0 * (base.odometry - loop), atol=1e-12)  # the same draws
    seen = base.used
    # the range noise is three times the default's, draw for draw
    k, j = np.nonzero(seen)
    clean = np.array([kf.range_bearing(base.truth[a], base.landmarks[b])[0] for a, b in zip(k, j, strict=True)])
    np.testing.assert_allclose(loud.z[k, j, 0] - clean, 3.0 * (base.z[k, j, 0] - clean), atol=1e-12)


@pytest.mark.fact
def test_kidnapping_sets_the_robot_down_half_a_lap_on():
    free = kf.sim.landmark_loop(0)
    k0, T = 50, free.t.size
    run = kf.sim.landmark_loop(0, kidnap=k0)
    np.testing.assert_array_equal(run.truth[:k0], free.truth[:k0])
    jump = np.linalg.norm(run.truth[k0, :2] - run.truth[k0 - 1, :2])
    assert jump > 3.0  # carried across the loop, not driven
    half = T // 2
    later = (np.arange(k0, T) + half) % T
    np.testing.assert_allclose(run.truth[k0:, :2], free.truth[later, :2], atol=1e-9)  # on the same loop


@pytest.mark.fact
def test_gated_filter_stays_confidently_wrong_after_a_kidnapping():
    run = kf.sim.landmark_loop(0, kidnap=50, gate=3.035)
    assert run.rejected[50:].any(axis=1).mean() > 0.8  # what it sees does not fit where it thinks it is
    assert run.error[-1] > 2.0
    assert not run.inside[60:].any()  # and its ellipse never admits it
    assert np.sqrt(run.Sig[-1, 0, 0]) < 0.5


@pytest.mark.fact
def test_a_gate_at_the_default_run_rejects_almost_nothing():
    run = kf.sim.landmark_loop(0, gate=3.035)
    assert kf.sim.landmark_loop(0).used.sum() == 228  # readings in range over the lap
    assert run.rejected.sum() <= 8  # a gate at 3.035 sigma turns away 1 % of true readings: 2.3 expected
    assert run.share_inside >= 0.95


@pytest.mark.fact
@pytest.mark.parametrize("filter", ["ekf", "ukf"])
@pytest.mark.parametrize("motion_noise", [0.1, 10.0])
@pytest.mark.parametrize("sensor_noise", [0.1, 10.0])
@pytest.mark.parametrize("labelled", [True, False])
def test_noise_extremes_stay_finite(filter, motion_noise, sensor_noise, labelled):
    noise = {"motion_noise": motion_noise, "sensor_noise": sensor_noise}
    run = kf.sim.landmark_loop(0, filter=filter, **noise, dropout=(30, 70), gate=3.035, labelled=labelled)
    for name in ("mu", "Sig", "mu_bar", "Sig_bar", "error", "area"):
        assert np.isfinite(getattr(run, name)).all(), name
    assert np.all(np.linalg.eigvalsh(run.Sig) > 0)


def test_process_noise_of_odometry_maps_the_control_noise():
    # straight ahead along +x, dt = 1, V = 0.5: speed noise moves x, turn-rate noise swings y and theta
    R = kf.sim.process_noise_of_odometry([0.0, 0.0, 0.0], [0.5, 0.0], 1.0, np.diag([0.04, 0.01]))
    Vu = np.array([[1.0, 0.0], [0.0, 0.25], [0.0, 1.0]])
    np.testing.assert_allclose(R, Vu @ np.diag([0.04, 0.01]) @ Vu.T, atol=1e-15)
    assert np.linalg.matrix_rank(R) == 2


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"filter": "pf"}, "filter"),
        ({"dropout": (80, 40)}, "dropout"),
        ({"dropout": 5}, "dropout"),
        ({"dropout": (-1, 4)}, "dropout[0]"),
        ({"motion_noise": 0.0}, "motion_noise"),
        ({"motion_noise": 1e-9}, "motion_noise"),
        ({"sensor_noise": 101.0}, "sensor_noise"),
        ({"sensor_noise": float("nan")}, "sensor_noise"),
        ({"kidnap": 10_000}, "kidnap"),
        ({"kidnap": 1.5}, "kidnap"),
        ({"wrap_bearing": "yes"}, "wrap_bearing"),
        ({"gate": 0.0}, "gate"),
        ({"filter_motion_noise": 0.0}, "filter_motion_noise"),
        ({"filter_sensor_noise": 1000.0}, "filter_sensor_noise"),
        ({"one_back": "yes"}, "one_back"),
        ({"laps": 0}, "laps"),
        ({"sensor_range": -1.0}, "sensor_range"),
        ({"landmarks": [[1.0, 2.0, 3.0]]}, "landmarks"),
        ({"start": [0.0, 0.0]}, "start"),
        ({"start": [0.0, np.nan, 0.0]}, "start"),
        ({"labelled": "no"}, "labelled"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=f"^{re.escape(name)} must"):
        kf.sim.landmark_loop(0, **kwargs)


# --------------------------------------------------------------- chapter 10: the world apart from the filter
def test_the_filter_is_honest_by_default_and_can_be_told_otherwise():
    honest = kf.sim.landmark_loop(0, motion_noise=2.0, sensor_noise=3.0)
    told = kf.sim.landmark_loop(0, motion_noise=2.0, sensor_noise=3.0, filter_motion_noise=2.0, filter_sensor_noise=3.0)
    np.testing.assert_array_equal(honest.mu, told.mu)  # None is the world's own noise
    assert (honest.filter_motion_noise, honest.filter_sensor_noise) == (2.0, 3.0)
    sure = kf.sim.landmark_loop(0, motion_noise=2.0, sensor_noise=3.0, filter_sensor_noise=0.3)
    for name in ("truth", "odometry", "z"):
        np.testing.assert_array_equal(getattr(sure, name), getattr(honest, name))  # the same world
    assert not np.array_equal(sure.mu, honest.mu)
    assert (sure.sensor_noise, sure.filter_sensor_noise) == (3.0, 0.3)


@pytest.mark.fact
def test_honesty_reads_the_mean_nees():
    run = kf.sim.landmark_loop(0, gate=4.0)
    e = run.truth[:, :2] - run.mu[:, :2]
    np.testing.assert_allclose(run.nees, kf.sim.nees(run.truth[:, :2], run.mu[:, :2], run.Sig[:, :2, :2]), rtol=1e-9)
    assert run.honesty() == (pytest.approx(run.nees.mean()), "honest")
    assert run.honesty(9)[0] == pytest.approx(run.nees[:10].mean())
    assert np.array_equal(run.inside, run.nees <= 9.0) and e.shape == (run.t.size, 2)
    assert kf.sim.landmark_loop(0, gate=4.0, filter_sensor_noise=0.1).honesty()[1] == "over-confident"
    assert kf.sim.landmark_loop(0, gate=4.0, filter_sensor_noise=10.0).honesty()[1] == "timid"


@pytest.mark.fact
def test_the_table_prints_the_steps():
    run = kf.sim.landmark_loop(0, dropout=(40, 70), gate=4.0)
    lines = run.table([39, 70]).splitlines()
    assert lines[0].split()[:3] == ["step", "used", "rejected"] and len(lines) == 4
    assert lines[3].split()[:3] == ["70", "3", "0"] and lines[3].split()[-1] == "yes"


@pytest.mark.fact
def test_sight_comes_back_one_landmark_first():
    every = kf.sim.landmark_loop(0, dropout=(40, 70))
    one = kf.sim.landmark_loop(0, dropout=(40, 70), one_back=True)
    assert every.used[70].sum() == 3 and one.used[70].sum() == 1 and one.one_back and not every.one_back
    seen = np.flatnonzero(every.used[70])
    nearest = seen[np.argmin(np.linalg.norm(one.landmarks[seen] - one.truth[70, :2], axis=1))]
    assert np.flatnonzero(one.used[70]).tolist() == [nearest]
    np.testing.assert_array_equal(one.used[71:], every.used[71:])  # only step 70 differs
    np.testing.assert_array_equal(one.z, every.z)  # and the draws are the same


# --------------------------------------------------------------------------- chapter 10: your own step
def chapter_step(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Chapter 10's step, as a student writes it: predict, then gate and update reading by reading."""
    W = kf.unicycle_control_jacobian(mu, u, dt)
    g, G = (lambda x, c: kf.unicycle(x, c, dt)), (lambda x, c: kf.unicycle_jacobian(x, c, dt))
    mu, Sig = kf.ekf_predict(mu, Sig, u, g, G, W @ M @ W.T)
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


# A fact: the written-out step and the course's EKF round apart, and a reading on the gate would split them.
@pytest.mark.fact
@pytest.mark.parametrize("gate", [None, 4.0])
def test_a_step_function_runs_the_loop_as_the_ekf_does(gate):
    settings = {"gate": gate, "dropout": (40, 70), "motion_noise": 3.0, "filter_sensor_noise": 2.0, "kidnap": 90}
    ekf = kf.sim.landmark_loop(1, **settings)
    mine = kf.sim.landmark_loop(1, filter=chapter_step, **settings)
    assert mine.filter == "chapter_step"
    for name in ("mu_bar", "Sig_bar", "mu", "Sig"):
        np.testing.assert_allclose(getattr(mine, name), getattr(ekf, name), atol=1e-9, err_msg=name)
    np.testing.assert_array_equal(mine.used, ekf.used)
    np.testing.assert_array_equal(mine.rejected, ekf.rejected)


def test_a_step_function_gets_copies_and_the_infinite_gate():
    seen = []

    def spy(mu, Sig, u, z, landmarks, dt, M, Q, gate):
        seen.append((gate, z.shape, landmarks.shape, M.shape, Q.shape, dt))
        out = chapter_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
        mu[:] = np.nan  # scribbling on its inputs changes nothing
        return out

    run = kf.sim.landmark_loop(0, filter=spy, laps=1)
    assert np.isfinite(run.mu).all() and {s[0] for s in seen} == {np.inf}
    assert seen[0][1:3] == ((0, 2), (0, 2)) and seen[1][1] == (seen[1][2][0], 2)  # the prediction, then the step
    assert seen[0][3:] == ((2, 2), (2, 2), 0.2)


def broken(kind):
    def step(mu, Sig, u, z, landmarks, dt, M, Q, gate):
        if kind == "raise":
            raise ZeroDivisionError("oops")
        mu, Sig, used = chapter_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
        return {
            "nan": (mu + np.nan, Sig, used),
            "shape": (mu, Sig[:2, :2], used),
            "psd": (mu, -Sig, used),
            "asym": (mu, Sig + np.triu(np.ones((3, 3)), 1), used),
            "used": (mu, Sig, used[:0] if len(z) else np.ones(3)),
            "one": mu,
        }[kind]

    step.__name__ = f"my_{kind}"
    return step


@pytest.mark.parametrize(
    ("kind", "said"),
    [
        ("raise", "raised ZeroDivisionError: oops"),
        ("nan", "returned mu must be finite"),
        ("shape", "returned Sig must"),
        ("psd", "returned Sig must be positive semi-definite"),
        ("asym", "returned Sig must be a symmetric"),
        ("used", "must return used, one True or False per reading"),
        ("one", "must return (mu, Sig, used)"),
    ],
)
def test_a_broken_step_function_gets_a_value_error_naming_it_and_the_step(kind, said):
    with pytest.raises(ValueError, match=rf"^the filter my_{kind} at step 0 \(\d readings?\) .*") as err:
        kf.sim.landmark_loop(0, filter=broken(kind))
    assert said in str(err.value)


def test_a_long_message_prints_the_returned_array_briefly():
    with pytest.raises(ValueError, match=r"returned Sig must be a symmetric covariance matrix, got \[\[") as err:
        kf.sim.landmark_loop(0, filter=broken("asym"))
    assert len(str(err.value)) < 250 and "\n" not in str(err.value)  # 3 digits a number, on one line


@pytest.mark.fact
def test_a_flat_ellipse_the_truth_leaves_is_infinitely_unlikely():
    def flat(mu, Sig, u, z, landmarks, dt, M, Q, gate):
        mu, _, used = chapter_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
        return mu, np.zeros((3, 3)), used  # "I know exactly where I am"

    run = kf.sim.landmark_loop(0, filter=flat)
    assert np.isinf(run.nees).all() and not run.inside.any() and (run.area == 0).all()
    assert run.honesty()[1] == "over-confident"
    line = np.array([[[1.0, 0.0], [0.0, 0.0]]] * 2)  # an ellipse flattened onto the x axis
    nees = kf.sim.nees(np.array([[0.5, 0.0], [0.5, 1e-3]]), np.zeros((2, 2)), line)  # the one NEES of the course
    assert nees[0] == pytest.approx(0.25) and np.isinf(nees[1])  # along its line, and off it


def test_a_step_function_wraps_as_written():
    with pytest.raises(ValueError, match=r"^wrap_bearing=False"):
        kf.sim.landmark_loop(0, filter=chapter_step, wrap_bearing=False)


# A fact: the written-out step and the course's EKF round apart, and a reading on the gate would split them.
@pytest.mark.fact
def test_a_step_function_gets_labelled_readings_and_may_start_elsewhere():
    with pytest.raises(ValueError, match=r"^labelled=False .* a step function gets labelled readings"):
        kf.sim.landmark_loop(0, filter=chapter_step, labelled=False)
    start = [0.3, -0.2, 0.1]
    mine = kf.sim.landmark_loop(0, filter=chapter_step, gate=4.0, start=start)
    ekf = kf.sim.landmark_loop(0, gate=4.0, start=start)
    np.testing.assert_allclose(mine.mu, ekf.mu, atol=1e-9)
    np.testing.assert_array_equal(mine.matched, ekf.matched)


# ---------------------------------------------------- chapter 11: the filter's start, readings without labels
@pytest.mark.fact
def test_by_default_the_filter_starts_at_the_truth_with_labelled_readings(ekf_run):
    np.testing.assert_array_equal(ekf_run.mu0, ekf_run.start)
    np.testing.assert_array_equal(ekf_run.start, [0.0, 0.0, 0.0])
    assert ekf_run.labelled
    gated = kf.sim.landmark_loop(0, kidnap=60, gate=4.0)  # some readings refused
    for run in (ekf_run, gated):
        lab = np.broadcast_to(np.arange(run.landmarks.shape[0]), run.used.shape)
        np.testing.assert_array_equal(run.matched, np.where(run.used, lab, -1))  # its own landmark, where used
    assert gated.rejected.any()


@pytest.mark.fact
def test_the_start_moves_the_filter_not_the_truth(ekf_run):
    start = [0.5, -0.3, 0.2]
    run = kf.sim.landmark_loop(0, start=start)
    np.testing.assert_array_equal(run.mu0, start)
    np.testing.assert_array_equal(run.start, ekf_run.start)
    np.testing.assert_array_equal(run.truth, ekf_run.truth)
    g = kf.unicycle(start, run.odometry[0], run.dt)  # the first prediction moves the filter's start
    np.testing.assert_allclose(run.mu_bar[0], g, atol=1e-12)
    assert np.linalg.norm(run.mu_bar[0, :2] - ekf_run.mu_bar[0, :2]) > 0.5


@pytest.mark.fact
@pytest.mark.parametrize("filter", ["ekf", "ukf"])
def test_unlabelled_readings_are_matched_by_the_filter_at_its_current_mean(filter):
    """At the true start the nearest neighbour always finds the reading's own landmark: the same run."""
    labelled = kf.sim.landmark_loop(3, filter=filter, gate=4.0)
    run = kf.sim.landmark_loop(3, filter=filter, gate=4.0, labelled=False)
    assert not run.labelled
    np.testing.assert_array_equal(run.matched, labelled.matched)
    np.testing.assert_array_equal(run.used, labelled.used)
    np.testing.assert_allclose(run.mu, labelled.mu, atol=1e-12)


@pytest.mark.fact
def test_an_unlabelled_reading_is_used_as_the_landmark_it_is_matched_to():
    """Every used reading, as the reading of the landmark it was matched to, is the nearest in
    Mahalanobis distance at the step's prediction: the first reading of each step is matched there."""
    run = kf.sim.landmark_loop(0, labelled=False, start=[0.0, 5.0, np.pi])  # the mirror of the start
    Q = np.diag([0.1, 0.03]) ** 2
    h, H = kf.range_bearing, kf.range_bearing_jacobian
    res = kf.models.range_bearing_residual
    firsts = 0
    for k in range(run.t.size):
        seen = np.flatnonzero(run.used[k] | run.rejected[k])
        if seen.size:
            z = run.z[k, seen[0]]
            _, dist = kf.associate(z, run.mu_bar[k], run.Sig_bar[k], run.landmarks, h, H, Q, 1.0, res)
            assert run.matched[k, seen[0]] == int(np.argmin(dist))
            firsts += 1
    assert firsts > 100
    assert (run.matched[~run.used] == -1).all() and (run.matched[run.used] >= 0).all()


def test_an_ellipse_too_small_to_invert_has_an_infinite_nees_without_a_warning():
    """A particle cloud collapsed onto one particle has a subnormal covariance: its inverse overflows."""

    err = np.array([[0.1, -0.2], [0.0, 0.0]])
    Sxy = np.array([np.eye(2) * 1e-320, np.eye(2)])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        nees = kf.sim.nees(err, np.zeros_like(err), Sxy)
    assert nees[0] == np.inf and nees[1] == 0.0


def _bit_for_bit(a, b) -> None:
    for name in a.__dataclass_fields__:
        x, y = getattr(a, name), getattr(b, name)
        if isinstance(x, np.ndarray):
            assert x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes(), name
        else:
            assert x == y, name


@pytest.mark.parametrize("filter", ["ekf", "ukf"])
@pytest.mark.parametrize(
    "change",
    [
        {"kidnap": 60},
        {"kidnap": 0},
        {"dropout": (60, 122)},
        {"dropout": (30, 60)},
        {"filter_motion_noise": 2.0},
        {"sensor_noise": 1.5},
        {"labelled": False},
        {},
    ],
)
def test_a_run_since_another_is_the_same_run_to_the_last_bit(filter, change):
    """``since``: the steps a run shares with the last (the same filter over the same world up to a
    kidnap or a dropout) are copied from it; the record is the one computed afresh, bit for bit."""
    settings = {"filter": filter, "gate": 4.0, "one_back": True}
    last = kf.sim.landmark_loop(0, **settings)
    _bit_for_bit(
        kf.sim.landmark_loop(0, **settings, **change, since=last), kf.sim.landmark_loop(0, **settings, **change)
    )


def test_since_copies_the_steps_before_a_kidnap_and_nothing_after_a_change_of_filter():
    last = kf.sim.landmark_loop(0, gate=4.0)
    copied = kf.sim.landmark_loop(0, gate=4.0, kidnap=60, since=last)
    assert copied.mu[:60].tobytes() == last.mu[:60].tobytes()
    assert copied.mu[60:].tobytes() != last.mu[60:].tobytes()
    world = loop_world(0, kidnap=60)
    setting = {"filter": "ekf", "wrap_bearing": True, "gate": 4.0, "labelled": True, "noise": (1.0, 1.0, 1.0, 1.0)}
    assert _steps_in_common(last, world, world.start, setting) == 60
    assert _steps_in_common(last, world, world.start, {**setting, "filter": "ukf"}) == 0
    assert _steps_in_common(last, world, world.start, {**setting, "gate": 3.0}) == 0
    with pytest.raises(ValueError, match=r"^since must be a LoopRun"):
        kf.sim.landmark_loop(0, since="the last run")
