"""The three filters of kfcourse and of filterpy 2.0, set up on the same problems.

One home for the set-up that ``benchmarks/bench_filters.py`` times and
``tests/filters/test_filterpy_agreement.py`` checks step by step:

- the linear Kalman filter on a 2-D constant-velocity tracker;
- the EKF and the UKF on a unicycle robot reading range and bearing to one landmark.

Each problem has its constants, a simulator of its readings, kfcourse's predict and
update (or whole step) as functions of the belief, and a builder of the filterpy
filter, which starts at the same belief and is then driven by its own ``predict``
(given ``u=CONTROL`` for the robot) and ``update(z)``.

The benchmark imports this module as its neighbour (``python benchmarks/bench_filters.py``
puts ``benchmarks/`` first on the import path); the tests import it as
``benchmarks.filterpy_pairs`` (pytest puts the repository root, home of the root
``conftest.py``, on the import path).

Noise letters differ between the libraries: kfcourse's ``R`` (process) is filterpy's
``Q``, and kfcourse's ``Q`` (measurement) is filterpy's ``R``.
"""

from __future__ import annotations

from functools import partial

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter, JulierSigmaPoints, KalmanFilter, UnscentedKalmanFilter

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual

DT = 0.1  # s, time step of every model
SEED = 20240601  # random seed for the simulated runs

# Constant-velocity tracker (2-D): state [px, py, vx, vy] (m, m, m/s, m/s).
CV_F, CV_H = kf.models.constant_velocity(DT, 2)
CV_R = np.diag([1e-4, 1e-4, 1e-2, 1e-2])  # process noise (m², m², m²/s², m²/s²)
CV_Q = np.diag([0.25, 0.25])  # measurement noise, m²
CV_MU0 = np.array([0.0, 0.0, 1.0, 0.5])  # initial mean (m, m, m/s, m/s)
CV_SIG0 = np.diag([1.0, 1.0, 4.0, 4.0])  # initial covariance (m², m², m²/s², m²/s²)

# Unicycle robot reading one landmark: pose [x, y, theta] (m, m, rad).
LANDMARK = np.array([5.0, 3.0])  # m
CONTROL = np.array([1.0, 0.2])  # [V (m/s), omega (rad/s)], a circle of radius 5 m
UNI_R = np.diag([1e-3, 1e-3, 1e-4])  # process noise (m², m², rad²)
UNI_Q = np.diag([0.01, 0.0025])  # measurement noise (m², rad²)
UNI_MU0 = np.array([0.0, 0.0, 0.0])  # initial pose (m, m, rad)
UNI_SIG0 = np.diag([0.1, 0.1, 0.05])  # initial covariance (m², m², rad²)

g = partial(kf.unicycle, dt=DT)  # g(x, u)
G = partial(kf.unicycle_jacobian, dt=DT)  # G(x, u)
h = partial(kf.range_bearing, landmark=LANDMARK)  # h(x)
H_jac = partial(kf.range_bearing_jacobian, landmark=LANDMARK)  # H(x)


# ---------------------------------------------------------------- simulated readings
def cv_readings(rng: np.random.Generator, steps: int) -> list[np.ndarray]:
    """Noisy 2-D positions of a target moving at constant velocity."""
    x, zs = CV_MU0.copy(), []
    for _ in range(steps):
        x = CV_F @ x + rng.multivariate_normal(np.zeros(4), CV_R)
        zs.append(CV_H @ x + rng.multivariate_normal(np.zeros(2), CV_Q))
    return zs


def unicycle_readings(rng: np.random.Generator, steps: int) -> list[np.ndarray]:
    """Noisy range-bearing readings of LANDMARK from a robot driving a circle."""
    x, zs = UNI_MU0.copy(), []
    for _ in range(steps):
        x = kf.unicycle(x, CONTROL, DT) + rng.multivariate_normal(np.zeros(3), UNI_R)
        z = kf.range_bearing(x, LANDMARK) + rng.multivariate_normal(np.zeros(2), UNI_Q)
        zs.append(np.array([z[0], kf.wrap_angle(z[1])]))
    return zs


# ---------------------------------------------------------------- kfcourse
def kfcourse_kf_predict(mu, Sig):
    return kf.kf_predict(mu, Sig, None, CV_F, None, CV_R)


def kfcourse_kf_step(mu, Sig, z):
    return kf.kf_step(mu, Sig, None, z, CV_F, None, CV_H, CV_R, CV_Q)


def kfcourse_ekf_predict(mu, Sig):
    return kf.ekf_predict(mu, Sig, CONTROL, g, G, UNI_R)


def kfcourse_ekf_update(mu, Sig, z):
    return kf.ekf_update(mu, Sig, z, h, H_jac, UNI_Q, residual=range_bearing_residual)


def kfcourse_ukf_predict(mu, Sig, lam):
    return kf.ukf_predict(mu, Sig, CONTROL, g, UNI_R, lam, residual=pose_residual, mean=pose_mean)


def kfcourse_ukf_update(mu, Sig, z, lam):
    return kf.ukf_update(
        mu,
        Sig,
        z,
        h,
        UNI_Q,
        lam,
        residual=range_bearing_residual,
        mean=range_bearing_mean,
        x_residual=pose_residual,  # the models take all sigma points at once; filterpy calls them per point
    )


# ---------------------------------------------------------------- filterpy
def filterpy_kf() -> KalmanFilter:
    """filterpy's Kalman filter for the tracker, at the initial belief."""
    f = KalmanFilter(dim_x=4, dim_z=2)
    f.F, f.H, f.Q, f.R = CV_F, CV_H, CV_R, CV_Q  # filterpy: Q process, R measurement
    f.x, f.P = CV_MU0.copy(), CV_SIG0.copy()
    return f


class UnicycleEKF(ExtendedKalmanFilter):
    """filterpy's EKF for the robot: the nonlinear motion model for the mean, its Jacobian
    at the previous mean for the covariance, and the landmark's range and bearing."""

    def predict_x(self, u=0):
        self.x = g(self.x, u)

    def predict(self, u=0):
        self.F = G(self.x, u)  # Jacobian at the previous mean, before predict_x moves it
        super().predict(u)

    def update(self, z):
        super().update(z, H_jac, h, residual=range_bearing_residual)


def filterpy_ekf() -> UnicycleEKF:
    """filterpy's EKF for the robot, at the initial belief."""
    f = UnicycleEKF(dim_x=3, dim_z=2)
    f.Q, f.R = UNI_R, UNI_Q  # filterpy: Q process, R measurement
    f.x, f.P = UNI_MU0.copy(), UNI_SIG0.copy()
    return f


def filterpy_ukf(lam: float) -> UnscentedKalmanFilter:
    """filterpy's UKF for the robot with Julier's sigma points of spread ``n + lam``
    (kfcourse's ``lam`` is Julier's ``kappa``), at the initial belief."""
    f = UnscentedKalmanFilter(
        dim_x=3,
        dim_z=2,
        dt=DT,
        hx=h,
        fx=lambda x, dt, u: kf.unicycle(x, u, dt),
        points=JulierSigmaPoints(n=3, kappa=lam),
        x_mean_fn=pose_mean,
        z_mean_fn=range_bearing_mean,
        residual_x=pose_residual,
        residual_z=range_bearing_residual,
    )
    f.Q, f.R = UNI_R, UNI_Q  # filterpy: Q process, R measurement
    f.x, f.P = UNI_MU0.copy(), UNI_SIG0.copy()
    return f
