"""The landmark localization loop: a robot drives round a map and an EKF or a UKF follows it (chapters 8-10).

:func:`simulate_robot` makes the world: the robot executes the loop's controls exactly
(and may be kidnapped), the filter is told them through noisy odometry, and the sensor
reads the landmarks within range (unless it is blind).  :func:`localize` is the loop of
chapter 8, over the public filter steps: predict with the odometry, then for each reading
in view, find its landmark (its label, or chapter 8's nearest neighbour), gate it and update
with it.  :func:`landmark_loop` puts the two together for every setting the course's last
chapters push on.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.association import associate, mahalanobis
from ..filters.ekf import ekf_predict, ekf_update
from ..filters.localization import _gate
from ..filters.ukf import ukf_predict, ukf_update
from ..models import (
    pose_mean,
    pose_residual,
    range_bearing,
    range_bearing_jacobian,
    range_bearing_mean,
    range_bearing_residual,
    unicycle,
    unicycle_control_jacobian,
    unicycle_jacobian,
    wrap_angle,
)
from .records import Record, read_only, text_table
from .robot import DEFAULT_LANDMARKS, RobotRun, loop_controls, simulate_robot
from .target import nees

FILTERS = ("ekf", "ukf")
V_STD, OMEGA_STD = 0.1, 0.05  # odometry noise at motion_noise = 1: m/s, rad/s
RANGE_STD, BEARING_STD = 0.1, 0.03  # reading noise at sensor_noise = 1: m, rad
SIG0 = read_only(np.diag([0.01, 0.01, 0.001]))  # the start is known to about 10 cm and 2 degrees
NOISE_SCALES = (0.01, 100.0)  # below, a reading so exact the gain's S^-1 loses its digits; above, no robot
UKF_LAM = 0.0  # lambda = 3 - n for the pose (n = 3): centre weight 0, six points of weight 1/6
HONEST_NEES = (1.0, 4.0)  # the band of the mean position NEES (2 for an honest filter) read as honest


@dataclass(frozen=True)
class Track(Record):
    """What a filter made of a drive (:func:`localize`); one row per step ``k = 0 .. T-1``."""

    mu_bar: np.ndarray  #: (T, n) predicted mean, before the updates of step k
    Sig_bar: np.ndarray  #: (T, n, n) predicted covariance
    mu: np.ndarray  #: (T, n) estimate after the updates of step k
    Sig: np.ndarray  #: (T, n, n) its covariance
    used: np.ndarray  #: (T, L) bool: the readings the filter used (in view and inside the gate)
    matched: np.ndarray  #: (T, L) int: the landmark the reading of landmark j was used as, -1 where not used


@dataclass(frozen=True)
class LoopRun(Record):
    """One drive round the loop and the filter that followed it; arrays have one row per step ``k = 0 .. T-1``.

    Step ``k``: the filter predicts with ``odometry[k]`` (giving ``mu_bar[k]``,
    ``Sig_bar[k]``), then updates with the readings ``z[k, used[k]]`` one landmark
    at a time (giving ``mu[k]``, ``Sig[k]``), each as the reading of the landmark
    ``matched[k, j]``: its own with labelled readings, the one it was matched to without.
    """

    t: np.ndarray  #: (T,) time after each step (s)
    dt: float  #: time step (s)
    truth: np.ndarray  #: (T, 3) true pose [x, y, theta] after each step
    odometry: np.ndarray  #: (T, 2) the controls [V, omega] the filter is told
    landmarks: np.ndarray  #: (L, 2) the map (m)
    z: np.ndarray  #: (T, L, 2) readings [r, phi]; zeros where out of range
    used: np.ndarray  #: (T, L) bool: readings the filter used (in range, the sensor not blind, inside the gate)
    rejected: np.ndarray  #: (T, L) bool: readings in range while the sensor could see, but outside the gate
    matched: np.ndarray  #: (T, L) int: the map index the reading of landmark j was used as, -1 where not used
    start: np.ndarray  #: (3,) the true pose before the first step
    mu0: np.ndarray  #: (3,) the filter's mean at the start: the true start unless it was told otherwise
    Sig0: np.ndarray  #: (3, 3) the filter's covariance at the start
    mu_bar: np.ndarray  #: (T, 3) predicted mean, before the updates of step k
    Sig_bar: np.ndarray  #: (T, 3, 3) predicted covariance
    mu: np.ndarray  #: (T, 3) estimate after the updates of step k
    Sig: np.ndarray  #: (T, 3, 3) its covariance
    error: np.ndarray  #: (T,) distance between the estimated and the true position (m)
    inside: np.ndarray  #: (T,) bool: the true position lies inside the 3-sigma position ellipse
    area: np.ndarray  #: (T,) area of the 1-sigma position ellipse, pi sqrt(det Sig_xy) (m^2)
    nees: np.ndarray  #: (T,) position NEES e^T Sig_xy^-1 e: 2 on average for an honest filter (chapter 6)
    filter: str  #: "ekf", "ukf", or the name of the step function that ran
    dropout: tuple[int, int] | None  #: the sensor is blind for steps t0 <= k < t1
    one_back: bool  #: at step t1 the sensor read only the nearest landmark: sight came back one landmark first
    motion_noise: float  #: scale of the world's odometry noise
    sensor_noise: float  #: scale of the world's reading noise
    filter_motion_noise: float  #: scale of the odometry noise the filter assumes (its R)
    filter_sensor_noise: float  #: scale of the reading noise the filter assumes (its Q)
    kidnap: int | None  #: step at which the true robot was carried half a lap further on
    wrap_bearing: bool  #: whether the bearing innovation was wrapped to (-pi, pi]
    gate: float | None  #: validation gate in standard deviations, or None
    labelled: bool  #: the readings came with the landmark they belong to; if not, nearest-neighbour association
    seed: int

    @property
    def share_inside(self) -> float:
        """Share of the steps with the truth inside the 3-sigma ellipse (0 to 1)."""
        return float(self.inside.mean())

    def honesty(self, k: int | None = None) -> tuple[float, str]:
        """The mean position NEES over steps 0 to ``k`` (by default the whole run) and what it says.

        An honest filter's position NEES is 2 on average (chapter 6).  Its mean over a lap
        stays within :data:`HONEST_NEES`, a band wider than chapter 6's for independent
        draws because one lap's errors are correlated from step to step.  Below it the
        filter is *timid* (its ellipse is larger than its errors), above it *over-confident*.
        """
        k = len(self.t) - 1 if k is None else int(k)
        mean = float(self.nees[: k + 1].mean())
        low, high = HONEST_NEES
        return mean, "timid" if mean < low else "over-confident" if mean > high else "honest"

    def table(self, steps) -> str:
        """One line per step of ``steps``: readings used and rejected, error, 1-sigma area before and after."""
        rows = []
        for k in steps:
            bar = np.pi * np.sqrt(np.linalg.det(self.Sig_bar[k, :2, :2]))
            rows.append(
                [
                    str(k),
                    str(int(self.used[k].sum())),
                    str(int(self.rejected[k].sum())),
                    f"{np.linalg.norm(self.truth[k, :2] - self.mu_bar[k, :2]):.2f}",
                    f"{self.error[k]:.2f}",
                    f"{bar:.3g}",
                    f"{self.area[k]:.3g}",
                    "yes" if self.inside[k] else "no",
                ]
            )
        header = ["step", "used", "rejected", "error before (m)", "after", "1σ area before (m²)", "after", "inside 3σ"]
        return text_table(header, rows)


def _noise_scale(x, name: str) -> float:
    value = v.scalar(x, name)
    if not NOISE_SCALES[0] <= value <= NOISE_SCALES[1]:
        raise ValueError(f"{name} must be a noise scale from {NOISE_SCALES[0]} to {NOISE_SCALES[1]}, got {value}")
    return value


def process_noise_of_odometry(mu, u, dt: float, M) -> np.ndarray:
    r"""Process noise R of one step when the noise is in the odometry: the control noise mapped into the pose.

    .. math:: R = W M W^\top, \qquad W = \partial g / \partial u \text{ at } (\mu, u)

    ``W`` is :func:`~kfcourse.models.unicycle_control_jacobian`.  R has rank 2 (two noisy
    controls move three pose numbers).  Introduced in chapter 8.

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
    mu = v.vector(mu, "mu", 3)  # each argument by its own name (the Jacobian would call mu "state")
    u = v.vector(u, "u", 2)
    dt = v.positive(dt, "dt", "a time step", "s")
    M = v.covariance(M, "M", 2)
    W = unicycle_control_jacobian(mu, u, dt)  # (3, 2): how each control moves the pose
    return W @ M @ W.T  # R = W M W^T


def localize(
    world: RobotRun,
    predict: Callable,
    update: Callable,
    Sig0,
    accept: Callable | None = None,
    *,
    mu0=None,
    identify: Callable | None = None,
    known: tuple[int, Track] | None = None,
) -> Track:
    """The localization loop of chapter 8: at each step predict with the odometry, then for each
    reading in view, find which landmark it belongs to, gate it and update with it, one landmark at a time.

    Introduced in chapter 8; chapter 7's :func:`~kfcourse.sim.run_ekf` and chapter 10's
    :func:`landmark_loop` run it.

    Parameters
    ----------
    world : RobotRun
        The drive (:func:`~kfcourse.sim.simulate_robot`): odometry, readings and the map.
    predict : callable ``predict(mu, Sig, odometry) -> (mu_bar, Sig_bar)``
    update : callable ``update(mu_bar, Sig_bar, z, landmark) -> (mu, Sig)``
    Sig0 : array_like, shape (n, n)
        The filter's covariance at the start.
    accept : callable ``accept(mu_bar, Sig_bar, z, landmark) -> bool``, optional
        The validation gate: a reading it refuses is not used.  By default every reading is.
    mu0 : array_like, shape (n,), optional
        The filter's mean at the start; by default the true start ``world.start``.
    identify : callable ``identify(mu_bar, Sig_bar, z) -> int or None``, optional
        Which landmark of the map a reading belongs to, worked out by the filter
        (:func:`nearest_landmark`), or ``None`` to refuse it.  By default the readings
        are labelled: the reading of landmark ``j`` is used as landmark ``j``'s.
    known : (int, Track), optional
        ``(k0, track)``: the first ``k0`` steps are already known, from a track of this filter
        over a world that is the same up to step ``k0``; they are copied, and the loop carries on
        from the estimate after step ``k0 - 1`` (a demo that changes only what comes later).

    Returns
    -------
    Track
    """
    world = _world(world)
    predict, update = v.function(predict, "predict"), v.function(update, "update")
    Sig0 = v.covariance(Sig0, "Sig0", len(world.start) if mu0 is None else None)
    accept = v.optional_function(accept, "accept")
    mu0 = world.start if mu0 is None else v.vector(mu0, "mu0", len(Sig0))
    identify = v.optional_function(identify, "identify")
    T, L = world.visible.shape
    known = None if known is None else _known(known, T)
    mu, Sig = np.array(mu0, dtype=float), np.array(Sig0, dtype=float)
    mu_bar, Sig_bar = np.empty((T, *mu.shape)), np.empty((T, *Sig.shape))
    mus, Sigs, used = np.empty_like(mu_bar), np.empty_like(Sig_bar), np.zeros((T, L), dtype=bool)
    matched = np.full((T, L), -1)
    k0 = 0
    if known is not None:  # copy the steps already known, then carry on from the last of them
        k0, track = known
        mine = {"mu_bar": mu_bar, "Sig_bar": Sig_bar, "mu": mus, "Sig": Sigs, "used": used, "matched": matched}
        for name, rows in mine.items():
            rows[:k0] = getattr(track, name)[:k0]
        if k0:
            mu, Sig = mus[k0 - 1].copy(), Sigs[k0 - 1].copy()
    for k in range(k0, T):
        mu, Sig = predict(mu, Sig, world.odometry[k])  # 1. predict with the odometry
        mu_bar[k], Sig_bar[k] = mu, Sig
        for j in np.flatnonzero(world.visible[k]):  # sequential updates, one reading at a time
            z = world.z[k, j]
            i = j if identify is None else identify(mu, Sig, z)  # 2. which landmark: the label, or the filter's guess
            if i is not None and (accept is None or accept(mu, Sig, z, world.landmarks[i])):  # 3. gate
                mu, Sig = update(mu, Sig, z, world.landmarks[i])  # 4. update as landmark i's reading
                used[k, j], matched[k, j] = True, i
        mus[k], Sigs[k] = mu, Sig
    return Track(mu_bar=mu_bar, Sig_bar=Sig_bar, mu=mus, Sig=Sigs, used=used, matched=matched)


def _world(world) -> RobotRun:
    if not isinstance(world, RobotRun):
        raise ValueError(f"world must be a RobotRun (kf.sim.simulate_robot), got {type(world).__name__}")
    return world


def _known(known, T: int) -> tuple[int, Track]:
    """``known`` of :func:`localize`: a pair (k0, track), the track's first k0 steps of the T to copy."""
    if not (isinstance(known, tuple) and len(known) == 2 and isinstance(known[1], Track | LoopRun)):
        got = type(known).__name__
        raise ValueError(f"known must be a pair (k0, track) of a step count and a Track or LoopRun, got {got}")
    k0, track = v.whole(known[0], "known[0]"), known[1]
    if k0 > min(T, len(track.mu)):
        raise ValueError(f"known[0] must be a step count up to {min(T, len(track.mu))}, the steps known; got {k0}")
    return k0, track


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


def loop_filter(filter: str, dt: float, M, Q, wrap_bearing: bool = True) -> tuple[Callable, Callable]:
    """The ``predict`` and ``update`` of the course's EKF or UKF on the unicycle and the range-bearing sensor.

    Both call the public filter steps.  The process noise is the odometry noise ``M``
    mapped into the pose (:func:`process_noise_of_odometry`); the update wraps the
    bearing innovation (unless ``wrap_bearing`` is False, chapter 8's bug) and the
    heading of the result.  The UKF uses λ = 0 and averages headings on the circle.
    Introduced in chapter 8 (EKF) and chapter 9 (UKF).
    """
    if not isinstance(filter, str) or filter not in FILTERS:
        raise ValueError(f"filter must be one of {FILTERS}, got {filter!r}")
    dt = v.positive(dt, "dt", "a time step", "s")
    M, Q = v.covariance(M, "M", 2), v.covariance(Q, "Q", 2)
    wrap_bearing = v.flag(wrap_bearing, "wrap_bearing")
    z_residual = range_bearing_residual if wrap_bearing else None
    z_mean = range_bearing_mean if wrap_bearing else None

    def predict(mu, Sig, u):
        R = process_noise_of_odometry(mu, u, dt, M)
        if filter == "ekf":
            return ekf_predict(mu, Sig, u, lambda x, c: unicycle(x, c, dt), lambda x, c: unicycle_jacobian(x, c, dt), R)
        return ukf_predict(mu, Sig, u, lambda X, c: unicycle(X, c, dt), R, UKF_LAM, pose_residual, pose_mean)

    def update(mu_bar, Sig_bar, z, m):
        h = lambda x: range_bearing(x, m)  # noqa: E731
        if filter == "ekf":
            H = lambda x: range_bearing_jacobian(x, m)  # noqa: E731
            mu, Sig = ekf_update(mu_bar, Sig_bar, z, h, H, Q, z_residual)
        else:
            mu, Sig = ukf_update(mu_bar, Sig_bar, z, h, Q, UKF_LAM, z_residual, z_mean, pose_residual)
        mu[2] = wrap_angle(mu[2])  # the update may push the heading past pi
        return mu, Sig

    return predict, update


def gate_within(gate: float, Q, wrap_bearing: bool = True) -> Callable:
    """A validation gate (chapter 8): accept a reading whose Mahalanobis distance from the landmark's
    predicted reading, with the linearized ``S = H Sig_bar H^T + Q``, is at most ``gate``."""
    gate = v.positive(gate, "gate", "a distance", "standard deviations")
    Q = v.covariance(Q, "Q", 2)
    wrap_bearing = v.flag(wrap_bearing, "wrap_bearing")

    def accept(mu_bar, Sig_bar, z, m) -> bool:
        z_hat, H = range_bearing(mu_bar, m), range_bearing_jacobian(mu_bar, m)
        y = range_bearing_residual(z, z_hat) if wrap_bearing else z - z_hat  # innovation
        return mahalanobis(y, H @ Sig_bar @ H.T + Q) <= gate

    return accept


def nearest_landmark(landmarks, gate: float | None, Q, wrap_bearing: bool = True) -> Callable:
    """Data association (chapter 8) for readings without labels: match a reading to the landmark of the map
    nearest in Mahalanobis distance (:func:`~kfcourse.associate`), or refuse it if even that one lies
    beyond ``gate``; with no gate (``None``) always the nearest.  Introduced in chapter 11."""
    residual = range_bearing_residual if wrap_bearing else None

    def identify(mu_bar, Sig_bar, z) -> int | None:
        h, H = range_bearing, range_bearing_jacobian
        best, dist = associate(z, mu_bar, Sig_bar, landmarks, h, H, Q, 1.0 if gate is None else gate, residual)
        return int(np.argmin(dist)) if gate is None else best  # no gate: the nearest, however far

    return identify


def loop_world(
    seed: int = 0, motion_noise: float = 1.0, sensor_noise: float = 1.0, landmarks=None, **drive
) -> RobotRun:
    """The capstone's world: the default robot drives :func:`loop_controls` through the map, its noise scaled.

    ``motion_noise`` scales the odometry noise (0.1 m/s, 0.05 rad/s at 1), ``sensor_noise`` the
    reading noise (0.1 m, 0.03 rad at 1), each from 0.01 to 100 (:data:`NOISE_SCALES`); ``drive``
    passes ``sensor_range``, ``laps``, ``kidnap`` and ``dropout`` to :func:`~kfcourse.sim.simulate_robot`.
    Introduced in chapter 11 (chapter 10's :func:`landmark_loop` drives it without naming it).
    """
    seed = v.whole(seed, "seed", 0)
    motion_noise = _noise_scale(motion_noise, "motion_noise")
    sensor_noise = _noise_scale(sensor_noise, "sensor_noise")
    dt = 0.2  # s
    return simulate_robot(
        loop_controls(dt=dt),
        dt,
        landmarks=DEFAULT_LANDMARKS if landmarks is None else landmarks,
        v_std=motion_noise * V_STD,
        omega_std=motion_noise * OMEGA_STD,
        range_std=sensor_noise * RANGE_STD,
        bearing_std=sensor_noise * BEARING_STD,
        seed=seed,
        **drive,
    )


def localize_with_step(world: RobotRun, step: Callable, Sig0, M, Q, gate: float, name: str = "step", mu0=None) -> Track:
    """The localization loop run by one function: ``step`` does a whole step, prediction and updates.

    ``step(mu, Sig, u, z, landmarks, dt, M, Q, gate) -> (mu, Sig, used)`` gets the readings
    of the landmarks in view at each step (chapter 10's exercise, the interface of
    :func:`~kfcourse.ekf_localization_step`).  Its prediction, for the record, is the same
    function with no reading.  What it returns is checked at every step: a
    ``ValueError`` names the function, the step and what went wrong.  The readings are labelled; the
    filter starts at ``mu0``, by default the true start.  Introduced in chapter 10.
    """
    world = _world(world)
    step = v.function(step, "step")
    Sig0 = v.covariance(Sig0, "Sig0", 3)
    M, Q = v.covariance(M, "M", 2), v.covariance(Q, "Q", 2)
    gate = _gate(gate)
    mu0 = world.start if mu0 is None else v.vector(mu0, "mu0", 3)
    T, L = world.visible.shape
    mu, Sig = np.array(mu0, dtype=float), np.array(Sig0, dtype=float)
    mu_bar, Sig_bar = np.empty((T, 3)), np.empty((T, 3, 3))
    mus, Sigs, used = np.empty_like(mu_bar), np.empty_like(Sig_bar), np.zeros((T, L), dtype=bool)
    nothing = np.empty((0, 2))
    for k in range(T):
        seen = np.flatnonzero(world.visible[k])
        u = world.odometry[k]
        mu_bar[k], Sig_bar[k], _ = _step_output(step, name, k, 0, mu, Sig, u, nothing, nothing, world.dt, M, Q, gate)
        z, marks = world.z[k, seen], world.landmarks[seen]
        mu, Sig, used[k, seen] = _step_output(step, name, k, len(seen), mu, Sig, u, z, marks, world.dt, M, Q, gate)
        mus[k], Sigs[k] = mu, Sig
    matched = np.where(used, np.arange(L), -1)  # each reading used as its own landmark's
    return Track(mu_bar=mu_bar, Sig_bar=Sig_bar, mu=mus, Sig=Sigs, used=used, matched=matched)


def _step_output(step, name, k, n_seen, *args):
    """Call a step function on copies of its inputs; its output checked, or a ValueError saying what went wrong."""
    where = f"the filter {name} at step {k} ({n_seen} reading{'s' if n_seen != 1 else ''})"
    try:
        out = step(*(np.array(a) if isinstance(a, np.ndarray) else a for a in args))
    except Exception as err:  # the student's code: whatever it raises becomes a message
        raise ValueError(f"{where} raised {type(err).__name__}: {err}") from None
    if not isinstance(out, tuple | list) or len(out) != 3:
        raise ValueError(f"{where} must return (mu, Sig, used), got {type(out).__name__}")
    try:
        mu = v.vector(out[0], "mu", 3)
    except ValueError as err:
        raise ValueError(f"{where} returned {_briefly(err, out[0])}") from None
    try:
        Sig = v.covariance(out[1], "Sig", 3)
    except ValueError as err:
        raise ValueError(f"{where} returned {_briefly(err, out[1])}") from None
    used = np.asarray(out[2])
    if used.shape != (n_seen,) or not (used.dtype == bool or np.isin(used, (0, 1)).all()):
        raise ValueError(f"{where} must return used, one True or False per reading, shape ({n_seen},); got {out[2]!r}")
    return mu, Sig, used.astype(bool)


def _briefly(err: ValueError, value) -> str:
    """A long message about a returned array, with the array printed to 3 digits on one line."""
    text = str(err)
    if len(text) <= 100 or ", got " not in text:
        return text
    try:
        shown = np.array2string(np.asarray(value, dtype=float), precision=3, separator=", ").replace("\n", "")
    except (TypeError, ValueError):
        return text[:100] + "..."
    return f"{text.split(', got ')[0]}, got {' '.join(shown.split())}"


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

    The world is :func:`~kfcourse.sim.simulate_robot`'s, draw for draw.  The filter
    starts at the true start (or at ``start``) with covariance :data:`SIG0`.  Its R (the odometry noise
    it assumes, mapped into the pose) and its Q are the world's own unless
    ``filter_motion_noise`` or ``filter_sensor_noise`` say otherwise: by default the
    filter is honest about the noise.

    Introduced in chapter 8; the capstone of chapter 10 drives every argument, chapter 11
    ``start`` and ``labelled``.

    Parameters
    ----------
    seed : int
        Seed of the noise (>= 0).  The same seed gives the same noise for every
        filter, dropout and kidnapping.
    filter : {"ekf", "ukf"} or callable
        Which filter follows the robot: the course's EKF (:func:`loop_filter` run by
        :func:`localize`), its UKF (λ = 0, headings averaged on the circle), or a
        function ``step(mu, Sig, u, z, landmarks, dt, M, Q, gate) -> (mu, Sig, used)``
        that does a whole step (chapter 10's exercise, run by :func:`localize_with_step`).
        A step that raises or returns something wrong gives a ``ValueError`` that names
        it and the step.
    dropout : (int, int), optional
        The sensor is blind for the steps ``t0 <= k < t1``.
    motion_noise, sensor_noise : float
        Scale of the world's odometry noise (0.1 m/s, 0.05 rad/s at 1) and reading
        noise (0.1 m, 0.03 rad at 1), from 0.01 to 100 (:data:`NOISE_SCALES`).
    filter_motion_noise, filter_sensor_noise : float, optional
        Scale of the odometry noise (its R) and the reading noise (its Q) the filter
        assumes, on the same scale; ``None`` (the default) is the world's.  A filter
        that assumes more noise than there is is timid, less is over-confident.
    one_back : bool
        Sight comes back one landmark first: at step ``t1`` the sensor reads only the
        nearest landmark in range (:func:`~kfcourse.sim.simulate_robot`).
    kidnap : int, optional
        At this step the true robot is lifted and set down half a lap further
        round the loop, where it carries on; the filter is not told.
    wrap_bearing : bool
        Wrap the bearing innovation to (-pi, pi].  False is the bug of chapter 8:
        a reading just across ±pi then looks 2 pi away.  Only for "ekf" and "ukf".
    gate : float, optional
        Validation gate (> 0, in standard deviations, chapter 8): a reading whose
        Mahalanobis distance from its landmark's predicted reading exceeds it is
        rejected.  Both filters measure the distance with the linearized
        :math:`S = H\bar\Sigma H^\top + Q`.  ``None`` (the default) uses every reading
        (a step function gets ``gate=np.inf``).
    laps : int
        Times round the loop (>= 1).
    landmarks : array_like, shape (L, 2), optional
        The map (m); by default :data:`~kfcourse.sim.DEFAULT_LANDMARKS`.
    sensor_range : float
        Largest range at which a landmark is seen (m), > 0.
    start : array_like, shape (3,), optional
        The filter's mean at the start, ``[x, y, theta]``; by default the true start.
        The truth starts where it always does (``LoopRun.start``); this is ``LoopRun.mu0``.
    labelled : bool
        The readings come with the landmark they belong to (the default).  False: the
        filter matches each reading to a landmark of the whole map itself, by the
        nearest neighbour of chapter 8 at its current mean (:func:`nearest_landmark`,
        gated by ``gate``, always the nearest without one), and uses it as that
        landmark's reading; ``LoopRun.matched`` records the match.  Only for "ekf" and
        "ukf": a step function gets labelled readings.
    since : LoopRun, optional
        A run of the course's EKF or UKF this one may start from: the steps it shares with ``since`` (the filter
        with the same noise, start and gate over a world the same up to then) are copied from it
        instead of computed again; the result is the same, to the last bit.  A demo passes its
        last run, so that a kidnap or a dropout set at step k reruns only the steps from k on.

    Returns
    -------
    LoopRun
    """
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
    drive = {"sensor_range": sensor_range, "laps": laps, "kidnap": kidnap, "dropout": dropout, "one_back": one_back}
    world = loop_world(seed, motion_noise, sensor_noise, landmarks, **drive)
    mu0 = world.start if mu0 is None else mu0
    dt = world.dt
    M = np.diag([trust_motion * V_STD, trust_motion * OMEGA_STD]) ** 2  # the odometry noise the filter assumes
    Q = np.diag([trust_sensor * RANGE_STD, trust_sensor * BEARING_STD]) ** 2  # the reading noise it assumes
    noise = (motion_noise, sensor_noise, trust_motion, trust_sensor)
    setting = {"filter": name, "wrap_bearing": wrap_bearing, "gate": gate, "labelled": labelled, "noise": noise}
    if callable(filter):
        track = localize_with_step(world, filter, SIG0, M, Q, np.inf if gate is None else gate, name, mu0)
    else:
        predict, update = loop_filter(filter, dt, M, Q, wrap_bearing)
        accept = None if gate is None or not labelled else gate_within(gate, Q, wrap_bearing)
        identify = None if labelled else nearest_landmark(world.landmarks, gate, Q, wrap_bearing)  # gates too
        known = None if since is None else (_steps_in_common(since, world, mu0, setting), since)
        try:
            track = localize(world, predict, update, SIG0, accept, mu0=mu0, identify=identify, known=known)
        except ValueError as err:  # a covariance no longer positive semi-definite, at extreme noise
            raise ValueError(
                f"the {filter.upper()} broke down with {motion_noise=} and {sensor_noise=}: {err}"
            ) from None
    return _loop_run(world, track, mu0, **setting)


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
