"""The landmark loop runs the public filter steps, which refuse a broken covariance: a broken filter is reported."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def test_a_ukf_broken_by_extreme_noise_scales_is_reported_not_returned():
    # Odometry 100 times noisier and readings 100 times more exact than the default robot: the UKF's
    # covariance Sig_bar - K S K^T loses its positive definiteness on the way round.
    with pytest.raises(ValueError, match=r"^the UKF broke down with motion_noise=100\.0 and sensor_noise=0\.01: Sig"):
        kf.sim.landmark_loop(0, filter="ukf", motion_noise=100.0, sensor_noise=0.01, gate=4.0, wrap_bearing=False)


def test_the_same_scales_leave_the_ekf_whole():
    run = kf.sim.landmark_loop(0, filter="ekf", motion_noise=100.0, sensor_noise=0.01, gate=4.0, wrap_bearing=False)
    assert np.isfinite(run.mu).all() and (np.linalg.eigvalsh(run.Sig) >= 0).all()


def test_a_filter_step_that_returns_nan_is_stopped_at_the_next_step():
    world = kf.sim.simulate_robot(seed=0)
    calls = []

    def predict(mu, Sig, u):
        calls.append(len(calls))
        return mu, Sig if len(calls) < 3 else np.full((3, 3), np.nan)

    def update(mu_bar, Sig_bar, z, m):
        h, H = lambda x: kf.range_bearing(x, m), lambda x: kf.range_bearing_jacobian(x, m)
        return kf.ekf_update(mu_bar, Sig_bar, z, h, H, np.eye(2))

    with pytest.raises(ValueError, match=r"^Sig_bar must be finite"):
        kf.sim.localize(world, predict, update, np.eye(3))
