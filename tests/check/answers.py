"""Answers to the exercises written the way a student might write them, independently of the
checker's own wrong variants: right answers in another form than the package's, and wrong
answers, one per mistake, grouped by checker family (Bayes filter; linear Kalman filter and
fusion; nonlinear models; sigma points and the unscented transform).  ``tests/check/test_check.py`` pairs each wrong
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


def kf_step_forgets_F_in_mean(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = mu + B @ u  # wrong: F mu, not mu
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def hand_sigma_points(mu, Sig, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    chi = [mu] + [mu + L[:, i] for i in range(n)] + [mu - L[:, i] for i in range(n)]
    w = [lam / (n + lam)] + [1 / (2 * (n + lam))] * (2 * n)
    return np.array(chi), np.array(w), np.array(w)


def lesson_H_analytic(state, m):
    x, y, _ = state
    dx, dy = m[0] - x, m[1] - y
    q = dx * dx + dy * dy
    r = np.sqrt(q)
    return np.array([[-dx / r, -dy / r, 0], [dy / q, -dx / q, -1]])


def jacobian_by_angles(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    r, a = math.hypot(dx, dy), math.atan2(dy, dx)
    return np.array([[-math.cos(a), -math.sin(a), 0.0], [math.sin(a) / r, -math.cos(a) / r, -1.0]])


def sigma_points_interleaved(mu, Sig, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    chi, w = [mu], [lam / (n + lam)]
    for i in range(n):  # mu + L_i, mu - L_i, one pair after the other, and the minus point first
        chi += [mu - L[:, i], mu + L[:, i]]
        w += [1 / (2 * (n + lam))] * 2
    return np.array(chi), np.array(w), np.array(w)


def sigma_points_centre_last(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    order = [*range(1, len(w)), 0]
    return chi[order], w[order], w[order]


def hand_unscented_transform(mu, Sig, f, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    points = [mu] + [mu + L[:, i] for i in range(n)] + [mu - L[:, i] for i in range(n)]
    weights = [lam / (n + lam)] + [1 / (2 * (n + lam))] * (2 * n)
    ys = [f(p) for p in points]  # one point at a time
    mu_y = sum(w * y for w, y in zip(weights, ys, strict=True))
    Sig_y = sum(w * np.outer(y - mu_y, y - mu_y) for w, y in zip(weights, ys, strict=True))
    return mu_y, Sig_y


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


def update_by_largest(belief, likelihood):
    bel = np.multiply(likelihood, belief)
    return bel / bel.max()  # wrong: eta is one over the sum


def update_adds(belief, likelihood):
    bel = np.add(likelihood, belief)  # wrong: Bayes multiplies
    return bel / bel.sum()


def predict_overwrites(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = (i + offset) % n if boundary == "wrap" else min(max(i + offset, 0), n - 1)
            out[j] = p * belief[i]  # wrong: = instead of +=
    return out


def predict_stays_put_at_wall(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = i + offset
            if boundary == "wrap":
                j = j % n
            elif not 0 <= j < n:
                j = i  # wrong: the robot stops at the wall, in the end cell
            out[j] += p * belief[i]
    return out


def predict_leaky_renormalised(belief, kernel, boundary="wall"):
    out = predict_leaky(belief, kernel, boundary)
    return out / out.sum()  # wrong: the lost mass is spread over every cell


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


def kf_1d_forgets_R(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var  # wrong: + R missing
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_forgets_Q(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar)  # wrong: + Q missing
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_forgets_bu(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu, a**2 * var + R  # wrong: + b u missing
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_gain_from_var(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var / (c**2 * var + Q)  # wrong: var, not var_bar
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_innovation_from_mu(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu), (1 - K * c) * var_bar  # wrong: mu, not mu_bar


def kf_1d_forgets_c_in_innovation(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - mu_bar), (1 - K * c) * var_bar  # wrong: z - mu_bar, not z - c mu_bar


def kf_1d_R_scaled_by_a(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + a * R  # wrong: R scaled by a
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_var_with_fixed_Q(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - c * c * var_bar / (c * c * var_bar + 0.1)) * var_bar  # wrong: Q = 0.1


def kf_1d_R_in_gain_too(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar + Q + R)  # wrong: R in the gain too
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_update_from_var(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var  # wrong: var, not var_bar


def kf_1d_gain_for_c_one(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = var_bar / (var_bar + Q)  # wrong: the c = 1 gain of chapter 4
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_innovation_backwards(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (c * mu_bar - z), (1 - K * c) * var_bar  # wrong: c mu_bar - z


def kf_1d_sqrt_noise(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + math.sqrt(R)  # wrong: R is already a variance
    K = c * var_bar / (c**2 * var_bar + math.sqrt(Q))
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def fuse_plain_average(mu1, var1, mu2, var2):
    return (mu1 + mu2) / 2, 1 / (1 / var1 + 1 / var2)  # wrong: a plain average of the means


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


def _kf_parts(mu, Sig, u, z, F, B, H, R, Q):
    """The right predict step and S: most wrong answers below get these right."""
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    return mu_bar, Sig_bar, H @ Sig_bar @ H.T + Q


def kf_step_forgets_R(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T  # wrong: + R missing
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_forgets_Bu(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu  # wrong: + B u missing
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_S_without_Q(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, _ = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    S = H @ Sig_bar @ H.T  # wrong: + Q missing
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_gain_from_Sig(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig @ H.T @ np.linalg.inv(S)  # wrong: Sig, not Sig_bar
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_gain_and_S_from_Sig(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, _ = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig @ H.T @ np.linalg.inv(H @ Sig @ H.T + Q)  # wrong: Sig, not Sig_bar, twice
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_innovation_from_mu(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu), (np.eye(len(mu)) - K @ H) @ Sig_bar  # wrong: H mu


def kf_step_update_from_Sig(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig  # wrong: Sig, not Sig_bar


def kf_step_no_inverse(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H.T @ S  # wrong: S, not its inverse
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_one_over_S(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H.T @ (1 / S)  # wrong: 1/S inverts each entry
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_update_on_the_right(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), Sig_bar @ (np.eye(len(mu)) - K @ H)  # wrong: on the right


def kf_step_plus_KH(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) + K @ H) @ Sig_bar  # wrong: I + K H


def kf_step_gain_without_HT(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar, Sig_bar, S = _kf_parts(mu, Sig, u, z, F, B, H, R, Q)
    K = Sig_bar @ H @ np.linalg.inv(S)  # wrong: H, not H.T (raises unless k = n)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_transpose_on_the_left(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F.T @ Sig @ F + R  # wrong: F^T on the left
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_row_vector(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = mu @ F + B @ u  # wrong: mu @ F is F^T mu
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_swapped_with_solve(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + Q  # wrong: Q in the predict step ...
    S = H @ Sig_bar @ H.T + R  # ... and R in S
    K = np.linalg.solve(S, H @ Sig_bar).T  # S is symmetric: K^T = S^-1 H Sig_bar
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


# nonlinear models: range_bearing, range_bearing_jacobian, unicycle
def range_bearing_unwrapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), np.arctan2(dy, dx) - state[2]])  # wrong: not wrapped


def range_bearing_atan(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), kf.wrap_angle(np.arctan(dy / dx) - state[2])])  # wrong: atan


def range_bearing_atan2_swapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), kf.wrap_angle(np.arctan2(dx, dy) - state[2])])  # wrong: (dx, dy)


def range_bearing_robot_minus_landmark(state, landmark):
    dx, dy = state[0] - landmark[0], state[1] - landmark[1]  # wrong: robot minus landmark
    return np.array([np.hypot(dx, dy), kf.wrap_angle(np.arctan2(dy, dx) - state[2])])


def range_bearing_shifted_wrap(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), (np.arctan2(dy, dx) - state[2]) % (2 * np.pi) - np.pi])  # wrong: turned by pi


def range_bearing_plus_theta(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), kf.wrap_angle(np.arctan2(dy, dx) + state[2])])  # wrong: + theta


def range_bearing_heading_minus_direction(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), kf.wrap_angle(state[2] - np.arctan2(dy, dx))])  # wrong: theta - atan2


def range_bearing_degrees(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), np.degrees(kf.wrap_angle(np.arctan2(dy, dx) - state[2]))])  # wrong: degrees


def range_bearing_mod_2pi(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), (np.arctan2(dy, dx) - state[2]) % (2 * np.pi)])  # wrong: [0, 2 pi)


def range_bearing_squared_range(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([dx**2 + dy**2, kf.wrap_angle(np.arctan2(dy, dx) - state[2])])  # wrong: q, not sqrt(q)


def range_bearing_bearing_first(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([kf.wrap_angle(np.arctan2(dy, dx) - state[2]), np.hypot(dx, dy)])  # wrong: [phi, r]


def jacobian_numeric(state, landmark):
    return kf.numeric_jacobian(lambda s: kf.range_bearing(s, landmark), state)  # wrong: not derived


def jacobian_lesson_finite_differences(state, m, eps=1e-6):
    J = np.zeros((2, 3))
    for i in range(3):  # wrong: the chapter's finite-difference check, not the derivation
        s1 = np.array(state, float)
        s1[i] += eps
        s0 = np.array(state, float)
        s0[i] -= eps
        J[:, i] = (kf.range_bearing(s1, m) - kf.range_bearing(s0, m)) / (2 * eps)
    return J


def jacobian_bearing_row_flipped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    return np.array([[-dx / np.sqrt(q), -dy / np.sqrt(q), 0], [-dy / q, dx / q, -1]])  # wrong: -dy/q, dx/q


def jacobian_range_row_flipped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    return np.array([[dx / np.sqrt(q), dy / np.sqrt(q), 0], [dy / q, -dx / q, -1]])  # wrong: +dx/r, +dy/r


def jacobian_r_in_bearing_row(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    r = np.hypot(dx, dy)
    return np.array([[-dx / r, -dy / r, 0], [dy / r, -dx / r, -1]])  # wrong: r, not q = r^2


def jacobian_q_in_range_row(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    return np.array([[-dx / q, -dy / q, 0], [dy / q, -dx / q, -1]])  # wrong: q, not sqrt(q)


def jacobian_dx_dy_swapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    r = np.sqrt(q)
    return np.array([[-dy / r, -dx / r, 0], [dx / q, -dy / q, -1]])  # wrong: dx and dy swapped


def jacobian_no_theta(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    r = np.sqrt(q)
    return np.array([[-dx / r, -dy / r, 0], [dy / q, -dx / q, 0]])  # wrong: d(phi)/d(theta) = -1


def jacobian_plus_one_theta(state, landmark):
    H = lesson_H_analytic(state, landmark)
    H[1, 2] = 1.0  # wrong: the bearing falls as theta grows
    return H


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


def unicycle_straight_below_1e_6(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 1e-6:  # right: below about 1e-6 the arc formula loses digits, above it is exact
        return np.array([x + V * dt * math.cos(theta), y + V * dt * math.sin(theta), kf.wrap_angle(theta + w * dt)])
    return hand_unicycle(state, u, dt)


def unicycle_straight_too_wide(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 0.02:  # wrong: a slow turn is driven as a straight line
        return np.array([x + V * dt * math.cos(theta), y + V * dt * math.sin(theta), kf.wrap_angle(theta + w * dt)])
    return hand_unicycle(state, u, dt)


def unicycle_unwrapped(state, u, dt):
    x, y, _ = hand_unicycle(state, u, dt)
    return np.array([x, y, state[2] + u[1] * dt])  # wrong: heading not wrapped


def unicycle_y_backwards(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 1e-9:
        return hand_unicycle(state, u, dt)
    x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))
    y = y + V / w * (np.cos(theta + w * dt) - np.cos(theta))  # wrong: the cosines the other way round
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_exact_zero_test(state, u, dt):
    x, y, theta = state
    V, w = u
    if w == 0:  # wrong: a tiny w still goes through V / w
        x, y = x + V * dt * np.cos(theta), y + V * dt * np.sin(theta)
    else:
        x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))
        y = y + V / w * (np.cos(theta) - np.cos(theta + w * dt))
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_exact_zero_test_math(state, u, dt):
    x, y, theta = map(float, state)
    V, w = map(float, u)
    if w == 0.0:  # wrong: a tiny w still goes through V / w
        return np.array([x + V * dt * math.cos(theta), y + V * dt * math.sin(theta), kf.wrap_angle(theta)])
    x_new = x + V / w * (math.sin(theta + w * dt) - math.sin(theta))
    y_new = y + V / w * (math.cos(theta) - math.cos(theta + w * dt))
    return np.array([x_new, y_new, kf.wrap_angle(theta + w * dt)])


def unicycle_sin_cos_swapped(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 1e-9:
        x, y = x + V * dt * np.sin(theta), y + V * dt * np.cos(theta)  # wrong: sin for x, cos for y
    else:
        x = x + V / w * (np.cos(theta) - np.cos(theta + w * dt))  # wrong: y's bracket
        y = y + V / w * (np.sin(theta + w * dt) - np.sin(theta))  # wrong: x's bracket
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_heading_without_dt(state, u, dt):
    x, y, _ = hand_unicycle(state, u, dt)
    return np.array([x, y, kf.wrap_angle(state[2] + u[1])])  # wrong: omega, not omega dt


def unicycle_speed_not_distance(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 1e-9:
        x, y = x + V * np.cos(theta), y + V * np.sin(theta)  # wrong: V, not V dt
    else:
        x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))
        y = y + V / w * (np.cos(theta) - np.cos(theta + w * dt))
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


def sigma_points_unscaled(mu, Sig, lam):
    L = np.linalg.cholesky(Sig)  # wrong: the (n + lam) is missing
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + L.T, mu - L.T]), w, w


def sigma_points_outer_weights_half_n(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    n = len(mu)
    w = np.array([lam / (n + lam)] + [1 / (2 * n)] * (2 * n))  # wrong: 1/(2n), lam forgotten
    return chi, w, w


def sigma_points_entrywise_sqrt(mu, Sig, lam):
    n = len(mu)
    S = np.sqrt((n + lam) * Sig)  # wrong: the root of each entry
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + S.T, mu - S.T]), w, w


def sigma_points_with_beta(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    wc = w.copy()
    wc[0] += 2.0  # wrong: the scaled transform's beta = 2, not used here
    return chi, w, wc


# unscented transform: unscented_transform
def unscented_points_not_through_f(mu, Sig, f, lam):
    chi, wm, wc = kf.sigma_points(mu, Sig, lam)
    Y = chi  # wrong: f is never applied
    mu_y = wm @ Y
    return mu_y, (wc[:, None] * (Y - mu_y)).T @ (Y - mu_y)


def unscented_mean_not_subtracted(mu, Sig, f, lam):
    chi, wm, wc = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    return wm @ Y, (wc[:, None] * Y).T @ Y  # wrong: Y, not Y - mu_y


def unscented_deviations_from_centre(mu, Sig, f, lam):
    chi, wm, wc = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    D = Y - f(mu)  # wrong: deviations from the centre point's image, not from the mean
    return wm @ Y, (wc[:, None] * D).T @ D


def unscented_plain_average(mu, Sig, f, lam):
    chi, _, _ = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    mu_y = Y.mean(axis=0)  # wrong: every point weighs 1/(2n + 1)
    return mu_y, (Y - mu_y).T @ (Y - mu_y) / len(Y)


def unscented_np_cov(mu, Sig, f, lam):
    chi, wm, _ = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    return wm @ Y, np.atleast_2d(np.cov(Y.T))  # wrong: np.cov ignores the weights


def unscented_inner_product(mu, Sig, f, lam):
    chi, wm, wc = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    mu_y = wm @ Y
    Sig_y = sum(w * ((y - mu_y) @ (y - mu_y)) for w, y in zip(wc, Y, strict=True))  # wrong: d^T d, a number
    return mu_y, Sig_y


def unscented_unscaled_points(mu, Sig, f, lam):
    L = np.linalg.cholesky(Sig)  # wrong: (n + lam) is missing
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    _, wm, wc = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    mu_y = wm @ Y
    return mu_y, (wc[:, None] * (Y - mu_y)).T @ (Y - mu_y)


def unscented_mean_at_mu(mu, Sig, f, lam):
    chi, _, wc = kf.sigma_points(mu, Sig, lam)
    Y = f(chi)
    mu_y = f(mu)  # wrong: the EKF's mean
    return mu_y, (wc[:, None] * (Y - mu_y)).T @ (Y - mu_y)
