"""An EKF over a real robot's log (chapter 12): wheel odometry to predict, radio ranges to beacons to update.

:func:`range_localize` runs the course's EKF steps over a :class:`~kfcourse.data.PlazaLog`: at each odometry
step it predicts with the unicycle of chapter 8 (the step's distance and turn over its duration), then updates
with each range that arrived during the step, one at a time, through the range-only model (chapter 12) and,
if asked, chapter 8's validation gate.  The radio's scale is the filter's to assume (a number) or to estimate
(``"online"``: a fourth state).  :func:`smoothed` runs the RTS smoother backwards over the result.  The record,
:class:`RangeRun`, measures the filter against the log's ground truth.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .. import _validate as v
from ..filters.association import mahalanobis
from ..filters.ekf import ekf_predict, ekf_update
from ..filters.smoother import ekf_rts_smoother
from ..filters.ukf import ukf_predict, ukf_update
from ..models import (
    pose_mean,
    pose_residual,
    range_only,
    range_only_jacobian,
    scaled_range,
    scaled_range_jacobian,
    unicycle,
    unicycle_jacobian,
    wrap_angle,
)
from .loop_filters import UKF_LAM, process_noise_of_odometry
from .records import Record
from .scores import nees, verdict

if TYPE_CHECKING:
    from ..data import PlazaLog

# What the filter is told before anyone looks at the data: the wheels' speed and turn-rate noise, and the radio's
# range noise as its maker would quote it, unbiased.  Chapter 12 shows what the log says of these.
DATA_SHEET = {"speed_std": 0.05, "turn_std": 0.02, "range_std": 0.5}  # m/s, rad/s, m
START_STD = (0.1, 0.1, 0.05)  # the filter's doubt about a start it is told: m, m, rad
SCALE_STD = 0.1  # the doubt about the radio's scale when the filter estimates it, about its guess of 1
FILTERS = ("ekf", "ukf")
NOISE_PER = ("second", "metre")
INSIDE = 9.0  # a position NEES at most this: the truth inside the 3-sigma ellipse (chapters 6 and 10)


class AgainstTruth:
    """What a run over a log says of itself against the log's ground truth, from its ``error`` and ``nees``
    fields (one entry per pose): shared by :class:`RangeRun`, :class:`~kfcourse.sim.RangeParticleRun` and
    :class:`~kfcourse.sim.FactorGraphRun`."""

    error: np.ndarray
    nees: np.ndarray

    @property
    def inside(self) -> np.ndarray:
        """(K + 1,) bool: the true position lies inside the 3-sigma ellipse."""
        return self.nees <= INSIDE

    def summary(self) -> dict:
        """The run in five figures: mean and 95th-percentile position error (m), the share of poses inside the
        3-sigma ellipse, the mean position NEES (2 when honest) and what it says (:func:`~kfcourse.sim.verdict`)."""
        return {
            "mean_error": float(self.error.mean()),
            "p95_error": float(np.percentile(self.error, 95)),
            "inside": float(self.inside.mean()),
            "mean_nees": float(self.nees.mean()),
            "verdict": verdict(float(self.nees.mean())),
        }


@dataclass(frozen=True)
class RangeRun(AgainstTruth, Record):
    """An EKF over a log, measured against its ground truth.

    Rows ``k = 0 .. K`` are poses: row 0 the start, row k after odometry step k-1 and the ranges that arrived
    during it.  The state is the pose ``[x, y, theta]``, with the radio's scale ``s`` as a fourth entry when
    the filter estimates it.  Ranges ``i = 0 .. M-1`` are the log's, in time order.
    """

    log: str  #: the log's name ("Plaza1", "Plaza2")
    filter: str  #: "ekf" or "ukf"
    t: np.ndarray  #: (K + 1,) time of each pose (s)
    truth: np.ndarray  #: (K + 1, 3) the log's ground truth [x, y, heading]
    controls: np.ndarray  #: (K + 1, 3) [V, omega, dt] of the step into each pose (m/s, rad/s, s); row 0 zeros
    mu_bar: np.ndarray  #: (K + 1, n) predicted mean, before the step's ranges; row 0 the start
    Sig_bar: np.ndarray  #: (K + 1, n, n) predicted covariance
    mu: np.ndarray  #: (K + 1, n) estimate after the step's ranges
    Sig: np.ndarray  #: (K + 1, n, n) its covariance
    step: np.ndarray  #: (M,) the pose row after whose prediction each range was used or refused
    beacon: np.ndarray  #: (M,) the beacon of each range (a row of ``beacons``)
    z: np.ndarray  #: (M,) the range read (m)
    distance: np.ndarray  #: (M,) the distance to the beacon at the filter's mean just before the range (m)
    z_hat: np.ndarray  #: (M,) the range the filter predicted: that distance times its scale (m)
    S: np.ndarray  #: (M,) the innovation variance H Sig H^T + Q of each range (m^2)
    used: np.ndarray  #: (M,) bool: the range was used (inside the gate, if any)
    beacons: np.ndarray  #: (B, 2) the beacons (m)
    error: np.ndarray  #: (K + 1,) distance between the estimated and the true position (m)
    nees: np.ndarray  #: (K + 1,) position NEES: 2 on average for an honest filter
    speed_std: float  #: the speed noise the filter assumes (m/s; per metre driven: m per square-root metre)
    turn_std: float  #: the turn-rate noise it assumes (rad/s; per metre driven: rad per square-root metre)
    noise_per: str  #: "second": the odometry noise grows with time (chapter 8); "metre": with distance driven
    range_std: float  #: the range noise it assumes (m)
    scale: float | str  #: the radio's scale it assumes, or "online": estimated as the fourth state
    gate: float | None  #: the validation gate (standard deviations), or None: every range used

    @property
    def innovation(self) -> np.ndarray:
        """(M,) each range minus the range the filter predicted, z - h(mu_bar) (m)."""
        return self.z - self.z_hat

    @property
    def nis(self) -> np.ndarray:
        """(M,) normalised innovation squared y^2 / S: 1 on average when the filter's noise is honest."""
        return self.innovation**2 / self.S

    def fitted_scale(self) -> float:
        """The radio's scale the innovations point to, no ground truth needed: the least-squares ``s`` of
        z ≈ s d over the ranges used, d the distance the filter predicted for each."""
        z, d = self.z[self.used], self.distance[self.used]
        return float(z @ d / (d @ d))


def log_steps(log, steps: int | None) -> int:
    """``steps`` checked against ``log``, itself checked as a :class:`~kfcourse.data.PlazaLog`: the first ``steps``
    odometry steps to follow (None: all of them).  Every run over a log checks its first two arguments here."""
    from ..data import PlazaLog  # here, not above: kfcourse.data builds its record from kfcourse.sim's

    if not isinstance(log, PlazaLog):
        raise ValueError(f"log must be a PlazaLog (kf.data.load_plaza), got {type(log).__name__}")
    return log.step_count(steps)


def against_truth(truth, mu, Sig) -> dict:
    """A run's ``error`` (distance between the estimated and the true position, m) and position ``nees``, one
    entry per pose, as every :class:`AgainstTruth` record stores them."""
    return {
        "error": np.hypot(*(truth[:, :2] - mu[:, :2]).T),
        "nees": nees(truth[:, :2], mu[:, :2], Sig[:, :2, :2]),
    }


def _settings(log, filter, speed_std, turn_std, noise_per, range_std, scale, gate, start, start_std, steps) -> tuple:
    steps = log_steps(log, steps)
    if not isinstance(filter, str) or filter not in FILTERS:
        raise ValueError(f"filter must be one of {FILTERS}, got {filter!r}")
    speed_std = v.positive(speed_std, "speed_std", "a standard deviation", "m/s")
    turn_std = v.positive(turn_std, "turn_std", "a standard deviation", "rad/s")
    if not isinstance(noise_per, str) or noise_per not in NOISE_PER:
        raise ValueError(f"noise_per must be one of {NOISE_PER}, got {noise_per!r}")
    range_std = v.positive(range_std, "range_std", "a standard deviation", "m")
    if not (isinstance(scale, str) and scale == "online"):
        scale = v.positive(scale, "scale", 'a scale (or "online")')
    gate = None if gate is None else v.positive(gate, "gate", "a distance", "standard deviations")
    start = None if start is None else v.vector(start, "start", 3)
    start_std = v.vector(start_std, "start_std", 3)
    if not np.all(start_std > 0):
        raise ValueError(f"start_std must hold standard deviations > 0 (m, m, rad), got {start_std.tolist()}")
    return filter, speed_std, turn_std, noise_per, range_std, scale, gate, start, start_std, steps


def range_localize(
    log: PlazaLog,
    *,
    filter: str = "ekf",
    speed_std: float = DATA_SHEET["speed_std"],
    turn_std: float = DATA_SHEET["turn_std"],
    noise_per: str = "second",
    range_std: float = DATA_SHEET["range_std"],
    scale=1.0,
    gate: float | None = None,
    start=None,
    start_std=START_STD,
    steps: int | None = None,
) -> RangeRun:
    r"""Follow a real robot's log with the course's EKF or UKF: odometry to predict, ranges to beacons to update.

    Predict (chapter 8): the unicycle with the step's speed and turn rate, its R the odometry noise
    :math:`M = \mathrm{diag}(\sigma_V^2, \sigma_\omega^2)` mapped into the pose (``process_noise_of_odometry``);
    with ``noise_per="metre"`` the noise grows with the distance driven instead of with time, a variance of
    :math:`\sigma^2 |d|` per step of length :math:`d = V\Delta t`: :math:`M = \mathrm{diag}(\sigma_V^2,
    \sigma_\omega^2)\,|V| / \Delta t`.
    Update (chapter 12), once per range that arrived during the step: :math:`h = s\,\lVert p - b\rVert`, its
    Jacobian, :math:`Q = \sigma_r^2`; with a ``gate``, a range whose innovation is more than ``gate``
    standard deviations off is refused (chapter 8).  With ``scale="online"`` the state is
    ``[x, y, theta, s]``: ``s`` starts at 1 with standard deviation :data:`SCALE_STD` and is never moved by the
    motion, only by the ranges (``scaled_range``).  Introduced in chapter 12.

    Parameters
    ----------
    log : PlazaLog
        :func:`kfcourse.data.load_plaza`.
    filter : {"ekf", "ukf"}
        The course's EKF (chapter 7) or UKF (chapter 9, λ = 0, headings averaged on the circle).  Either
        gates, and records each range's innovation variance, with the linearized S (chapter 8).
    speed_std, turn_std : float
        The odometry noise the filter assumes: speed (m/s) and turn rate (rad/s), or with
        ``noise_per="metre"`` distance and turn per square-root metre driven; by default :data:`DATA_SHEET`'s.
    noise_per : {"second", "metre"}
        What the odometry noise grows with: time (chapter 8's M, the default) or the distance driven.
    range_std : float
        The range noise the filter assumes (m); by default :data:`DATA_SHEET`'s.
    scale : float or "online"
        The radio's scale the filter assumes (1: it reads true distances), or ``"online"`` to estimate it.
    gate : float, optional
        Validation gate in standard deviations (> 0); ``None`` uses every range.
    start : array_like, shape (3,), optional
        The filter's mean at the start; by default the true start.
    start_std : array_like, shape (3,)
        The filter's standard deviations about its start (m, m, rad), by default :data:`START_STD`: a start it
        is told.  A start it does not know needs tens of metres and pi.
    steps : int, optional
        Follow only the first ``steps`` odometry steps (>= 1); by default the whole log.

    Returns
    -------
    RangeRun
    """
    filter, speed_std, turn_std, noise_per, range_std, scale, gate, start, start_std, steps = _settings(
        log, filter, speed_std, turn_std, noise_per, range_std, scale, gate, start, start_std, steps
    )
    online = scale == "online"
    pose0 = log.truth[0] if start is None else start
    mu0 = np.append(pose0, 1.0) if online else np.array(pose0, dtype=float)
    Sig0 = np.diag(np.square([*start_std, SCALE_STD] if online else start_std))
    M, Q = np.diag([speed_std**2, turn_std**2]), np.array([[range_std**2]])
    track = _follow(log, steps, mu0, Sig0, _steps(filter, scale, M, Q, noise_per), gate)
    settings = {"speed_std": speed_std, "turn_std": turn_std, "noise_per": noise_per, "range_std": range_std}
    return _record(log, filter, steps, track, {**settings, "scale": scale, "gate": gate})


def _record(log, filter: str, steps: int, track: dict, settings: dict) -> RangeRun:
    """The run of :func:`_follow` as a record, measured against the log's ground truth."""
    truth, mus, Sigs = log.truth[: steps + 1], track["mu"], track["Sig"]
    shared = ("controls", "mu_bar", "Sig_bar", "step", "distance", "z_hat", "S", "used")
    return RangeRun(
        log=log.name,
        filter=filter,
        t=log.t_truth[: steps + 1],
        truth=truth,
        mu=mus,
        Sig=Sigs,
        beacon=log.beacon[track["ranges"]],
        z=log.range[track["ranges"]],
        beacons=log.beacons,
        **against_truth(truth, mus, Sigs),
        **settings,
        **{name: track[name] for name in shared},
    )


def _follow(log, steps: int, mu, Sig, filter_steps: tuple, gate) -> dict:
    """The filter over the first ``steps`` odometry steps of ``log`` from ``mu``, ``Sig``: at each step, predict
    with the odometry, then update with every range of the step, one at a time, each through the gate if any.
    ``filter_steps`` is ``(predict, update, reading)`` of :func:`_steps`."""
    predict, update, reading = filter_steps
    n = mu.size
    controls = np.zeros((steps + 1, 3))
    controls[1:, :2], controls[1:, 2] = log.controls()[:steps], log.dt[:steps]
    mu_bar, Sig_bar = np.empty((steps + 1, n)), np.empty((steps + 1, n, n))
    mus, Sigs = np.empty_like(mu_bar), np.empty_like(Sig_bar)
    mu_bar[0], Sig_bar[0], mus[0], Sigs[0] = mu, Sig, mu, Sig
    ranges, step = log.range_steps(steps)  # the ranges of these steps, and the pose after whose predict each comes
    distance, z_hat, S = np.empty(ranges.size), np.empty(ranges.size), np.empty(ranges.size)
    used = np.zeros(ranges.size, dtype=bool)
    i = 0
    for k in range(1, steps + 1):
        mu, Sig = predict(mu, Sig, controls[k])  # 1. predict with the odometry
        mu_bar[k], Sig_bar[k] = mu, Sig
        while i < ranges.size and step[i] == k:  # 2. every range of the step, one at a time
            b = log.beacons[log.beacon[ranges[i]]]
            z = log.range[ranges[i] : ranges[i] + 1]
            distance[i] = range_only(mu, b)[0]
            z_hat[i], S[i] = reading(mu, Sig, b)  # predicted range, innovation variance
            if gate is None or mahalanobis(z - z_hat[i : i + 1], [[S[i]]]) <= gate:  # 3. the gate
                mu, Sig = update(mu, Sig, z, b)  # 4. update with the range
                used[i] = True
            i += 1
        mus[k], Sigs[k] = mu, Sig
    return {"controls": controls, "mu_bar": mu_bar, "Sig_bar": Sig_bar, "mu": mus, "Sig": Sigs, "ranges": ranges,
            "step": step, "distance": distance, "z_hat": z_hat, "S": S, "used": used}  # fmt: skip


def _steps(filter: str, scale, M, Q, noise_per: str) -> tuple:
    """``predict(mu, Sig, c)``, ``update(mu_bar, Sig_bar, z, b)`` and ``reading(mu_bar, Sig_bar, b)`` of the
    course's EKF or UKF for a control ``c = [V, omega, dt]`` and a range to beacon ``b``; ``reading`` is the
    predicted range h(mu_bar) and its linearized innovation variance H Sig_bar H^T + Q."""
    online = scale == "online"
    g, G = _motion(online)
    residual, mean = _state_residual(online), _state_mean(online)

    def predict(mu, Sig, c):
        R = np.zeros((mu.size, mu.size))
        M_k = M if noise_per == "second" else M * abs(c[0]) / c[2]  # per metre: variance |d| s^2, d = V dt
        R[:3, :3] = process_noise_of_odometry(mu[:3], c[:2], c[2], M_k)  # the odometry noise, in the pose
        if filter == "ekf":
            return ekf_predict(mu, Sig, c, g, G, R)
        return ukf_predict(mu, Sig, c, g, R, UKF_LAM, residual, mean)

    def update(mu_bar, Sig_bar, z, b):
        h, H = _reading(online, scale, b)
        if filter == "ekf":
            mu, Sig = ekf_update(mu_bar, Sig_bar, z, h, H, Q)
        else:
            mu, Sig = ukf_update(mu_bar, Sig_bar, z, h, Q, UKF_LAM, None, None, residual)
        mu[2] = wrap_angle(mu[2])  # the update may push the heading past pi
        return mu, Sig

    def reading(mu_bar, Sig_bar, b):
        h, H = _reading(online, scale, b)
        H_t = H(mu_bar)
        return h(mu_bar)[0], (H_t @ Sig_bar @ H_t.T + Q)[0, 0]

    return predict, update, reading


def _state_residual(online: bool):
    """``a - b`` for states (or stacks of them): the heading wrapped, the scale a plain difference."""
    if not online:
        return pose_residual
    return lambda a, b: np.concatenate([pose_residual(a[..., :3], b[..., :3]), (a[..., 3:] - b[..., 3:])], axis=-1)


def _state_mean(online: bool):
    """The weighted mean of states, the heading on the circle (the scale, if any, a plain mean)."""
    if not online:
        return pose_mean
    return lambda X, w: np.append(pose_mean(X[:, :3], w), w @ X[:, 3])


def _motion(online: bool):
    """``g(x, c)`` and ``G(x, c)`` of the unicycle for a control ``c = [V, omega, dt]``; with the scale as a
    fourth state (``online``), the scale rides along unchanged: g = [unicycle(pose), s], G = diag(G_pose, 1)."""

    def g(x, c):  # one state, or the UKF's stack of sigma points
        pose = unicycle(x[..., :3], c[:2], c[2])
        return np.concatenate([pose, x[..., 3:]], axis=-1) if online else pose

    def G(x, c):
        J = np.eye(x.size)
        J[:3, :3] = unicycle_jacobian(x[:3], c[:2], c[2])
        return J

    return g, G


def _reading(online: bool, scale, b):
    """``h`` and ``H`` of a range to beacon ``b``: s r with the assumed scale, or with the estimated one."""
    if online:
        return (lambda x: scaled_range(x, b)), (lambda x: scaled_range_jacobian(x, b))
    return (lambda x: scale * range_only(x, b)), (lambda x: scale * range_only_jacobian(x, b))


def smoothed(run: RangeRun) -> RangeRun:
    """The run afterwards: :func:`~kfcourse.ekf_rts_smoother` over its predictions and estimates, the same
    record with the smoothed means and covariances as ``mu`` and ``Sig`` (and its error and NEES).
    Introduced in chapter 12."""
    if not isinstance(run, RangeRun) or run.filter != "ekf":
        got = f"a {run.filter.upper()} run" if isinstance(run, RangeRun) else type(run).__name__
        raise ValueError(f"run must be an EKF's RangeRun (range_localize), got {got}")
    online = run.scale == "online"
    _, G = _motion(online)
    mu_s, Sig_s = ekf_rts_smoother(run.mu, run.Sig, run.mu_bar, run.Sig_bar, G, run.controls, _state_residual(online))
    fields = {name: getattr(run, name) for name in run.__dataclass_fields__}
    fields.update(
        mu=mu_s,
        Sig=Sig_s,
        **against_truth(run.truth, mu_s, Sig_s),
    )
    return RangeRun(**fields)
