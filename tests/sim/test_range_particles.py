"""The particle filter over CMU's Plaza logs (kfcourse/sim/range_particles.py): chapter 12's "start from nowhere".

A seeded particle filter is a chaotic chain of draws: another CPU's rounding sends it down another path, as
another seed would.  Every figure here holds for twenty seeds with margin, not only for the five tried
(``fact``: repeated under other rounding).
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.range_particles import FOUND, KEEP, plaza_box

pytestmark = pytest.mark.fact

SHORT = 1000  # odometry steps: Plaza2's first 100 s; the robot stands still for 20 s, then drives


@pytest.fixture(scope="module")
def plaza2():
    return kf.data.load_plaza("Plaza2")


@pytest.fixture(scope="module")
def lost(plaza2):
    """Global starts over Plaza2's first 100 s, a thousand particles, five seeds."""
    return [kf.sim.range_particles(plaza2, n_particles=1000, seed=seed, steps=SHORT) for seed in range(5)]


def test_a_global_start_spreads_the_cloud_over_the_plaza(lost, plaza2):
    box = plaza_box(plaza2)
    for run in lost:
        assert run.start is None and run.kept[0] == 0
        start = run.particles[0]
        assert np.all((box[:, 0] <= start[:, :2]) & (start[:, :2] <= box[:, 1]))
        assert np.all(box[:, 0] <= plaza2.beacons.min(axis=0)) and np.all(plaza2.beacons.max(axis=0) <= box[:, 1])
        assert np.sqrt(run.Sig[0, 0, 0]) > 15 and np.sqrt(run.Sig[0, 1, 1]) > 15  # nobody knows where
        assert run.error[0] > 5.0


def test_a_global_start_finds_the_robot_within_a_minute(lost):
    """Every seed finds the robot (its estimate within FOUND metres to the end) in under 60 s: twenty seeds
    take at most 45 s, the heading waiting for the robot to drive."""
    for run in lost:
        k = run.found()
        assert k is not None and run.t[k] - run.t[0] < 60.0
        assert run.summary()["found"] == k and run.summary()["found_after"] == run.t[k] - run.t[0]


def test_once_found_the_error_is_half_a_metre(lost):
    """From 60 s on, every seed's error: mean under 0.7 m, never over 2 m (twenty seeds: 0.43 to 0.52, at most
    1.15)."""
    for run in lost:
        late = run.t >= 60.0
        assert run.error[late].mean() < 0.7 and run.error[late].max() < 2.0


def test_over_the_whole_log_it_stays_found(plaza2):
    run = kf.sim.range_particles(plaza2, n_particles=1000, seed=0)
    s = run.summary()
    assert s["found"] is not None and s["found_after"] < 60.0
    assert s["error_after"] < 0.8
    assert 0 < run.resampled.sum() < plaza2.range.size  # resampled now and then, never more than once per range


def test_hearing_two_beacons_the_cloud_finds_the_robot_the_ekf_mirrors():
    """Plaza1 with beacons 2 and 3 alone (where the EKF from the mirrored start follows the mirror image): a global
    start finds the robot within the first ten minutes, for every seed tried."""
    two = kf.data.load_plaza("Plaza1").only([2, 3])
    for seed in range(3):
        s = kf.sim.range_particles(two, seed=seed, steps=3000).summary()
        assert s["found_after"] is not None and s["found_after"] < 300.0 and s["error_after"] < 1.0


def test_from_a_known_start_it_tracks_the_robot_from_the_first_step(plaza2):
    """The noise that lets a lost cloud find the robot keeps a found one wider than its error: NEES under 2."""
    run = kf.sim.range_particles(plaza2, start=plaza2.truth[0], steps=SHORT)
    s = run.summary()
    assert s["found"] == 0 and s["mean_error"] < 0.6 and s["p95_error"] < 1.2
    assert s["inside"] > 0.95 and s["mean_nees"] < 2.0
    assert run.found(radius=FOUND) == 0 and run.found(radius=0.01) is None  # never within a centimetre at the end


def test_the_record_keeps_the_estimate_of_every_step_and_the_cloud_of_a_few(plaza2):
    steps, N = 150, 200
    run = kf.sim.range_particles(plaza2, n_particles=N, steps=steps)
    K1 = steps + 1
    assert run.mu.shape == (K1, 3) and run.Sig.shape == (K1, 3, 3) and run.truth.shape == (K1, 3)
    assert run.error.shape == run.nees.shape == run.ess.shape == run.resampled.shape == run.readings.shape == (K1,)
    assert run.readings.sum() == np.count_nonzero(plaza2.t_range <= plaza2.t_truth[steps]) and run.readings[0] == 0
    np.testing.assert_array_equal(run.kept, [k for k in KEEP if k <= steps])
    assert run.particles.shape == (run.kept.size, N, 3) and run.particles.dtype == np.float32
    assert run.w.shape == (run.kept.size, N) and np.allclose(run.w.sum(axis=1), 1.0, atol=1e-5)
    assert np.all(run.resampled == (run.ess < N / 2)) and np.all((1.0 <= run.ess) & (run.ess <= N + 1e-9))
    np.testing.assert_array_equal(run.nees, kf.sim.nees(run.truth[:, :2], run.mu[:, :2], run.Sig[:, :2, :2]))
    assert run.log == "Plaza2" and run.n_particles == N and run.scale == 1.07
    chosen = kf.sim.range_particles(plaza2, n_particles=N, steps=steps, keep=[150, 5, 5, 999])
    np.testing.assert_array_equal(chosen.kept, [5, 150])
    np.testing.assert_array_equal(chosen.mu, run.mu)  # which clouds are kept changes nothing of the run
    with pytest.raises(ValueError):
        run.mu[0, 0] = 1.0  # a record is read-only


def test_the_same_seed_gives_the_same_run(plaza2):
    a, b = (kf.sim.range_particles(plaza2, n_particles=100, seed=3, steps=60) for _ in range(2))
    np.testing.assert_array_equal(a.mu, b.mu)
    np.testing.assert_array_equal(a.particles, b.particles)
    other = kf.sim.range_particles(plaza2, n_particles=100, seed=4, steps=60)
    assert not np.array_equal(a.mu, other.mu)


@pytest.mark.parametrize(
    ("name", "bad"),
    [
        ("log", "Plaza2"),
        ("n_particles", 0),
        ("n_particles", 10_001),
        ("n_particles", 10.0),
        ("seed", -1),
        ("speed_std", 0.0),
        ("turn_std", -0.1),
        ("range_std", np.nan),
        ("scale", "online"),
        ("scale", 0.0),
        ("start", [0.0, 0.0]),
        ("steps", 0),
        ("steps", 10**6),
        ("keep", [1.5]),
        ("keep", [-1]),
        ("keep", 3),
    ],
)
def test_bad_inputs_are_refused_by_name(plaza2, name, bad):
    arguments = {"log": plaza2, "n_particles": 10, "steps": 5, name: bad}
    with pytest.raises(ValueError, match=rf"^{name} "):
        kf.sim.range_particles(**arguments)


def test_a_bad_radius_is_refused_by_name(plaza2):
    run = kf.sim.range_particles(plaza2, n_particles=10, steps=5)
    with pytest.raises(ValueError, match=r"^radius "):
        run.found(radius=0.0)
