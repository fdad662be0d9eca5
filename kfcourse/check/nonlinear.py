"""Checkers for chapters 7 and 8: the range-bearing sensor, its Jacobian, the unicycle model."""

from __future__ import annotations

import math

import numpy as np

from .. import models
from ._core import Case, CheckResult, Probe, Step, Variant, angle_in_range, moved, non_negative, run_check

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
    """The worked example, a landmark straight ahead (bearing exactly 0: a bearing turned by π lands on the seam,
    π when wrapped into (−π, π] and −π by (φ mod 2π) − π), landmarks straight behind the robot (bearing near ±π),
    random ones."""
    cases = [Case("chapter 7's worked example", state=ROBOT, landmark=LANDMARK)]
    cases.append(Case("a landmark straight ahead", state=np.array([1.0, 2.0, 0.0]), landmark=np.array([4.0, 2.0])))
    for theta, landmark_angle in [(0.0, np.pi - 0.05), (0.0, -np.pi + 0.05), (3.0, -2.9), (-3.0, 2.9)]:
        landmark = 2.0 * np.array([np.cos(landmark_angle), np.sin(landmark_angle)])
        cases.append(Case("bearing near ±π", state=np.array([0.0, 0.0, theta]), landmark=landmark))
    for _ in range(10):
        state, landmark = _pose_and_landmark(rng)
        if abs(abs(models.range_bearing(state, landmark)[1]) - np.pi) > 1e-3:  # stay clear of the ±π seam
            cases.append(Case("random poses and landmarks", state=state, landmark=landmark))
    return cases


# Each part of the pose and of the landmark moved alone (run_check's diagnosis): r follows the offset
# (Δx, Δy) alone, φ the offset and θ; H follows the offset alone, never θ.
OFFSET = "Δx = m_x − x and Δy = m_y − y, and through them r = √q and φ = atan2(Δy, Δx) − θ"
SENSOR_PROBES = (
    Probe("state", moved(0, 0.5), OFFSET, "the robot's x"),
    Probe("state", moved(1, 0.5), OFFSET, "the robot's y"),
    Probe("state", moved(2, 0.3), "the bearing only, φ = atan2(Δy, Δx) − θ", "the heading θ"),
    Probe("landmark", moved(0, 0.5), OFFSET, "the landmark's m_x"),
    Probe("landmark", moved(1, 0.5), OFFSET, "the landmark's m_y"),
)
ENTRIES = "every entry of H but ∂φ/∂θ = −1, through Δx, Δy and q"
JACOBIAN_PROBES = (
    Probe("state", moved(0, 0.5), ENTRIES, "the robot's x"),
    Probe("state", moved(1, 0.5), ENTRIES, "the robot's y"),
    Probe("state", moved(2, 0.3), "no entry of H (φ has − θ, whose derivative is −1)", "the heading θ"),
    Probe("landmark", moved(0, 0.5), ENTRIES, "the landmark's m_x"),
    Probe("landmark", moved(1, 0.5), ENTRIES, "the landmark's m_y"),
)


def _with_entry(name: str, index: int, value: float):
    """A step's isolation: entry ``index`` of the input ``name`` set to ``value`` (the heading θ = 0, say)."""

    def isolate(inputs: dict) -> dict:
        a = np.array(inputs[name], dtype=float)
        a[index] = value
        return {**inputs, name: a}

    return isolate


SENSOR_STEPS = (
    Step("the heading θ = 0", "r = √q and the landmark's direction atan2(Δy, Δx) alone", _with_entry("state", 2, 0.0)),
)


# ------------------------------------------------------------------ range_bearing
def _range_bearing_with(state, landmark, *, wrap=True, flip=False, atan2=True, **mistake):
    """h of chapter 7, with knobs for the mistakes (the defaults are right)."""
    wrong = mistake.get
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    if wrong("robot_minus_landmark"):
        dx, dy = -dx, -dy
    if not atan2:
        angle = math.atan(dy / dx)
    else:
        angle = math.atan2(dx, dy) if wrong("swap_atan2") else math.atan2(dy, dx)
    if wrong("degrees_first"):
        angle = math.degrees(angle)
    phi = state[2] - angle if flip else angle + (state[2] if wrong("plus_theta") else -state[2])
    if wrong("mod_2pi"):
        phi = phi % (2 * np.pi)
    elif wrong("shifted_wrap"):
        phi = phi % (2 * np.pi) - np.pi
    elif wrap:
        phi = models.wrap_angle(phi) if wrap == "(-pi, pi]" else _wrap(phi)
    if wrong("degrees"):
        phi = math.degrees(phi)
    r = dx * dx + dy * dy if wrong("q") else math.hypot(dx, dy)
    return np.array([phi, r] if wrong("swapped") else [r, phi])


def _rb_variant(mistake: str, hint: str, **knobs) -> Variant:
    return Variant(mistake, lambda s, m: _range_bearing_with(s, m, **knobs), hint)


def range_bearing(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``range_bearing(state, landmark)`` against :func:`kfcourse.range_bearing`.

    The first case is chapter 7's worked example.  Introduced in chapter 7.

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
    WRAP = "atan2(Δy, Δx) − θ can leave (−π, π] (up to ±2π); wrap it, e.g. with kf.wrap_angle."
    DEGREES = "NumPy's angles are radians: leave atan2's answer as it is, without np.degrees."
    variants = [
        _rb_variant("unwrapped_angle", WRAP, wrap=False),
        _rb_variant(
            "unwrapped_angle", "% 2π wraps into [0, 2π); the bearing lives in (−π, π] (kf.wrap_angle).", mod_2pi=True
        ),
        _rb_variant(
            "sign_flip",
            "The bearing is the landmark's direction minus the heading, not the other way round.",
            flip=True,
        ),
        _rb_variant(
            "heading_sign", "The bearing is measured from the heading: atan2(Δy, Δx) − θ, minus θ.", plus_theta=True
        ),
        _rb_variant(
            "atan_not_atan2",
            "atan(Δy/Δx) cannot tell a landmark ahead from one behind; atan2(Δy, Δx) can.",
            atan2=False,
        ),
        _rb_variant(
            "atan2_arguments_swapped", "np.arctan2(y, x) takes the y offset first: atan2(Δy, Δx).", swap_atan2=True
        ),
        *(
            _rb_variant(
                "robot_minus_landmark",
                "Δx = m_x − x and Δy = m_y − y point from the robot to the landmark; "
                "the other way round the bearing is off by π.",
                robot_minus_landmark=True,
                wrap=wrap,
            )
            for wrap in ("(-pi, pi]", "[-pi, pi)")
        ),
        _rb_variant(
            "wrap_shifted_by_pi",
            "(φ mod 2π) lies in [0, 2π), so (φ mod 2π) − π is in range but turned by π; wrap with "
            "π − ((π − φ) mod 2π), or kf.wrap_angle.",
            shifted_wrap=True,
        ),
        _rb_variant("degrees", DEGREES, degrees=True),
        _rb_variant("degrees", DEGREES, degrees=True, wrap=False),
        _rb_variant("degrees", DEGREES, degrees_first=True),
        _rb_variant("degrees", DEGREES, degrees_first=True, wrap=False),
        _rb_variant("q_not_sqrt_q", "The range is the distance √q = √(Δx² + Δy²), not its square q.", q=True),
        _rb_variant("outputs_swapped", "Return [r, φ]: the range first, then the bearing.", swapped=True),
    ]
    return run_check(
        "range_bearing",
        student_fn,
        models.range_bearing,
        cases,
        variants,
        ("z",),
        where,
        steps=SENSOR_STEPS,
        probes=SENSOR_PROBES,
        invariants=(
            non_negative("z", "a distance", index=0, label="range r"),
            angle_in_range("z", 1, "bearing φ"),
        ),
    )


# --------------------------------------------------------- range_bearing_jacobian
def _jacobian_with(state, landmark, *, d_sign=1.0, theta_entry=-1.0, **mistake):
    """H of chapter 7, with knobs for the mistakes (the defaults are right)."""
    wrong = mistake.get
    dx, dy = d_sign * (landmark[0] - state[0]), d_sign * (landmark[1] - state[1])
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    range_row = np.array([-dx, -dy]) / (q if wrong("q_in_range_row") else r)
    bearing_row = np.array([dy, -dx]) / (r if wrong("r_in_bearing_row") else q)
    if wrong("swap_in_range_row"):
        range_row = range_row[::-1]
    if wrong("swap_in_bearing_row"):
        bearing_row = np.array([dx, -dy]) / q
    range_row = -range_row if wrong("range_sign") else range_row
    bearing_row = -bearing_row if wrong("bearing_sign") else bearing_row
    return np.array(
        [[*range_row, 0.0], [*bearing_row, -theta_entry if wrong("bearing_sign") == "row" else theta_entry]]
    )


def _jacobian_variant(mistake: str, hint: str, **knobs) -> Variant:
    return Variant(mistake, lambda s, m: _jacobian_with(s, m, **knobs), hint)


def _numeric_jacobian(state, landmark):
    """The Jacobian by central differences, as kf.numeric_jacobian gives it (no derivation)."""
    return models.numeric_jacobian(lambda s: models.range_bearing(s, landmark), state)


JACOBIAN_WHERE = (
    "chapter 7, the Jacobian H: with Δx = m_x − x, Δy = m_y − y, q = Δx² + Δy², "
    "H = [[−Δx/√q, −Δy/√q, 0], [Δy/q, −Δx/q, −1]]"
)


NUMERIC = (
    "kf.numeric_jacobian is the tool that checks a Jacobian; the exercise asks for the Jacobian itself: derive "
    "each entry of H by hand from h and write the formula."
)


def _jacobian_variants() -> list[Variant]:
    """The catalogue of :func:`range_bearing_jacobian`: each known mistake as a wrong version, with its hint."""
    BEARING = (
        "The bearing row is the derivative of atan2(Δy, Δx): ∂φ/∂x = Δy/q and ∂φ/∂y = −Δx/q (a robot that moves "
        "up sees the landmark turn clockwise). Work it out from d atan(t)/dt = 1/(1 + t²)."
    )
    return [
        _jacobian_variant("bearing_row_sign", BEARING, bearing_sign=True),
        _jacobian_variant("bearing_row_sign", BEARING + " And ∂φ/∂θ = −1.", bearing_sign="row"),
        _jacobian_variant(
            "range_row_sign",
            "Moving the robot toward the landmark shortens the range, so ∂r/∂x = −Δx/√q and ∂r/∂y = −Δy/√q.",
            range_sign=True,
        ),
        _jacobian_variant(
            "position_entries_flipped",
            "H is the derivative with respect to the robot's pose, with Δx = m_x − x and Δy = m_y − y pointing from "
            "the robot to the landmark: moving the robot toward the landmark shortens the range, so ∂r/∂x = −Δx/√q.",
            d_sign=-1.0,
        ),
        _jacobian_variant(
            "sign_flip",
            "The bearing is atan2(Δy, Δx) − θ, so ∂φ/∂θ = −1: turning left moves the landmark right.",
            theta_entry=1.0,
        ),
        _jacobian_variant(
            "missing_theta",
            "The bearing is atan2(Δy, Δx) − θ, so ∂φ/∂θ = −1: turning left moves the landmark right.",
            theta_entry=0.0,
        ),
        _jacobian_variant(
            "q_not_sqrt_q",
            "The range row divides by √q (the range), the bearing row by q (the range squared).",
            q_in_range_row=True,
            r_in_bearing_row=True,
        ),
        _jacobian_variant(
            "q_not_sqrt_q", "The range row divides by √q, the range: ∂r/∂x = −Δx/√q.", q_in_range_row=True
        ),
        _jacobian_variant(
            "q_not_sqrt_q", "The bearing row divides by q, the range squared: ∂φ/∂x = Δy/q.", r_in_bearing_row=True
        ),
        _jacobian_variant(
            "dx_dy_swapped",
            "∂r/∂x goes with Δx and ∂r/∂y with Δy; in the bearing row, ∂φ/∂x = Δy/q and ∂φ/∂y = −Δx/q.",
            swap_in_range_row=True,
            swap_in_bearing_row=True,
        ),
        _jacobian_variant(
            "dx_dy_swapped", "The range row is −(Δx, Δy)/√q: ∂r/∂x goes with Δx.", swap_in_range_row=True
        ),
        _jacobian_variant("dx_dy_swapped", BEARING, swap_in_bearing_row=True),
        Variant("numeric_not_derived", _numeric_jacobian, NUMERIC),
    ]


def range_bearing_jacobian(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``range_bearing_jacobian(state, landmark)`` against :func:`kfcourse.range_bearing_jacobian`.

    The first case is chapter 7's worked example.  The exercise asks for H derived by hand: a
    Jacobian differentiated numerically (``kf.numeric_jacobian`` or finite differences of your
    own) agrees within the tolerance but only to about 1e-10, where the formula agrees to
    rounding, and it is told so.  Introduced in chapter 7.

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
    return run_check(
        "range_bearing_jacobian",
        student_fn,
        models.range_bearing_jacobian,
        cases,
        _jacobian_variants(),
        ("H",),
        JACOBIAN_WHERE + " (check each entry against kf.numeric_jacobian while you derive it)",
        approximation=(1e-12, "numeric_not_derived", NUMERIC),
        probes=JACOBIAN_PROBES,
    )


# ----------------------------------------------------------------------- unicycle
# With ω = 0 the robot drives the straight line alone, with V = 0 it turns on the spot alone.
MOTION_STEPS = (
    Step("ω = 0", "the straight line x' = x + VΔt cos θ, y' = y + VΔt sin θ, θ' = θ", _with_entry("u", 1, 0.0)),
    Step("V = 0", "the turn on the spot: x' = x, y' = y, θ' = θ + ωΔt wrapped", _with_entry("u", 0, 0.0)),
)
ARC = "x' and y' along the arc (or the straight line), and θ' = θ + ωΔt"
MOTION_PROBES = (
    Probe("state", moved(0, 0.5), "x' = x + ..., and nothing else", "the robot's x"),
    Probe("state", moved(2, 0.3), "every line: the arc's direction and θ' = θ + ωΔt", "the heading θ"),
    Probe("u", moved(0, 0.5), "x' and y', the distance driven (V/ω on the arc, VΔt on the line)", "the speed V"),
    Probe("u", moved(1, 0.2), ARC, "the turn rate ω"),
    Probe("dt", lambda dt: dt * 1.5, ARC, "the time step Δt"),
)


NEAR_ZERO = 1e-9  # |ω| below which a right answer may drive the straight line: the arc formula is exact above ~1e-6


def _unicycle_with(
    state, u, dt, *, limit=NEAR_ZERO, wrap=True, euler=False, y_sign=1.0, sin=np.sin, cos=np.cos, **mistake
):
    """The unicycle model of chapter 8 with the arc formula and a straight-line branch for |ω| < ``limit``
    (``limit=0``: only at ω == 0; ``None``: never), and knobs for the mistakes."""
    wrong = mistake.get
    x, y, theta = state
    V, w = u
    distance = V if wrong("no_dt_in_distance") else V * dt
    turn = w if wrong("no_dt_in_heading") else w * dt
    arc_turn = w if wrong("no_dt_in_arc") else w * dt
    swap = wrong("swap_sin_cos")  # True: everywhere; "arc" or "line": only there
    line_sin, line_cos = (cos, sin) if swap in (True, "line") else (sin, cos)
    arc_sin, arc_cos = (cos, sin) if swap in (True, "arc") else (sin, cos)
    if euler or (limit is not None and (w == 0 or abs(w) < limit)):  # the straight line
        x_new, y_new = x + distance * line_cos(theta), y + distance * line_sin(theta)
    else:  # the arc
        x_new = x + V / w * (arc_sin(theta + arc_turn) - arc_sin(theta))
        y_new = y + y_sign * V / w * (arc_cos(theta) - arc_cos(theta + arc_turn))
        if wrong("swap_brackets"):  # x' with y's bracket and y' with x's
            x_new, y_new = x + (y_new - y), y + (x_new - x)
    theta_new = theta + turn
    return np.array([x_new, y_new, _wrap(theta_new) if wrap else theta_new])


def _unicycle_in_floats(state, u, dt):
    """The arc in Python floats, no straight-line limit: at ω = 0 it raises ZeroDivisionError."""
    x, y, theta = (float(s) for s in state)
    V, w = float(u[0]), float(u[1])
    x_new = x + V / w * (math.sin(theta + w * dt) - math.sin(theta))
    y_new = y + V / w * (math.cos(theta) - math.cos(theta + w * dt))
    return np.array([x_new, y_new, _wrap(theta + w * dt)])


def _unicycle_variant(mistake: str, hint: str, **knobs) -> Variant:
    return Variant(mistake, lambda s, u, dt: _unicycle_with(s, u, dt, **knobs), hint)


def _motion_cases(rng) -> list[Case]:
    """The cases of :func:`unicycle`: chapter 8's worked example, the edge cases and the slow turns, then seeded
    random ones."""
    origin = np.zeros(3)
    cases = [
        Case("chapter 8's worked example: θ = 0, V = 0.5, ω = 0, Δt = 1", state=origin, u=np.array([0.5, 0.0]), dt=1.0),
        Case("ω = 0: a straight line at θ = 1", state=np.array([1.0, -2.0, 1.0]), u=np.array([2.0, 0.0]), dt=0.5),
        Case("turning on the spot", state=np.array([1.0, 1.0, 0.5]), u=np.array([0.0, 1.0]), dt=0.5),
        Case("a quarter circle", state=origin, u=np.array([np.pi / 2, np.pi / 2]), dt=1.0),
        Case("heading crossing +π", state=np.array([0.0, 0.0, 3.0]), u=np.array([1.0, 0.5]), dt=1.0),
        Case("heading crossing −π", state=np.array([2.0, 1.0, -3.0]), u=np.array([0.5, -0.4]), dt=1.0),
        Case(
            "ω = 1e-15: chapter 8's nearly straight line",
            state=np.array([0.0, 0.0, 0.3]),
            u=np.array([0.5, 1e-15]),
            dt=1.0,
        ),
    ]
    for slow in (1e-5, 1e-3, 1e-2, 5e-2):  # slow turns, both ways: the arc formula exact, the robot turning
        for w in (slow, -slow):
            cases.append(Case(f"ω = {w:g}: a slow turn", state=np.array([0.0, 0.0, 0.3]), u=np.array([2.0, w]), dt=1.0))
    while len(cases) < 25:
        state = np.array([*rng.uniform(-5, 5, 2), rng.uniform(-np.pi, np.pi)])
        u, dt = np.array([rng.uniform(-1, 2), rng.uniform(-1.5, 1.5)]), float(rng.uniform(0.05, 1.0))
        if abs(abs(models.unicycle(state, u, dt)[2]) - np.pi) > 1e-3:  # stay clear of the ±π seam
            cases.append(Case("random poses and controls", state=state, u=u, dt=dt))
    return cases


MOTION_WHERE = (
    "chapter 8, the unicycle model: x' = x + V/ω (sin(θ + ωΔt) − sin θ), y' = y + V/ω (cos θ − cos(θ + ωΔt)), "
    "θ' = θ + ωΔt wrapped into (−π, π]; for ω at or near 0 the straight line x' = x + VΔt cos θ, "
    "y' = y + VΔt sin θ"
)


def _motion_variants() -> list[Variant]:
    LIMIT = "At ω = 0, V/ω is a division by zero: handle ω = 0 (or |ω| tiny) with the straight-line limit."
    TINY = (
        "Near ω = 0 the arc formula loses its digits (chapter 8 shows it 2 cm off at ω = 1e-15): drive the straight "
        "line whenever |ω| is tiny, e.g. abs(omega) < 1e-9, not only when omega == 0."
    )
    SIN_COS = "x moves with cos θ and y with sin θ: heading θ = 0 drives along +x."
    WIDE = (
        "Only |ω| below about 1e-6 needs the straight line: at ω = 1e-3 the arc formula is still exact to about "
        "1e-13 m, and the robot already turns (2 m along the arc, it ends 1 mm to the side of the straight line)."
    )
    return [
        _unicycle_variant("exact_zero_test", TINY, limit=0.0),
        _unicycle_variant("exact_zero_test", TINY, limit=0.0, sin=math.sin, cos=math.cos),
        *(_unicycle_variant("straight_too_wide", WIDE, limit=limit) for limit in (1e-4, 1e-3, 1e-2, 5e-2, 1e-1)),
        _unicycle_variant("divides_by_omega", LIMIT, limit=None),
        Variant("divides_by_omega", _unicycle_in_floats, LIMIT),
        _unicycle_variant(
            "unwrapped_angle", "θ + ωΔt can leave (−π, π]; wrap it, e.g. with kf.wrap_angle.", wrap=False
        ),
        _unicycle_variant(
            "sign_flip",
            "Check the order in y': cos θ − cos(θ + ωΔt), so that turning left (ω > 0) from θ = 0 moves "
            "the robot to +y.",
            y_sign=-1.0,
        ),
        _unicycle_variant(
            "euler_step",
            "While ω ≠ 0 the robot drives along an arc; the straight line is only the ω = 0 limit.",
            euler=True,
        ),
        _unicycle_variant("sin_cos_swapped", SIN_COS, swap_sin_cos=True),
        _unicycle_variant("sin_cos_swapped", SIN_COS + " (In the arc too: x' has the sines.)", swap_sin_cos="arc"),
        _unicycle_variant("sin_cos_swapped", SIN_COS, swap_sin_cos="line"),
        _unicycle_variant("sin_cos_swapped", SIN_COS + " In the arc, x' has the sines.", swap_brackets=True),
        _unicycle_variant(
            "sin_cos_swapped", SIN_COS + " In the arc, x' has the sines.", swap_brackets=True, swap_sin_cos="line"
        ),
        _unicycle_variant(
            "heading_without_dt", "ω is a rate: over a step the heading turns by ωΔt.", no_dt_in_heading=True
        ),
        _unicycle_variant(
            "heading_without_dt",
            "ω is a rate: over a step the heading turns by ωΔt, in θ' and in the arc's sin(θ + ωΔt).",
            no_dt_in_heading=True,
            no_dt_in_arc=True,
        ),
        _unicycle_variant(
            "speed_not_distance",
            "V is a speed: the straight line covers VΔt metres, x' = x + VΔt cos θ.",
            no_dt_in_distance=True,
        ),
    ]


def unicycle(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``unicycle(state, u, dt)`` (one pose) against :func:`kfcourse.unicycle`.

    The first case is chapter 8's example (θ = 0, V = 0.5 m/s, ω = 0, Δt = 1 s); one case
    drives with ω = 1e-15, where chapter 8 shows the arc formula 2 cm off: a test for
    exactly ω == 0 does not protect it.  Slow turns at ω = ±1e-5, ±0.001, ±0.01 and ±0.05, where
    the arc formula is exact, catch a straight-line branch taken too far from 0.  Introduced in chapter 8.

    Parameters
    ----------
    student_fn : callable ``(state [x, y, theta], u [V, omega], dt) -> next state [x, y, theta]``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _motion_cases(np.random.default_rng(seed))
    return run_check(
        "unicycle",
        student_fn,
        models.unicycle,
        cases,
        _motion_variants(),
        ("state",),
        MOTION_WHERE,
        steps=MOTION_STEPS,
        probes=MOTION_PROBES,
        invariants=(angle_in_range("state", 2, "heading θ'"),),
    )
