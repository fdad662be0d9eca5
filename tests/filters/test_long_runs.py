"""Long runs of the nonlinear filters: the EKF and the UKF keep Σ symmetric positive
semi-definite.

One run of 10^5 steps per filter on a pendulum observed through the sine of its angle
(two states, cheap enough for 10^5 steps), and shorter runs of a unicycle robot that
drives a circle and reads range and bearing to one landmark, with the noise scaled so
that R/Q runs from 1e-8 to 1e8 (the angle hooks of both filters in use).  Every few steps the
result is checked for what a forced symmetrisation cannot fake: it is PSD, the update
took uncertainty away (Σ̄ - Σ is PSD), and for the EKF it equals the textbook update
written out here in plain numpy.  (The linear filter's long runs, with a NEES check, are in
``test_kalman.py``.)

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual

pytestmark = pytest.mark.slow  # 10^5 steps: make test runs them once, make check leaves them out

DT = 0.1  # s
LANDMARK = np.array([5.0, 3.0])  # m
CONTROL = np.array([1.0, 0.2])  # [V (m/s), omega (rad/s)]: a circle of radius 5 m
R0 = np.diag([1e-3, 1e-3, 1e-4])  # process noise at R/Q = 1 (m², m², rad²)
Q0 = np.diag([0.01, 0.0025])  # measurement noise at R/Q = 1 (m², rad²)
MU0 = np.array([0.0, 0.0, 0.0])
SIG0 = np.diag([0.1, 0.1, 0.05])
LAM = 0.0  # UKF spread: n + lam = 3

N_LONG = 10**5
N_SHORT = 1000
RATIOS = [1e-8, 1e-4, 1.0, 1e4, 1e8]

g = partial(kf.unicycle, dt=DT)
G = partial(kf.unicycle_jacobian, dt=DT)
h = partial(kf.range_bearing, landmark=LANDMARK)
H_jac = partial(kf.range_bearing_jacobian, landmark=LANDMARK)


# ================================================================ properties (the only section: long runs)
def simulate(ratio: float, n_steps: int, seed: int = 4242):
    """Noise matrices for R/Q = ratio and seeded readings of a robot driven by the same model.

    The true path is written out in plain math (the unicycle's arc in chord form), which is
    both an independent copy of the model and cheap enough for 10^5 steps.
    """
    s = math.sqrt(ratio)
    R, Q = s * R0, Q0 / s
    rng = np.random.default_rng(seed)
    w = rng.multivariate_normal(np.zeros(3), R, n_steps).tolist()
    V, omega = CONTROL
    half = 0.5 * omega * DT
    chord = V * DT * math.sin(half) / half  # V dt sinc(omega dt / 2)
    x, y, th = MU0
    truth = np.empty((n_steps, 3))
    for t in range(n_steps):
        x, y, th = x + chord * math.cos(th + half) + w[t][0], y + chord * math.sin(th + half) + w[t][1], th
        th = math.remainder(th + omega * DT + w[t][2], 2 * math.pi)
        truth[t] = x, y, th
    dx, dy = LANDMARK[0] - truth[:, 0], LANDMARK[1] - truth[:, 1]
    zs = np.column_stack([np.hypot(dx, dy), np.arctan2(dy, dx) - truth[:, 2]])
    zs += rng.multivariate_normal(np.zeros(2), Q, n_steps)
    zs[:, 1] = np.remainder(zs[:, 1] + math.pi, 2 * math.pi) - math.pi  # bearings in [-pi, pi)
    return R, Q, zs


def assert_psd(Sig: np.ndarray, what: str) -> None:
    assert np.all(np.isfinite(Sig)), what
    assert np.linalg.eigvalsh(Sig)[0] >= -1e-12 * np.abs(Sig).max(), (what, np.linalg.eigvalsh(Sig))


def assert_update_shrinks(Sig_bar: np.ndarray, Sig: np.ndarray, what: str) -> None:
    """Sig_bar - Sig = K S K^T is PSD: an update never adds uncertainty."""
    assert np.linalg.eigvalsh(Sig_bar - Sig)[0] >= -1e-9 * np.abs(Sig_bar).max(), what


def textbook_ekf_update(mu_bar, Sig_bar, z, Q):
    """The lesson's EKF update in plain numpy: no Joseph form, no symmetrisation."""
    Hx = H_jac(mu_bar)
    y = z - h(mu_bar)
    y[1] = math.remainder(y[1], 2 * math.pi)  # the short way round
    K = Sig_bar @ Hx.T @ np.linalg.inv(Hx @ Sig_bar @ Hx.T + Q)
    return mu_bar + K @ y, (np.eye(3) - K @ Hx) @ Sig_bar


def run_ekf(ratio: float, n_steps: int, check_every: int) -> None:
    R, Q, zs = simulate(ratio, n_steps)
    mu, Sig = MU0, SIG0
    for t in range(n_steps):
        mu_bar, Sig_bar = kf.ekf_predict(mu, Sig, CONTROL, g, G, R)
        mu, Sig = kf.ekf_update(mu_bar, Sig_bar, zs[t], h, H_jac, Q, residual=range_bearing_residual)
        if (t + 1) % check_every == 0:
            what = f"R/Q={ratio:g}, step {t}"
            assert np.array_equal(Sig, Sig.T), what
            assert_psd(Sig, what)
            assert_update_shrinks(Sig_bar, Sig, what)
            mu_tb, Sig_tb = textbook_ekf_update(mu_bar, Sig_bar, zs[t], Q)
            d = np.sqrt(np.diag(Sig_tb))  # compare in correlation units: entries differ in scale
            np.testing.assert_array_less(np.abs(Sig - Sig_tb), 1e-6 * np.outer(d, d) + 1e-300, what)
            np.testing.assert_allclose(mu, mu_tb, rtol=0, atol=1e-6 * (1 + np.abs(mu_tb).max()), err_msg=what)
    assert np.all(np.isfinite(mu))


def run_ukf(ratio: float, n_steps: int, check_every: int) -> None:
    R, Q, zs = simulate(ratio, n_steps)
    mu, Sig = MU0, SIG0
    z_hooks = {"residual": range_bearing_residual, "mean": range_bearing_mean, "x_residual": pose_residual}
    for t in range(n_steps):
        mu_bar, Sig_bar = kf.ukf_predict(mu, Sig, CONTROL, g, R, LAM, residual=pose_residual, mean=pose_mean)
        mu, Sig = kf.ukf_update(mu_bar, Sig_bar, zs[t], h, Q, LAM, **z_hooks)
        if (t + 1) % check_every == 0:
            what = f"R/Q={ratio:g}, step {t}"
            assert np.array_equal(Sig, Sig.T), what
            assert_psd(Sig_bar, what)
            assert_psd(Sig, what)
            assert_update_shrinks(Sig_bar, Sig, what)
    assert np.all(np.isfinite(mu))


# ---------------------------------------------------------------- the 10^5-step runs: a pendulum
PEND_DT = 0.05  # s
PEND_W2 = 4.0  # g / L, 1/s²
PEND_R = np.diag([1e-6, 1e-4])  # process noise (rad², rad²/s²)
PEND_Q = np.array([[0.01]])  # measurement noise of sin(angle)
PEND_MU0 = np.array([0.5, 0.0])  # angle (rad), angular velocity (rad/s)
PEND_SIG0 = np.diag([0.1, 0.1])


def pend_g(x, u):
    """One Euler step of theta'' = -(g/L) sin theta; x is (2,) or a stack (N, 2)."""
    th, om = x[..., 0], x[..., 1]
    return np.stack([th + om * PEND_DT, om - PEND_W2 * np.sin(th) * PEND_DT], axis=-1)


def pend_G(x, u):
    return np.array([[1.0, PEND_DT], [-PEND_W2 * math.cos(x[0]) * PEND_DT, 1.0]])


def pend_h(x):
    return np.sin(x[..., :1])  # the bob's horizontal offset over L


def pend_H(x):
    return np.array([[math.cos(x[0]), 0.0]])


def pendulum_readings(n_steps: int, seed: int = 777) -> np.ndarray:
    rng = np.random.default_rng(seed)
    w = rng.multivariate_normal(np.zeros(2), PEND_R, n_steps).tolist()
    v = rng.normal(0.0, math.sqrt(PEND_Q[0, 0]), n_steps)
    th, om = PEND_MU0
    zs = np.empty((n_steps, 1))
    for t in range(n_steps):
        th, om = th + om * PEND_DT + w[t][0], om - PEND_W2 * math.sin(th) * PEND_DT + w[t][1]
        zs[t, 0] = math.sin(th) + v[t]
    return zs


def test_ekf_covariance_stays_psd_over_1e5_steps():
    zs = pendulum_readings(N_LONG)
    mu, Sig = PEND_MU0, PEND_SIG0
    for t in range(N_LONG):
        mu_bar, Sig_bar = kf.ekf_predict(mu, Sig, None, pend_g, pend_G, PEND_R)
        mu, Sig = kf.ekf_update(mu_bar, Sig_bar, zs[t], pend_h, pend_H, PEND_Q)
        if (t + 1) % 1000 == 0:
            what = f"step {t}"
            assert np.array_equal(Sig, Sig.T), what
            assert_psd(Sig, what)
            assert_update_shrinks(Sig_bar, Sig, what)
            # the textbook update from the same prior, in plain numpy
            Hx = pend_H(mu_bar)
            K = Sig_bar @ Hx.T / (Hx @ Sig_bar @ Hx.T + PEND_Q)
            Sig_tb = (np.eye(2) - K @ Hx) @ Sig_bar
            d = np.sqrt(np.diag(Sig_tb))
            np.testing.assert_array_less(np.abs(Sig - Sig_tb), 1e-6 * np.outer(d, d) + 1e-300, what)
            np.testing.assert_allclose(mu, mu_bar + K[:, 0] * (zs[t, 0] - math.sin(mu_bar[0])), atol=1e-9)
    assert np.all(np.isfinite(mu))


def test_ukf_covariance_stays_psd_over_1e5_steps():
    zs = pendulum_readings(N_LONG)
    mu, Sig = PEND_MU0, PEND_SIG0
    for t in range(N_LONG):
        mu_bar, Sig_bar = kf.ukf_predict(mu, Sig, None, pend_g, PEND_R, 1.0)
        mu, Sig = kf.ukf_update(mu_bar, Sig_bar, zs[t], pend_h, PEND_Q, 1.0)
        if (t + 1) % 1000 == 0:
            what = f"step {t}"
            assert np.array_equal(Sig, Sig.T), what
            assert_psd(Sig_bar, what)
            assert_psd(Sig, what)
            assert_update_shrinks(Sig_bar, Sig, what)
    assert np.all(np.isfinite(mu))


# ---------------------------------------------------------------- shorter runs over R/Q: a unicycle
@pytest.mark.parametrize("ratio", RATIOS, ids=lambda r: f"R/Q={r:g}")
def test_ekf_covariance_stays_psd_over_noise_ratios(ratio):
    run_ekf(ratio, N_SHORT, 50)


@pytest.mark.parametrize("ratio", RATIOS, ids=lambda r: f"R/Q={r:g}")
def test_ukf_covariance_stays_psd_over_noise_ratios(ratio):
    run_ukf(ratio, N_SHORT, 50)
