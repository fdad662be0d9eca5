"""A target moving in the plane, seen by a noisy position sensor (chapter 6).

Two worlds live here.  :func:`simulate_target` makes one target that drives
straight, turns, and drives on: the path a student watches in the tracker demo,
where a constant-velocity filter must cope with turns it does not model.
:func:`simulate_tracks` makes many targets that follow the constant-velocity model
exactly (with random accelerations), the world in which a well-tuned filter is
*consistent*: its covariance matches its real errors, which the NEES measures.

The filter's assumed noise (``R``, ``Q`` passed to :func:`filter_target` and
:func:`filter_tracks`) is separate from the world's true noise: retuning the
filter never changes the target.  The run records measure themselves: a
:class:`TargetEstimates` gives its lag, roughness, ellipse and honesty (the
position NEES of one run against its chi-square band), and :meth:`TargetRun.tuning_table`
and :meth:`TrackBatch.nees_table` print the tables of chapter 6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.batch import kf_step_batch
from ..filters.kalman import kf_step
from ..models import constant_velocity
from .records import Record, read_only, text_table
from .scores import FADE_TIME, nees, nees_band, verdict

DT = 0.1  # s between readings
SPEED = 2.0  # m/s, the target's constant speed
SENSOR_STD = 1.0  # m, the world's true position noise (per axis)
START_SPEED_STD = 2.0  # m/s, the spread of the NEES targets' starting velocities (per axis)
START_STEPS = 20  # readings (2 s) through which filter_target fits its starting line
START_STD = 1.0  # m, the sensor's rated noise, used for the starting line whatever Q the filter assumes
START_SPEED_VAR = 1e4  # (m/s)², "no idea of the velocity" before the second reading

# The turning target's path: (duration in s, turn rate in rad/s) per leg.
LEGS = (
    (3.0, 0.0),
    (2.0, math.pi / 4),  # 90 degrees left in 2 s
    (2.5, 0.0),
    (3.0, -math.pi / 3),  # 180 degrees right in 3 s
    (2.5, 0.0),
    (2.0, math.pi / 4),  # 90 degrees left in 2 s
    (1.0, 0.0),
)


@dataclass(frozen=True)
class TargetRun(Record):
    """One turning target and its readings; one row per time step ``k = 0 .. T-1``."""

    t: np.ndarray  #: (T,) time (s)
    truth: np.ndarray  #: (T, 4) true state [px, py, vx, vy] (m, m, m/s, m/s)
    z: np.ndarray  #: (T, 2) position readings [zx, zy] (m)
    turning: np.ndarray  #: (T,) bool: the target is turning at step k
    dt: float  #: time step (s)
    sensor_std: float  #: the world's true sensor noise per axis (m)
    seed: int

    def tuning_table(self, estimates: dict) -> str:
        """A table of filters run over this target (label -> :class:`TargetEstimates`) and of the readings
        themselves: the final position gain, the lag in the turns, the roughness, and the honesty test."""
        rows = []
        for label, est in estimates.items():
            h = est.honesty()
            rows.append(
                [label, f"{est.K[-1, 0, 0]:.3f}", f"{est.lag_in_turns():.2f}", f"{est.roughness():.2f}",
                 f"{h.mean_nees:.2f}", h.verdict]
            )  # fmt: skip
        lag_z = np.linalg.norm(self.z - self.truth[:, :2], axis=1)[self.turning].mean()
        rows.append(["the readings", "", f"{lag_z:.2f}", f"{roughness(self.z):.2f}", "", ""])
        return text_table(["filter assumes", "K", "lag in turns (m)", "roughness (m)", "mean NEES", "verdict"], rows)


@dataclass(frozen=True)
class Honesty:
    """The tracker's honesty test (chapter 6): the position NEES averaged over one run, against its band."""

    mean_nees: float  #: the position NEES averaged over the tracking steps
    low: float  #: where an honest filter's mean_nees lies (95 % of the time, or the level asked for): from ...
    high: float  #: ... to
    draws: int  #: the independent draws the band counts (one per FADE_TIME of tracking)
    verdict: str  #: "honest", "timid" (below the band) or "over-confident" (above it)


@dataclass(frozen=True)
class TargetEstimates(Record):
    """A filter's output over a :class:`TargetRun`; one row per time step."""

    mu: np.ndarray  #: (T, 4) estimated state [px, py, vx, vy]
    Sig: np.ndarray  #: (T, 4, 4) estimated covariance
    K: np.ndarray  #: (T, 4, 2) Kalman gain used at step k (zero at k = 0; the start-up gain up to START_STEPS - 1)
    R: np.ndarray  #: (4, 4) the process noise the filter assumed
    Q: np.ndarray  #: (2, 2) the measurement noise the filter assumed
    run: TargetRun  #: the world the filter tracked

    def position_error(self) -> np.ndarray:
        """(T,) distance (m) of the estimated position from the true one."""
        return np.linalg.norm(self.mu[:, :2] - self.run.truth[:, :2], axis=1)

    def lag_in_turns(self) -> float:
        """Mean distance (m) of the estimate from the truth over the steps where the target turns."""
        return float(self.position_error()[self.run.turning].mean())

    def roughness(self) -> float:
        r"""Mean :math:`\lVert \mu_{k+1} - 2\mu_k + \mu_{k-1} \rVert` of the position once tracking (m):
        how much the estimate changes direction from one step to the next."""
        return roughness(self.mu[:, :2])

    def ellipse_radius(self, k: int, nsig: float = 2.0) -> float:
        """Half the long axis (m) of the ``nsig``-sigma position ellipse at step ``k``."""
        return float(nsig * np.sqrt(np.linalg.eigvalsh(self.Sig[k, :2, :2])[-1]))

    def honesty(self, level: float = 0.95) -> Honesty:
        r"""Is the position ellipse honest?  Chapter 6's NEES test on one run.

        :math:`\mathrm{NEES}_k = (p_k - \mu_{p,k})^\top \Sigma_{pp,k}^{-1} (p_k - \mu_{p,k})`, the NEES of
        the position (the ellipse drawn), is :math:`\chi^2(2)` at each step if the filter is honest.
        Its average :math:`\overline{\mathrm{NEES}}` over the tracking steps is compared with the band of
        :func:`nees_band`.  The steps of one run are not independent draws: an error takes about
        ``FADE_TIME`` to fade, so the band counts one draw per ``FADE_TIME`` of tracking.
        """
        nees_k = nees(self.run.truth[START_STEPS:, :2], self.mu[START_STEPS:, :2], self.Sig[START_STEPS:, :2, :2])
        draws = max(round(nees_k.size * self.run.dt / FADE_TIME), 1)
        low, high = nees_band(draws, 2, level)
        mean_nees = float(nees_k.mean())
        return Honesty(mean_nees, low, high, draws, verdict(mean_nees, (low, high)))


def roughness(xy) -> float:
    r"""Mean :math:`\lVert p_{k+1} - 2p_k + p_{k-1} \rVert` (m) of a path ``xy`` (T, 2) once tracking
    (from step ``START_STEPS``): how much it changes direction from one step to the next."""
    xy = np.asarray(xy, float)[START_STEPS:]
    return float(np.linalg.norm(np.diff(xy, 2, axis=0), axis=1).mean())


def process_noise(dt: float, accel_var: float) -> np.ndarray:
    r"""Process noise ``R`` of a constant-velocity model driven by random accelerations.

    A constant acceleration :math:`a \sim N(0, \sigma_a^2 I)` held for one step moves
    the state by :math:`\Gamma a` with :math:`\Gamma = [\tfrac{\Delta t^2}{2} I;\ \Delta t\, I]`
    (the noise input matrix, "Gamma"), so :math:`R = \sigma_a^2\, \Gamma \Gamma^\top`.
    Introduced in chapter 6.

    Parameters
    ----------
    dt : float
        Time step (s), > 0.
    accel_var : float
        Acceleration variance :math:`\sigma_a^2` per axis (m²/s⁴), >= 0.

    Returns
    -------
    R : ndarray, shape (4, 4)
    """
    dt = v.positive(dt, "dt", "a time step", "s")
    accel_var = v.variance(accel_var, "accel_var")
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])  # how an acceleration moves [p, v]
    return accel_var * Gamma @ Gamma.T  # R = sigma_a^2 Gamma Gamma^T


def simulate_target(seed: int = 0, sensor_std: float = SENSOR_STD) -> TargetRun:
    r"""A target driving at constant speed along straight legs and turns (see ``LEGS``).

    Truth: heading :math:`\theta_k = \theta_{k-1} + \omega_k \Delta t`, velocity
    :math:`v_k = s\,[\cos\theta_k, \sin\theta_k]`, position :math:`p_k = p_{k-1} + v_k \Delta t`.
    Readings: :math:`z_k = p_k + \sigma\, e_k` with standard-normal :math:`e_k`.
    The path is the same for every seed; the seed draws the sensor noise.
    Introduced in chapter 6.

    Parameters
    ----------
    seed : int
    sensor_std : float
        The world's sensor noise per axis (m), > 0.

    Returns
    -------
    TargetRun
    """
    seed = v.whole(seed, "seed", 0)
    sensor_std = v.positive(sensor_std, "sensor_std", "a standard deviation", "m")
    omega = np.concatenate([np.full(round(duration / DT), rate) for duration, rate in LEGS])  # rad/s per step
    theta = np.cumsum(omega * DT)  # heading (rad)
    vel = SPEED * np.column_stack([np.cos(theta), np.sin(theta)])
    pos = np.cumsum(vel * DT, axis=0)
    e = np.random.default_rng(seed).standard_normal(pos.shape)
    return TargetRun(
        t=DT * np.arange(omega.size),
        truth=np.hstack([pos, vel]),
        z=pos + sensor_std * e,
        turning=omega != 0,
        dt=DT,
        sensor_std=sensor_std,
        seed=seed,
    )


def filter_target(run: TargetRun, R, Q) -> TargetEstimates:
    r"""Track ``run`` with a constant-velocity Kalman filter that assumes noise ``R``, ``Q``.

    **Start-up** (the first ``START_STEPS`` readings, 2 s): the velocity comes from the
    readings, not from a guess.  The filter starts at the first reading, "no idea of
    the velocity" (variance ``START_SPEED_VAR``), and fits a straight line at constant
    velocity through the readings so far: Kalman cycles with no process noise and the
    sensor's rated noise ``START_STD`` — the same start whatever ``R`` and ``Q`` the
    filter is told.  **Tracking**: from then on one :func:`kf_step` per reading with
    the assumed ``R`` and ``Q``.  The gains of all steps are recomputed afterwards from
    the recorded covariances, all at once.  Introduced in chapter 6.

    Parameters
    ----------
    run : TargetRun
    R : array_like, shape (4, 4)
        The process noise the filter assumes (e.g. :func:`process_noise`).
    Q : array_like, shape (2, 2)
        The measurement noise the filter assumes.

    Returns
    -------
    TargetEstimates
    """
    if not isinstance(run, TargetRun):
        raise ValueError(f"run must be a TargetRun (kf.sim.simulate_target), got {type(run).__name__}")
    R = v.covariance(R, "R", 4)
    Q = v.covariance(Q, "Q", 2)
    F, H = constant_velocity(run.dt, dim=2)
    T = run.t.size
    R_used = np.where(np.arange(T)[:, None, None] < START_STEPS, 0.0, R)  # (T, 4, 4): no process noise at start-up
    Q_used = np.where(np.arange(T)[:, None, None] < START_STEPS, START_STD**2 * np.eye(2), Q)  # (T, 2, 2)
    mu_all, Sig_all, K_all = np.empty((T, 4)), np.empty((T, 4, 4)), np.zeros((T, 4, 2))
    mu = np.concatenate([run.z[0], np.zeros(2)])  # at the first reading, velocity unknown
    Sig = np.diag([START_STD**2, START_STD**2, START_SPEED_VAR, START_SPEED_VAR])
    mu_all[0], Sig_all[0] = mu, Sig
    for k in range(1, T):
        mu, Sig = kf_step(mu, Sig, None, run.z[k], F, None, H, R_used[k], Q_used[k])
        mu_all[k], Sig_all[k] = mu, Sig
    # The gain of every update, all at once from the covariance before it (a stack of T - 1 matrices):
    Sig_bar = F @ Sig_all[:-1] @ F.T + R_used[1:]  # Sig_bar = F Sig F^T + R
    S = H @ Sig_bar @ H.T + Q_used[1:]  # innovation covariance S = H Sig_bar H^T + Q
    K_all[1:] = Sig_bar @ H.T @ np.linalg.inv(S)  # K = Sig_bar H^T S^-1
    return TargetEstimates(mu_all, Sig_all, K_all, R, Q, run)


# --------------------------------------------------------------- many tracks at once: the NEES
@dataclass(frozen=True)
class TrackBatch(Record):
    """Many constant-velocity targets; arrays are (N tracks, T steps, ...)."""

    truth: np.ndarray  #: (N, T, 4) true states
    z: np.ndarray  #: (N, T, 2) position readings
    dt: float  #: time step (s)
    accel_std: float  #: the world's random acceleration per axis (m/s²)
    sensor_std: float  #: the world's sensor noise per axis (m)
    seed: int

    @property
    def R(self) -> np.ndarray:
        """The world's true process noise, (4, 4)."""
        return process_noise(self.dt, self.accel_std**2)

    @property
    def Q(self) -> np.ndarray:
        """The world's true measurement noise, (2, 2)."""
        return self.sensor_std**2 * np.eye(2)

    def nees_table(self, assumed: dict, level: float = 0.95) -> str:
        """A table of filters run over these tracks (label -> the ``(R, Q)`` they assume): the NEES averaged over
        the tracks and the steps, the share of steps whose average lies below, inside and above the ``level`` band
        of :func:`nees_band`, and the mean distance of the position estimates from the truth (m)."""
        n_tracks = self.truth.shape[0]
        low, high = nees_band(n_tracks, 4, level)
        rows = []
        for label, (R, Q) in assumed.items():
            mu, Sig = filter_tracks(self, R, Q)
            avg_nees = nees(self.truth, mu, Sig).mean(axis=0)  # average over the tracks, at each step
            error = np.linalg.norm(mu[:, :, :2] - self.truth[:, :, :2], axis=2).mean()
            below, above = np.mean(avg_nees < low), np.mean(avg_nees > high)
            shares = [f"{share:.0%}" for share in (below, 1.0 - below - above, above)]
            rows.append([label, f"{avg_nees.mean():.2f}", *shares, f"{error:.2f}"])
        header = ["filter assumes", "mean NEES", "below", "inside", "above", "error (m)"]
        return f"band [{low:.2f}, {high:.2f}] for {n_tracks} tracks\n" + text_table(header, rows)


def simulate_tracks(
    n_tracks: int = 300,
    n_steps: int = 100,
    accel_std: float = 1.0,
    sensor_std: float = SENSOR_STD,
    dt: float = DT,
    seed: int = 0,
) -> TrackBatch:
    r"""``n_tracks`` targets that follow the constant-velocity model exactly.

    Each starts at the origin with a velocity drawn from :math:`N(0, 2^2 I)` m/s
    (``START_SPEED_STD``), then :math:`x_k = F x_{k-1} + \Gamma a_k` with random
    accelerations :math:`a_k \sim N(0, \sigma_a^2 I)` (so the true process noise is
    :func:`process_noise`), and reads :math:`z_k = p_k + \sigma\, e_k`.
    Introduced in chapter 6.

    Returns
    -------
    TrackBatch
    """
    seed = v.whole(seed, "seed", 0)
    n_tracks, n_steps = v.whole(n_tracks, "n_tracks", 2), v.whole(n_steps, "n_steps", 2)
    accel_std = v.non_negative(accel_std, "accel_std", "a standard deviation", "m/s²")
    sensor_std = v.positive(sensor_std, "sensor_std", "a standard deviation", "m")
    dt = v.positive(dt, "dt", "a time step", "s")
    rng = np.random.default_rng(seed)
    F, _ = constant_velocity(dt, dim=2)
    Gamma = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])  # how an acceleration moves [p, v]
    x = np.zeros((n_tracks, 4))
    x[:, 2:] = START_SPEED_STD * rng.standard_normal((n_tracks, 2))
    truth = np.empty((n_tracks, n_steps, 4))
    truth[:, 0] = x
    for k in range(1, n_steps):
        a = accel_std * rng.standard_normal((n_tracks, 2))
        truth[:, k] = truth[:, k - 1] @ F.T + a @ Gamma.T  # x_k = F x_{k-1} + Gamma a_k
    z = truth[:, :, :2] + sensor_std * rng.standard_normal((n_tracks, n_steps, 2))
    return TrackBatch(truth, z, dt, accel_std, sensor_std, seed)


def filter_tracks(batch: TrackBatch, R, Q) -> tuple[np.ndarray, np.ndarray]:
    """Run one constant-velocity filter per track, all at once with :func:`kf_step_batch`.

    Each filter starts at its first reading, standing still, with position
    covariance ``Q`` and velocity variance ``START_SPEED_STD**2``: in this world the
    velocities are drawn from exactly that spread, so the start is honest when ``Q``
    is.  Introduced in chapter 6.

    Returns
    -------
    (mu, Sig) : read-only arrays, shapes (N, T, 4), (N, T, 4, 4)
    """
    if not isinstance(batch, TrackBatch):
        raise ValueError(f"batch must be a TrackBatch (kf.sim.simulate_tracks), got {type(batch).__name__}")
    R = v.covariance(R, "R", 4)
    Q = v.covariance(Q, "Q", 2)
    F, H = constant_velocity(batch.dt, dim=2)
    N, T, _ = batch.truth.shape
    mu_all, Sig_all = np.empty((N, T, 4)), np.empty((N, T, 4, 4))
    # Each filter's first guess: its first reading, standing still, as vague about the velocity as the world is.
    mu = np.hstack([batch.z[:, 0], np.zeros((N, 2))])  # (N, 4)
    Sig = np.zeros((N, 4, 4))
    Sig[:, :2, :2] = Q  # as sure of the position as of one reading
    Sig[:, 2:, 2:] = START_SPEED_STD**2 * np.eye(2)  # the spread the targets' velocities are drawn from
    mu_all[:, 0], Sig_all[:, 0] = mu, Sig
    for k in range(1, T):
        mu, Sig = kf_step_batch(mu, Sig, None, batch.z[:, k], F, None, H, R, Q)
        mu_all[:, k], Sig_all[:, k] = mu, Sig
    return read_only(mu_all), read_only(Sig_all)
