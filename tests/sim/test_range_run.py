"""The EKF over CMU's Plaza logs (kfcourse/sim/range_run.py): what chapter 12 will say of each filter.

The logs are fixed measurements, but a filter run over thousands of steps is a long chain of rounding:
every figure is stated with a margin, and the tests are repeated under other rounding (``fact``).
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact


@pytest.fixture(scope="module", params=kf.data.PLAZA_RUNS)
def log(request):
    return kf.data.load_plaza(request.param)


@pytest.fixture(scope="module")
def plaza2():
    return kf.data.load_plaza("Plaza2")


def test_tuned_as_the_data_sheet_says_the_ekf_is_over_confident(log):
    """An unbiased radio with half a metre of noise: the filter believes it to within its ellipse, and the
    truth lies outside its 3-sigma ellipse nearly all the time."""
    run = kf.sim.range_localize(log)
    s = run.summary()
    assert s["mean_error"] > 2.0 and s["inside"] < 0.05 and s["mean_nees"] > 100
    assert run.nis.mean() > 10  # the innovations say it too, without the truth
    assert 1.02 < run.fitted_scale() < 1.06  # and they point to a radio that reads long


def test_with_the_radio_s_scale_the_error_falls_tenfold(log):
    run = kf.sim.range_localize(log, scale=1.07)
    s = run.summary()
    assert s["mean_error"] < 0.4 and s["inside"] > 0.7 and s["mean_nees"] < 10
    assert 1.06 < run.fitted_scale() < 1.08  # the innovations now agree with the scale assumed


def test_the_scale_as_a_fourth_state_is_learned_from_the_ranges(plaza2):
    run = kf.sim.range_localize(plaza2, scale="online")
    assert run.mu.shape == (len(plaza2.distance) + 1, 4) and run.mu[0, 3] == 1.0
    assert 1.06 < run.mu[-1, 3] < 1.08 and np.sqrt(run.Sig[-1, 3, 3]) < 0.005
    assert run.summary()["mean_error"] < 0.4


def test_the_ukf_follows_the_log_as_closely_as_the_ekf(plaza2):
    """A range is nearly linear at tens of metres: the UKF's sigma points find what the EKF's tangent does."""
    ekf = kf.sim.range_localize(plaza2, scale=1.07).summary()
    ukf = kf.sim.range_localize(plaza2, filter="ukf", scale=1.07).summary()
    assert abs(ukf["mean_error"] - ekf["mean_error"]) < 0.05 and abs(ukf["inside"] - ekf["inside"]) < 0.05


def test_from_a_start_it_is_not_told_the_ekf_finds_the_robot_on_plaza2(plaza2):
    for guess in ([0.0, 0.0, 0.0], [-40.0, 40.0, 1.0], [10.0, 10.0, -2.0]):
        run = kf.sim.range_localize(plaza2, scale=1.07, start=guess, start_std=(30.0, 30.0, 3.0))
        assert np.median(run.error[1000:]) < 0.5


def test_hearing_two_beacons_from_the_mirrored_start_the_ekf_follows_the_mirror_image():
    """Two circles meet in two points.  Plaza1 with beacons 2 and 3 alone: from the start reflected across their
    line, even with a first ellipse of 10 m, the EKF follows the reflected path and never comes near the robot;
    from the true start it follows the robot."""
    plaza1 = kf.data.load_plaza("Plaza1")
    two = plaza1.only([2, 3])
    lost = kf.sim.range_localize(two, scale=1.07, start=plaza1.mirrored_start([2, 3]), start_std=(10.0, 10.0, 1.0))
    a, b = plaza1.beacons[[2, 3]]
    d = (b - a) / np.hypot(*(b - a))
    p = plaza1.truth[:, :2] - a
    reflected = a + 2.0 * (p @ d)[:, None] * d - p  # the true path reflected across the beacons' line
    assert np.median(np.hypot(*(lost.mu[:, :2] - reflected).T)) < 3.0
    assert np.median(lost.error) > 30.0 and lost.error.min() > 3.0
    assert np.median(kf.sim.range_localize(two, scale=1.07).error) < 0.5


def test_with_no_ranges_the_ekf_dead_reckons(plaza2):
    """The EKF's predictions alone are the log's dead reckoning, pose for pose; only its ellipse is new."""
    blind = kf.sim.range_localize(plaza2.only([]))
    np.testing.assert_array_equal(blind.mu, plaza2.dead_reckoning())
    area = np.sqrt(np.linalg.det(blind.Sig[:, :2, :2]))
    assert blind.z.size == 0 and area[-1] > 100 * area[0]  # nothing stops the ellipse growing


def test_only_an_ekf_run_is_smoothed(plaza2):
    with pytest.raises(ValueError, match=r"^run must be an EKF's RangeRun"):
        kf.sim.smoothed(kf.sim.range_localize(plaza2, filter="ukf", steps=10))


def test_noise_per_metre_driven_tuned_on_one_log_is_honest_on_the_other():
    """Plaza2 drives three times as fast as Plaza1, in steps half as long: a noise per second tuned on Plaza1
    is over-confident on Plaza2, the same noise per metre driven is honest on both."""
    per_second = {"speed_std": 0.15, "turn_std": 0.02, "range_std": 0.5, "scale": "online"}
    per_metre = {"speed_std": 0.05, "turn_std": 0.01, "range_std": 0.7, "scale": "online", "noise_per": "metre"}
    logs = [kf.data.load_plaza(name) for name in kf.data.PLAZA_RUNS]
    first, second = (kf.sim.range_localize(log, **per_second).summary() for log in logs)
    assert first["verdict"] == "honest" and second["verdict"] == "over-confident"
    for log in logs:
        s = kf.sim.range_localize(log, **per_metre).summary()
        assert s["verdict"] == "honest" and s["inside"] > 0.9 and s["mean_error"] < 0.4


def test_the_gate_refuses_a_few_ranges(plaza2):
    run = kf.sim.range_localize(plaza2, scale=1.07, gate=3.0)
    refused = 1.0 - run.used.mean()
    assert 0.0 < refused < 0.03
    assert np.all(run.nis[~run.used] > 9.0)  # each refused range was more than 3 sigma off
    assert np.all(run.nis[run.used] <= 9.0)


def test_the_smoother_knows_more_afterwards(plaza2):
    run = kf.sim.range_localize(plaza2, scale="online")
    after = kf.sim.smoothed(run)
    np.testing.assert_array_equal(after.mu[-1], run.mu[-1])  # nothing comes after the last step
    assert after.summary()["mean_error"] < 0.8 * run.summary()["mean_error"]
    assert np.all(np.linalg.eigvalsh(run.Sig[:-1] - after.Sig[:-1]) > -1e-9)  # never less sure than the filter


def test_a_run_of_the_first_steps_is_the_start_of_the_whole_run(plaza2):
    whole = kf.sim.range_localize(plaza2, steps=400)
    part = kf.sim.range_localize(plaza2, steps=100)
    np.testing.assert_array_equal(part.mu, whole.mu[:101])
    assert part.z.size == np.count_nonzero(plaza2.t_range <= plaza2.t_truth[100])


def test_ranges_are_used_after_the_prediction_of_their_step(plaza2):
    run = kf.sim.range_localize(plaza2, steps=300)
    t_range = plaza2.t_range[: run.z.size]
    assert np.all((run.t[run.step - 1] < t_range) | (run.step == 1))
    assert np.all(t_range <= run.t[run.step])
    assert np.all(np.diff(run.step) >= 0)
