"""A robot driving a loop through a map of landmarks (chapters 8-10).

The robot executes its commanded controls exactly, so its true path is the clean
loop the controls describe.  What the filter is told is the *odometry*: the true
control plus Gaussian noise, ``[V, omega] + [v_std, omega_std] * e``.  A filter that
only integrates odometry (dead reckoning) therefore drifts away from the truth, and
the landmark readings pull it back.  No filter runs here: this module only makes data.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..models import range_bearing, unicycle, wrap_angle
from .records import Record, read_only

# The default map: six landmarks around the default loop of :func:`loop_controls`
# (x from -4 to 4 m, y from 0 to 5 m) and one in its middle, so that with the default
# 4 m sensor range the robot sees one to three landmarks wherever it is.
DEFAULT_LANDMARKS = read_only(
    [
        [-5.5, -1.0],  # m
        [0.0, -1.5],
        [5.5, -1.0],
        [5.5, 6.0],
        [0.0, 6.5],
        [-5.5, 6.0],
        [0.0, 2.5],
    ]
)


@dataclass(frozen=True)
class RobotRun(Record):
    """One simulated drive; every array has one row per time step ``k = 0 .. T-1``.

    Step ``k`` applies control ``u[k]`` for ``dt`` seconds, moving the robot from
    ``truth[k-1]`` (``start`` for k = 0) to ``truth[k]``, then takes the scan
    ``z[k]`` from ``truth[k]``.  A filter starts at ``start``, predicts with
    ``odometry[k]`` and updates with the readings ``z[k, visible[k]]``.
    """

    t: np.ndarray  #: (T,) time of each pose (s): (k + 1) dt
    dt: float  #: time step (s)
    u: np.ndarray  #: (T, 2) commanded controls [V, omega] (m/s, rad/s); the robot executes these
    odometry: np.ndarray  #: (T, 2) the controls the filter is told: u plus noise
    start: np.ndarray  #: (3,) pose before the first step [x, y, theta]
    truth: np.ndarray  #: (T, 3) true pose after each step
    landmarks: np.ndarray  #: (L, 2) landmark positions [mx, my] (m)
    visible: np.ndarray  #: (T, L) bool: a reading of the landmark: within sensor range, the sensor not blind
    z: np.ndarray  #: (T, L, 2) readings [r, phi] (m, rad), bearing in (-pi, pi]; zeros where not visible
    sensor_range: float  #: the sensor sees landmarks at most this far away (m)
    v_std: float  #: odometry speed noise (m/s)
    omega_std: float  #: odometry turn-rate noise (rad/s)
    range_std: float  #: range noise (m)
    bearing_std: float  #: bearing noise (rad)
    seed: int
    kidnap: int | None = None  #: step at which the robot was carried half its controls further on
    dropout: tuple[int, int] | None = None  #: the sensor is blind for steps t0 <= k < t1
    one_back: bool = False  #: at step t1, the first after the dropout, the sensor read only the nearest landmark


def loop_controls(
    length: float = 8.0, width: float = 5.0, radius: float = 1.0, speed: float = 1.0, dt: float = 0.2, laps: int = 1
) -> np.ndarray:
    r"""Controls that drive a unicycle around a rounded rectangle, counter-clockwise.

    Starting at the middle of the bottom side heading along +x, the robot drives
    straight at ``speed``, turns left through 90° on each corner with a constant
    turn rate, and comes back to where it started.  With ``length = width = 2 radius``
    the loop is a circle.  From the start pose ``(0, 0, 0)`` the loop spans
    x in [-length/2, length/2] and y in [0, width].

    Each corner takes ``n`` whole steps with :math:`\omega = (\pi/2) / (n\,\Delta t)`,
    so the heading turns exactly 90°; the arc radius is then :math:`V/\omega`, close
    to ``radius``.  Opposite sides take the same number of steps, so the loop closes.
    Introduced in chapter 10.

    Parameters
    ----------
    length, width : float
        Outer size of the loop (m), each >= 2 radius.
    radius : float
        Corner radius (m), > 0.
    speed : float
        Forward speed V (m/s), > 0.
    dt : float
        Time step (s), > 0.
    laps : int
        Number of times round the loop (>= 1).

    Returns
    -------
    ndarray, shape (T, 2)
        One control ``[V, omega]`` (m/s, rad/s) per step.
    """
    length = v.scalar(length, "length")
    width = v.scalar(width, "width")
    radius = v.positive(radius, "radius", "a radius", "m")
    for name, side in (("length", length), ("width", width)):
        if side < 2 * radius:
            raise ValueError(f"{name} must be at least 2 radius = {2 * radius} m, got {side}")
    speed = v.positive(speed, "speed", "a speed", "m/s")
    dt = v.positive(dt, "dt", "a time step", "s")
    laps = v.whole(laps, "laps", 1)
    step = speed * dt  # m driven per step
    n_turn = max(1, round((math.pi / 2) * radius / step))  # steps per quarter circle
    n_long = round((length - 2 * radius) / step)  # steps along a long straight
    n_short = round((width - 2 * radius) / step)
    straight = [speed, 0.0]
    turn = [speed, (math.pi / 2) / (n_turn * dt)]  # omega: 90 degrees in n_turn steps
    half = n_long // 2
    lap = (
        [straight] * half
        + [turn] * n_turn
        + [straight] * n_short
        + [turn] * n_turn
        + [straight] * n_long
        + [turn] * n_turn
        + [straight] * n_short
        + [turn] * n_turn
        + [straight] * (n_long - half)
    )
    return np.array(lap * laps, dtype=float)


def readings(truth, landmarks, sensor_range: float, range_std: float, bearing_std: float, xi):
    r"""Noisy range-bearing readings of every landmark within range of each true pose.

    :math:`z_{k,j} = h(x_k, m_j) + (\sigma_r \xi_{k,j,0},\, \sigma_\phi \xi_{k,j,1})`, bearing
    wrapped to :math:`(-\pi, \pi]`, kept where the true range is at most ``sensor_range``.
    Introduced in chapter 7.

    Parameters
    ----------
    truth : ndarray, shape (T, 3)
        True poses.
    landmarks : ndarray, shape (L, 2)
    sensor_range : float
        Largest range at which a landmark is seen (m), > 0.
    range_std, bearing_std : float
        Reading noise on the range (m) and the bearing (rad), >= 0.
    xi : ndarray, shape (T, L, 2)
        Standard normal draws.

    Returns
    -------
    z : ndarray, shape (T, L, 2)
        Readings ``[r, phi]``; zeros where not visible.
    visible : ndarray, shape (T, L), bool
    """
    truth = v.matrix(truth, "truth", cols=3)
    landmarks = _landmark_map(landmarks)
    sensor_range = v.positive(sensor_range, "sensor_range", "a range", "m")
    range_std = v.non_negative(range_std, "range_std", "a standard deviation", "m")
    bearing_std = v.non_negative(bearing_std, "bearing_std", "a standard deviation", "rad")
    xi = v.finite(xi, "xi")
    if xi.shape != (len(truth), len(landmarks), 2):
        want = (len(truth), len(landmarks), 2)
        raise ValueError(f"xi must have shape {want}, a pair of draws per pose and landmark; got {xi.shape}")
    z = np.zeros((len(truth), len(landmarks), 2))
    visible = np.zeros((len(truth), len(landmarks)), dtype=bool)
    for j, mj in enumerate(landmarks):
        h = range_bearing(truth, mj)  # (T, 2): [r, phi] from every true pose to landmark j
        noisy = h + [range_std, bearing_std] * xi[:, j]  # z = h(x, m_j) + noise
        noisy[:, 1] = wrap_angle(noisy[:, 1])
        visible[:, j] = h[:, 0] <= sensor_range
        z[visible[:, j], j] = noisy[visible[:, j]]
    return z, visible


def _dropout(dropout) -> tuple[int, int] | None:
    if dropout is None:
        return None
    if np.ndim(dropout) != 1 or len(dropout) != 2:
        raise ValueError(f"dropout must be None or a pair of steps (t0, t1), got {dropout!r}")
    t0, t1 = v.whole(dropout[0], "dropout[0]"), v.whole(dropout[1], "dropout[1]")
    if t1 < t0:
        raise ValueError(f"dropout must have t0 <= t1, got {dropout!r}")
    return t0, t1


def true_path(u, dt: float, start, laps: int = 1, kidnap: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    r"""Where the robot goes: :math:`x_k = g(x_{k-1}, u_k)`, ``u`` driven ``laps`` times.

    With ``kidnap``, at that step the robot is lifted and set down half of ``u`` further
    on (half a lap of a loop), where it drives on with the controls of that place; the
    filter is not told.  Introduced in chapter 10.

    Returns
    -------
    (truth, u_driven) : shapes (laps T, 3), (laps T, 2)
        The true pose after each step, and the control the robot executed at it.
    """
    n_steps = laps * len(u)
    shift = np.zeros(n_steps, dtype=int)
    if kidnap is not None:
        shift[kidnap:] = len(u) // 2
    place = (np.arange(n_steps) + shift) % len(u)  # which control of u the robot drives at step k
    truth, pose = np.empty((n_steps, 3)), start
    for k in range(n_steps):
        if k == kidnap:  # lifted and set down where u puts the robot before control place[k]
            pose = start
            for c in u[: place[k]]:
                pose = unicycle(pose, c, dt)
        pose = unicycle(pose, u[place[k]], dt)  # x_k = g(x_{k-1}, u_k)
        truth[k] = pose
    return truth, u[place]


def simulate_robot(
    u=None,
    dt: float = 0.2,
    start=(0.0, 0.0, 0.0),
    landmarks=None,
    sensor_range: float = 4.0,
    v_std: float = 0.1,
    omega_std: float = 0.05,
    range_std: float = 0.1,
    bearing_std: float = 0.03,
    seed: int = 0,
    laps: int = 1,
    kidnap: int | None = None,
    dropout=None,
    one_back: bool = False,
) -> RobotRun:
    r"""Drive a unicycle robot under controls ``u``; record noisy odometry and landmark readings.

    Truth: :math:`x_k = g(x_{k-1}, u_k)` with :func:`~kfcourse.models.unicycle`
    (the robot does exactly what it is told).  Odometry, the control the filter
    is told: :math:`\tilde u_k = u_k + (\sigma_V e_{k,0},\, \sigma_\omega e_{k,1})`.
    Readings, for every landmark :math:`m_j` within ``sensor_range`` of :math:`x_k`:
    :math:`z_{k,j} = h(x_k, m_j) + (\sigma_r \xi_{k,j,0},\, \sigma_\phi \xi_{k,j,1})`,
    bearing wrapped to :math:`(-\pi, \pi]`, with :func:`~kfcourse.models.range_bearing`.
    All e and ξ are independent standard normal draws.  A very noisy range can come
    out negative: the Gaussian model says so, and nothing is clipped.

    The draws depend only on ``seed``, the number of steps and the number of
    landmarks, so changing a ``*_std`` rescales the same noise: a slider changes the
    picture smoothly.  Introduced in chapter 7 (a short run for the EKF).

    Parameters
    ----------
    u : array_like, shape (T, 2), optional
        Commanded controls ``[V, omega]`` (m/s, rad/s); by default one lap of
        :func:`loop_controls` with this ``dt``.
    dt : float
        Time step (s), > 0.
    start : array_like, shape (3,)
        Pose ``[x, y, theta]`` before the first step.
    landmarks : array_like, shape (L, 2), optional
        The map (m); by default :data:`DEFAULT_LANDMARKS`.  L may be 0.
    sensor_range : float
        Largest range at which a landmark is seen (m), > 0.
    v_std, omega_std : float
        Odometry noise on the speed (m/s) and the turn rate (rad/s), >= 0.
    range_std, bearing_std : float
        Reading noise on the range (m) and the bearing (rad), >= 0.
    seed : int
        Seed of the random generator (>= 0).
    laps : int
        Times the robot drives ``u`` (>= 1).
    kidnap : int, optional
        At this step the robot is lifted and set down half of ``u`` further on (half a
        lap of a loop), where it drives on (:func:`true_path`); the filter is not told.
    dropout : (int, int), optional
        The sensor is blind for the steps ``t0 <= k < t1``: no readings there.
    one_back : bool
        Sight comes back one landmark first: at step ``t1``, the first after the
        dropout, the sensor reads only the nearest landmark in range (chapter 10's
        "a single good reading").  The draws are the same either way.

    Returns
    -------
    RobotRun
    """
    dt = v.positive(dt, "dt", "a time step", "s")
    u = loop_controls(dt=dt) if u is None else v.matrix(u, "u", cols=2)
    if len(u) == 0:
        raise ValueError("u must hold at least one control, got none")
    start = v.vector(start, "start", 3)
    m = _landmark_map(landmarks)
    sensor_range = v.positive(sensor_range, "sensor_range", "a range", "m")
    stds = _noise_stds(v_std, omega_std, range_std, bearing_std)
    seed, laps = v.whole(seed, "seed", 0), v.whole(laps, "laps", 1)
    if kidnap is not None and not v.whole(kidnap, "kidnap") < laps * len(u):
        raise ValueError(f"kidnap must be a step below {laps * len(u)}, got {kidnap}")
    dropout, one_back = _dropout(dropout), v.flag(one_back, "one_back")
    return _drive(u, dt, start, m, sensor_range, stds, seed, laps, kidnap, dropout, one_back)


def _noise_stds(v_std, omega_std, range_std, bearing_std) -> dict[str, float]:
    """The noise of :func:`simulate_robot`, checked: odometry (m/s, rad/s) and readings (m, rad), by name."""
    v_std = v.non_negative(v_std, "v_std", "a standard deviation", "m/s")
    omega_std = v.non_negative(omega_std, "omega_std", "a standard deviation", "rad/s")
    range_std = v.non_negative(range_std, "range_std", "a standard deviation", "m")
    bearing_std = v.non_negative(bearing_std, "bearing_std", "a standard deviation", "rad")
    return {"v_std": v_std, "omega_std": omega_std, "range_std": range_std, "bearing_std": bearing_std}


def _landmark_map(landmarks) -> np.ndarray:
    """The checked map (L, 2): :data:`DEFAULT_LANDMARKS` for None, and L may be 0."""
    if landmarks is None:
        return DEFAULT_LANDMARKS
    if np.size(landmarks) == 0:
        return np.empty((0, 2))  # an empty map: nothing to see
    return v.matrix(landmarks, "landmarks", cols=2)


def _drive(u, dt, start, m, sensor_range, stds, seed, laps, kidnap, dropout, one_back) -> RobotRun:
    """:func:`simulate_robot` once its arguments are checked: the draws, the truth and the readings."""
    n_steps, n_marks = laps * len(u), len(m)
    rng = np.random.default_rng(seed)
    e = rng.standard_normal((n_steps, 2))  # odometry draws
    xi = rng.standard_normal((n_steps, n_marks, 2))  # reading draws

    truth, u = true_path(u, dt, start, laps, kidnap)
    odometry = u + [stds["v_std"], stds["omega_std"]] * e  # u~_k = u_k + noise
    z, visible = readings(truth, m, sensor_range, stds["range_std"], stds["bearing_std"], xi)
    if dropout is not None:
        visible[dropout[0] : dropout[1]] = False  # the sensor is blind
        k = dropout[1]  # the first step with sight back
        if one_back and k < n_steps and visible[k].any():
            dist = np.where(visible[k], np.linalg.norm(m - truth[k, :2], axis=1), np.inf)
            visible[k] = np.arange(n_marks) == np.argmin(dist)  # only the nearest landmark in range

    return RobotRun(
        t=dt * np.arange(1, n_steps + 1),
        dt=dt,
        u=u,
        odometry=odometry,
        start=start,
        truth=truth,
        landmarks=np.asarray(m),
        visible=visible,
        z=z,
        sensor_range=sensor_range,
        **stds,
        seed=seed,
        kidnap=kidnap,
        dropout=dropout,
        one_back=one_back,
    )
