r"""The particle filter of chapter 11 over a real robot's log (chapter 12): start from nowhere.

:func:`range_particles` follows a :class:`~kfcourse.data.PlazaLog` with the steps of
:mod:`kfcourse.filters.particle`, the same odometry steps and the same ranges as the EKF of
:func:`~kfcourse.sim.range_localize` (each range used after the prediction of the step it arrived in):

- predict: every particle moves by the unicycle with its own noisy copy of the step's odometry
  ``[V, omega]`` over the step's ``dt``, (1)-(2) (:func:`~kfcourse.pf_predict`);
- weight: by each range of the step, in log space, (3) for the range-only sensor (:func:`range_weight`);
- normalise (4) and the effective sample size (5); the estimate (7) from the weighted cloud;
- resample (6), systematic, when :math:`N_{\text{eff}} < N/2`.

Without a start the cloud starts uniform over the plaza (the beacons' box grown by :data:`MARGIN`) and
every heading: the filter does not know where the robot is, and the ranges find it.  The EKF from a wrong
start may instead settle on a mirror image of the path (on the Plaza logs, when it hears only two beacons).
The record, :class:`RangeParticleRun`, keeps the estimate of every step and the cloud itself only at a few
steps (:data:`KEEP`), for a picture.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .. import _validate as v
from ..filters.particle import (
    effective_sample_size,
    inject_random,
    normalise,
    pf_estimate,
    pf_predict,
    resample_systematic,
)
from ..models import range_only, wrap_angle
from .range_run import START_STD, AgainstTruth, against_truth, log_steps
from .records import Record

if TYPE_CHECKING:
    from ..data import PlazaLog

# The particle filter's noise: far wider than the EKF's data sheet (kf.sim.DATA_SHEET), as a particle filter's often
# is.  A cloud of a thousand poses over a plaza of 10 000 m^2 holds no particle within centimetres of the truth, and
# a few ranges leave only the handful of particles that happened to start near it, with their few headings.  The
# ranges say nothing of the heading until the robot drives, so the odometry noise must keep spreading the survivors
# over headings and positions (0.5 m/s, 0.3 rad/s) for one of them to fit the drive, and the range noise must let a
# particle a metre or two off keep some weight (2 m; the radio's own spread is about 0.55 m).  The price: once the
# robot is found the cloud is wider than its error (a position NEES well under 2), and without ranges it spreads
# fast: in Plaza1's 97 s without a range (from t = 947 s) the cloud grows to tens of metres and its mean drifts up
# to 15 m off, where the EKF dead-reckons to within 2 m.  The radio's scale is the one chapter 12 measured.
PF_NOISE = {"speed_std": 0.5, "turn_std": 0.3, "range_std": 2.0}  # m/s, rad/s, m
SCALE = 1.07  # the radio reads about 7 % long (chapter 12)
MARGIN = 20.0  # m: a lost robot may be anywhere in the beacons' box grown by this much on every side
FOUND = 5.0  # m: the robot is found once the estimate stays this close to the truth (a mirror is tens of m off)
KEEP = (0, 1, 10, 100, 1000)  # the steps whose cloud the record keeps, those the run reaches
MAX_PARTICLES = 10_000


@dataclass(frozen=True)
class RangeParticleRun(AgainstTruth, Record):
    """A particle filter over a log, measured against its ground truth.

    Rows ``k = 0 .. K`` are poses, as in :class:`~kfcourse.sim.RangeRun`: row 0 the start cloud, row k the cloud
    after odometry step k-1 and the ranges that arrived during it (the estimate before any resampling).
    """

    log: str  #: the log's name ("Plaza1", "Plaza2")
    t: np.ndarray  #: (K + 1,) time of each pose (s)
    truth: np.ndarray  #: (K + 1, 3) the log's ground truth [x, y, heading]
    mu: np.ndarray  #: (K + 1, 3) the cloud's weighted mean (:func:`~kfcourse.pf_estimate`)
    Sig: np.ndarray  #: (K + 1, 3, 3) its weighted covariance
    error: np.ndarray  #: (K + 1,) distance between the estimated and the true position (m)
    nees: np.ndarray  #: (K + 1,) position NEES (kf.sim.nees): 2 on average for an honest filter
    ess: np.ndarray  #: (K + 1,) effective sample size of the weights at each pose, from 1 to N
    readings: np.ndarray  #: (K + 1,) how many ranges weighed the cloud at each pose
    resampled: np.ndarray  #: (K + 1,) bool: the cloud was resampled after the pose (ess < N/2)
    beacons: np.ndarray  #: (B, 2) the beacons (m)
    box: np.ndarray  #: (2, 2) [[x_min, x_max], [y_min, y_max]]: the plaza a global start spreads over (m)
    start: np.ndarray | None  #: (3,) the pose the cloud started around, or None: a global start
    kept: np.ndarray  #: (S,) the steps whose cloud is kept
    particles: np.ndarray  #: (S, N, 3) float32: the cloud at each kept step, as it was weighed
    w: np.ndarray  #: (S, N) float32: its normalised weights
    n_particles: int  #: N
    seed: int  #: the seed of the filter's draws: np.random.default_rng(seed)
    speed_std: float  #: the speed noise the filter assumes (m/s)
    turn_std: float  #: the turn-rate noise it assumes (rad/s)
    range_std: float  #: the range noise it assumes (m)
    scale: float  #: the radio's scale it assumes

    def found(self, radius: float = FOUND) -> int | None:
        """The first pose from which the estimate stays within ``radius`` (m) of the true position to the end of
        the run, or None if it is not within it at the end."""
        radius = v.positive(radius, "radius", "a distance", "m")
        away = np.flatnonzero(self.error > radius)
        if away.size == 0:
            return 0
        return None if away[-1] == len(self.error) - 1 else int(away[-1] + 1)

    def summary(self, radius: float = FOUND) -> dict:
        """:class:`~kfcourse.sim.RangeRun`'s five figures over every pose (mean and 95th-percentile position
        error in m, share inside the 3-sigma ellipse, mean position NEES and its verdict), and the search:
        ``found``, the pose from which the robot stays found (:meth:`found`, None if never), ``found_after``
        the time it took (s, NaN if never), and ``error_after`` the mean error from then on (m, NaN if never)."""
        k = self.found(radius)
        return {
            **super().summary(),
            "found": k,
            "found_after": np.nan if k is None else float(self.t[k] - self.t[0]),
            "error_after": np.nan if k is None else float(self.error[k:].mean()),
        }


def range_weight(particles, z, beacon, scale: float, range_std: float, log_w) -> np.ndarray:
    r"""Weigh every particle by one range to a beacon, in log space: equation (3) for the range-only sensor.

    .. math:: \ell^{[i]} \leftarrow \ell^{[i]} + \log \mathcal N\big(z;\ s\,r(\bar x^{[i]}),\ \sigma_r^2\big)
              = \ell^{[i]} - \tfrac12 \Big(\frac{z - s\,r(\bar x^{[i]})}{\sigma_r}\Big)^2
                - \log\big(\sqrt{2\pi}\,\sigma_r\big)

    with ``r`` the range of :func:`~kfcourse.models.range_only` over the whole cloud at once and ``s`` the radio's
    scale.  :func:`~kfcourse.pf_weight` does the same for range-bearing readings.
    """
    nu = z - scale * range_only(particles, beacon)[:, 0]  # each particle's innovation: (N,)
    return log_w - 0.5 * (nu / range_std) ** 2 - np.log(np.sqrt(2.0 * np.pi) * range_std)


def _settings(log, n_particles, seed, speed_std, turn_std, range_std, scale, start, steps, keep) -> dict:
    """The settings of :func:`range_particles`, checked, by the names of :class:`RangeParticleRun`'s fields."""
    steps = log_steps(log, steps)
    N = v.whole(n_particles, "n_particles", 1)
    if N > MAX_PARTICLES:
        raise ValueError(f"n_particles must be a whole number from 1 to {MAX_PARTICLES}, got {N}")
    keep = KEEP if keep is None else keep
    if isinstance(keep, str) or np.ndim(keep) != 1 or not all(isinstance(k, int | np.integer) for k in keep):
        raise ValueError(f"keep must be a list of whole numbers of steps, got {keep!r}")
    if any(k < 0 for k in keep):
        raise ValueError(f"keep must hold steps >= 0, got {list(keep)}")
    return {
        "n_particles": N,
        "seed": v.whole(seed, "seed", 0),
        "speed_std": v.positive(speed_std, "speed_std", "a standard deviation", "m/s"),
        "turn_std": v.positive(turn_std, "turn_std", "a standard deviation", "rad/s"),
        "range_std": v.positive(range_std, "range_std", "a standard deviation", "m"),
        "scale": v.positive(scale, "scale", "a scale"),
        "start": None if start is None else v.vector(start, "start", 3),
        "steps": steps,
        "kept": np.unique([int(k) for k in keep if k <= steps]).astype(int),
    }


def plaza_box(log: PlazaLog) -> np.ndarray:
    """The plaza a lost robot may be in: the beacons' bounding box grown by :data:`MARGIN` on every side,
    [[x_min, x_max], [y_min, y_max]] (m)."""
    b = np.asarray(log.beacons, dtype=float)
    return np.stack([b.min(axis=0) - MARGIN, b.max(axis=0) + MARGIN], axis=1)


def range_particles(
    log: PlazaLog,
    *,
    n_particles: int = 1000,
    seed: int = 0,
    speed_std: float = PF_NOISE["speed_std"],
    turn_std: float = PF_NOISE["turn_std"],
    range_std: float = PF_NOISE["range_std"],
    scale: float = SCALE,
    start=None,
    steps: int | None = None,
    keep=None,
) -> RangeParticleRun:
    r"""Follow a real robot's log with the particle filter of chapter 11: odometry to move, ranges to weigh.

    Each odometry step (equations of :mod:`kfcourse.filters.particle`): every particle moves by the unicycle with
    its own draw of ``[V, omega]`` from :math:`\mathcal N(u, M)`, :math:`M = \mathrm{diag}(\sigma_V^2,
    \sigma_\omega^2)`, over the step's ``dt`` (1)-(2); each range that arrived during the step adds its
    log-likelihood :math:`\log \mathcal N(z; s\,r, \sigma_r^2)` (:func:`range_weight`), (3); the weights are
    normalised (4), the estimate and its covariance taken (7), and the cloud resampled, systematic (6), when
    :math:`N_{\text{eff}} < N/2` (5).  The draws come from ``np.random.default_rng(seed)``.  Introduced in
    chapter 12.

    Parameters
    ----------
    log : PlazaLog
        :func:`kfcourse.data.load_plaza`.
    n_particles : int
        N, from 1 to :data:`MAX_PARTICLES`.
    seed : int
        Seed of the filter's draws (>= 0): the start cloud, the odometry noise, resampling.
    speed_std, turn_std, range_std : float
        The noise the filter assumes: odometry speed (m/s), turn rate (rad/s), range (m); by default
        :data:`PF_NOISE`'s.
    scale : float
        The radio's scale the filter assumes; by default :data:`SCALE`, chapter 12's 1.07.
    start : array_like, shape (3,), optional
        A pose ``[x, y, heading]`` to start around (the cloud spread by the EKF's ``START_STD``); by default none:
        a global start, the cloud uniform over :func:`plaza_box` and every heading.
    steps : int, optional
        Follow only the first ``steps`` odometry steps (>= 1); by default the whole log.
    keep : list of int, optional
        The steps whose cloud the record keeps (those beyond ``steps`` are dropped); by default :data:`KEEP`.

    Returns
    -------
    RangeParticleRun
    """
    s = _settings(log, n_particles, seed, speed_std, turn_std, range_std, scale, start, steps, keep)
    N, steps = s["n_particles"], s.pop("steps")
    rng = np.random.default_rng(s["seed"])
    box = plaza_box(log)
    if s["start"] is None:  # nowhere known: anywhere in the plaza, any heading
        x = inject_random(np.zeros((N, 3)), 1.0, box, rng)
    else:
        x = s["start"] + rng.normal(0.0, START_STD, size=(N, 3))
        x[:, 2] = wrap_angle(x[:, 2])
    track = _follow(log, steps, x, rng, s)
    truth, mu, Sig = log.truth[: steps + 1], track.pop("mu"), track.pop("Sig")
    return RangeParticleRun(
        log=log.name,
        t=log.t_truth[: steps + 1],
        truth=truth,
        mu=mu,
        Sig=Sig,
        **against_truth(truth, mu, Sig),
        beacons=log.beacons,
        box=box,
        **track,
        **s,
    )


def _follow(log, steps: int, x: np.ndarray, rng, s: dict) -> dict:
    """The particle filter over the first ``steps`` odometry steps of ``log`` from the cloud ``x``: at each step,
    predict with the odometry, weigh by every range of the step, estimate, and resample if the weights ask for it;
    its arrays by the names of :class:`RangeParticleRun`'s fields."""
    N, kept = s["n_particles"], s["kept"]
    M = np.diag([s["speed_std"] ** 2, s["turn_std"] ** 2])
    controls, dt = log.controls()[:steps], log.dt[:steps]
    ranges, step = log.range_steps(steps)  # the ranges of these steps, used as range_localize uses them
    first = np.searchsorted(step, np.arange(steps + 2))  # ranges first[k] .. first[k + 1] - 1 belong to step k
    mu, Sig = np.empty((steps + 1, 3)), np.empty((steps + 1, 3, 3))
    ess, resampled = np.full(steps + 1, float(N)), np.zeros(steps + 1, dtype=bool)
    clouds, weights = np.empty((kept.size, N, 3), np.float32), np.empty((kept.size, N), np.float32)
    log_w, w, n_eff = np.zeros(N), np.full(N, 1.0 / N), float(N)
    for k in range(steps + 1):
        if k > 0:
            x = pf_predict(x, controls[k - 1], dt[k - 1], M, rng)  # (1)-(2)
        for i in ranges[first[k] : first[k + 1]]:  # (3) every range of the step
            log_w = range_weight(x, log.range[i], log.beacons[log.beacon[i]], s["scale"], s["range_std"], log_w)
        if first[k + 1] > first[k]:  # the weights changed (else w and its N_eff are the last step's)
            w = normalise(log_w)  # (4)
            n_eff = effective_sample_size(w)  # (5)
        ess[k] = n_eff
        mu[k], Sig[k] = pf_estimate(x, w)  # (7)
        if k in kept:
            row = np.searchsorted(kept, k)
            clouds[row], weights[row] = x, w
        if ess[k] < N / 2:
            x, resampled[k] = x[resample_systematic(w, rng)], True  # (6): every weight 1/N
            log_w, w, n_eff = np.zeros(N), np.full(N, 1.0 / N), float(N)
        else:
            log_w = log_w - log_w.max()  # keep the weights (the largest as 0, so the sum never drifts off)
    readings = np.diff(first)[: steps + 1]
    return {"mu": mu, "Sig": Sig, "ess": ess, "readings": readings, "resampled": resampled, "particles": clouds,
            "w": weights}  # fmt: skip
