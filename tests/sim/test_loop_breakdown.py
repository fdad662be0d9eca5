"""The landmark loop checks its arguments once and its result after the lap: a broken filter is reported."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.localization import _check_filter_held


def test_a_ukf_broken_by_extreme_noise_scales_is_reported_not_returned():
    # Odometry 100 times noisier and readings 100 times more exact than the default robot: the UKF's
    # covariance Sig_bar - K S K^T loses its positive definiteness on the way round.
    with pytest.raises(ValueError, match=r"^the UKF broke down with motion_noise=100\.0 and sensor_noise=0\.01: Sig\["):
        kf.sim.landmark_loop(0, filter="ukf", motion_noise=100.0, sensor_noise=0.01, gate=4.0, wrap_bearing=False)


def test_the_same_scales_leave_the_ekf_whole():
    run = kf.sim.landmark_loop(0, filter="ekf", motion_noise=100.0, sensor_noise=0.01, gate=4.0, wrap_bearing=False)
    assert np.isfinite(run.mu).all() and (np.linalg.eigvalsh(run.Sig) >= 0).all()


def test_a_number_that_is_not_finite_is_named_with_its_step():
    T = 5
    mu, Sig = np.zeros((T, 3)), np.tile(np.eye(3), (T, 1, 1))
    _check_filter_held("ekf", 1.0, 1.0, mu, Sig, mu, Sig)  # a whole lap passes
    broken = mu.copy()
    broken[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"^the EKF broke down .*: mu is not finite \(no NaN or inf\) from step 3$"):
        _check_filter_held("ekf", 1.0, 1.0, mu, Sig, broken, Sig)
