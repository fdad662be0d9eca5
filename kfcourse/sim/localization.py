"""The landmark localization loop: a robot drives round a map and an EKF or a UKF follows it (chapters 8-10).

The robot executes the loop's controls exactly; the filter is told them through
noisy odometry and corrects itself with labelled range-bearing readings of the
landmarks within sensor range, one landmark at a time.  Everything the course's
last chapters push on is an argument here: the filter, a sensor dropout, the two
noise levels, a kidnapping, and forgetting to wrap the bearing innovation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.association import _mahalanobis
from ..filters.ekf import _ekf_correct, _ekf_innovation, _ekf_predict
from ..filters.linalg import gain
from ..filters.ukf import _ukf_correct, _ukf_moments, _ukf_predict
from ..models import (
    _pose_mean,
    _pose_residual,
    _range_bearing,
    _range_bearing_jacobian,
    _range_bearing_mean,
    _range_bearing_residual,
    _unicycle,
    _unicycle_control_jacobian,
    _unicycle_jacobian,
    unicycle_control_jacobian,
    wrap_angle,
)
from .records import read_only
from .robot import DEFAULT_LANDMARKS, loop_controls, readings

FILTERS = ("ekf", "ukf")
V_STD, OMEGA_STD = 0.1, 0.05  # odometry noise at motion_noise = 1: m/s, rad/s
RANGE_STD, BEARING_STD = 0.1, 0.03  # reading noise at sensor_noise = 1: m, rad
SIG0 = read_only(np.diag([0.01, 0.01, 0.001]))  # the start is known to about 10 cm and 2 degrees
NOISE_SCALES = (0.01, 100.0)  # below, a reading so exact the gain's S^-1 loses its digits; above, no robot
UKF_LAM = 0.0  # lambda = 3 - n for the pose (n = 3): centre weight 0, six points of weight 1/6


@dataclass(frozen=True)
class LoopRun:
    """One drive round the loop and the filter that followed it; arrays have one row per step ``k = 0 .. T-1``.

    Step ``k``: the filter predicts with ``odometry[k]`` (giving ``mu_bar[k]``,
    ``Sig_bar[k]``), then updates with the readings ``z[k, used[k]]`` one landmark
    at a time (giving ``mu[k]``, ``Sig[k]``).
    """

    t: np.ndarray  #: (T,) time after each step (s)
    dt: float  #: time step (s)
    truth: np.ndarray  #: (T, 3) true pose [x, y, theta] after each step
    odometry: np.ndarray  #: (T, 2) the controls [V, omega] the filter is told
    landmarks: np.ndarray  #: (L, 2) the map (m)
    z: np.ndarray  #: (T, L, 2) readings [r, phi]; zeros where out of range
    used: np.ndarray  #: (T, L) bool: readings the filter used (in range, the sensor not blind, inside the gate)
    rejected: np.ndarray  #: (T, L) bool: readings in range while the sensor could see, but outside the gate
    start: np.ndarray  #: (3,) the pose before the first step, known to the filter
    Sig0: np.ndarray  #: (3, 3) the filter's covariance at the start
    mu_bar: np.ndarray  #: (T, 3) predicted mean, before the updates of step k
    Sig_bar: np.ndarray  #: (T, 3, 3) predicted covariance
    mu: np.ndarray  #: (T, 3) estimate after the updates of step k
    Sig: np.ndarray  #: (T, 3, 3) its covariance
    error: np.ndarray  #: (T,) distance between the estimated and the true position (m)
    inside: np.ndarray  #: (T,) bool: the true position lies inside the 3-sigma position ellipse
    area: np.ndarray  #: (T,) area of the 1-sigma position ellipse, pi sqrt(det Sig_xy) (m^2)
    filter: str  #: "ekf" or "ukf"
    dropout: tuple[int, int] | None  #: the sensor is blind for steps t0 <= k < t1
    motion_noise: float  #: scale of the odometry noise and of R
    sensor_noise: float  #: scale of the reading noise and of Q
    kidnap: int | None  #: step at which the true robot was carried half a lap further on
    wrap_bearing: bool  #: whether the bearing innovation was wrapped to (-pi, pi]
    gate: float | None  #: validation gate in standard deviations, or None
    seed: int

    @property
    def share_inside(self) -> float:
        """Share of the steps with the truth inside the 3-sigma ellipse (0 to 1)."""
        return float(self.inside.mean())


def _noise_scale(x, name: str) -> float:
    value = v.scalar(x, name)
    if not NOISE_SCALES[0] <= value <= NOISE_SCALES[1]:
        raise ValueError(f"{name} must be a noise scale from {NOISE_SCALES[0]} to {NOISE_SCALES[1]}, got {value}")
    return value


def _dropout(dropout) -> tuple[int, int] | None:
    if dropout is None:
        return None
    if np.ndim(dropout) != 1 or len(dropout) != 2:
        raise ValueError(f"dropout must be None or a pair of steps (t0, t1), got {dropout!r}")
    t0, t1 = v.whole(dropout[0], "dropout[0]"), v.whole(dropout[1], "dropout[1]")
    if t1 < t0:
        raise ValueError(f"dropout must have t0 <= t1, got {dropout!r}")
    return t0, t1


def process_noise_of_odometry(mu, u, dt: float, M) -> np.ndarray:
    r"""Process noise R of one step when the noise is in the odometry: the control noise mapped into the pose.

    .. math:: R = W M W^\top, \qquad W = \partial g / \partial u \text{ at } (\mu, u)

    ``W`` is :func:`~kfcourse.models.unicycle_control_jacobian`.  R has rank 2 (two noisy
    controls move three pose numbers).  Introduced in chapter 10.

    Parameters
    ----------
    mu : array_like, shape (3,)
        Pose at which to linearize.
    u : array_like, shape (2,)
        Odometry ``[V, omega]``.
    dt : float
        Time step (s).
    M : array_like, shape (2, 2)
        Covariance of the odometry noise.

    Returns
    -------
    ndarray, shape (3, 3)
    """
    M = v.covariance(M, "M", 2)
    W = unicycle_control_jacobian(mu, u, dt)  # (3, 2): how each control moves the pose
    return W @ M @ W.T  # R = W M W^T


def _check_filter_held(filter, motion_noise, sensor_noise, mu_bar, Sig_bar, mu, Sig) -> None:
    """After the lap: every number finite and every covariance positive semi-definite, else a ValueError.

    The run checks its arguments once and then calls the filters' unchecked cores, so a filter that broke
    down at extreme noise scales is caught here (the public filter steps refuse such a covariance).
    """
    broke = f"the {filter.upper()} broke down with motion_noise={motion_noise} and sensor_noise={sensor_noise}"
    for name, a in (("mu_bar", mu_bar), ("Sig_bar", Sig_bar), ("mu", mu), ("Sig", Sig)):
        finite = np.isfinite(a).reshape(len(a), -1).all(axis=1)  # one bool per step
        if not finite.all():
            raise ValueError(f"{broke}: {name} is not finite (no NaN or inf) from step {np.argmin(finite)}")
    for name, a in (("Sig_bar", Sig_bar), ("Sig", Sig)):
        try:
            v.covariance_stack(a, name, *a.shape[:2])
        except ValueError as err:
            raise ValueError(f"{broke}: {err}") from None


def landmark_loop(
    seed: int = 0,
    *,
    filter: str = "ekf",
    dropout=None,
    motion_noise: float = 1.0,
    sensor_noise: float = 1.0,
    kidnap: int | None = None,
    wrap_bearing: bool = True,
    gate: float | None = None,
    laps: int = 1,
    landmarks=None,
    sensor_range: float = 4.0,
) -> LoopRun:
    r"""Drive the loop of :func:`loop_controls` through a map and localize with an EKF or a UKF.

    Truth: the robot executes the loop's controls :math:`u_k` exactly.  Odometry:
    :math:`\tilde u_k = u_k + (\sigma_V e_{k,0}, \sigma_\omega e_{k,1})`.  Readings:
    :math:`z_{k,j} = h(x_k, m_j) + (\sigma_r\epsilon_{k,j,0}, \sigma_\phi\epsilon_{k,j,1})`
    for every landmark within ``sensor_range`` (the draws of
    :func:`~kfcourse.sim.simulate_robot`, which this matches step for step).

    Filter: it starts at the true start with covariance :data:`SIG0`, predicts
    with the unicycle model and the process noise
    :math:`R_k = W M W^\top` (:func:`process_noise_of_odometry`,
    :math:`M = \mathrm{diag}(\sigma_V^2, \sigma_\omega^2)`), and updates with every
    used reading in turn, :math:`Q = \mathrm{diag}(\sigma_r^2, \sigma_\phi^2)`.  Its
    R and Q are the simulation's own: the filter is honest about the noise.

    Introduced in chapter 8; the capstone of chapter 10 drives every argument.

    Parameters
    ----------
    seed : int
        Seed of the noise (>= 0).  The same seed gives the same noise for every
        filter, dropout and kidnapping.
    filter : {"ekf", "ukf"}
        Which filter follows the robot.  The UKF uses λ = 0 and averages headings
        on the circle.
    dropout : (int, int), optional
        The sensor is blind for the steps ``t0 <= k < t1``.
    motion_noise, sensor_noise : float
        Scale of the odometry noise (and of R) and of the reading noise (and of Q),
        from 0.01 to 100 (:data:`NOISE_SCALES`); 1 is the default robot.
    kidnap : int, optional
        At this step the true robot is lifted and set down half a lap further
        round the loop, where it carries on; the filter is not told.
    wrap_bearing : bool
        Wrap the bearing innovation to (-pi, pi].  False is the bug of chapter 8:
        a reading just across ±pi then looks 2 pi away.
    gate : float, optional
        Validation gate (> 0, in standard deviations, chapter 8): a reading whose
        Mahalanobis distance from its landmark's predicted reading exceeds it is
        rejected.  Both filters measure the distance with the linearized
        :math:`S = H\bar\Sigma H^\top + Q`.  ``None`` (the default) uses every reading.
    laps : int
        Times round the loop (>= 1).
    landmarks : array_like, shape (L, 2), optional
        The map (m); by default :data:`~kfcourse.sim.DEFAULT_LANDMARKS`.
    sensor_range : float
        Largest range at which a landmark is seen (m), > 0.

    Returns
    -------
    LoopRun
    """
    seed = v.whole(seed, "seed", 0)
    if filter not in FILTERS:
        raise ValueError(f"filter must be one of {FILTERS}, got {filter!r}")
    motion_noise = _noise_scale(motion_noise, "motion_noise")
    sensor_noise = _noise_scale(sensor_noise, "sensor_noise")
    wrap_bearing = v.flag(wrap_bearing, "wrap_bearing")
    gate = None if gate is None else v.positive(gate, "gate", "a distance", "standard deviations")
    laps = v.whole(laps, "laps", 1)
    m = DEFAULT_LANDMARKS if landmarks is None else v.matrix(landmarks, "landmarks", cols=2)
    sensor_range = v.positive(sensor_range, "sensor_range", "a range", "m")

    dt = 0.2  # s
    lap = loop_controls(dt=dt)
    n_steps, n_marks = laps * len(lap), len(m)
    dropout = _dropout(dropout)
    if kidnap is not None:
        kidnap = v.whole(kidnap, "kidnap")
        if kidnap >= n_steps:
            raise ValueError(f"kidnap must be a step below {n_steps}, got {kidnap}")

    # The arguments are checked: from here on the run calls the models' and filters' unchecked cores.
    # Truth: after a kidnapping the robot is half a lap further on and drives the controls of that place.
    path = [np.zeros(3)]  # path[i]: where the loop puts the robot before its control i
    for c in lap:
        path.append(_unicycle(path[-1], c, dt))
    start = path[0]
    shift = np.zeros(n_steps, dtype=int)
    if kidnap is not None:
        shift[kidnap:] = len(lap) // 2
    place = (np.arange(n_steps) + shift) % len(lap)  # which control of the lap the robot drives at step k
    u = lap[place]
    truth = np.empty((n_steps, 3))
    pose = start
    for k in range(n_steps):
        if k == kidnap:
            pose = path[place[k]]  # lifted and set down; the filter is not told
        pose = _unicycle(pose, u[k], dt)  # x_k = g(x_{k-1}, u_k)
        truth[k] = pose

    v_std, omega_std = motion_noise * V_STD, motion_noise * OMEGA_STD
    range_std, bearing_std = sensor_noise * RANGE_STD, sensor_noise * BEARING_STD
    rng = np.random.default_rng(seed)
    e = rng.standard_normal((n_steps, 2))  # odometry draws
    eps = rng.standard_normal((n_steps, n_marks, 2))  # reading draws
    odometry = u + [v_std, omega_std] * e
    z, visible = readings(truth, m, sensor_range, range_std, bearing_std, eps)
    seen = visible.copy()  # readings the sensor delivers
    if dropout is not None:
        seen[dropout[0] : dropout[1]] = False
    used = np.zeros_like(seen)

    M = np.diag([v_std, omega_std]) ** 2  # odometry noise covariance
    Q = np.diag([range_std, bearing_std]) ** 2  # measurement noise covariance
    z_residual = _range_bearing_residual if wrap_bearing else None
    z_mean = _range_bearing_mean if wrap_bearing else None
    mu, Sig = start.copy(), np.array(SIG0)
    mu_bar, Sig_bar = np.empty((n_steps, 3)), np.empty((n_steps, 3, 3))
    mus, Sigs = np.empty((n_steps, 3)), np.empty((n_steps, 3, 3))
    g = lambda x, c: _unicycle(x, c, dt)  # noqa: E731
    G = lambda x, c: _unicycle_jacobian(x, c, dt)  # noqa: E731
    for k in range(n_steps):
        W = _unicycle_control_jacobian(mu, odometry[k], dt)
        R = W @ M @ W.T  # R = W M W^T, as in process_noise_of_odometry
        if filter == "ekf":
            mu, Sig = _ekf_predict(mu, Sig, odometry[k], g, G, R)
        else:
            g_all = lambda chi, c=odometry[k]: g(chi, c)  # every sigma point (a row of chi) at once  # noqa: E731
            mu, Sig = _ukf_predict(mu, Sig, g_all, R, UKF_LAM, 0.0, _pose_residual, _pose_mean)
        mu_bar[k], Sig_bar[k] = mu, Sig
        for j in np.flatnonzero(seen[k]):  # one landmark at a time: sequential updates
            h = lambda x, mj=m[j]: _range_bearing(x, mj)  # noqa: E731
            H = lambda x, mj=m[j]: _range_bearing_jacobian(x, mj)  # noqa: E731
            if filter == "ekf" or gate is not None:  # innovation, H and S: for the EKF's update and either's gate
                y, Hj, S = _ekf_innovation(mu, Sig, z[k, j], h, H, Q, z_residual)
            if gate is not None and _mahalanobis(y, S) > gate:
                continue  # outside the validation gate: rejected
            used[k, j] = True
            if filter == "ekf":
                mu, Sig = _ekf_correct(mu, Sig, y, Hj, S, Q)
            else:
                z_hat, S_u, Sig_xz = _ukf_moments(mu, Sig, h, Q, UKF_LAM, 0.0, z_residual, z_mean, _pose_residual)
                y_u = z[k, j] - z_hat if z_residual is None else z_residual(z[k, j], z_hat)  # innovation
                mu, Sig = _ukf_correct(mu, Sig, y_u, S_u, gain(Sig_xz, S_u))  # K = Sig_xz S^-1
            mu[2] = wrap_angle(mu[2])  # the update may push the heading past pi
        mus[k], Sigs[k] = mu, Sig
    _check_filter_held(filter, motion_noise, sensor_noise, mu_bar, Sig_bar, mus, Sigs)

    err = truth[:, :2] - mus[:, :2]
    Sxy = Sigs[:, :2, :2]
    d2 = np.einsum("ti,tij,tj->t", err, np.linalg.inv(Sxy), err)  # e^T Sig_xy^-1 e
    return LoopRun(
        t=read_only(dt * np.arange(1, n_steps + 1)),
        dt=dt,
        truth=read_only(truth),
        odometry=read_only(odometry),
        landmarks=read_only(m),
        z=read_only(z),
        used=read_only(used, dtype=bool),
        rejected=read_only(seen & ~used, dtype=bool),
        start=read_only(start),
        Sig0=SIG0,
        mu_bar=read_only(mu_bar),
        Sig_bar=read_only(Sig_bar),
        mu=read_only(mus),
        Sig=read_only(Sigs),
        error=read_only(np.linalg.norm(err, axis=1)),
        inside=read_only(d2 <= 9.0, dtype=bool),
        area=read_only(np.pi * np.sqrt(np.linalg.det(Sxy))),
        filter=filter,
        dropout=dropout,
        motion_noise=motion_noise,
        sensor_noise=sensor_noise,
        kidnap=kidnap,
        wrap_bearing=wrap_bearing,
        gate=gate,
        seed=seed,
    )
