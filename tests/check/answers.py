"""Answers to the exercises written the way a student might write them, independently of the
checker's own wrong variants: right answers in another form than the package's, and wrong
answers, one per mistake, grouped by checker family (Bayes filter; linear Kalman filter and
fusion; nonlinear models; sigma points).  ``tests/check/test_check.py`` pairs each wrong
answer with the mistake its checker must name.

Noise letters: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np

import kfcourse as kf


# ----------------------------------------------------- right answers, written by hand
def hand_bayes_predict(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = (i + offset) % n if boundary == "wrap" else min(max(i + offset, 0), n - 1)
            out[j] += p * belief[i]
    return out


def hand_kf_step(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def hand_unicycle(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 1e-9:
        x, y = x + V * dt * math.cos(theta), y + V * dt * math.sin(theta)
    else:
        x = x + V / w * (math.sin(theta + w * dt) - math.sin(theta))
        y = y + V / w * (math.cos(theta) - math.cos(theta + w * dt))
    return np.array([x, y, math.atan2(math.sin(theta + w * dt), math.cos(theta + w * dt))])


def hand_sigma_points(mu, Sig, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    chi = [mu] + [mu + L[:, i] for i in range(n)] + [mu - L[:, i] for i in range(n)]
    w = [lam / (n + lam)] + [1 / (2 * (n + lam))] * (2 * n)
    return np.array(chi), np.array(w), np.array(w)


# ------------------------------------------------------ wrong answers, one per mistake
# Bayes filter: bayes_predict, bayes_update
def predict_backwards(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = (i - offset) % n if boundary == "wrap" else min(max(i - offset, 0), n - 1)  # wrong: minus
            out[j] += p * belief[i]
    return out


def predict_always_ring(belief, kernel, boundary="wall"):
    return sum(p * np.roll(belief, offset) for offset, p in kernel.items())  # wrong: ignores boundary


def predict_leaky(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = i + offset
            if boundary == "wrap":
                out[j % n] += p * belief[i]
            elif 0 <= j < n:  # wrong: what hits the wall is lost
                out[j] += p * belief[i]
    return out


def update_unnormalised(belief, likelihood):
    return np.multiply(likelihood, belief)  # wrong: no eta


# linear Kalman filter and fusion: kf_1d_step, fuse, kf_step
def kf_1d_swapped(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + Q  # wrong: Q in the predict step
    K = c * var_bar / (c**2 * var_bar + R)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_squares_noise(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R**2  # wrong: R is already a variance
    K = c * var_bar / (c**2 * var_bar + Q**2)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_a_once(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a * var + R  # wrong: a, not a squared
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def fuse_own_weights(mu1, var1, mu2, var2):
    return (var1 * mu1 + var2 * mu2) / (var1 + var2), 1 / (1 / var1 + 1 / var2)  # wrong: weights swapped


def fuse_squares(mu1, var1, mu2, var2):
    w1, w2 = 1 / var1**2, 1 / var2**2  # wrong: var1 and var2 are already variances
    return (w1 * mu1 + w2 * mu2) / (w1 + w2), 1 / (w1 + w2)


def fuse_adds(mu1, var1, mu2, var2):
    K = var1 / (var1 + var2)
    return mu1 + K * (mu2 - mu1), var1 + var2  # wrong: variances add in a predict, not in a fusion


def kf_step_swapped(mu, Sig, u, z, F, B, H, R, Q):
    return hand_kf_step(mu, Sig, u, z, F, B, H, Q, R)  # wrong: R and Q swapped


def kf_step_no_transpose(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F + R  # wrong: F^T
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_innovation_backwards(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (H @ mu_bar - z), (np.eye(len(mu)) - K @ H) @ Sig_bar  # wrong: H mu_bar - z


# nonlinear models: range_bearing, range_bearing_jacobian, unicycle
def range_bearing_unwrapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), np.arctan2(dy, dx) - state[2]])  # wrong: not wrapped


def range_bearing_atan(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), kf.wrap_angle(np.arctan(dy / dx) - state[2])])  # wrong: atan


def jacobian_robot_minus_landmark(state, landmark):
    dx, dy = state[0] - landmark[0], state[1] - landmark[1]  # wrong: robot minus landmark
    q = dx**2 + dy**2
    return np.array([[-dx / np.sqrt(q), -dy / np.sqrt(q), 0], [dy / q, -dx / q, -1]])


def jacobian_q_and_r_mixed(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    return np.array([[-dx / q, -dy / q, 0], [dy / np.sqrt(q), -dx / np.sqrt(q), -1]])  # wrong: q <-> sqrt(q)


def unicycle_no_limit(state, u, dt):
    x, y, theta = state
    V, w = u
    x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))  # wrong: no branch for w = 0
    y = y + V / w * (np.cos(theta) - np.cos(theta + w * dt))
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_no_limit_floats(state, u, dt):
    x, y, theta = map(float, state)
    V, w = map(float, u)
    x = x + V / w * (math.sin(theta + w * dt) - math.sin(theta))  # wrong: raises at w = 0
    y = y + V / w * (math.cos(theta) - math.cos(theta + w * dt))
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_unwrapped(state, u, dt):
    x, y, _ = hand_unicycle(state, u, dt)
    return np.array([x, y, state[2] + u[1] * dt])  # wrong: heading not wrapped


def unicycle_y_backwards(state, u, dt):
    x, y, theta = state
    V, w = u
    if w == 0:
        return hand_unicycle(state, u, dt)
    x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))
    y = y + V / w * (np.cos(theta + w * dt) - np.cos(theta))  # wrong: the cosines the other way round
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_euler(state, u, dt):
    x, y, theta = state
    V, w = u
    return np.array([x + V * dt * np.cos(theta), y + V * dt * np.sin(theta), kf.wrap_angle(theta + w * dt)])


# sigma points: sigma_points
def sigma_points_rows_of_L(mu, Sig, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + L, mu - L]), w, w  # wrong: rows of L, not columns


def sigma_points_no_root(mu, Sig, lam):
    n = len(mu)
    A = (n + lam) * Sig  # wrong: no square root
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + A.T, mu - A.T]), w, w


def sigma_points_weights_without_half(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    w = np.array([lam / (len(mu) + lam)] + [1 / (len(mu) + lam)] * (2 * len(mu)))  # wrong: no 1/2
    return chi, w, w


def sigma_points_columns(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    return chi.T, w, w  # wrong: one point per column


def sigma_points_symmetric_root(mu, Sig, lam):
    n = len(mu)
    vals, vecs = np.linalg.eigh((n + lam) * Sig)
    S = vecs @ np.diag(np.sqrt(vals)) @ vecs.T  # a square root, but not the Cholesky factor
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + S.T, mu - S.T]), w, w
