"""Chapter 8: forgetting to wrap the bearing innovation breaks the EKF on the loop; wrapping it does not."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf


@pytest.fixture(scope="module")
def runs():
    return {(seed, wrap): kf.sim.landmark_loop(seed, wrap_bearing=wrap) for seed in (0, 1, 3) for wrap in (True, False)}


@pytest.mark.parametrize("seed", [0, 3])
def test_unwrapped_bearing_breaks_the_estimate(runs, seed):
    wrapped, unwrapped = runs[seed, True], runs[seed, False]
    assert not unwrapped.wrap_bearing and wrapped.wrap_bearing
    assert unwrapped.error.max() > 1.0  # m: the estimate jumps off the loop
    assert unwrapped.error.max() > 5 * wrapped.error.max()
    assert unwrapped.share_inside < 0.85  # and is confidently wrong for a stretch of the drive
    assert np.allclose(unwrapped.truth, wrapped.truth) and np.allclose(unwrapped.z, wrapped.z)  # same world


@pytest.mark.parametrize("seed", [0, 1, 3])
def test_wrapped_bearing_tracks_and_is_honest(runs, seed):
    wrapped = runs[seed, True]
    assert wrapped.error.max() < 0.3  # m
    assert wrapped.share_inside > 0.95


def test_the_break_starts_at_a_reading_across_plus_minus_pi(runs):
    """Before the first reading whose raw bearing difference exceeds pi, both filters agree exactly."""
    wrapped, unwrapped = runs[0, True], runs[0, False]
    across = [
        k
        for k, j in zip(*np.nonzero(unwrapped.used), strict=True)
        if abs(unwrapped.z[k, j, 1] - kf.range_bearing(unwrapped.mu_bar[k], unwrapped.landmarks[j])[1]) > np.pi
    ]
    assert across, "no reading crossed +-pi: the run does not show the bug"
    k0 = min(across)
    assert np.allclose(unwrapped.mu[:k0], wrapped.mu[:k0])
    assert not np.allclose(unwrapped.mu[k0], wrapped.mu[k0])


def test_a_run_without_a_crossing_does_not_show_the_bug(runs):
    """Seed 1: no reading lands across +-pi from its prediction, so the missing wrap never matters."""
    assert np.allclose(runs[1, True].mu, runs[1, False].mu)
