"""Checkers for chapters 7 and 8: the range-bearing sensor, its Jacobian, the unicycle model."""

from __future__ import annotations

import math

import numpy as np

from .. import models
from ._core import Case, CheckResult, Variant, run_check

ROBOT = np.array([1.0, 2.0, 0.0])  # chapter 7's worked example: robot (1, 2, 0) ...
LANDMARK = np.array([4.0, 6.0])  # ... and landmark (4, 6)


def _wrap(a):
    """Wrap into [−π, π) (every case stays clear of ±π, where this and (−π, π] differ)."""
    return (a + np.pi) % (2 * np.pi) - np.pi


def _pose_and_landmark(rng) -> tuple[np.ndarray, np.ndarray]:
    """A random pose and a landmark 0.5 to 8 m away, in any direction."""
    pose = np.array([*rng.uniform(-5, 5, 2), rng.uniform(-np.pi, np.pi)])
    distance, direction = rng.uniform(0.5, 8.0), rng.uniform(-np.pi, np.pi)
    return pose, pose[:2] + distance * np.array([np.cos(direction), np.sin(direction)])


def _sensor_cases(rng) -> list[Case]:
    """The worked example, landmarks straight behind the robot (bearing near ±π), random ones."""
    cases = [Case("chapter 7's worked example", state=ROBOT, landmark=LANDMARK)]
    for theta, landmark_angle in [(0.0, np.pi - 0.05), (0.0, -np.pi + 0.05), (3.0, -2.9), (-3.0, 2.9)]:
        landmark = 2.0 * np.array([np.cos(landmark_angle), np.sin(landmark_angle)])
        cases.append(Case("bearing near ±π", state=np.array([0.0, 0.0, theta]), landmark=landmark))
    for _ in range(10):
        state, landmark = _pose_and_landmark(rng)
        if abs(abs(models.range_bearing(state, landmark)[1]) - np.pi) > 1e-3:  # stay clear of the ±π seam
            cases.append(Case("random poses and landmarks", state=state, landmark=landmark))
    return cases


# ------------------------------------------------------------------ range_bearing
def _range_bearing_with(state, landmark, *, wrap=True, flip=False, atan2=True):
    """h of chapter 7, with knobs for the mistakes."""
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    angle = math.atan2(dy, dx) if atan2 else math.atan(dy / dx)
    phi = state[2] - angle if flip else angle - state[2]
    return np.array([math.hypot(dx, dy), _wrap(phi) if wrap else phi])


def range_bearing(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``range_bearing(state, landmark)`` against :func:`kfcourse.range_bearing`.

    Introduced in chapter 7.

    Parameters
    ----------
    student_fn : callable ``(state [x, y, theta], landmark [mx, my]) -> [r, phi]``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _sensor_cases(np.random.default_rng(seed))
    where = "chapter 7, the range-bearing model: r = √q, φ = atan2(Δy, Δx) − θ, wrapped into (−π, π]"
    variants = [
        Variant(
            "unwrapped_angle",
            lambda s, m: _range_bearing_with(s, m, wrap=False),
            "atan2(Δy, Δx) − θ can leave (−π, π] (up to ±2π); wrap it, e.g. with kf.wrap_angle.",
        ),
        Variant(
            "sign_flip",
            lambda s, m: _range_bearing_with(s, m, flip=True),
            "The bearing is the landmark's direction minus the heading, not the other way round.",
        ),
        Variant(
            "atan_not_atan2",
            lambda s, m: _range_bearing_with(s, m, atan2=False),
            "atan(Δy/Δx) cannot tell a landmark ahead from one behind; atan2(Δy, Δx) can.",
        ),
    ]
    return run_check("range_bearing", student_fn, models.range_bearing, cases, variants, ("z",), where)


# --------------------------------------------------------- range_bearing_jacobian
def _jacobian_with(state, landmark, *, d_sign=1.0, theta_entry=-1.0, q_rows=False):
    """H of chapter 7, with knobs for the mistakes."""
    dx, dy = d_sign * (landmark[0] - state[0]), d_sign * (landmark[1] - state[1])
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    range_by, bearing_by = (q, r) if q_rows else (r, q)
    return np.array([[-dx / range_by, -dy / range_by, 0.0], [dy / bearing_by, -dx / bearing_by, theta_entry]])


def range_bearing_jacobian(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``range_bearing_jacobian(state, landmark)`` against :func:`kfcourse.range_bearing_jacobian`.

    Introduced in chapter 7.

    Parameters
    ----------
    student_fn : callable ``(state [x, y, theta], landmark [mx, my]) -> H (2, 3)``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _sensor_cases(np.random.default_rng(seed))
    where = (
        "chapter 7, the Jacobian H: with Δx = m_x − x, Δy = m_y − y, q = Δx² + Δy², "
        "H = [[−Δx/√q, −Δy/√q, 0], [Δy/q, −Δx/q, −1]]"
    )
    variants = [
        Variant(
            "sign_flip",
            lambda s, m: _jacobian_with(s, m, d_sign=-1.0),
            "Δx and Δy point from the robot to the landmark (landmark minus robot); moving the robot "
            "toward the landmark shortens the range, so ∂r/∂x = −Δx/√q.",
        ),
        Variant(
            "sign_flip",
            lambda s, m: _jacobian_with(s, m, theta_entry=1.0),
            "The bearing is atan2(Δy, Δx) − θ, so ∂φ/∂θ = −1: turning left moves the landmark right.",
        ),
        Variant(
            "q_not_sqrt_q",
            lambda s, m: _jacobian_with(s, m, q_rows=True),
            "The range row divides by √q (the range), the bearing row by q (the range squared).",
        ),
    ]
    return run_check(
        "range_bearing_jacobian",
        student_fn,
        models.range_bearing_jacobian,
        cases,
        variants,
        ("H",),
        where + " (kf.numeric_jacobian shows which entries are wrong)",
    )


# ----------------------------------------------------------------------- unicycle
def _unicycle_with(state, u, dt, *, limit=True, wrap=True, euler=False, y_sign=1.0):
    """The unicycle model of chapter 8, with knobs for the mistakes."""
    x, y, theta = state
    V, w = u
    if euler or (limit and w == 0):  # the straight line
        x_new, y_new = x + V * dt * np.cos(theta), y + V * dt * np.sin(theta)
    else:  # the arc
        x_new = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))
        y_new = y + y_sign * V / w * (np.cos(theta) - np.cos(theta + w * dt))
    theta_new = theta + w * dt
    return np.array([x_new, y_new, _wrap(theta_new) if wrap else theta_new])


def _unicycle_in_floats(state, u, dt):
    """The arc in Python floats, no straight-line limit: at ω = 0 it raises ZeroDivisionError."""
    x, y, theta = (float(s) for s in state)
    V, w = float(u[0]), float(u[1])
    return np.array([x + V / w * (math.sin(theta + w * dt) - math.sin(theta)), y, theta])


def unicycle(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``unicycle(state, u, dt)`` (one pose) against :func:`kfcourse.unicycle`.

    Introduced in chapter 8.

    Parameters
    ----------
    student_fn : callable ``(state [x, y, theta], u [V, omega], dt) -> next state [x, y, theta]``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    origin = np.zeros(3)
    cases = [
        Case("ω = 0: chapter 8's example", state=origin, u=np.array([0.5, 0.0]), dt=1.0),
        Case("ω = 0: a straight line at θ = 1", state=np.array([1.0, -2.0, 1.0]), u=np.array([2.0, 0.0]), dt=0.5),
        Case("turning on the spot", state=np.array([1.0, 1.0, 0.5]), u=np.array([0.0, 1.0]), dt=0.5),
        Case("a quarter circle", state=origin, u=np.array([np.pi / 2, np.pi / 2]), dt=1.0),
        Case("heading crossing +π", state=np.array([0.0, 0.0, 3.0]), u=np.array([1.0, 0.5]), dt=1.0),
        Case("heading crossing −π", state=np.array([2.0, 1.0, -3.0]), u=np.array([0.5, -0.4]), dt=1.0),
    ]
    while len(cases) < 16:
        state = np.array([*rng.uniform(-5, 5, 2), rng.uniform(-np.pi, np.pi)])
        u, dt = np.array([rng.uniform(-1, 2), rng.uniform(-1.5, 1.5)]), float(rng.uniform(0.05, 1.0))
        if abs(abs(models.unicycle(state, u, dt)[2]) - np.pi) > 1e-3:  # stay clear of the ±π seam
            cases.append(Case("random poses and controls", state=state, u=u, dt=dt))
    where = (
        "chapter 8, the unicycle model: x' = x + V/ω (sin(θ + ωΔt) − sin θ), y' = y + V/ω (cos θ − cos(θ + ωΔt)), "
        "θ' = θ + ωΔt wrapped into (−π, π]; at ω = 0 the straight line x' = x + VΔt cos θ, y' = y + VΔt sin θ"
    )
    variants = [
        Variant(
            "divides_by_omega",
            lambda s, u, dt: _unicycle_with(s, u, dt, limit=False),
            "At ω = 0, V/ω is a division by zero: handle ω = 0 (or |ω| tiny) with the straight-line limit.",
        ),
        Variant(
            "divides_by_omega",
            _unicycle_in_floats,
            "At ω = 0, V/ω is a division by zero: handle ω = 0 (or |ω| tiny) with the straight-line limit.",
        ),
        Variant(
            "unwrapped_angle",
            lambda s, u, dt: _unicycle_with(s, u, dt, wrap=False),
            "θ + ωΔt can leave (−π, π]; wrap it, e.g. with kf.wrap_angle.",
        ),
        Variant(
            "sign_flip",
            lambda s, u, dt: _unicycle_with(s, u, dt, y_sign=-1.0),
            "Check the order in y': cos θ − cos(θ + ωΔt), so that turning left (ω > 0) from θ = 0 moves "
            "the robot to +y.",
        ),
        Variant(
            "euler_step",
            lambda s, u, dt: _unicycle_with(s, u, dt, euler=True),
            "While ω ≠ 0 the robot drives along an arc; the straight line is only the ω = 0 limit.",
        ),
    ]
    return run_check("unicycle", student_fn, models.unicycle, cases, variants, ("state",), where)
