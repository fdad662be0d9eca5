"""Wrong (and a few right) solutions to the "Your turn" exercises of chapters 6-11.

Written from the exercise texts and the chapters' equations only, as students who had read the chapter would write
them, without looking at the checkers. One mistake per wrong solution; the right ones take a style of their own.

Chapters 6 to 9 number none of their equations, so their mistakes name none (""); chapter 10's exercise numbers the
steps of the localization step (1)-(5), and chapter 11 numbers resampling (6).

The exercise of chapter 10 lets students call ``kf.unicycle``, ``kf.range_bearing`` and their Jacobians; here the
private helpers below stand in for them, written in plain numpy from chapters 7 and 8.
"""

from __future__ import annotations

import math

import numpy as np

from tests.check.wrong_set import right, wrong

TWO_PI = 2.0 * np.pi


# ---------------------------------------------------------------- helpers (right, as kf's functions are)
def _wrap(a):
    """Angles into (-pi, pi]: one turn back, or the modulo further out (as ``kf.wrap_angle``)."""
    a = np.asarray(a, dtype=float)
    out = np.where(a > np.pi, a - TWO_PI, np.where(a <= -np.pi, a + TWO_PI, a))
    far = (out > np.pi) | (out <= -np.pi)
    if np.any(far):
        wrapped = np.pi - np.mod(np.pi - a, TWO_PI)
        out = np.where(far, np.where(wrapped <= -np.pi, np.pi, wrapped), out)
    return out[()] if out.ndim == 0 else out


def _rb(state, landmark):
    """h(x) = [sqrt(q), atan2(dy, dx) - theta], the bearing wrapped (chapter 7)."""
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx * dx + dy * dy), _wrap(np.arctan2(dy, dx) - state[2])])


def _rb_jacobian(state, landmark):
    """H = dh/d(x, y, theta) of the range-bearing model (chapter 7)."""
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx * dx + dy * dy
    r = np.sqrt(q)
    return np.array([[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, -1.0]])


def _rb_residual(a, b):
    """a - b for readings [r, phi], the bearing difference wrapped."""
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    d[1] = _wrap(d[1])
    return d


def _unicycle(state, u, dt):
    """The unicycle in chord form (chapter 8): d = V dt sin(h)/h in the direction theta + h, h = omega dt / 2."""
    x, y, th = state
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * (math.sin(h) / h if h else 1.0)
    return np.array([x + d * math.cos(th + h), y + d * math.sin(th + h), _wrap(th + w * dt)])


def _unicycle_G(state, u, dt):
    """G = dg/d(x, y, theta) (chapter 8)."""
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * (math.sin(h) / h if h else 1.0)
    phi = state[2] + h
    return np.array([[1.0, 0.0, -d * math.sin(phi)], [0.0, 1.0, d * math.cos(phi)], [0.0, 0.0, 1.0]])


def _unicycle_W(state, u, dt):
    """W = dg/d(V, omega), which carries the odometry noise into the pose (chapter 8)."""
    V, w = u
    h = 0.5 * w * dt
    s = math.sin(h) / h if h else 1.0
    ds = (math.cos(h) - s) / h if abs(h) > 1e-3 else -h / 3
    d, phi = V * dt * s, state[2] + h
    c, n = math.cos(phi), math.sin(phi)
    return np.array(
        [
            [dt * s * c, 0.5 * dt * (V * dt * ds * c - d * n)],
            [dt * s * n, 0.5 * dt * (V * dt * ds * n + d * c)],
            [0.0, dt],
        ]
    )


def _predict(mu, Sig, u, dt, M):
    """(1): mu_bar = g(mu, u), Sig_bar = G Sig G^T + W M W^T, both Jacobians at the previous mean."""
    G, W = _unicycle_G(mu, u, dt), _unicycle_W(mu, u, dt)
    return _unicycle(mu, u, dt), G @ Sig @ G.T + W @ M @ W.T


def _readings(z, landmarks):
    z = np.asarray(z, dtype=float).reshape(-1, 2)
    return z, np.asarray(landmarks, dtype=float).reshape(-1, 2)


def _sigma(mu, Sig, lam):
    """Sigma points one a row (mu, mu + columns of L, mu - columns of L) and the weights, wc = wm (chapter 9)."""
    mu, Sig = np.asarray(mu, dtype=float), np.asarray(Sig, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * Sig)
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 0.5 / (n + lam))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


# ---------------------------------------------------------------- cv_model (chapter 6)
def _cv_F(dt):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    return F


@wrong("cv_model", equation="", what="the position rows of Gamma are dt^2 instead of dt^2 / 2")
def cv_gamma_without_half(dt, accel_var):
    Gamma = np.vstack([dt**2 * np.eye(2), dt * np.eye(2)])
    return _cv_F(dt), accel_var * Gamma @ Gamma.T


@wrong("cv_model", equation="", what="the position rows of Gamma are dt / 2 instead of dt^2 / 2")
def cv_gamma_half_dt(dt, accel_var):
    Gamma = np.vstack([0.5 * dt * np.eye(2), dt * np.eye(2)])
    return _cv_F(dt), accel_var * Gamma @ Gamma.T


@wrong("cv_model", equation="", what="the velocity rows of Gamma are 1 instead of dt")
def cv_gamma_velocity_without_dt(dt, accel_var):
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), np.eye(2)])
    return _cv_F(dt), accel_var * Gamma @ Gamma.T


@wrong("cv_model", equation="", what="Gamma's two blocks are swapped: dt on the positions, dt^2 / 2 on the velocities")
def cv_gamma_rows_swapped(dt, accel_var):
    Gamma = np.vstack([dt * np.eye(2), 0.5 * dt**2 * np.eye(2)])
    return _cv_F(dt), accel_var * Gamma @ Gamma.T


@wrong(
    "cv_model",
    equation="",
    inputs=("accel_var",),
    what="accel_var is taken for a standard deviation and squared, so R scales with sigma_a^4",
)
def cv_accel_var_squared(dt, accel_var):
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])
    return _cv_F(dt), accel_var**2 * Gamma @ Gamma.T


@wrong("cv_model", equation="", inputs=("accel_var",), what="R is Gamma Gamma^T without the factor sigma_a^2")
def cv_R_without_accel_var(dt, accel_var):
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])
    return _cv_F(dt), Gamma @ Gamma.T


@wrong("cv_model", equation="", what="R keeps only its diagonal, dropping the position-velocity correlation")
def cv_diagonal_R(dt, accel_var):
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])
    return _cv_F(dt), np.diag(np.diag(accel_var * Gamma @ Gamma.T))


@wrong(
    "cv_model",
    equation="",
    what="one acceleration drives both axes (Gamma a 4 x 1 column), which couples x with y in R",
)
def cv_one_acceleration_for_both_axes(dt, accel_var):
    gamma = np.array([[0.5 * dt**2], [0.5 * dt**2], [dt], [dt]])
    return _cv_F(dt), accel_var * gamma @ gamma.T


@wrong(
    "cv_model",
    equation="",
    what="R is the continuous white-noise-acceleration matrix (dt^3/3, dt^2/2, dt) instead of sigma_a^2 Gamma Gamma^T",
)
def cv_continuous_white_noise(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    R = np.zeros((4, 4))
    for i in range(2):
        R[i, i] = dt**3 / 3
        R[i, i + 2] = R[i + 2, i] = dt**2 / 2
        R[i + 2, i + 2] = dt
    return F, accel_var * R


@wrong(
    "cv_model", equation="", what="F is transposed: the dt entries sit below the diagonal, moving velocity by position"
)
def cv_F_transposed(dt, accel_var):
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])
    return _cv_F(dt).T, accel_var * Gamma @ Gamma.T


@wrong("cv_model", equation="", inputs=("dt",), what="F carries velocity into position with 1 instead of dt")
def cv_F_one_for_dt(dt, accel_var):
    F = np.eye(4)
    F[0, 2] = F[1, 3] = 1.0
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])
    return F, accel_var * Gamma @ Gamma.T


@wrong(
    "cv_model", equation="", what="F and R are built for the state order [px, vx, py, vy] instead of [px, py, vx, vy]"
)
def cv_interleaved_state(dt, accel_var):
    F1 = np.array([[1.0, dt], [0.0, 1.0]])
    g = np.array([[0.5 * dt**2], [dt]])
    F = np.block([[F1, np.zeros((2, 2))], [np.zeros((2, 2)), F1]])
    R1 = accel_var * g @ g.T
    R = np.block([[R1, np.zeros((2, 2))], [np.zeros((2, 2)), R1]])
    return F, R


@wrong("cv_model", equation="", what="returns the pair in the wrong order, (R, F)")
def cv_returns_R_F(dt, accel_var):
    F = np.array([[1.0, 0.0, dt, 0.0], [0.0, 1.0, 0.0, dt], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    Gamma = np.array([[0.5 * dt**2, 0.0], [0.0, 0.5 * dt**2], [dt, 0.0], [0.0, dt]])
    return accel_var * Gamma @ Gamma.T, F


@right("cv_model", what="every entry written out by hand in loops: dt^4/4, dt^3/2 and dt^2 times sigma_a^2")
def cv_by_entries(dt, accel_var):
    F = [[0.0] * 4 for _ in range(4)]
    R = [[0.0] * 4 for _ in range(4)]
    for i in range(4):
        F[i][i] = 1.0
    for axis in range(2):
        p, v = axis, axis + 2
        F[p][v] = dt
        R[p][p] = accel_var * dt**4 / 4
        R[p][v] = R[v][p] = accel_var * dt**3 / 2
        R[v][v] = accel_var * dt**2
    return np.array(F), np.array(R)


@right("cv_model", what="Kronecker products of the one-axis model with the 2 x 2 identity")
def cv_kronecker(dt, accel_var):
    F = np.kron(np.array([[1.0, dt], [0.0, 1.0]]), np.eye(2))
    g = np.array([[dt**2 / 2], [dt]])
    return F, np.kron(accel_var * (g @ g.T), np.eye(2))


# ---------------------------------------------------------------- range_bearing (chapter 7)
@wrong("range_bearing", equation="", inputs=("state",), what="the bearing forgets to subtract the robot's heading")
def rb_bearing_without_heading(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), np.arctan2(dy, dx)])


@wrong(
    "range_bearing", equation="", inputs=("state",), what="the heading is added to the bearing instead of subtracted"
)
def rb_heading_added(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), _wrap(np.arctan2(dy, dx) + state[2])])


@wrong("range_bearing", equation="", what="atan2 gets its arguments swapped, atan2(dx, dy)")
def rb_atan2_swapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), _wrap(np.arctan2(dx, dy) - state[2])])


@wrong("range_bearing", equation="", what="atan(dy / dx) in place of atan2, which loses the half-plane behind x")
def rb_arctan_of_quotient(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = np.arctan(np.float64(dy) / np.float64(dx))
    return np.array([np.sqrt(dx**2 + dy**2), _wrap(phi - state[2])])


@wrong(
    "range_bearing",
    equation="",
    inputs=("state", "landmark"),
    what="the offset is taken robot minus landmark, which turns the bearing round by pi",
)
def rb_offset_reversed(state, landmark):
    dx, dy = state[0] - landmark[0], state[1] - landmark[1]
    return np.array([np.hypot(dx, dy), _wrap(np.arctan2(dy, dx) - state[2])])


@wrong("range_bearing", equation="", what="the range is q, the squared distance, without the square root")
def rb_squared_range(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([dx**2 + dy**2, _wrap(np.arctan2(dy, dx) - state[2])])


@wrong("range_bearing", equation="", inputs=("state",), what="the range is the landmark's distance from the origin")
def rb_range_from_origin(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(landmark[0], landmark[1]), _wrap(np.arctan2(dy, dx) - state[2])])


@wrong(
    "range_bearing", equation="", what="the bearing is not wrapped, so a landmark behind the robot can read beyond pi"
)
def rb_unwrapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), np.arctan2(dy, dx) - state[2]])


@wrong("range_bearing", equation="", what="the wrap only handles bearings above pi, not those at or below -pi")
def rb_wrap_only_above(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    phi = np.arctan2(dy, dx) - state[2]
    if phi > np.pi:
        phi -= 2 * np.pi
    return np.array([np.sqrt(dx**2 + dy**2), phi])


@wrong("range_bearing", equation="", what="the bearing is wrapped into [0, 2 pi) with a modulo, not into (-pi, pi]")
def rb_wrap_zero_to_two_pi(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), np.mod(np.arctan2(dy, dx) - state[2], 2 * np.pi)])


# Written as a wrong one, but the checkers take any wrap that differs from (−π, π] only at exactly ±π (the same
# direction, and the common idioms): counted as right.
@right("range_bearing", what="the (φ + π) % 2π − π wrap")
def rb_wrap_half_open_below(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), (np.arctan2(dy, dx) - state[2] + np.pi) % (2 * np.pi) - np.pi])


# Written as a wrong one, but the checkers take any wrap that differs from (−π, π] only at exactly ±π (the same
# direction, and the common idioms): counted as right.
@right("range_bearing", what="the atan2(sin φ, cos φ) wrap")
def rb_wrap_by_sin_cos(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    phi = np.arctan2(dy, dx) - state[2]
    return np.array([np.sqrt(dx**2 + dy**2), np.arctan2(np.sin(phi), np.cos(phi))])


@wrong("range_bearing", equation="", what="the bearing is returned in degrees")
def rb_degrees(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.sqrt(dx**2 + dy**2), np.degrees(_wrap(np.arctan2(dy, dx) - state[2]))])


@wrong("range_bearing", equation="", what="returns [phi, r] instead of [r, phi]")
def rb_swapped_outputs(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([_wrap(np.arctan2(dy, dx) - state[2]), np.sqrt(dx**2 + dy**2)])


@wrong(
    "range_bearing",
    equation="",
    inputs=("landmark",),
    what="the offset is computed in place in the caller's landmark array (right answer, but the input is changed)",
)
def rb_landmark_in_place(state, landmark):
    d = np.asarray(landmark, dtype=float)
    d -= np.asarray(state, dtype=float)[:2]
    return np.array([np.sqrt(d[0] ** 2 + d[1] ** 2), _wrap(np.arctan2(d[1], d[0]) - state[2])])


@right("range_bearing", what="scalar math module (hypot, atan2), the bearing wrapped with while loops")
def rb_scalar_math(state, landmark):
    x, y, theta = (float(s) for s in state)
    mx, my = (float(m) for m in landmark)
    phi = math.atan2(my - y, mx - x) - theta
    while phi > math.pi:
        phi -= 2 * math.pi
    while phi <= -math.pi:
        phi += 2 * math.pi
    return np.array([math.hypot(mx - x, my - y), phi])


@right("range_bearing", what="the offset as a vector: np.linalg.norm, np.angle of the complex offset, np.where wrap")
def rb_vector_form(state, landmark):
    state = np.asarray(state, dtype=float)
    d = np.asarray(landmark, dtype=float) - state[:2]
    phi = np.angle(d[0] + 1j * d[1]) - state[2]
    phi = np.where(phi > np.pi, phi - 2 * np.pi, np.where(phi <= -np.pi, phi + 2 * np.pi, phi))
    return np.array([np.linalg.norm(d), float(phi)])


# ---------------------------------------------------------------- range_bearing_jacobian (chapter 7)
def _offsets(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    return dx, dy, q, np.sqrt(q)


@wrong("range_bearing_jacobian", equation="", what="the whole bearing row has its sign flipped (chapter 7's flipped H)")
def rbj_bearing_row_flipped(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[-dx / r, -dy / r, 0.0], [-dy / q, dx / q, 1.0]])


@wrong(
    "range_bearing_jacobian",
    equation="",
    what="the bearing row forgets the chain-rule factor -1 of dDx/dx and dDy/dy (its position entries flip sign)",
)
def rbj_bearing_row_without_chain_rule(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[-dx / r, -dy / r, 0.0], [-dy / q, dx / q, -1.0]])


@wrong(
    "range_bearing_jacobian",
    equation="",
    what="the range row forgets the chain-rule factor -1: +dx/sqrt(q), +dy/sqrt(q)",
)
def rbj_range_row_without_chain_rule(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[dx / r, dy / r, 0.0], [dy / q, -dx / q, -1.0]])


@wrong(
    "range_bearing_jacobian",
    equation="",
    inputs=("state", "landmark"),
    what="differentiates with respect to the landmark's position (dDx/dx = +1), flipping both rows' position entries",
)
def rbj_derivative_wrt_landmark(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[dx / r, dy / r, 0.0], [-dy / q, dx / q, -1.0]])


@wrong("range_bearing_jacobian", equation="", what="d(phi)/d(theta) is +1 instead of -1")
def rbj_heading_plus_one(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, 1.0]])


@wrong("range_bearing_jacobian", equation="", what="d(phi)/d(theta) is left at 0, as if the heading did not enter")
def rbj_heading_zero(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, 0.0]])


@wrong("range_bearing_jacobian", equation="", what="the bearing row divides by sqrt(q) instead of q")
def rbj_bearing_over_r(state, landmark):
    dx, dy, _, r = _offsets(state, landmark)
    return np.array([[-dx / r, -dy / r, 0.0], [dy / r, -dx / r, -1.0]])


@wrong("range_bearing_jacobian", equation="", what="the range row divides by q instead of sqrt(q)")
def rbj_range_over_q(state, landmark):
    dx, dy, q, _ = _offsets(state, landmark)
    return np.array([[-dx / q, -dy / q, 0.0], [dy / q, -dx / q, -1.0]])


@wrong("range_bearing_jacobian", equation="", what="dx and dy are swapped in the bearing row: [dx/q, -dy/q, -1]")
def rbj_bearing_dx_dy_swapped(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[-dx / r, -dy / r, 0.0], [dx / q, -dy / q, -1.0]])


@wrong(
    "range_bearing_jacobian",
    equation="",
    what="the 2 x 2 position block is transposed: H[0, 1] and H[1, 0] trade places",
)
def rbj_position_block_transposed(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[-dx / r, dy / q, 0.0], [-dy / r, -dx / q, -1.0]])


@wrong("range_bearing_jacobian", equation="", what="the rows are in the wrong order, the bearing row first")
def rbj_rows_swapped(state, landmark):
    dx, dy, q, r = _offsets(state, landmark)
    return np.array([[dy / q, -dx / q, -1.0], [-dx / r, -dy / r, 0.0]])


@wrong(
    "range_bearing_jacobian",
    equation="",
    what="central finite differences of h instead of the derived formula (right to about 1e-10 only)",
)
def rbj_finite_differences(state, landmark):
    state = np.asarray(state, dtype=float)
    eps = 1e-6
    H = np.zeros((2, 3))
    for i in range(3):
        step = np.zeros(3)
        step[i] = eps
        hi, lo = _rb(state + step, landmark), _rb(state - step, landmark)
        diff = hi - lo
        diff[1] = _wrap(diff[1])
        H[:, i] = diff / (2 * eps)
    return H


@wrong(
    "range_bearing_jacobian",
    equation="",
    inputs=("landmark",),
    what="the offset is computed in place in the caller's landmark array (right answer, but the input is changed)",
)
def rbj_landmark_in_place(state, landmark):
    d = np.asarray(landmark, dtype=float)
    d -= np.asarray(state, dtype=float)[:2]
    q = d @ d
    return np.array([[-d[0] / np.sqrt(q), -d[1] / np.sqrt(q), 0.0], [d[1] / q, -d[0] / q, -1.0]])


@right("range_bearing_jacobian", what="entry by entry on Python floats, the range r from math.hypot")
def rbj_scalar_entries(state, landmark):
    dx = float(landmark[0]) - float(state[0])
    dy = float(landmark[1]) - float(state[1])
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    H = np.zeros((2, 3))
    H[0, 0], H[0, 1] = -dx / r, -dy / r
    H[1, 0], H[1, 1], H[1, 2] = dy / q, -dx / q, -1.0
    return H


@right("range_bearing_jacobian", what="the chain rule as a product: dh/d(dx, dy, theta) times diag(-1, -1, 1)")
def rbj_chain_rule_product(state, landmark):
    state = np.asarray(state, dtype=float)
    d = np.asarray(landmark, dtype=float) - state[:2]
    q = d @ d
    dh_dv = np.array([[d[0] / np.sqrt(q), d[1] / np.sqrt(q), 0.0], [-d[1] / q, d[0] / q, -1.0]])
    return dh_dv @ np.diag([-1.0, -1.0, 1.0])


# ---------------------------------------------------------------- unicycle (chapter 8)
@wrong(
    "unicycle",
    equation="",
    what="the arc formula with no straight-line case: it divides by omega = 0 (nan) and loses digits near it",
)
def uni_arc_never_straight(state, u, dt):
    x, y, th = np.asarray(state, dtype=float)
    V, w = np.asarray(u, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.array(
            [
                x + V / w * (np.sin(th + w * dt) - np.sin(th)),
                y + V / w * (np.cos(th) - np.cos(th + w * dt)),
                _wrap(th + w * dt),
            ]
        )


@wrong(
    "unicycle",
    equation="",
    what="drives straight only when omega == 0 exactly, so a nearly straight omega (1e-15) loses its digits",
)
def uni_straight_only_at_zero(state, u, dt):
    x, y, th = state
    V, w = u
    if w == 0:
        return np.array([x + V * dt * np.cos(th), y + V * dt * np.sin(th), _wrap(th)])
    return np.array(
        [
            x + V / w * (np.sin(th + w * dt) - np.sin(th)),
            y + V / w * (np.cos(th) - np.cos(th + w * dt)),
            _wrap(th + w * dt),
        ]
    )


@wrong(
    "unicycle",
    equation="",
    what="takes the straight line whenever |omega| < 0.01, so slow turns (omega = 0.001) drive straight",
)
def uni_straight_threshold_too_large(state, u, dt):
    x, y, th = state
    V, w = u
    if abs(w) < 0.01:
        return np.array([x + V * dt * np.cos(th), y + V * dt * np.sin(th), _wrap(th + w * dt)])
    return np.array(
        [
            x + V / w * (np.sin(th + w * dt) - np.sin(th)),
            y + V / w * (np.cos(th) - np.cos(th + w * dt)),
            _wrap(th + w * dt),
        ]
    )


@wrong(
    "unicycle",
    equation="",
    inputs=("dt",),
    what="the straight-line case forgets dt: x + V cos(theta) instead of x + V dt cos(theta)",
)
def uni_straight_branch_without_dt(state, u, dt):
    x, y, th = state
    V, w = u
    if abs(w) < 1e-6:
        return np.array([x + V * np.cos(th), y + V * np.sin(th), _wrap(th + w * dt)])
    return np.array(
        [
            x + V / w * (np.sin(th + w * dt) - np.sin(th)),
            y + V / w * (np.cos(th) - np.cos(th + w * dt)),
            _wrap(th + w * dt),
        ]
    )


@wrong(
    "unicycle",
    equation="",
    inputs=("dt",),
    what="the sines and cosines take theta + omega instead of theta + omega dt",
)
def uni_omega_without_dt_in_arc(state, u, dt):
    x, y, th = state
    V, w = u
    if abs(w) < 1e-6:
        return np.array([x + V * dt * np.cos(th), y + V * dt * np.sin(th), _wrap(th + w * dt)])
    return np.array(
        [
            x + V / w * (np.sin(th + w) - np.sin(th)),
            y + V / w * (np.cos(th) - np.cos(th + w)),
            _wrap(th + w * dt),
        ]
    )


@wrong("unicycle", equation="", inputs=("dt",), what="the new heading is theta + omega, without dt")
def uni_heading_without_dt(state, u, dt):
    x, y, th = state
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * (np.sin(h) / h if h != 0 else 1.0)
    return np.array([x + d * np.cos(th + h), y + d * np.sin(th + h), _wrap(th + w)])


@wrong("unicycle", equation="", what="the new heading is not wrapped into (-pi, pi]")
def uni_heading_unwrapped(state, u, dt):
    x, y, th = state
    V, w = u
    if abs(w) < 1e-6:
        return np.array([x + V * dt * np.cos(th), y + V * dt * np.sin(th), th + w * dt])
    return np.array(
        [
            x + V / w * (np.sin(th + w * dt) - np.sin(th)),
            y + V / w * (np.cos(th) - np.cos(th + w * dt)),
            th + w * dt,
        ]
    )


# Written as a wrong one, but the checkers take any wrap that differs from (−π, π] only at exactly ±π (the same
# direction, and the common idioms): counted as right.
@right("unicycle", what="the (θ + π) % 2π − π wrap")
def uni_wrap_half_open(state, u, dt):
    x, y, th = state
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * np.sinc(h / np.pi)
    return np.array([x + d * np.cos(th + h), y + d * np.sin(th + h), (th + w * dt + np.pi) % (2 * np.pi) - np.pi])


@wrong("unicycle", equation="", what="the y bracket has its sign flipped: cos(theta + omega dt) - cos(theta)")
def uni_y_sign_flipped(state, u, dt):
    x, y, th = state
    V, w = u
    if abs(w) < 1e-6:
        return np.array([x + V * dt * np.cos(th), y + V * dt * np.sin(th), _wrap(th + w * dt)])
    return np.array(
        [
            x + V / w * (np.sin(th + w * dt) - np.sin(th)),
            y + V / w * (np.cos(th + w * dt) - np.cos(th)),
            _wrap(th + w * dt),
        ]
    )


@wrong("unicycle", equation="", what="the x and y formulas are swapped (x gets the cosine bracket, y the sine one)")
def uni_xy_swapped(state, u, dt):
    x, y, th = state
    V, w = u
    if abs(w) < 1e-6:
        return np.array([x + V * dt * np.sin(th), y + V * dt * np.cos(th), _wrap(th + w * dt)])
    return np.array(
        [
            x + V / w * (np.cos(th) - np.cos(th + w * dt)),
            y + V / w * (np.sin(th + w * dt) - np.sin(th)),
            _wrap(th + w * dt),
        ]
    )


@wrong("unicycle", equation="", what="an Euler step: drives straight along the old heading even while turning")
def uni_euler_old_heading(state, u, dt):
    x, y, th = state
    V, w = u
    return np.array([x + V * dt * np.cos(th), y + V * dt * np.sin(th), _wrap(th + w * dt)])


@wrong("unicycle", equation="", what="the chord form uses np.sinc(omega dt / 2) without dividing its argument by pi")
def uni_sinc_without_pi(state, u, dt):
    x, y, th = state
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * np.sinc(h)
    return np.array([x + d * np.cos(th + h), y + d * np.sin(th + h), _wrap(th + w * dt)])


@wrong(
    "unicycle",
    equation="",
    what="the chord points along the final heading theta + omega dt instead of half-way, theta + omega dt / 2",
)
def uni_chord_full_angle(state, u, dt):
    x, y, th = state
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * np.sinc(h / np.pi)
    return np.array([x + d * np.cos(th + w * dt), y + d * np.sin(th + w * dt), _wrap(th + w * dt)])


@wrong("unicycle", equation="", inputs=("u",), what="unpacks the control as [omega, V], swapping speed and turn rate")
def uni_V_omega_swapped(state, u, dt):
    x, y, th = state
    w, V = u
    h = 0.5 * w * dt
    d = V * dt * np.sinc(h / np.pi)
    return np.array([x + d * np.cos(th + h), y + d * np.sin(th + h), _wrap(th + w * dt)])


@wrong(
    "unicycle",
    equation="",
    inputs=("state",),
    what="moves the caller's pose in place and returns it (right numbers, but the input is changed)",
)
def uni_in_place(state, u, dt):
    V, w = u
    h = 0.5 * w * dt
    d = V * dt * np.sinc(h / np.pi)
    pose = np.asarray(state, dtype=float)
    pose[0] += d * np.cos(pose[2] + h)
    pose[1] += d * np.sin(pose[2] + h)
    pose[2] = _wrap(pose[2] + w * dt)
    return pose


@right("unicycle", what="the arc formula on Python floats, the straight line below |omega| < 1e-6, a while-loop wrap")
def uni_arc_with_branch(state, u, dt):
    x, y, th = (float(s) for s in state)
    V, w = (float(c) for c in u)
    if abs(w) < 1e-6:
        x_new, y_new = x + V * dt * math.cos(th), y + V * dt * math.sin(th)
    else:
        x_new = x + V / w * (math.sin(th + w * dt) - math.sin(th))
        y_new = y + V / w * (math.cos(th) - math.cos(th + w * dt))
    th_new = th + w * dt
    while th_new > math.pi:
        th_new -= 2 * math.pi
    while th_new <= -math.pi:
        th_new += 2 * math.pi
    return np.array([x_new, y_new, th_new])


@right("unicycle", what="the chord form with its own sin(h)/h (1 at h = 0) and the displacement as a rotated vector")
def uni_chord_rotated(state, u, dt):
    state = np.asarray(state, dtype=float)
    V, w = np.asarray(u, dtype=float)
    h = w * dt / 2
    chord = V * dt * (np.sin(h) / h if h != 0 else 1.0)
    a = state[2] + h
    move = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]) @ np.array([chord, 0.0])
    heading = state[2] + w * dt
    heading = np.where(heading > np.pi, heading - 2 * np.pi, np.where(heading <= -np.pi, heading + 2 * np.pi, heading))
    return np.array([state[0] + move[0], state[1] + move[1], float(heading)])


# ---------------------------------------------------------------- sigma_points (chapter 9)
@wrong(
    "sigma_points", equation="", what="adds the rows of L instead of its columns (the same only for a diagonal Sigma)"
)
def sp_rows_of_L(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L, mu - L])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    what="uses the symmetric matrix square root of (n + lambda) Sigma, not its lower Cholesky factor",
)
def sp_symmetric_square_root(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    vals, vecs = np.linalg.eigh((n + lam) * np.asarray(Sig, dtype=float))
    S = vecs @ np.diag(np.sqrt(vals)) @ vecs.T
    chi = np.vstack([mu, mu + S.T, mu - S.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    what="takes the element-wise square root of (n + lambda) Sigma instead of a matrix square root",
)
def sp_elementwise_sqrt(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    with np.errstate(invalid="ignore"):
        L = np.sqrt((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong("sigma_points", equation="", what="spreads the points by the standard deviations alone, ignoring correlations")
def sp_diagonal_only(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.diag(np.sqrt((n + lam) * np.diag(np.asarray(Sig, dtype=float))))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    inputs=("lam",),
    what="the points come from the Cholesky factor of Sigma, without the factor n + lambda",
)
def sp_without_spread(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky(np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong("sigma_points", equation="", what="scales the Cholesky factor by n + lambda instead of its square root")
def sp_spread_not_square_rooted(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = (n + lam) * np.linalg.cholesky(np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    what="keeps the one-dimensional spread 1 + lambda for every n instead of n + lambda",
)
def sp_one_d_spread(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((1 + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    what="keeps the one-dimensional weights lambda / (1 + lambda) and 1 / (2 (1 + lambda)) for every n",
)
def sp_one_d_weights(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (1 + lam)))
    wm[0] = lam / (1 + lam)
    return chi, wm, wm.copy()


@wrong("sigma_points", equation="", what="the outer weights are 1 / (n + lambda), without the 2, so they sum past 1")
def sp_outer_weights_without_two(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (n + lam))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@wrong("sigma_points", equation="", what="the centre weight is lambda / (2 (n + lambda)), halved like the outer ones")
def sp_centre_weight_halved(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (2 * (n + lam))
    return chi, wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    what="adds beta = 2 to the centre's covariance weight, though the exercise asks for wc equal to wm",
)
def sp_beta_two(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    wc = wm.copy()
    wc[0] += 2.0
    return chi, wm, wc


# Written as a wrong one, but the checker takes the points in any order, each with its weights (the transform
# does not depend on it): counted as right.
@right("sigma_points", what="the points in pairs, μ + Lᵢ then μ − Lᵢ")
def sp_interleaved_order(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    points = [mu]
    for i in range(n):
        points += [mu + L[:, i], mu - L[:, i]]
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return np.array(points), wm, wm.copy()


@wrong(
    "sigma_points",
    equation="",
    inputs=("Sig",),
    what="scales the caller's Sigma in place by n + lambda before the Cholesky factor (right points, input changed)",
)
def sp_scales_Sig_in_place(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    Sig = np.asarray(Sig, dtype=float)
    Sig *= n + lam
    L = np.linalg.cholesky(Sig)
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))
    wm[0] = lam / (n + lam)
    return chi, wm, wm.copy()


@right("sigma_points", what="a loop over the points, with sqrt(n + lambda) times the Cholesky factor of Sigma")
def sp_loops(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    n = len(mu)
    L = math.sqrt(n + lam) * np.linalg.cholesky(np.asarray(Sig, dtype=float))
    chi = np.empty((2 * n + 1, n))
    wm = np.empty(2 * n + 1)
    chi[0], wm[0] = mu, lam / (n + lam)
    for i in range(n):
        chi[1 + i] = mu + L[:, i]
        chi[1 + n + i] = mu - L[:, i]
        wm[1 + i] = wm[1 + n + i] = 1.0 / (2.0 * (n + lam))
    return chi, wm, wm.copy()


@right("sigma_points", what="a hand-written Cholesky-Banachiewicz factor of (n + lambda) Sigma, points by broadcasting")
def sp_hand_cholesky(mu, Sig, lam):
    mu = np.asarray(mu, dtype=float)
    A = (mu.size + lam) * np.asarray(Sig, dtype=float)
    n = mu.size
    L = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1):
            s = A[i, j] - L[i, :j] @ L[j, :j]
            L[i, j] = math.sqrt(s) if i == j else s / L[j, j]
    chi = mu + np.concatenate([np.zeros((1, n)), L.T, -L.T])
    wm = np.concatenate([[lam / (n + lam)], np.full(2 * n, 0.5 / (n + lam))])
    return chi, wm, wm.copy()


# ---------------------------------------------------------------- unscented_transform (chapter 9)
@wrong("unscented_transform", equation="", what="the mean of the images is their plain average, without the weights")
def ut_unweighted_mean(mu, Sig, f, lam):
    chi, _, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = Y.mean(axis=0)
    dY = Y - mu_y
    return mu_y, (wc[:, None] * dY).T @ dY


@wrong("unscented_transform", equation="", what="the covariance averages the outer products with equal weights")
def ut_unweighted_covariance(mu, Sig, f, lam):
    chi, wm, _ = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = wm @ Y
    dY = Y - mu_y
    return mu_y, dY.T @ dY / len(Y)


@wrong(
    "unscented_transform",
    equation="",
    what="takes f(mu), the image of the mean, as the output mean (the EKF's answer) and the spread about it",
)
def ut_image_of_the_mean(mu, Sig, f, lam):
    chi, _, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = Y[0]
    dY = Y - mu_y
    return mu_y, (wc[:, None] * dY).T @ dY


@wrong(
    "unscented_transform",
    equation="",
    what="the mean is right, but the covariance measures the spread about f(mu) instead of about mu_y",
)
def ut_spread_about_f_of_mu(mu, Sig, f, lam):
    chi, wm, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    dY = Y - Y[0]
    return wm @ Y, (wc[:, None] * dY).T @ dY


@wrong("unscented_transform", equation="", what="forgets to subtract the mean: sum of w_i Y_i Y_i^T, a second moment")
def ut_second_moment(mu, Sig, f, lam):
    chi, wm, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    return wm @ Y, (wc[:, None] * Y).T @ Y


@wrong(
    "unscented_transform",
    equation="",
    what="np.cov(Y.T, aweights=w) for the covariance, which applies a bias correction (and raises for a negative w_0)",
)
def ut_np_cov(mu, Sig, f, lam):
    chi, wm, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    return wm @ Y, np.atleast_2d(np.cov(Y.T, aweights=wc))


@wrong(
    "unscented_transform",
    equation="",
    what="writes the covariance as (sqrt(w) dY)^T (sqrt(w) dY), which fails (nan) when lambda < 0 makes w_0 negative",
)
def ut_sqrt_weights(mu, Sig, f, lam):
    chi, wm, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = wm @ Y
    with np.errstate(invalid="ignore"):
        A = np.sqrt(wc)[:, None] * (Y - mu_y)
    return mu_y, A.T @ A


@wrong(
    "unscented_transform",
    equation="",
    what="leaves out the centre point and gives the 2n others weight 1 / (2n) (right only at lambda = 0)",
)
def ut_without_centre(mu, Sig, f, lam):
    chi, _, _ = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)[1:]
    mu_y = Y.mean(axis=0)
    dY = Y - mu_y
    return mu_y, dY.T @ dY / len(Y)


@wrong(
    "unscented_transform",
    equation="",
    inputs=("lam",),
    what="the sigma points come from the Cholesky factor of Sigma without the factor n + lambda",
)
def ut_points_without_spread(mu, Sig, f, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky(np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    w = np.full(2 * n + 1, 0.5 / (n + lam))
    w[0] = lam / (n + lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = w @ Y
    dY = Y - mu_y
    return mu_y, (w[:, None] * dY).T @ dY


@wrong(
    "unscented_transform",
    equation="",
    what="the sigma points add the rows of the Cholesky factor instead of its columns",
)
def ut_rows_of_L(mu, Sig, f, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    L = np.linalg.cholesky((n + lam) * np.asarray(Sig, dtype=float))
    chi = np.vstack([mu, mu + L, mu - L])
    w = np.full(2 * n + 1, 0.5 / (n + lam))
    w[0] = lam / (n + lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = w @ Y
    dY = Y - mu_y
    return mu_y, (w[:, None] * dY).T @ dY


@wrong(
    "unscented_transform",
    equation="",
    what="uses the one-dimensional weights lambda / (1 + lambda) and 1 / (2 (1 + lambda)) whatever n is",
)
def ut_one_d_weights(mu, Sig, f, lam):
    chi, _, _ = _sigma(mu, Sig, lam)
    n = np.asarray(mu).size
    w = np.full(2 * n + 1, 0.5 / (1 + lam))
    w[0] = lam / (1 + lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = w @ Y
    dY = Y - mu_y
    return mu_y, (w[:, None] * dY).T @ dY


@wrong(
    "unscented_transform",
    equation="",
    inputs=("Sig",),
    what="scales the caller's Sigma in place by n + lambda to build the points (right answer, input changed)",
)
def ut_scales_Sig_in_place(mu, Sig, f, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    Sig = np.asarray(Sig, dtype=float)
    Sig *= n + lam
    L = np.linalg.cholesky(Sig)
    chi = np.vstack([mu, mu + L.T, mu - L.T])
    w = np.full(2 * n + 1, 0.5 / (n + lam))
    w[0] = lam / (n + lam)
    Y = np.asarray(f(chi), dtype=float)
    mu_y = w @ Y
    dY = Y - mu_y
    return mu_y, (w[:, None] * dY).T @ dY


@right("unscented_transform", what="one call of f, then the weighted sums accumulated point by point in a loop")
def ut_loops(mu, Sig, f, lam):
    chi, wm, wc = _sigma(mu, Sig, lam)
    Y = np.asarray(f(chi), dtype=float)
    k = Y.shape[1]
    mu_y = np.zeros(k)
    for i in range(len(Y)):
        mu_y += wm[i] * Y[i]
    Sig_y = np.zeros((k, k))
    for i in range(len(Y)):
        d = Y[i] - mu_y
        Sig_y += wc[i] * np.outer(d, d)
    return mu_y, Sig_y


@right("unscented_transform", what="points from sqrt(n + lambda) chol(Sigma), moments by np.einsum")
def ut_einsum(mu, Sig, f, lam):
    mu = np.asarray(mu, dtype=float)
    n = mu.size
    S = math.sqrt(n + lam) * np.linalg.cholesky(np.asarray(Sig, dtype=float))
    chi = np.concatenate([mu[None, :], mu + S.T, mu - S.T])
    w = np.concatenate([[lam / (n + lam)], np.full(2 * n, 1.0 / (2 * (n + lam)))])
    Y = np.asarray(f(chi), dtype=float)
    mu_y = np.einsum("i,ij->j", w, Y)
    dY = Y - mu_y
    return mu_y, np.einsum("i,ij,ik->jk", w, dY, dY)


# ---------------------------------------------------------------- localization_step (chapter 10)
def _update(mu, Sig, nu, H, Q):
    """(4) with a given innovation and Jacobian: K = Sig H^T S^-1, mu + K nu, (I - K H) Sig."""
    S = H @ Sig @ H.T + Q
    K = Sig @ H.T @ np.linalg.inv(S)
    return mu + K @ nu, (np.eye(3) - K @ H) @ Sig


@wrong(
    "localization_step",
    equation="(2)-(4)",
    what="the bearing innovation is not wrapped, so a landmark behind the robot looks like a huge surprise",
)
def loc_unwrapped_innovation(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = z[j] - _rb(mu, landmarks[j])
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(3)",
    inputs=("gate",),
    what="gates the squared distance nu^T S^-1 nu against gate instead of gate**2",
)
def loc_gate_not_squared(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong("localization_step", equation="(3)", what="the gate multiplies by S instead of S^-1: nu^T S nu")
def loc_gate_with_S_not_inverse(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ S @ nu <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(3)-(4)",
    what="updates with every reading; the gate only sets the used flag",
)
def loc_gate_only_flags(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        used[j] = nu @ np.linalg.solve(S, nu) <= gate**2
        mu, Sig = _update(mu, Sig, nu, H, Q)
        mu[2] = _wrap(mu[2])
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(2)-(4)",
    inputs=("Q",),
    what="forgets Q in the innovation covariance, S = H Sigma H^T, for the gate and the gain",
)
def loc_Q_forgotten(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            K = Sig @ H.T @ np.linalg.inv(S)
            mu, Sig = mu + K @ nu, (np.eye(3) - K @ H) @ Sig
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(2)",
    what="every reading is linearized and compared at the stale prediction mu_bar, not at the current mean",
)
def loc_stale_prediction(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu_bar, Sig = _predict(mu, Sig, u, dt, M)
    mu = mu_bar.copy()
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu_bar, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu_bar, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(2)-(3)",
    what="computes every reading's S (and so its gate) once from the predicted covariance, before any update",
)
def loc_stale_S(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    S_all = [_rb_jacobian(mu, m) @ Sig @ _rb_jacobian(mu, m).T + Q for m in landmarks]
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = S_all[j]
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            K = Sig @ H.T @ np.linalg.inv(S)
            mu, Sig = mu + K @ nu, (np.eye(3) - K @ H) @ Sig
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(2)-(4)",
    what="gates each reading at the prediction, then stacks the accepted ones into one big update at mu_bar",
)
def loc_stacked_update(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    Hs, nus = [], []
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        if nu @ np.linalg.solve(H @ Sig @ H.T + Q, nu) <= gate**2:
            Hs.append(H)
            nus.append(nu)
            used[j] = True
    if Hs:
        H, nu = np.vstack(Hs), np.concatenate(nus)
        Q_all = np.kron(np.eye(len(Hs)), Q)
        K = Sig @ H.T @ np.linalg.inv(H @ Sig @ H.T + Q_all)
        mu, Sig = mu + K @ nu, (np.eye(3) - K @ H) @ Sig
        mu[2] = _wrap(mu[2])
    return mu, Sig, used


@wrong("localization_step", equation="(2)", what="the innovation has its sign flipped, h(mu) - z")
def loc_innovation_sign(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(_rb(mu, landmarks[j]), z[j])
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong("localization_step", equation="(5)", what="the heading is not wrapped after an update")
def loc_heading_unwrapped(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, M)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(1)",
    inputs=("M",),
    what="forgets the process noise: the prediction's covariance is G Sigma G^T without W M W^T",
)
def loc_process_noise_forgotten(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    G = _unicycle_G(mu, u, dt)
    mu, Sig = _unicycle(mu, u, dt), G @ Sig @ G.T
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(1)",
    what="takes the Jacobians G and W at the predicted mean g(mu, u) instead of at the previous mean",
)
def loc_jacobians_at_prediction(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu = _unicycle(mu, u, dt)
    G, W = _unicycle_G(mu, u, dt), _unicycle_W(mu, u, dt)
    Sig = G @ Sig @ G.T + W @ M @ W.T
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="(1)-(4)",
    inputs=("M", "Q"),
    what="swaps the two noises: the prediction adds W Q W^T and the readings' S adds M",
)
def loc_M_and_Q_swapped(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu, Sig = _predict(mu, Sig, u, dt, Q)
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + M
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, M)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@wrong(
    "localization_step",
    equation="",
    inputs=("mu",),
    what="predicts into the caller's mu in place (mu[:] = g(mu, u)): right numbers, but the input is changed",
)
def loc_predicts_in_place(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    G, W = _unicycle_G(mu, u, dt), _unicycle_W(mu, u, dt)
    mu[:] = _unicycle(mu, u, dt)
    Sig = G @ Sig @ G.T + W @ M @ W.T
    z, landmarks = _readings(z, landmarks)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu, landmarks[j]))
        S = H @ Sig @ H.T + Q
        if nu @ np.linalg.solve(S, nu) <= gate**2:
            mu, Sig = _update(mu, Sig, nu, H, Q)
            mu[2] = _wrap(mu[2])
            used[j] = True
    return mu, Sig, used


@right("localization_step", what="written out by hand: K by np.linalg.solve, the gate on the distance d <= gate")
def loc_by_hand(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu = np.array(mu, dtype=float)
    Sig = np.array(Sig, dtype=float)
    G, W = _unicycle_G(mu, u, dt), _unicycle_W(mu, u, dt)
    mu = _unicycle(mu, u, dt)
    Sig = G @ Sig @ G.T + W @ np.asarray(M) @ W.T
    readings = np.asarray(z, dtype=float).reshape(-1, 2)
    marks = np.asarray(landmarks, dtype=float).reshape(-1, 2)
    used = []
    for z_j, m in zip(readings, marks, strict=True):
        dx, dy = m[0] - mu[0], m[1] - mu[1]
        q = dx * dx + dy * dy
        H = np.array([[-dx / math.sqrt(q), -dy / math.sqrt(q), 0.0], [dy / q, -dx / q, -1.0]])
        nu = np.array([z_j[0] - math.sqrt(q), z_j[1] - (math.atan2(dy, dx) - mu[2])])
        nu[1] = math.atan2(math.sin(nu[1]), math.cos(nu[1]))
        S = H @ Sig @ H.T + Q
        if math.sqrt(nu @ np.linalg.solve(S, nu)) > gate:
            used.append(False)
            continue
        K = np.linalg.solve(S, H @ Sig).T  # K = Sig H^T S^-1, S and Sig symmetric
        mu = mu + K @ nu
        Sig = (np.eye(3) - K @ H) @ Sig
        mu[2] = math.atan2(math.sin(mu[2]), math.cos(mu[2]))
        used.append(True)
    return mu, Sig, np.array(used, dtype=bool)


@right("localization_step", what="the Joseph-form covariance and a gate on the innovation whitened by chol(S)")
def loc_joseph_whitened(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    mu_t, Sig_t = _predict(np.asarray(mu, dtype=float), np.asarray(Sig, dtype=float), u, dt, np.asarray(M))
    z, landmarks = _readings(z, landmarks)
    Q = np.asarray(Q, dtype=float)
    used = np.zeros(len(z), dtype=bool)
    for j in range(len(z)):
        H = _rb_jacobian(mu_t, landmarks[j])
        nu = _rb_residual(z[j], _rb(mu_t, landmarks[j]))
        S = H @ Sig_t @ H.T + Q
        e = np.linalg.solve(np.linalg.cholesky(S), nu)  # L^-1 nu, whose squared length is nu^T S^-1 nu
        if e @ e > gate**2:
            continue
        K = Sig_t @ H.T @ np.linalg.inv(S)
        A = np.eye(3) - K @ H
        mu_t = mu_t + K @ nu
        Sig_t = A @ Sig_t @ A.T + K @ Q @ K.T
        mu_t[2] = _wrap(mu_t[2])
        used[j] = True
    return mu_t, Sig_t, used


# ---------------------------------------------------------------- resample_systematic (chapter 11)
@wrong(
    "resample_systematic", equation="(6)", what="stratified: a fresh random number for every position, (k + U_k) / N"
)
def rs_stratified(w, rng):
    N = len(w)
    p = (np.arange(N) + rng.random(N)) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong("resample_systematic", equation="(6)", what="multinomial: N independent positions U_k, not evenly spaced")
def rs_multinomial(w, rng):
    N = len(w)
    p = rng.random(N)
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong("resample_systematic", equation="(6)", inputs=("rng",), what="no random offset at all: positions k / N")
def rs_no_offset(w, rng):
    N = len(w)
    p = np.arange(N) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    inputs=("rng",),
    what="draws the offset from a new generator, np.random.default_rng(), ignoring the rng it is given",
)
def rs_fresh_generator(w, rng):
    N = len(w)
    U = np.random.default_rng().random()
    p = (np.arange(N) + U) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    what="positions k + U, not divided by N: all but the first lie beyond 1 and give indices past the end",
)
def rs_positions_not_divided(w, rng):
    N = len(w)
    p = np.arange(N) + rng.random()
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    what="the offset is not divided by N: positions k / N + U, which run past 1",
)
def rs_offset_not_divided(w, rng):
    N = len(w)
    p = np.arange(N) / N + rng.random()
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    what="the offset is divided by N twice: U = rng.random() / N, then positions (k + U) / N",
)
def rs_offset_divided_twice(w, rng):
    N = len(w)
    U = rng.random() / N
    p = (np.arange(N) + U) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    what="counts k from 1 to N in (k + U) / N, so the last position passes 1 and its index runs past the end",
)
def rs_positions_from_one(w, rng):
    N = len(w)
    p = (np.arange(1, N + 1) + rng.random()) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    inputs=("w",),
    what="the cumulative weights are not divided by their last entry: a sum below 1 lets an index run past the end",
)
def rs_cumsum_not_normalised(w, rng):
    N = len(w)
    p = (np.arange(N) + rng.random()) / N
    return np.searchsorted(np.cumsum(w), p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    inputs=("w",),
    what="sets c[-1] = 1 instead of dividing by it, handing any shortfall of the weights to the last particle",
)
def rs_last_set_to_one(w, rng):
    N = len(w)
    p = (np.arange(N) + rng.random()) / N
    c = np.cumsum(w)
    c[-1] = 1.0
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="(6)",
    what="takes the first i with p <= c_i (searchsorted side='left'): a position on a boundary picks the slice before",
)
def rs_side_left(w, rng):
    N = len(w)
    p = (np.arange(N) + rng.random()) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, p)


@wrong(
    "resample_systematic",
    equation="(6)",
    what="puts a 0 in front of the cumulative weights, so every index comes out one too high",
)
def rs_cumsum_shifted(w, rng):
    N = len(w)
    p = (np.arange(N) + rng.random()) / N
    c = np.concatenate([[0.0], np.cumsum(w)])
    c /= c[-1]
    return np.searchsorted(c, p, side="right")


@wrong(
    "resample_systematic",
    equation="",
    what="returns how many times each particle is drawn instead of the indices of the particles drawn",
)
def rs_counts_instead_of_indices(w, rng):
    N = len(w)
    p = (np.arange(N) + rng.random()) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.bincount(np.searchsorted(c, p, side="right"), minlength=N)


@wrong(
    "resample_systematic",
    equation="",
    inputs=("w",),
    what="builds the cumulative weights in place over the caller's w (right indices, but the input is changed)",
)
def rs_cumsum_in_place(w, rng):
    N = len(w)
    U = rng.random()
    c = np.asarray(w, dtype=float)
    for i in range(1, N):
        c[i] += c[i - 1]
    c /= c[-1]
    return np.searchsorted(c, (np.arange(N) + U) / N, side="right")


@right("resample_systematic", what="one walk along the cumulative weights in a Python loop")
def rs_loop_walk(w, rng):
    N = len(w)
    U = rng.random()
    c = np.cumsum(w)
    c = c / c[-1]
    idx = np.zeros(N, dtype=int)
    i = 0
    for k in range(N):
        p = (k + U) / N
        while i < N - 1 and c[i] <= p:  # the first i with p < c_i
            i += 1
        idx[k] = i
    return idx


@right("resample_systematic", what="the offset drawn with rng.uniform() and the slices found with np.digitize")
def rs_digitize(w, rng):
    w = np.asarray(w, dtype=float)
    N = w.size
    U = rng.uniform()
    positions = np.minimum((np.arange(N) + U) / N, np.nextafter(1.0, 0.0))
    edges = np.cumsum(w)
    return np.digitize(positions, edges / edges[-1])
