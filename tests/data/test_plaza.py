"""CMU's Plaza logs as the course reads them (kfcourse/data/plaza.py): what the chapter's text says of the data.

The logs are measurements, not seeded draws: every figure here is a fact of a fixed file.
"""

from __future__ import annotations

from importlib import metadata

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.data import plaza


@pytest.fixture(scope="module", params=kf.data.PLAZA_RUNS)
def log(request) -> kf.data.PlazaLog:
    return kf.data.load_plaza(request.param)


# name: odometry steps, ranges, duration (s), path length (m), as the issue and the chapter give them
SIZES = {"Plaza1": (9657, 3529, 1933, 1859), "Plaza2": (4090, 1816, 410, 1354)}


def test_the_record_holds_the_whole_log(log):
    steps, ranges, seconds, metres = SIZES[log.name]
    assert log.distance.shape == log.turn.shape == log.t_odometry.shape == (steps,)
    assert log.truth.shape == (steps + 1, 3) and log.t_truth.shape == (steps + 1,)
    assert log.range.shape == log.beacon.shape == log.t_range.shape == (ranges,)
    assert log.beacons.shape == (4, 2) and sorted(log.beacon_ids.tolist()) == [0, 1, 5, 6]
    assert round(log.duration) == seconds and round(log.path_length) == metres
    assert abs(log.distance.sum() - log.path_length) < 0.002 * log.path_length  # the wheels measure the path


def test_times_start_at_zero_and_increase(log):
    assert log.t_truth[0] == 0.0 and np.all(np.diff(log.t_truth) > 0)
    np.testing.assert_array_equal(log.t_odometry, log.t_truth[1:])
    assert np.all(np.diff(log.t_range) >= 0)  # Plaza1's two blocks out of order, sorted
    assert log.t_range[0] >= 0 and log.t_range[-1] <= log.t_truth[-1]  # every range falls within the truth


def test_the_heading_is_the_direction_of_travel(log):
    step = np.diff(log.truth[:, :2], axis=0)
    moving = np.hypot(*step.T) > 0.02  # m per step: driving, not standing
    travel = np.arctan2(step[:, 1], step[:, 0])
    off = kf.wrap_angle(log.truth[1:, 2] - travel)[moving]
    assert np.mean(np.abs(off) < np.pi / 4) > 0.99  # Plaza2's log angle points backwards: turned by pi
    assert np.all((log.truth[:, 2] > -np.pi) & (log.truth[:, 2] <= np.pi))


def test_the_odometry_turns_as_the_truth_does(log):
    true_turn = kf.wrap_angle(np.diff(log.truth[:, 2]))
    assert np.median(np.abs(log.turn - true_turn)) < 0.01  # rad per step


def test_dead_reckoning_drifts_a_few_metres_in_plaza1_and_tens_in_plaza2(log):
    """The odometry alone, from the true start: chapter 0's drift, on a real robot."""
    error = np.hypot(*(log.dead_reckoning()[:, :2] - log.truth[:, :2]).T)
    assert error[0] == 0.0
    if log.name == "Plaza1":  # 1.86 km: a metre off at the median, about 4.4 m at the end
        assert 0.8 < np.median(error) < 1.2 and 4.0 < error[-1] < 5.0 and error.max() < 5.0
    else:  # 1.35 km: about 25 m off at the median, up to about 71 m
        assert 22 < np.median(error) < 28 and 65 < error.max() < 78


def test_the_odometry_as_controls_drives_the_unicycle_of_chapter_8(log):
    V, omega = log.controls().T
    np.testing.assert_allclose(V * log.dt, log.distance, rtol=1e-12)
    np.testing.assert_allclose(omega * log.dt, log.turn, rtol=1e-12, atol=1e-15)
    start = [1.0, -2.0, 0.5]
    np.testing.assert_array_equal(log.dead_reckoning(start)[0], start)
    np.testing.assert_array_equal(log.dead_reckoning(start, steps=10), log.dead_reckoning(start)[:11])


def test_the_ranges_read_seven_percent_long(log):
    """A scale error, not noise: the least-squares line of range against true distance has slope 1.07 and
    crosses near 0; about that line each beacon's robust spread is about half a metre."""
    d = log.true_distance()
    slope, intercept = np.polyfit(d, log.range, 1)
    assert 1.065 < slope < 1.075 and abs(intercept) < 0.1
    for b in range(4):
        mine = log.beacon == b
        residual = log.range[mine] - slope * d[mine] - intercept
        spread = 1.4826 * np.median(np.abs(residual - np.median(residual)))  # robust standard deviation
        assert 0.4 < spread < 0.8


def test_the_record_is_read_only(log):
    with pytest.raises(ValueError, match="read-only"):
        log.range[0] = 0.0


def test_a_log_with_fewer_beacons_keeps_only_their_ranges(log):
    two = log.only([2, 3])
    assert set(two.beacon.tolist()) == {2, 3} and two.range.size == np.isin(log.beacon, [2, 3]).sum()
    np.testing.assert_array_equal(two.truth, log.truth)
    np.testing.assert_array_equal(two.beacons, log.beacons)  # the rows keep their meaning
    assert log.only([]).range.size == 0
    for bad in ([4], [-1], [0.5]):
        with pytest.raises(ValueError, match=r"^beacons must be rows"):
            log.only(bad)


def test_the_mirrored_start_is_as_far_from_both_beacons_as_the_start(log):
    mirror = log.mirrored_start([2, 3])
    for b in log.beacons[[2, 3]]:
        assert np.hypot(*(mirror[:2] - b)) == pytest.approx(np.hypot(*(log.truth[0, :2] - b)), rel=1e-12)
    assert np.hypot(*(mirror[:2] - log.truth[0, :2])) > 10.0  # elsewhere on the plaza
    with pytest.raises(ValueError, match=r"^beacons must be two different rows"):
        log.mirrored_start([2, 2])


def test_a_bad_start_is_refused(log):
    with pytest.raises(ValueError, match=r"^start must have length 3"):
        log.dead_reckoning([0.0, 0.0])


def test_a_name_that_is_no_run_is_refused():
    for bad in ("Plaza3", "plaza1", 1, None):
        with pytest.raises(ValueError, match=r"^name must be one of \('Plaza1', 'Plaza2'\)"):
            kf.data.load_plaza(bad)


def test_without_gtsam_the_error_says_how_to_get_the_data(monkeypatch):
    def missing(name):
        raise metadata.PackageNotFoundError(name)

    monkeypatch.setattr(plaza.metadata, "distribution", missing)
    with pytest.raises(ModuleNotFoundError, match=r"pip install gtsam==4\.3\.0.*Windows.*Binder or in WSL"):
        kf.data.load_plaza("Plaza1")
