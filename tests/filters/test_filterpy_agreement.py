"""kfcourse's filters agree with filterpy 2.0's, step by step.

The linear Kalman filter on a 2-D constant-velocity tracker, and the EKF and the UKF on
a unicycle robot reading range and bearing to one landmark, run side by side in both
libraries from the same belief on the same readings; mean and covariance must agree at
every step.  The model set-up is the one of ``benchmarks/bench_filters.py``.

Noise letters differ between the libraries: kfcourse's ``R`` (process) is filterpy's
``Q``, and kfcourse's ``Q`` (measurement) is filterpy's ``R``.
"""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter, JulierSigmaPoints, KalmanFilter, UnscentedKalmanFilter

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual

STEPS = 400  # filter steps compared (KF, EKF)
UKF_STEPS = 150  # filterpy's UKF is slow; the bearing crosses +-pi at steps 76-79
DT = 0.1  # s, time step of every model
SEED = 20240601

# Constant-velocity tracker (2-D): state [px, py, vx, vy] (m, m, m/s, m/s).
CV_R = np.diag([1e-4, 1e-4, 1e-2, 1e-2])  # process noise
CV_Q = np.diag([0.25, 0.25])  # measurement noise, m²
CV_MU0 = np.array([0.0, 0.0, 1.0, 0.5])
CV_SIG0 = np.diag([1.0, 1.0, 4.0, 4.0])

# Unicycle robot reading one landmark: pose [x, y, theta] (m, m, rad).
LANDMARK = np.array([5.0, 3.0])  # m
CONTROL = np.array([1.0, 0.2])  # [V (m/s), omega (rad/s)], a circle of radius 5 m
UNI_R = np.diag([1e-3, 1e-3, 1e-4])  # process noise (m², m², rad²)
UNI_Q = np.diag([0.01, 0.0025])  # measurement noise (m², rad²)
UNI_MU0 = np.array([0.0, 0.0, 0.0])
UNI_SIG0 = np.diag([0.1, 0.1, 0.05])

g = partial(kf.unicycle, dt=DT)  # g(x, u)
G = partial(kf.unicycle_jacobian, dt=DT)  # G(x, u)
h = partial(kf.range_bearing, landmark=LANDMARK)  # h(x)
H_jac = partial(kf.range_bearing_jacobian, landmark=LANDMARK)  # H(x)


def assert_same_step(t, ours, theirs):
    (m1, S1), (m2, S2) = ours, theirs
    np.testing.assert_allclose(m1, m2, rtol=1e-7, atol=1e-9, err_msg=f"mean at step {t}")
    np.testing.assert_allclose(S1, S2, rtol=1e-7, atol=1e-9, err_msg=f"covariance at step {t}")


@pytest.fixture(scope="module")
def cv_readings() -> list[np.ndarray]:
    rng = np.random.default_rng(SEED)
    F, H = kf.models.constant_velocity(DT, 2)
    x, zs = CV_MU0.copy(), []
    for _ in range(STEPS):
        x = F @ x + rng.multivariate_normal(np.zeros(4), CV_R)
        zs.append(H @ x + rng.multivariate_normal(np.zeros(2), CV_Q))
    return zs


@pytest.fixture(scope="module")
def unicycle_readings() -> list[np.ndarray]:
    rng = np.random.default_rng(SEED + 1)
    x, zs = UNI_MU0.copy(), []
    for _ in range(STEPS):
        x = kf.unicycle(x, CONTROL, DT) + rng.multivariate_normal(np.zeros(3), UNI_R)
        z = kf.range_bearing(x, LANDMARK) + rng.multivariate_normal(np.zeros(2), UNI_Q)
        zs.append(np.array([z[0], kf.wrap_angle(z[1])]))
    return zs


def test_readings_cross_the_bearing_seam(unicycle_readings):
    # the robot circles with the landmark behind it at times, so the residual hooks are exercised
    bearings = np.array([z[1] for z in unicycle_readings[:UKF_STEPS]])
    assert bearings.max() > 3.0 and bearings.min() < -3.0


def test_kf_step_agrees_with_filterpy(cv_readings):
    F, H = kf.models.constant_velocity(DT, 2)
    f = KalmanFilter(dim_x=4, dim_z=2)
    f.F, f.H, f.Q, f.R = F, H, CV_R, CV_Q  # filterpy: Q process, R measurement
    f.x, f.P = CV_MU0.copy(), CV_SIG0.copy()
    mu, Sig = CV_MU0, CV_SIG0
    for t, z in enumerate(cv_readings):
        mu_bar, Sig_bar = kf.kf_predict(mu, Sig, None, F, None, CV_R)
        f.predict()
        assert_same_step(t, (mu_bar, Sig_bar), (f.x, f.P))
        mu, Sig = kf.kf_step(mu, Sig, None, z, F, None, H, CV_R, CV_Q)
        f.update(z)
        assert_same_step(t, (mu, Sig), (f.x, f.P))


class _UnicycleEKF(ExtendedKalmanFilter):
    """filterpy's EKF with the nonlinear motion model for the mean."""

    def predict_x(self, u=0):
        self.x = g(self.x, u)


def test_ekf_steps_agree_with_filterpy(unicycle_readings):
    f = _UnicycleEKF(dim_x=3, dim_z=2)
    f.Q, f.R = UNI_R, UNI_Q  # filterpy: Q process, R measurement
    f.x, f.P = UNI_MU0.copy(), UNI_SIG0.copy()
    mu, Sig = UNI_MU0, UNI_SIG0
    for t, z in enumerate(unicycle_readings):
        mu, Sig = kf.ekf_predict(mu, Sig, CONTROL, g, G, UNI_R)
        f.F = G(f.x, CONTROL)  # Jacobian at the previous mean, before predict_x moves it
        f.predict(CONTROL)
        assert_same_step(t, (mu, Sig), (f.x, f.P))
        mu, Sig = kf.ekf_update(mu, Sig, z, h, H_jac, UNI_Q, residual=range_bearing_residual)
        f.update(z, H_jac, h, residual=range_bearing_residual)
        assert_same_step(t, (mu, Sig), (f.x, f.P))


@pytest.mark.parametrize(
    ("lam", "vectorized"), [(0.0, True), (1.0, False)], ids=["lam=0-vectorized", "lam=1-per-point"]
)
def test_ukf_steps_agree_with_filterpy(unicycle_readings, lam, vectorized):
    points = JulierSigmaPoints(n=3, kappa=lam)  # spread n + kappa, as kfcourse's n + lam
    f = UnscentedKalmanFilter(
        dim_x=3,
        dim_z=2,
        dt=DT,
        hx=h,
        fx=lambda x, dt, u: kf.unicycle(x, u, dt),
        points=points,
        x_mean_fn=pose_mean,
        z_mean_fn=range_bearing_mean,
        residual_x=pose_residual,
        residual_z=range_bearing_residual,
    )
    f.Q, f.R = UNI_R, UNI_Q  # filterpy: Q process, R measurement
    f.x, f.P = UNI_MU0.copy(), UNI_SIG0.copy()
    mu, Sig = UNI_MU0, UNI_SIG0
    hooks = {"residual": range_bearing_residual, "mean": range_bearing_mean, "x_residual": pose_residual}
    for t, z in enumerate(unicycle_readings[:UKF_STEPS]):
        mu, Sig = kf.ukf_predict(
            mu, Sig, CONTROL, g, UNI_R, lam, residual=pose_residual, mean=pose_mean, vectorized=vectorized
        )
        f.predict(u=CONTROL)
        assert_same_step(t, (mu, Sig), (f.x, f.P))
        mu, Sig = kf.ukf_update(mu, Sig, z, h, UNI_Q, lam, vectorized=vectorized, **hooks)
        f.update(z)
        assert_same_step(t, (mu, Sig), (f.x, f.P))
