"""Motion and measurement models with their Jacobians.

A pose is ``[x, y, theta]`` (m, m, rad); a control is ``[V, omega]`` (m/s, rad/s);
a landmark is ``[mx, my]`` (m); a range-bearing reading is ``[r, phi]`` (m, rad); a beacon is
``[bx, by]`` (m) and a range-only reading ``[r]`` (m).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from . import _validate as v

__all__ = [
    "constant_velocity",
    "numeric_jacobian",
    "pose_mean",
    "pose_residual",
    "range_bearing",
    "range_bearing_jacobian",
    "range_bearing_mean",
    "range_bearing_residual",
    "range_only",
    "range_only_jacobian",
    "scaled_range",
    "scaled_range_jacobian",
    "unicycle",
    "unicycle_control_jacobian",
    "unicycle_jacobian",
    "wrap_angle",
]


def wrap_angle(a):
    r"""Wrap an angle (or array of angles) into :math:`(-\pi, \pi]`.

    Introduced in chapter 7 (bearing innovations must be wrapped).

    Parameters
    ----------
    a : float or array_like
        Angles in radians.

    Returns
    -------
    float or ndarray, same shape
    """
    a = v.finite(a, "a")
    # a - 2 pi k with k chosen for (-pi, pi]; angles already in range are returned unchanged.
    # An angle within a turn of the range (as a difference of two wrapped angles is) takes one
    # turn, 2 pi, back towards it: exact in floating point, as a and 2 pi are within a factor 2.
    # Farther ones take the modulo, which keeps even huge angles in range; it can round up to
    # exactly 2 pi, which would give -pi: that end maps to pi.
    if a.ndim == 0:  # one angle, on a Python float: Python's % rounds as np.mod does, bit for bit
        x = float(a)
        if -math.pi < x <= math.pi:
            return x
        once = x - math.copysign(2.0 * math.pi, x)  # one turn back
        if -math.pi < once <= math.pi:
            return once
        out = math.pi - (math.pi - x) % (2.0 * math.pi)
        return math.pi if out <= -math.pi else out
    above, below = a > np.pi, a <= -np.pi
    if not (above.any() or below.any()):
        return a.copy()
    out = a - np.where(above, 2.0 * np.pi, np.where(below, -2.0 * np.pi, 0.0))  # one turn back (in range: a - 0)
    far = (out > np.pi) | (out <= -np.pi)
    if far.any():  # more than a turn out: the modulo
        wrapped = np.pi - np.mod(np.pi - a[far], 2.0 * np.pi)
        out[far] = np.where(wrapped <= -np.pi, np.pi, wrapped)
    return out


def numeric_jacobian(f: Callable, x, eps: float = 1e-6, residual: Callable | None = None) -> np.ndarray:
    r"""Jacobian of ``f`` at ``x`` by central differences.

    .. math:: J_{:,i} \approx \frac{f(x + \varepsilon e_i) - f(x - \varepsilon e_i)}{2\varepsilon}

    Introduced in chapter 7, to check a hand-derived Jacobian.

    Parameters
    ----------
    f : callable ``f(x) -> array (k,)``
    x : array_like, shape (n,)
    eps : float
        Step, > 0.
    residual : callable ``residual(a, b) -> a - b``, optional
        Difference of two outputs; pass one that wraps angles when an output is an
        angle (e.g. :func:`range_bearing_residual`).

    Returns
    -------
    ndarray, shape (k, n)
    """
    f = v.function(f, "f")
    x = v.vector(x, "x")
    eps = v.positive(eps, "eps", "a finite-difference step")
    diff = v.optional_function(residual, "residual") or np.subtract
    cols = []
    for i in range(x.size):
        step = np.zeros_like(x)
        step[i] = eps
        hi = v.vector(f(x + step), "the result of f")
        lo = v.vector(f(x - step), "the result of f", hi.size)
        cols.append(np.asarray(diff(hi, lo), dtype=float) / (2.0 * eps))
    return np.column_stack(cols)


def constant_velocity(dt: float, dim: int = 1) -> tuple[np.ndarray, np.ndarray]:
    r"""Constant-velocity model matrices for ``dim`` axes.

    The state is ``[p_1..p_dim, v_1..v_dim]``; each position advances by its
    velocity times ``dt`` and the sensor sees positions only:

    .. math:: F = \begin{bmatrix} I & \Delta t\, I \\ 0 & I \end{bmatrix}, \qquad
              H = \begin{bmatrix} I & 0 \end{bmatrix}

    Introduced in chapter 5 (``dim=1``) and chapter 6 (``dim=2``).

    Parameters
    ----------
    dt : float
        Time step in s, > 0.
    dim : int
        Number of spatial axes (>= 1).

    Returns
    -------
    (F, H) : shapes (2 dim, 2 dim), (dim, 2 dim)
    """
    dt = v.positive(dt, "dt", "a time step", "s")
    dim = v.whole(dim, "dim", 1)
    eye = np.eye(dim)
    F = np.block([[eye, dt * eye], [np.zeros((dim, dim)), eye]])
    H = np.hstack([eye, np.zeros((dim, dim))])
    return F, H


def _rows(x, name: str, n: int) -> np.ndarray:
    """A checked vector (n,) or stack of them (N, n), one a row."""
    a = v.finite(x, name)
    if a.shape[-1:] != (n,) or a.ndim > 2:
        raise ValueError(f"{name} must have shape ({n},) or (N, {n}), got {a.shape}")
    return a


def _pose_control(state, u, dt, one_pose: bool = False):
    """Checked pose (3,) and control (2,), or unless ``one_pose`` a stack of poses (N, 3) with one
    control (2,) for all or one each (N, 2); and the time step."""
    s = _rows(state, "state", 3)
    if one_pose:  # a Jacobian is taken at one point, for one control
        if s.ndim != 1:
            raise ValueError(f"state must have shape (3,), got {s.shape}")
        return s, v.vector(u, "u", 2), v.positive(dt, "dt", "a time step", "s")
    c = _rows(u, "u", 2)
    if c.ndim == 2 and (s.ndim != 2 or len(c) != len(s)):
        raise ValueError(f"u of shape {c.shape} needs as many poses, one a row; state has shape {s.shape}")
    return s, c, v.positive(dt, "dt", "a time step", "s")


def unicycle(state, u, dt) -> np.ndarray:
    r"""Unicycle (differential-drive) motion over ``dt`` with a zero-order hold.

    .. math::
        x' = x + \tfrac{V}{\omega}\left(\sin(\theta + \omega\Delta t) - \sin\theta\right),\;
        y' = y + \tfrac{V}{\omega}\left(\cos\theta - \cos(\theta + \omega\Delta t)\right),\;
        \theta' = \theta + \omega\Delta t

    Written in the equivalent form
    :math:`x' = x + V\Delta t\,\cos(\theta + \omega\Delta t/2)\,\mathrm{sinc}(\omega\Delta t/2)`
    (and the same with sin for y), which never divides by ω and equals the
    straight-line limit :math:`x' = x + V\Delta t\cos\theta` exactly at ω = 0.
    Introduced in chapter 8.

    Parameters
    ----------
    state : array_like, shape (3,) or (N, 3)
        Pose ``[x, y, theta]``, or N poses one a row (as the UKF passes its
        sigma points).
    u : array_like, shape (2,) or (N, 2)
        Control ``[V, omega]``, or one for each of the N poses (as the particle filter of
        chapter 11 passes each particle its own noisy odometry).
    dt : float
        Time step in s, > 0.

    Returns
    -------
    ndarray, shape (3,) or (N, 3)
        Next pose, heading wrapped to (-pi, pi].
    """
    s, c, dt = _pose_control(state, u, dt)
    V, w = c.T  # numbers for one control, columns for a stack
    x, y, th = s.T
    half = 0.5 * w * dt
    d = V * dt * np.sinc(half / np.pi)  # chord length: V dt sin(half) / half (np.sinc(t) = sin(pi t) / (pi t))
    out = np.empty(s.shape)
    out[..., 0] = x + d * np.cos(th + half)  # x' = x + d cos(theta + omega dt/2)
    out[..., 1] = y + d * np.sin(th + half)  # y' = y + d sin(theta + omega dt/2)
    out[..., 2] = wrap_angle(th + w * dt)  # theta' = theta + omega dt, wrapped
    return out


def unicycle_jacobian(state, u, dt) -> np.ndarray:
    r"""Jacobian :math:`G = \partial g / \partial (x, y, \theta)` of :func:`unicycle`.

    .. math:: G = \begin{bmatrix} 1 & 0 & -d\sin(\theta + \omega\Delta t/2) \\
                                  0 & 1 & \phantom{-}d\cos(\theta + \omega\Delta t/2) \\
                                  0 & 0 & 1 \end{bmatrix},
              \qquad d = V\Delta t\,\mathrm{sinc}(\omega\Delta t/2)

    At ω = 0 this is the lesson's :math:`-V\Delta t\sin\theta`,
    :math:`V\Delta t\cos\theta`.  Introduced in chapter 8.

    Parameters
    ----------
    state : array_like, shape (3,)
    u : array_like, shape (2,)
    dt : float

    Returns
    -------
    ndarray, shape (3, 3)
    """
    s, (V, w), dt = _pose_control(state, u, dt, one_pose=True)
    half = 0.5 * w * dt
    d = V * dt * (math.sin(half) / half if half else 1.0)  # chord length: V dt sin(half) / half
    phi = s[2] + half  # heading of the chord
    return np.array([[1.0, 0.0, -d * math.sin(phi)], [0.0, 1.0, d * math.cos(phi)], [0.0, 0.0, 1.0]])


def unicycle_control_jacobian(state, u, dt) -> np.ndarray:
    r"""Jacobian :math:`W = \partial g / \partial (V, \omega)` of :func:`unicycle`: how each control moves the pose.

    With :math:`h = \omega\Delta t/2`, :math:`s = \sin h / h`, :math:`d = V\Delta t\, s`, :math:`\varphi = \theta + h`:

    .. math:: W = \begin{bmatrix}
                  \Delta t\, s\cos\varphi & \tfrac{\Delta t}{2}(V\Delta t\, s'\cos\varphi - d\sin\varphi) \\
                  \Delta t\, s\sin\varphi & \tfrac{\Delta t}{2}(V\Delta t\, s'\sin\varphi + d\cos\varphi) \\
                  0 & \Delta t \end{bmatrix},
              \qquad s' = \frac{\cos h - s}{h} \to -\frac{h}{3} \text{ as } h \to 0

    It carries odometry noise into the pose: :math:`R = W M W^\top`.  Introduced in chapter 8.

    Parameters
    ----------
    state : array_like, shape (3,)
    u : array_like, shape (2,)
    dt : float

    Returns
    -------
    ndarray, shape (3, 2)
    """
    pose, (V, w), dt = _pose_control(state, u, dt, one_pose=True)
    h = 0.5 * w * dt
    s = math.sin(h) / h if h else 1.0  # sin(h) / h, 1 in the limit h -> 0
    ds = (math.cos(h) - s) / h if abs(h) > 1e-3 else -h / 3  # ds/dh; the series near 0 avoids 0/0
    d, phi = V * dt * s, pose[2] + h
    c, n = math.cos(phi), math.sin(phi)
    return np.array(
        [
            [dt * s * c, 0.5 * dt * (V * dt * ds * c - d * n)],
            [dt * s * n, 0.5 * dt * (V * dt * ds * n + d * c)],
            [0.0, dt],
        ]
    )


def _pose_offset(state, landmark, one_pose: bool = False):
    """Checked pose(s), and the landmark's offset from each, the landmark away from every pose:
    (s, dx, dy, q), with q = dx^2 + dy^2 (numbers for one pose and one landmark; else one entry
    per pose or landmark, shape (N,), (J,) or (J, N))."""
    s = _rows(state, "state", 3)
    if one_pose and s.ndim != 1:  # a Jacobian is taken at one point
        raise ValueError(f"state must have shape (3,), got {s.shape}")
    m = v.vector(landmark, "landmark", 2) if one_pose else _rows(landmark, "landmark", 2)
    if m.ndim == 2:  # J landmarks: a row of offsets for each
        m = m.T[..., None] if s.ndim == 2 else m.T
    dx, dy = m[0] - s.T[0], m[1] - s.T[1]
    q = dx * dx + dy * dy  # q = dx^2 + dy^2
    if np.count_nonzero(q == 0.0):
        raise ValueError("landmark must not sit exactly at the robot's position (bearing undefined)")
    return s, dx, dy, q


def range_bearing(state, landmark) -> np.ndarray:
    r"""Range and bearing from a pose to a landmark.

    .. math:: h = \begin{bmatrix} \sqrt{(m_x - x)^2 + (m_y - y)^2} \\
                  \operatorname{atan2}(m_y - y,\, m_x - x) - \theta \end{bmatrix}

    Introduced in chapter 7; chapter 11 takes every particle to every landmark of the map at once.

    Parameters
    ----------
    state : array_like, shape (3,) or (N, 3)
        Pose ``[x, y, theta]``, or N poses one a row.
    landmark : array_like, shape (2,) or (J, 2)
        Landmark ``[mx, my]``, or J landmarks one a row.

    Returns
    -------
    ndarray, shape (2,), (N, 2), (J, 2) or (J, N, 2)
        ``[r, phi]``, bearing wrapped to (-pi, pi]; with J landmarks, row j for landmark j.
    """
    s, dx, dy, q = _pose_offset(state, landmark)
    out = np.empty((*np.shape(dx), 2))
    out[..., 0] = np.sqrt(q)  # r = sqrt(q)
    out[..., 1] = wrap_angle(np.arctan2(dy, dx) - s.T[2])  # phi = atan2(dy, dx) - theta, wrapped
    return out


def range_bearing_jacobian(state, landmark) -> np.ndarray:
    r"""Jacobian :math:`H = \partial h / \partial (x, y, \theta)` of :func:`range_bearing`.

    With :math:`\Delta x = m_x - x`, :math:`\Delta y = m_y - y`, :math:`q = \Delta x^2 + \Delta y^2`:

    .. math:: H = \begin{bmatrix} -\Delta x/\sqrt q & -\Delta y/\sqrt q & 0 \\
                                  \Delta y/q & -\Delta x/q & -1 \end{bmatrix}

    Introduced in chapter 7.

    Returns
    -------
    ndarray, shape (2, 3)
    """
    _, dx, dy, q = _pose_offset(state, landmark, one_pose=True)
    r = math.sqrt(q)
    return np.array([[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, -1.0]])


def _angle_residual(a, b, index: int) -> np.ndarray:
    """Rows of ``a`` minus ``b`` (either may be a stack) for checked arrays, the angle at ``index`` wrapped."""
    d = a - b
    d[..., index] = wrap_angle(d[..., index])
    return d


def pose_residual(a, b) -> np.ndarray:
    """``a - b`` for poses ``[x, y, theta]`` (or stacks of them, one a row), the
    heading difference wrapped.

    Introduced in chapter 9 (the UKF needs it to average headings).

    Returns
    -------
    ndarray, shape (3,)
    """
    return _angle_residual(_rows(a, "pose_residual a", 3), _rows(b, "pose_residual b", 3), 2)


def range_bearing_residual(a, b) -> np.ndarray:
    """``a - b`` for readings ``[r, phi]`` (or stacks of them, one a row), the
    bearing difference wrapped.

    Introduced in chapter 8: pass it as ``residual`` to the EKF/UKF update.

    Returns
    -------
    ndarray, shape (2,)
    """
    return _angle_residual(_rows(a, "range_bearing_residual a", 2), _rows(b, "range_bearing_residual b", 2), 1)


def _points_weights(points, weights) -> tuple[np.ndarray, np.ndarray]:
    pts = v.matrix(points, "points")
    return pts, v.vector(weights, "weights", pts.shape[0])


def _mean_with_angle(pts, w, index: int) -> np.ndarray:
    """Weighted mean of checked rows ``pts`` (N, k) with weights ``w`` (N,), the angle at ``index`` on the circle."""
    mean = w @ pts
    ang = pts[:, index]
    mean[index] = math.atan2(w @ np.sin(ang), w @ np.cos(ang))  # circular mean
    return mean


def pose_mean(points, weights) -> np.ndarray:
    """Weighted mean of poses, rows ``[x, y, theta]``, headings averaged on the circle.

    Introduced in chapter 9 (``mean`` hook of the UKF).

    Returns
    -------
    ndarray, shape (3,)
    """
    return _mean_with_angle(*_points_weights(points, weights), 2)


def range_bearing_mean(points, weights) -> np.ndarray:
    """Weighted mean of readings, rows ``[r, phi]``, bearings averaged on the circle.

    Introduced in chapter 9 (``mean`` hook of the UKF).

    Returns
    -------
    ndarray, shape (2,)
    """
    return _mean_with_angle(*_points_weights(points, weights), 1)


def _beacon_offset(state, beacon, n: int | None = None, jacobian: bool = False):
    """Checked state(s), and each robot's offset from the beacon and range: (s, dx, dy, r) with dx = x - bx,
    dy = y - by, r = hypot(dx, dy) (numbers for one state, else one entry per state, shape (N,)).  A state
    has n entries (any n >= 2 unless given), the position [x, y] first; a Jacobian (``jacobian``) is taken
    at one state, away from the beacon."""
    if n is not None:
        s = _rows(state, "state", n)
    else:
        s = v.finite(state, "state")
        if s.ndim not in (1, 2) or s.shape[-1] < 2:
            raise ValueError(f"state must have shape (n,) or (N, n) with n >= 2 ([x, y, ...]), got {s.shape}")
    if jacobian and s.ndim != 1:  # a Jacobian is taken at one point
        raise ValueError(f"state must have shape ({'n' if n is None else n},), got {s.shape}")
    b = v.vector(beacon, "beacon", 2)
    dx, dy = s.T[0] - b[0], s.T[1] - b[1]
    r = np.hypot(dx, dy)  # r = sqrt(dx^2 + dy^2), 0 only where the robot stands on the beacon
    if jacobian and r == 0.0:
        raise ValueError(
            "beacon must not sit exactly at the robot's position: the robot stands on the beacon, where the "
            "range has no direction (Jacobian undefined)"
        )
    return s, dx, dy, r


def range_only(state, beacon) -> np.ndarray:
    r"""Range from the robot to a beacon at a known position: what a ranging radio reads.

    .. math:: h = \sqrt{(x - b_x)^2 + (y - b_y)^2}

    Only the position ``[x, y]``, the first two entries of the state, counts: the state may be a
    pose ``[x, y, theta]`` or a pose with more entries (such as the range scale of
    :func:`scaled_range`).  A robot standing exactly at the beacon reads 0.
    Introduced in chapter 12; the particle filter there weighs every particle at once.

    Parameters
    ----------
    state : array_like, shape (n,) or (N, n), n >= 2
        State ``[x, y, ...]``, or N states one a row.
    beacon : array_like, shape (2,)
        Beacon ``[bx, by]``.

    Returns
    -------
    ndarray, shape (1,) or (N, 1)
        ``[r]``, or one row per state: a reading is a vector of length 1, so that it plugs into the
        EKF's ``z``, ``h`` and ``H`` with a (1, 1) ``Q``.
    """
    _, _, _, r = _beacon_offset(state, beacon)
    return r[..., None]  # h = r, one entry per reading


def range_only_jacobian(state, beacon) -> np.ndarray:
    r"""Jacobian :math:`H = \partial h / \partial (x, y, \ldots)` of :func:`range_only`.

    With :math:`r = \sqrt{(x - b_x)^2 + (y - b_y)^2}`:

    .. math:: H = \begin{bmatrix} \dfrac{x - b_x}{r} & \dfrac{y - b_y}{r} & 0 & \cdots & 0 \end{bmatrix}

    the unit vector from the beacon to the robot, and a zero for every entry after the position
    (the heading does not change a range).  :func:`range_bearing_jacobian` writes the offset the
    other way round, :math:`\Delta x = m_x - x`, so its range row reads :math:`-\Delta x/\sqrt q`:
    the same numbers.  At the beacon (r = 0) the direction, and so H, is undefined.
    Introduced in chapter 12.

    Parameters
    ----------
    state : array_like, shape (n,), n >= 2
    beacon : array_like, shape (2,)

    Returns
    -------
    ndarray, shape (1, n)
    """
    s, dx, dy, r = _beacon_offset(state, beacon, jacobian=True)
    H = np.zeros((1, s.size))
    H[0, 0], H[0, 1] = dx / r, dy / r  # H = [(x - bx)/r, (y - by)/r, 0]
    return H


def scaled_range(state, beacon) -> np.ndarray:
    r"""Range to a beacon as read by a radio that reads ``s`` times the true distance.

    .. math:: h = s\,\sqrt{(x - b_x)^2 + (y - b_y)^2}

    The state is the pose augmented with the range scale, ``[x, y, theta, s]``, so that the filter
    estimates the scale along with the pose (the chapter's radio reads about 7 % long,
    s ≈ 1.07).  Introduced in chapter 12.

    Parameters
    ----------
    state : array_like, shape (4,) or (N, 4)
        State ``[x, y, theta, s]``, or N states one a row.
    beacon : array_like, shape (2,)
        Beacon ``[bx, by]``.

    Returns
    -------
    ndarray, shape (1,) or (N, 1)
        ``[s r]``, or one row per state.
    """
    s, _, _, r = _beacon_offset(state, beacon, 4)
    return (s.T[3] * r)[..., None]  # h = s r


def scaled_range_jacobian(state, beacon) -> np.ndarray:
    r"""Jacobian :math:`H = \partial h / \partial (x, y, \theta, s)` of :func:`scaled_range`.

    With :math:`r = \sqrt{(x - b_x)^2 + (y - b_y)^2}`:

    .. math:: H = \begin{bmatrix} s\,\dfrac{x - b_x}{r} & s\,\dfrac{y - b_y}{r} & 0 & r \end{bmatrix}

    the scale times :func:`range_only_jacobian` for the position, and the true distance for the
    scale.  At the beacon (r = 0) the direction, and so H, is undefined.  Introduced in chapter 12.

    Parameters
    ----------
    state : array_like, shape (4,)
    beacon : array_like, shape (2,)

    Returns
    -------
    ndarray, shape (1, 4)
    """
    s, dx, dy, r = _beacon_offset(state, beacon, 4, jacobian=True)
    k = s[3]  # the range scale
    return np.array([[k * dx / r, k * dy / r, 0.0, r]])  # H = [s(x - bx)/r, s(y - by)/r, 0, r]
