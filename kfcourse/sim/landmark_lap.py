"""A lap of chapter 10's capstone: the loop's world, the EKF, UKF or student's step that follows it, and the record.

:func:`landmark_loop` checks its settings, builds the world (:func:`~kfcourse.sim.loop_world`), runs the filter over
it (:func:`~kfcourse.sim.localize` or :func:`~kfcourse.sim.localize_with_step`) and records the lap as a
:class:`~kfcourse.sim.LoopRun`, the truth measured against the filter.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as v
from .capstone_world import SIG0, _noise_scale, filter_noise, loop_world
from .loop_filters import FILTERS, gate_within, localize, loop_filter, nearest_landmark
from .loop_records import LoopRun, Track
from .robot import RobotRun
from .scores import nees
from .student_step import localize_with_step


def landmark_loop(
    seed: int = 0,
    *,
    filter="ekf",
    dropout=None,
    motion_noise: float = 1.0,
    sensor_noise: float = 1.0,
    filter_motion_noise: float | None = None,
    filter_sensor_noise: float | None = None,
    one_back: bool = False,
    kidnap: int | None = None,
    wrap_bearing: bool = True,
    gate: float | None = None,
    laps: int = 1,
    landmarks=None,
    sensor_range: float = 4.0,
    start=None,
    labelled: bool = True,
    since: LoopRun | None = None,
) -> LoopRun:
    r"""Drive the loop of :func:`loop_controls` through a map and localize with an EKF, a UKF or your own step.

    The world is :func:`~kfcourse.sim.simulate_robot`'s, draw for draw; the filter starts with covariance :data:`SIG0`,
    its R (its odometry noise, mapped into the pose) and Q those of ``filter_*_noise``, by default the world's.
    Introduced in chapter 8; chapter 10's capstone drives every argument, chapter 11 ``start`` and ``labelled``.

    Parameters
    ----------
    seed : int
        Seed of the noise (>= 0): the same noise for every filter, dropout and kidnapping.
    filter : {"ekf", "ukf"} or callable
        The course's EKF or UKF (:func:`loop_filter` run by :func:`localize`; the UKF with λ = 0, headings averaged on
        the circle), or a whole step ``step(mu, Sig, u, z, landmarks, dt, M, Q, gate) -> (mu, Sig, used)`` (chapter
        10's exercise, :func:`localize_with_step`: a ``ValueError`` names a step that raises or returns nonsense).
    dropout : (int, int), optional
        The sensor is blind for the steps ``t0 <= k < t1``.
    motion_noise, sensor_noise : float
        Scale of the world's odometry noise (0.1 m/s, 0.05 rad/s at 1) and reading noise (0.1 m, 0.03 rad at 1),
        from 0.01 to 100 (:data:`NOISE_SCALES`).
    filter_motion_noise, filter_sensor_noise : float, optional
        The same scales of the noise the filter assumes (its R, its Q); ``None``, the default, is the world's.  A
        filter that assumes more noise than there is is timid, less is over-confident.
    one_back : bool
        Sight comes back one landmark first: at step ``t1`` the sensor reads only the nearest landmark in range.
    kidnap : int, optional
        At this step the true robot is set down half a lap further round the loop; the filter is not told.
    wrap_bearing : bool
        Wrap the bearing innovation to (-pi, pi].  False is the bug of chapter 8: a reading just across ±pi then
        looks 2 pi away.  Only for "ekf" and "ukf".
    gate : float, optional
        Validation gate (> 0, in standard deviations, chapter 8): a reading whose Mahalanobis distance from its
        landmark's predicted reading, with the linearized :math:`S = H\bar\Sigma H^\top + Q`, exceeds it is
        rejected.  ``None`` (the default) uses every reading (a step function gets ``gate=np.inf``).
    laps, landmarks, sensor_range : int, array_like (L, 2) or None, float
        Times round the loop (>= 1); the map (m), by default :data:`~kfcourse.sim.DEFAULT_LANDMARKS`; the largest
        range at which a landmark is seen (m, > 0).
    start : array_like, shape (3,), optional
        The filter's mean at the start, ``[x, y, theta]`` (``LoopRun.mu0``); by default the true start, where the
        truth always starts (``LoopRun.start``).
    labelled : bool
        The readings come with their landmark (the default).  False: the filter matches each reading to a landmark
        itself, the nearest at its mean (:func:`nearest_landmark`, gated by ``gate``, always the nearest without
        one), recorded in ``LoopRun.matched``.  Only for "ekf" and "ukf": a step function gets labelled readings.
    since : LoopRun, optional
        A run of the course's EKF or UKF whose steps in common with this one (the same filter, noise, start and
        gate, over a world the same up to then) are copied, not computed again: the same result to the last bit.
        A demo passes its last run, so that a kidnap or a dropout set at step k reruns only the steps from k on.

    Returns
    -------
    LoopRun
    """
    setting, mu0 = _lap_settings(filter, motion_noise, sensor_noise, filter_motion_noise, filter_sensor_noise,
                                 wrap_bearing, gate, start, labelled, since)  # fmt: skip
    drive = {"sensor_range": sensor_range, "laps": laps, "kidnap": kidnap, "dropout": dropout, "one_back": one_back}
    world = loop_world(seed, *setting["noise"][:2], landmarks, **drive)
    mu0 = world.start if mu0 is None else mu0
    track = _follow(world, filter, mu0, setting, since)
    return _loop_run(world, track, mu0, **setting)


def _lap_settings(
    filter,
    motion_noise,
    sensor_noise,
    filter_motion_noise,
    filter_sensor_noise,
    wrap_bearing,
    gate,
    start,
    labelled,
    since,
) -> tuple[dict, np.ndarray | None]:
    """The settings of :func:`landmark_loop`, checked: the filter's (name, wrap, gate, labels, and the noise scales
    of the world and of the filter) for :func:`_follow` and :func:`_loop_run`; and its start, None for the truth's."""
    if not callable(filter) and filter not in FILTERS:
        raise ValueError(f"filter must be one of {FILTERS} or a step function, got {filter!r}")
    name = getattr(filter, "__name__", "step") if callable(filter) else filter
    motion_noise = _noise_scale(motion_noise, "motion_noise")
    sensor_noise = _noise_scale(sensor_noise, "sensor_noise")
    trust_motion = (
        motion_noise if filter_motion_noise is None else _noise_scale(filter_motion_noise, "filter_motion_noise")
    )
    trust_sensor = (
        sensor_noise if filter_sensor_noise is None else _noise_scale(filter_sensor_noise, "filter_sensor_noise")
    )
    wrap_bearing = v.flag(wrap_bearing, "wrap_bearing")
    if callable(filter) and not wrap_bearing:
        raise ValueError(
            "wrap_bearing=False switches the wrap off in the course's filters only; a step function wraps as written"
        )
    gate = None if gate is None else v.positive(gate, "gate", "a distance", "standard deviations")
    mu0 = None if start is None else v.vector(start, "start", 3)
    labelled = v.flag(labelled, "labelled")
    if callable(filter) and not labelled:
        raise ValueError(
            "labelled=False leaves the association to the course's filters only; a step function gets labelled readings"
        )
    if since is not None and not isinstance(since, LoopRun):
        raise ValueError(f"since must be a LoopRun (a run of landmark_loop) or None, got {type(since).__name__}")
    noise = (motion_noise, sensor_noise, trust_motion, trust_sensor)
    return {"filter": name, "wrap_bearing": wrap_bearing, "gate": gate, "labelled": labelled, "noise": noise}, mu0


def _follow(world: RobotRun, filter, mu0, setting: dict, since: LoopRun | None) -> Track:
    """Run the filter of ``setting`` over ``world`` from ``mu0``: a step function through :func:`localize_with_step`,
    the course's EKF or UKF through :func:`localize` (copying the steps it shares with ``since``)."""
    motion_noise, sensor_noise, trust_motion, trust_sensor = setting["noise"]
    gate, labelled, wrap_bearing = setting["gate"], setting["labelled"], setting["wrap_bearing"]
    M, Q = filter_noise(trust_motion, trust_sensor)  # the odometry and reading noise the filter assumes
    if callable(filter):
        return localize_with_step(world, filter, SIG0, M, Q, np.inf if gate is None else gate, setting["filter"], mu0)
    predict, update = loop_filter(filter, world.dt, M, Q, wrap_bearing)
    accept = None if gate is None or not labelled else gate_within(gate, Q, wrap_bearing)
    identify = None if labelled else nearest_landmark(world.landmarks, gate, Q, wrap_bearing)  # gates too
    known = None if since is None else (_steps_in_common(since, world, mu0, setting), since)
    try:
        return localize(world, predict, update, SIG0, accept, mu0=mu0, identify=identify, known=known)
    except ValueError as err:  # a covariance no longer positive semi-definite, at extreme noise
        raise ValueError(f"the {filter.upper()} broke down with {motion_noise=} and {sensor_noise=}: {err}") from None


def _steps_in_common(old: LoopRun, world: RobotRun, mu0, setting: dict) -> int:
    """How many first steps a run of the filter ``setting`` over ``world`` from ``mu0`` shares with the run
    ``old``: none if the filter, the noise it assumes or its start changed; else all of them up to the
    first step at which the world tells the filter something else (odometry, which landmarks it reads,
    or a reading)."""
    T = world.visible.shape[0]
    mine = (setting["filter"], setting["wrap_bearing"], setting["gate"], setting["labelled"], *setting["noise"][2:])
    theirs = (old.filter, old.wrap_bearing, old.gate, old.labelled, old.filter_motion_noise, old.filter_sensor_noise)
    if (
        mine != theirs
        or (old.t.size, old.dt) != (T, world.dt)
        or not (np.array_equal(old.mu0, mu0) and np.array_equal(old.landmarks, world.landmarks))
    ):
        return 0
    same = (
        (old.odometry == world.odometry).all(axis=1)
        & ((old.used | old.rejected) == world.visible).all(axis=1)  # what it could read, gated or not
        & (old.z == world.z).all(axis=(1, 2))
    )
    return T if same.all() else int(np.argmin(same))  # the first step that differs


def _loop_run(world: RobotRun, track: Track, mu0, *, filter, wrap_bearing, gate, labelled, noise) -> LoopRun:
    """The record of one lap: the world, the filter's track, and the truth measured against it.

    ``noise`` is (world's motion, world's sensor, filter's motion, filter's sensor) noise scales."""
    err, Sxy = world.truth[:, :2] - track.mu[:, :2], track.Sig[:, :2, :2]
    d2 = nees(world.truth[:, :2], track.mu[:, :2], Sxy)  # the position NEES, every step
    return LoopRun(
        t=world.t,
        dt=world.dt,
        truth=world.truth,
        odometry=world.odometry,
        landmarks=world.landmarks,
        z=world.z,
        used=track.used,
        rejected=world.visible & ~track.used,
        matched=track.matched,
        start=world.start,
        mu0=mu0,
        Sig0=SIG0,
        mu_bar=track.mu_bar,
        Sig_bar=track.Sig_bar,
        mu=track.mu,
        Sig=track.Sig,
        error=np.linalg.norm(err, axis=1),
        inside=d2 <= 9.0,
        area=np.pi * np.sqrt(np.maximum(np.linalg.det(Sxy), 0.0)),  # det may round just below 0 when flat
        nees=d2,
        filter=filter,
        dropout=world.dropout,
        one_back=world.one_back,
        motion_noise=noise[0],
        sensor_noise=noise[1],
        filter_motion_noise=noise[2],
        filter_sensor_noise=noise[3],
        kidnap=world.kidnap,
        wrap_bearing=wrap_bearing,
        gate=gate,
        labelled=labelled,
        seed=world.seed,
    )
