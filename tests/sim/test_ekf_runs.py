"""Chapter 7: the EKF with the right Jacobian tracks and is honest; with one sign flipped it diverges."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_right_jacobian_tracks_and_is_honest(seed):
    run = kf.sim.run_ekf(flipped=False, seed=seed)
    assert run.final_error < 0.15  # m
    assert run.error.max() < 0.5
    assert run.share_inside > 0.95


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_flipped_bearing_row_diverges(seed):
    # A diverged run's final error depends on the last bit of a sine (numpy's SIMD path): it is
    # no fact. When the error passes 1 m, how large it gets and how often the truth is outside are.
    run = kf.sim.run_ekf(flipped=True, seed=seed)
    assert run.t[np.argmax(run.error > 1.0)] <= 5.0  # s: a metre off within the first 5 s
    assert np.mean(run.error > 0.5) > 0.8  # m: more than half a metre off at most steps
    assert run.error.max() > 3.0
    assert run.share_inside < 0.2  # the truth leaves the 3-sigma ellipse


def test_flipped_jacobian_is_the_true_one_with_the_bearing_row_negated():
    pose, mark = np.array([1.0, 2.0, 0.0]), np.array([4.0, 6.0])
    right = kf.models.range_bearing_jacobian(pose, mark)
    wrong = kf.sim.flipped_bearing_jacobian(pose, mark)
    assert wrong[0] == pytest.approx(right[0])
    assert wrong[1] == pytest.approx(-right[1])


def test_record_shapes_and_read_only():
    run = kf.sim.run_ekf(seed=0)
    T = run.t.size
    assert run.mu.shape == (T, 3) and run.Sig.shape == (T, 3, 3) and run.inside.shape == (T,)
    assert np.allclose(run.Sig, np.swapaxes(run.Sig, 1, 2))
    with pytest.raises(ValueError):
        run.mu[0, 0] = 1.0
    assert run.landmarks.shape == (2, 2)


def test_same_seed_same_run_and_bad_input():
    a, b = kf.sim.run_ekf(True, seed=3), kf.sim.run_ekf(True, seed=3)
    assert np.array_equal(a.mu, b.mu)
    with pytest.raises(ValueError, match="flipped"):
        kf.sim.run_ekf(flipped="yes")
    with pytest.raises(ValueError, match="seed"):
        kf.sim.run_ekf(seed=-1)


def test_the_comparison_table_counts_the_seeds_the_ukf_wins():
    from types import SimpleNamespace

    def run(errors, inside):
        return SimpleNamespace(error=np.array(errors), share_inside=inside)

    runs = {0: (run([1.0, 1.0], 0.4), run([0.5, 0.5], 0.7)), 7: (run([0.2, 0.2], 0.9), run([0.3, 0.3], 0.8))}
    table = kf.sim.ekf_runs.comparison_table(runs)
    lines = table.splitlines()
    assert lines[0].split()[:3] == ["seed", "EKF", "RMS"]
    assert lines[2].split() == ["0", "1.00", "m", "0.50", "m", "40%", "70%"]
    assert lines[3].split()[0] == "7"
    assert lines[-1] == "the UKF's RMS error is smaller in 1 of 2 seeds"
