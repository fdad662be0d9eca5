"""Answers to the exercises of chapters 0, 2, 6 and 10, written the way a student might write them,
independently of the checkers' own wrong versions: a right answer in another form than the
package's, and wrong answers, one per mistake of each checker's catalogue.
``tests/check/test_new_exercises.py`` pairs each wrong answer with the mistake its checker must name.

Noise letters: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np

import kfcourse as kf


# ------------------------------------------------------------- chapter 0: drift_sigma
def drift_sigma(step_std, n):
    return step_std * np.sqrt(n)


def drift_linear(step_std, n):
    return step_std * np.asarray(n)  # wrong: n, not sqrt(n)


def drift_variance(step_std, n):
    return n * step_std**2  # wrong: the variance


def drift_divides(step_std, n):
    return step_std / np.sqrt(n)  # wrong: divides


def drift_counts_start(step_std, n):
    return step_std * np.sqrt(np.asarray(n) + 1)  # wrong: one step too many


def drift_math_sqrt(step_std, n):
    return step_std * math.sqrt(n)  # wrong: one number of steps only


def drift_root_of_wrong_thing(step_std, n):
    return np.sqrt(step_std * np.asarray(n))  # wrong: the root of sigma n, not of n sigma^2


def drift_loop(step_std, n):
    """Adds the variances one step at a time, but starts counting at 1."""
    out = []
    for steps in np.atleast_1d(n):
        var = 0.0
        for _ in range(1, int(steps)):  # wrong: n - 1 steps
            var += step_std**2
        out.append(math.sqrt(var))
    return out[0] if np.ndim(n) == 0 else np.array(out)


# ------------------------------------------------------- chapter 2: affine_gaussian
def affine_gaussian(mu, Sig, A, b):
    mu_y = np.dot(A, mu) + b
    Sig_y = np.einsum("ij,jk,lk->il", A, Sig, A)
    return mu_y, Sig_y


def affine_half(mu, Sig, A, b):
    return A @ mu + b, A @ Sig  # wrong: A Sig


def affine_scalar_thinking(mu, Sig, A, b):
    return A @ mu + b, A * Sig  # wrong: the variance times A, as if in 1-D


def affine_star(mu, Sig, A, b):
    return A @ mu + b, A * Sig * A.T  # wrong: * where @ belongs (right only in 1-D)


def affine_no_transpose(mu, Sig, A, b):
    return A @ mu + b, A @ Sig @ A  # wrong: A Sig A


def affine_transpose_first(mu, Sig, A, b):
    return A @ mu + b, A.T @ Sig @ A  # wrong: A^T Sig A


def affine_b_everywhere(mu, Sig, A, b):
    return A @ mu + b, A @ Sig @ A.T + b  # wrong: b in the covariance


def affine_no_b(mu, Sig, A, b):
    return A @ mu, A @ Sig @ A.T  # wrong: b forgotten


# ----------------------------------------------------------- chapter 6: cv_model
def cv_model(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    G = np.array([[dt**2 / 2, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])
    return F, accel_var * G @ G.T


def cv_no_half(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    G = np.array([[dt**2, 0], [0, dt**2], [dt, 0], [0, dt]])  # wrong: no 1/2
    return F, accel_var * G @ G.T


def cv_dt_for_position(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    G = np.array([[dt / 2, 0], [0, dt / 2], [dt, 0], [0, dt]])  # wrong: dt, not dt^2
    return F, accel_var * G @ G.T


def cv_diagonal(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    R = accel_var * np.diag([dt**4 / 4, dt**4 / 4, dt**2, dt**2])  # wrong: no cross terms
    return F, R


def cv_interleaved(dt, accel_var):
    """The state [px, vx, py, vy]: one axis after the other."""
    F1 = np.array([[1, dt], [0, 1]])
    R1 = accel_var * np.array([[dt**4 / 4, dt**3 / 2], [dt**3 / 2, dt**2]])
    return np.kron(np.eye(2), F1), np.kron(np.eye(2), R1)  # wrong order of the state


def cv_F_transposed(dt, accel_var):
    F = np.eye(4)
    F[2, 0] = F[3, 1] = dt  # wrong: below the diagonal
    return F, kf.sim.process_noise(dt, accel_var)


def cv_sigma_a(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    G = np.array([[dt**2 / 2, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])
    return F, np.sqrt(accel_var) * G @ G.T  # wrong: sigma_a, not sigma_a^2


# ------------------------------------------------------ chapter 10: localization step
def localization_step(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Predict, then gate and update with each reading; right, written out by hand."""
    G = kf.unicycle_jacobian(mu, u, dt)
    W = kf.unicycle_control_jacobian(mu, u, dt)
    mu = kf.unicycle(mu, u, dt)
    Sig = G @ Sig @ G.T + W @ M @ W.T
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = kf.range_bearing_jacobian(mu, landmarks[j])
        nu = z[j] - kf.range_bearing(mu, landmarks[j])
        nu[1] = kf.wrap_angle(nu[1])
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.inv(S) @ nu > gate**2:
            continue
        K = Sig @ H.T @ np.linalg.inv(S)
        mu = mu + K @ nu
        mu[2] = kf.wrap_angle(mu[2])
        Sig = (np.eye(3) - K @ H) @ Sig
        used[j] = True
    return mu, Sig, used


def localization_with_package_steps(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Right, with the package's EKF steps and mahalanobis."""
    R = kf.sim.process_noise_of_odometry(mu, u, dt, M)
    mu, Sig = kf.ekf_predict(
        mu, Sig, u, lambda x, c: kf.unicycle(x, c, dt), lambda x, c: kf.unicycle_jacobian(x, c, dt), R
    )
    used = []
    for z_j, m in zip(z, landmarks, strict=True):
        H = kf.range_bearing_jacobian(mu, m)
        nu = kf.models.range_bearing_residual(z_j, kf.range_bearing(mu, m))
        ok = kf.mahalanobis(nu, H @ Sig @ H.T + Q) <= gate
        if ok:
            h, Hf = (lambda x, m=m: kf.range_bearing(x, m)), (lambda x, m=m: kf.range_bearing_jacobian(x, m))
            mu, Sig = kf.ekf_update(mu, Sig, z_j, h, Hf, Q, kf.models.range_bearing_residual)
            mu[2] = kf.wrap_angle(mu[2])
        used.append(ok)
    return mu, Sig, np.array(used, dtype=bool)


def _student_step(mu, Sig, u, z, landmarks, dt, M, Q, gate, **bug):
    """The right step above with one bug switched on: each wrong answer below names its own."""
    G = kf.unicycle_jacobian(mu, u, dt)
    W = kf.unicycle_control_jacobian(mu, u, dt)
    if bug.get("blind_skips") and len(z) == 0:
        return mu, Sig, np.zeros(0, dtype=bool)
    mu_bar = kf.unicycle(mu, u, dt)
    R = {"right": W @ M @ W.T, "none": 0, "M": M}[bug.get("R", "right")]
    Sig_bar = G @ Sig @ G.T + R
    mu, Sig = mu_bar, Sig_bar
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        at = mu_bar if bug.get("stale") else mu
        H = kf.range_bearing_jacobian(at, landmarks[j])
        nu = z[j] - kf.range_bearing(at, landmarks[j])
        if bug.get("innovation_backwards"):
            nu = -nu  # h(mu) - z
        if not bug.get("no_wrap"):
            nu[1] = kf.wrap_angle(nu[1])
        S = H @ Sig @ H.T + (0 if bug.get("no_Q") in ("both", "gate") else Q)
        d2 = nu @ np.linalg.inv(S) @ nu
        tests = {"d2": d2 > gate**2, "d2 vs gate": d2 > gate, "S not inverted": nu @ S @ nu > gate**2, "none": False}
        refused = tests[bug.get("gate_test", "d2")]
        if refused:
            continue
        S = H @ Sig @ H.T + (0 if bug.get("no_Q") in ("both", "update") else Q)
        K = Sig @ H.T @ np.linalg.inv(S)
        mu = mu + K @ nu
        if not bug.get("heading_unwrapped"):
            mu[2] = kf.wrap_angle(mu[2])
        Sig = (np.eye(3) - K @ H) @ Sig
        used[j] = True
    if bug.get("all_used"):
        used = np.ones(len(z), dtype=bool)
    return mu, Sig, used


def localization_M_and_Q_swapped(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    return localization_step(mu, Sig, u, z, landmarks, dt, Q, M, gate)  # wrong: the two noises swapped


def localization_innovation_backwards(*args):
    return _student_step(*args, innovation_backwards=True)


def localization_jacobians_at_mu_bar(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu_bar = kf.unicycle(mu, u, dt)
    G, W = kf.unicycle_jacobian(mu_bar, u, dt), kf.unicycle_control_jacobian(mu_bar, u, dt)  # wrong: at mu_bar
    return localization_step(mu_bar, G @ Sig @ G.T + W @ M @ W.T, np.zeros(2), z, landmarks, dt, 0 * M, Q, gate)


def localization_forgets_used(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    G = kf.unicycle_jacobian(mu, u, dt)
    W = kf.unicycle_control_jacobian(mu, u, dt)
    mu, Sig = kf.unicycle(mu, u, dt), G @ Sig @ G.T + W @ M @ W.T
    used = np.zeros(len(z), dtype=bool)  # wrong: never set to True below
    for z_j, m in zip(z, landmarks, strict=True):
        H = kf.range_bearing_jacobian(mu, m)
        nu = kf.models.range_bearing_residual(z_j, kf.range_bearing(mu, m))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            K = Sig @ H.T @ np.linalg.inv(S)
            mu = mu + K @ nu
            mu[2] = kf.wrap_angle(mu[2])
            Sig = (np.eye(3) - K @ H) @ Sig
    return mu, Sig, used


def localization_restarts_from_prediction(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    G = kf.unicycle_jacobian(mu, u, dt)
    W = kf.unicycle_control_jacobian(mu, u, dt)
    mu_bar, Sig_bar = kf.unicycle(mu, u, dt), G @ Sig @ G.T + W @ M @ W.T
    mu, Sig = mu_bar, Sig_bar
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = kf.range_bearing_jacobian(mu_bar, landmarks[j])
        nu = kf.models.range_bearing_residual(z[j], kf.range_bearing(mu_bar, landmarks[j]))
        S = H @ Sig_bar @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            K = Sig_bar @ H.T @ np.linalg.inv(S)
            mu = mu_bar + K @ nu  # wrong: every reading starts again from the prediction
            mu[2] = kf.wrap_angle(mu[2])
            Sig = (np.eye(3) - K @ H) @ Sig_bar
            used[j] = True
    return mu, Sig, used


def localization_ekf_predict_with_M(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    g = lambda x, c: kf.unicycle(x, c, dt)  # noqa: E731
    G = lambda x, c: kf.unicycle_jacobian(x, c, dt)  # noqa: E731
    mu, Sig = kf.ekf_predict(mu, Sig, u, g, G, M)  # wrong: M is the odometry's noise, not the pose's
    return localization_step(mu, Sig, np.zeros(2), z, landmarks, dt, M, Q, gate)


def localization_no_wrap(*args):
    return _student_step(*args, no_wrap=True)


def localization_update_without_residual(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Gates with the wrapped innovation, but hands kf.ekf_update no residual."""
    R = kf.sim.process_noise_of_odometry(mu, u, dt, M)
    mu, Sig = kf.ekf_predict(
        mu, Sig, u, lambda x, c: kf.unicycle(x, c, dt), lambda x, c: kf.unicycle_jacobian(x, c, dt), R
    )
    used = np.zeros(len(z), dtype=bool)
    for j, m in enumerate(landmarks):
        H = kf.range_bearing_jacobian(mu, m)
        nu = kf.models.range_bearing_residual(z[j], kf.range_bearing(mu, m))
        if kf.mahalanobis(nu, H @ Sig @ H.T + Q) <= gate:
            h, Hf = (lambda x, m=m: kf.range_bearing(x, m)), (lambda x, m=m: kf.range_bearing_jacobian(x, m))
            mu, Sig = kf.ekf_update(mu, Sig, z[j], h, Hf, Q)  # wrong: the update's bearing innovation unwrapped
            mu[2] = kf.wrap_angle(mu[2])
            used[j] = True
    return mu, Sig, used


def localization_d2_vs_gate(*args):
    return _student_step(*args, gate_test="d2 vs gate")


def localization_gate_with_S(*args):
    return _student_step(*args, gate_test="S not inverted")  # wrong: the gate takes nu^T S nu, not nu^T S^-1 nu


def localization_d_vs_gate2(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Measures the distance with kf.mahalanobis (a distance), then compares it with gate squared."""
    R = kf.sim.process_noise_of_odometry(mu, u, dt, M)
    mu, Sig = kf.ekf_predict(
        mu, Sig, u, lambda x, c: kf.unicycle(x, c, dt), lambda x, c: kf.unicycle_jacobian(x, c, dt), R
    )
    used = np.zeros(len(z), dtype=bool)
    for j, m in enumerate(landmarks):
        H = kf.range_bearing_jacobian(mu, m)
        nu = kf.models.range_bearing_residual(z[j], kf.range_bearing(mu, m))
        if kf.mahalanobis(nu, H @ Sig @ H.T + Q) <= gate**2:  # wrong: a distance against gate^2
            h, Hf = (lambda x, m=m: kf.range_bearing(x, m)), (lambda x, m=m: kf.range_bearing_jacobian(x, m))
            mu, Sig = kf.ekf_update(mu, Sig, z[j], h, Hf, Q, kf.models.range_bearing_residual)
            mu[2] = kf.wrap_angle(mu[2])
            used[j] = True
    return mu, Sig, used


def localization_no_Q(*args):
    return _student_step(*args, no_Q="both")


def localization_no_Q_in_gate(*args):
    return _student_step(*args, no_Q="gate")


def localization_no_Q_in_update(*args):
    return _student_step(*args, no_Q="update")


def localization_stale(*args):
    return _student_step(*args, stale=True)


def localization_gain_from_prediction(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """Linearizes every reading at the prediction (H, S and K from mu_bar, Sig_bar), but updates the current belief."""
    W = kf.unicycle_control_jacobian(mu, u, dt)
    G = kf.unicycle_jacobian(mu, u, dt)
    mu_bar, Sig_bar = kf.unicycle(mu, u, dt), G @ Sig @ G.T + W @ M @ W.T
    mu, Sig = mu_bar.copy(), Sig_bar.copy()
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = kf.range_bearing_jacobian(mu_bar, landmarks[j])  # wrong: at mu_bar, not the current mean
        nu = z[j] - kf.range_bearing(mu_bar, landmarks[j])
        nu[1] = kf.wrap_angle(nu[1])
        S = H @ Sig_bar @ H.T + Q  # wrong: Sig_bar, not the current Sig
        if nu @ np.linalg.solve(S, nu) > gate**2:
            continue
        K = Sig_bar @ H.T @ np.linalg.inv(S)
        mu = mu + K @ nu
        mu[2] = kf.wrap_angle(mu[2])
        Sig = (np.eye(3) - K @ H) @ Sig
        used[j] = True
    return mu, Sig, used


def localization_R_is_M(*args):
    return _student_step(*args, R="M")


def localization_no_R(*args):
    return _student_step(*args, R="none")


def localization_heading_unwrapped(*args):
    return _student_step(*args, heading_unwrapped=True)


def localization_no_gate(*args):
    return _student_step(*args, gate_test="none")


def localization_all_used(*args):
    return _student_step(*args, all_used=True)


def localization_blind_skips(*args):
    return _student_step(*args, blind_skips=True)
