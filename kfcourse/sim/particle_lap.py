r"""A lap of chapter 11: the particle filter follows the robot round the capstone's loop, a cloud of weighted poses.

:func:`particle_loop` drives the robot of :func:`~kfcourse.sim.loop_world` round the map, draw for
draw the world of chapter 10's EKF and UKF for the same seed, and follows it with the steps of
:mod:`kfcourse.filters.particle`.  One step, with the chapter's equation numbers:

- predict: every particle moves with its own noisy copy of the odometry, (1)-(2);
- weight: by the likelihood of every reading in view, in log space, (3); no gate: a reading
  far from what the cloud expects drags no estimate through a gain, it only re-weighs the
  particles, and after a kidnap it is the reading that finds the robot.  With unlabelled
  readings, a reading may come from any landmark of the map, (3');
- normalise (4), and the effective sample size (5);
- resample (6) when :math:`N_{\text{eff}} < N/2`;
- injection (8), when asked for, just after resampling;
- the estimate (7), from the weighted cloud before resampling.

:func:`localized` says whether a run, of this filter or of any other, has found the robot.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.particle import (
    effective_sample_size,
    inject_random,
    normalise,
    pf_estimate,
    pf_predict,
    pf_weight,
    resample_multinomial,
    resample_stratified,
    resample_systematic,
)
from .capstone_world import SIG0, _noise_scale, filter_noise, loop_world
from .records import Record
from .scores import nees

RESAMPLERS = {
    "multinomial": resample_multinomial,
    "stratified": resample_stratified,
    "systematic": resample_systematic,
}
MAX_PARTICLES = 10_000  # the cloud of every step is kept: 10 000 particles for a lap is about 20 MB
LOCALIZED = 0.5  # m: a run is localized when its error stays under this over the last quarter lap
ALPHA_SLOW, ALPHA_FAST = 0.001, 0.1  # augmented MCL: how fast its long- and short-term averages follow
PF_STREAM = 11  # the filter's own draws come from default_rng([seed, PF_STREAM]), apart from the world's


@dataclass(frozen=True)
class ParticleRun(Record):
    """One drive round the loop and the particle filter that followed it; one row per step ``k = 0 .. T-1``.

    Step ``k``: the particles move with ``odometry[k]``, are weighed by the readings
    ``z[k, visible[k]]`` (``particles[k]``, ``w[k]``), give the estimate ``mu[k]``, ``Sig[k]``,
    and are then resampled if ``resampled[k]`` (and ``injected[k]`` of them replaced).
    """

    t: np.ndarray  #: (T,) time after each step (s)
    dt: float  #: time step (s)
    truth: np.ndarray  #: (T, 3) true pose [x, y, theta] after each step
    odometry: np.ndarray  #: (T, 2) the controls [V, omega] the filter is told
    landmarks: np.ndarray  #: (L, 2) the map (m)
    z: np.ndarray  #: (T, L, 2) readings [r, phi]; zeros where not visible
    visible: np.ndarray  #: (T, L) bool: the readings of step k, every one of them used
    start: np.ndarray  #: (3,) the true pose before the first step
    bounds: np.ndarray | None  #: (2, 2) [[x_min, x_max], [y_min, y_max]]: the map's box (global start, injection)
    starts: np.ndarray | None  #: (K, 3) the poses the cloud started around, each as likely; None: a global start
    particles: np.ndarray  #: (T, N, 3) float32: the cloud after the prediction of step k, as it was weighed
    w: np.ndarray  #: (T, N) float32: its normalised weights, before resampling
    ess: np.ndarray  #: (T,) effective sample size of w[k], from 1 to N
    resampled: np.ndarray  #: (T,) bool: the cloud was resampled after step k (ess[k] < N/2)
    injected: np.ndarray  #: (T,) how many particles were replaced by random poses after step k
    mu: np.ndarray  #: (T, 3) the cloud's weighted mean after step k
    Sig: np.ndarray  #: (T, 3, 3) its weighted covariance
    error: np.ndarray  #: (T,) distance between the estimated and the true position (m)
    inside: np.ndarray  #: (T,) bool: the true position lies inside the 3-sigma position ellipse
    nees: np.ndarray  #: (T,) position NEES e^T Sig_xy^-1 e
    n_particles: int  #: N
    resample: str  #: "multinomial", "stratified" or "systematic"
    global_start: bool  #: the cloud started uniform over the map's box and every heading
    labelled: bool  #: each reading came with its landmark (False: it may be any landmark of the map)
    kidnap: int | None  #: step at which the true robot was carried half a lap further on
    injection: float | str  #: share of the particles replaced after each resampling, or "augmented"
    dropout: tuple[int, int] | None  #: the sensor is blind for steps t0 <= k < t1
    motion_noise: float  #: scale of the odometry noise (the world's, and the filter's M)
    sensor_noise: float  #: scale of the reading noise (the world's, and the filter's Q)
    laps: int  #: times round the loop
    seed: int

    @property
    def share_inside(self) -> float:
        """Share of the steps with the truth inside the 3-sigma ellipse (0 to 1)."""
        return float(self.inside.mean())

    def localized(self, bound: float = LOCALIZED) -> bool:
        """Whether the error stays under ``bound`` (m) at every step of the last quarter lap: :func:`localized`."""
        return localized(self, bound)


def localized(run, bound: float = LOCALIZED) -> bool:
    """Whether a run has found the robot: its error stays under ``bound`` at every step of the last quarter lap.

    The same test for every filter: ``run`` is any run record with the error of each step,
    ``error`` (T,), and its times ``t``; where it has ``laps`` (a run of several laps), the
    quarter is a quarter of one lap.  Introduced in chapter 11.

    Parameters
    ----------
    run : ParticleRun or LoopRun
        A run of the loop.
    bound : float
        The largest error still localized (m), > 0; by default :data:`LOCALIZED`.

    Returns
    -------
    bool
    """
    if not (hasattr(run, "t") and hasattr(run, "error")):
        got = type(run).__name__
        raise ValueError(f"run must be a run record with t and error (a LoopRun or ParticleRun), got {got}")
    bound = v.positive(bound, "bound", "an error", "m")
    T = len(run.t)
    quarter = max(1, T // getattr(run, "laps", 1) // 4)  # steps in a quarter lap, at least the last one
    return bool((np.asarray(run.error)[T - quarter :] < bound).all())


def _map_box(landmarks: np.ndarray, setting: dict) -> np.ndarray | None:
    """The map's bounding box [[x_min, x_max], [y_min, y_max]], where a lost robot may be; None if it has no area,
    which a ``setting`` that needs the box (a global start, injection) may not have."""
    box = None
    if len(landmarks):
        box = np.stack([landmarks.min(axis=0), landmarks.max(axis=0)], axis=1)
        box = box if (box[:, 0] < box[:, 1]).all() else None
    if box is None and (setting["global_start"] or setting["injection"] == "augmented" or setting["injection"] > 0):
        raise ValueError("landmarks must span a box of some width and height for a global start or injection")
    return box


def particle_loop(
    seed: int = 0,
    *,
    n_particles: int = 2000,
    resample: str = "systematic",
    global_start: bool = False,
    starts=None,
    labelled: bool = True,
    kidnap: int | None = None,
    injection: float | str = 0.0,
    dropout=None,
    motion_noise: float = 1.0,
    sensor_noise: float = 1.0,
    laps: int = 1,
    landmarks=None,
    sensor_range: float = 4.0,
) -> ParticleRun:
    r"""Drive the loop of chapter 10 and follow the robot with a particle filter.

    The world is :func:`~kfcourse.sim.loop_world`'s for this seed, draw for draw: the truth, the odometry and the
    readings are those :func:`~kfcourse.sim.landmark_loop` gives the EKF and the UKF.  The filter's own draws (the
    start, the prediction's noise, resampling and injection) come from a second generator,
    ``np.random.default_rng([seed, PF_STREAM])``, so they leave the world's untouched.  Its M and Q are the world's.

    Each step (equations (1)-(8) of :mod:`kfcourse.filters.particle`, listed in this module's docstring): predict,
    weigh by all the readings in view, normalise, estimate, then resample if :math:`N_{\text{eff}} < N/2` (resampling
    nearly equal weights would only copy some particles and drop others at random, and lose variety for nothing) and,
    after resampling, replace ``injection`` of the particles by random poses.  Introduced in chapter 11.

    Parameters
    ----------
    seed : int
        Seed of the world's noise and of the filter's draws (>= 0).
    n_particles, resample : int, {"multinomial", "stratified", "systematic"}
        N, from 1 to :data:`MAX_PARTICLES`; the resampling scheme.
    global_start : bool
        False: the cloud starts at the true start, spread by :data:`~kfcourse.sim.capstone_world.SIG0` (as the EKF of
        chapter 10).  True: the start is unknown; the cloud starts uniform over the map's bounding box, any heading.
    starts : array_like, shape (K, 3), optional
        The poses the robot may have started from, each as likely (one of K docks): N particles split as evenly as
        possible among them, each group spread by :data:`~kfcourse.sim.capstone_world.SIG0` around its pose.  By
        default the true start alone.  Not with ``global_start``.
    labelled : bool
        True: each reading comes with the landmark it came from, equation (3).  False: a reading may come from any
        landmark of the map, equation (3').  On a map that looks the same from two poses the belief then has two
        equal peaks; the cloud keeps both only where it holds particles at both (``starts``), while a global start
        keeps one, by luck (chapter 11).
    kidnap : int, optional
        At this step the true robot is carried half a lap further on; the filter is not told.
    injection : float or "augmented"
        Share of the particles replaced by poses uniform over the map's box after each resampling, from 0 to 1; or
        ``"augmented"``, Thrun's augmented MCL: the share is :math:`\max(0, 1 - w_{\text{fast}} / w_{\text{slow}})`,
        where :math:`w_{\text{slow}}` and :math:`w_{\text{fast}}` follow the readings' average likelihood
        :math:`\sum_i w^{[i]} p(z \mid x^{[i]})` (per reading, so that one landmark more in view changes nothing) at
        the rates :data:`ALPHA_SLOW` and :data:`ALPHA_FAST`.  It injects when the readings suddenly fit the cloud
        worse than they used to: when the robot may be lost.
    dropout : (int, int), optional
        The sensor is blind for the steps ``t0 <= k < t1``.
    motion_noise, sensor_noise : float
        Scale of the odometry noise (0.1 m/s, 0.05 rad/s at 1) and the reading noise (0.1 m, 0.03 rad at 1), from
        0.01 to 100; the world's and the filter's alike.
    laps, landmarks, sensor_range : int, array_like (L, 2) or None, float
        Times round the loop (>= 1); the map (m), by default :data:`~kfcourse.sim.DEFAULT_LANDMARKS`; the largest
        range at which a landmark is seen (m, > 0).

    Returns
    -------
    ParticleRun
    """
    setting = _settings(
        seed, n_particles, resample, global_start, starts, labelled, injection, motion_noise, sensor_noise
    )
    drive = {"sensor_range": sensor_range, "laps": laps, "kidnap": kidnap, "dropout": dropout}
    world = loop_world(setting["seed"], setting["motion_noise"], setting["sensor_noise"], landmarks, **drive)
    box = _map_box(world.landmarks, setting)
    rng = np.random.default_rng([setting["seed"], PF_STREAM])
    setting["starts"], x = _start_cloud(world, setting, box, rng)
    lap = _follow_cloud(world, x, box, rng, setting)
    return _particle_run(world, box, lap, **setting, laps=int(laps))


def _settings(
    seed, n_particles, resample, global_start, starts, labelled, injection, motion_noise, sensor_noise
) -> dict:
    """The settings of :func:`particle_loop`, checked, by the names of :class:`ParticleRun`'s fields."""
    seed = v.whole(seed, "seed", 0)
    N = v.whole(n_particles, "n_particles", 1)
    if N > MAX_PARTICLES:
        raise ValueError(f"n_particles must be a whole number from 1 to {MAX_PARTICLES}, got {N}")
    if not isinstance(resample, str) or resample not in RESAMPLERS:
        raise ValueError(f"resample must be one of {tuple(RESAMPLERS)}, got {resample!r}")
    global_start = v.flag(global_start, "global_start")
    if starts is not None:
        if global_start:
            raise ValueError("starts must be None with global_start=True: a global start knows no poses")
        starts = v.matrix(starts, "starts", cols=3)
        if len(starts) == 0:
            raise ValueError("starts must hold at least one pose [x, y, theta], got none")
    labelled = v.flag(labelled, "labelled")
    augmented = isinstance(injection, str) and injection == "augmented"
    if isinstance(injection, bool | np.bool_) or (isinstance(injection, str) and not augmented):
        raise ValueError(f"injection must be a share from 0 to 1 or 'augmented', got {injection!r}")
    injection = injection if augmented else v.probability(injection, "injection")
    motion_noise = _noise_scale(motion_noise, "motion_noise")
    sensor_noise = _noise_scale(sensor_noise, "sensor_noise")
    return {
        "seed": seed,
        "n_particles": N,
        "resample": resample,
        "global_start": global_start,
        "starts": starts,
        "labelled": labelled,
        "injection": injection,
        "motion_noise": motion_noise,
        "sensor_noise": sensor_noise,
    }


def _start_cloud(world, setting: dict, box, rng) -> tuple[np.ndarray | None, np.ndarray]:
    """The poses the cloud starts around (None for a global start) and its N particles at the start, drawn from rng."""
    N, starts = setting["n_particles"], setting["starts"]
    if setting["global_start"]:  # the start unknown: anywhere in the map's box, any heading
        return None, inject_random(np.zeros((N, 3)), 1.0, box, rng)
    # one of K known poses (chapter 10's filters know the true one): N/K particles round each
    starts = world.start[None] if starts is None else starts
    K = len(starts)
    groups = np.repeat(starts, N // K + (np.arange(K) < N % K), axis=0)  # N rows, as even as can be
    return starts, groups + rng.multivariate_normal(np.zeros(3), SIG0, size=N)


def _follow_cloud(world, x: np.ndarray, box, rng, setting: dict) -> dict:
    """The particle filter's lap over ``world`` from the cloud ``x``: one step of equations (1)-(8) per step of the
    world (see the module's docstring); its arrays by the names of :class:`ParticleRun`'s fields."""
    N, labelled, injection = setting["n_particles"], setting["labelled"], setting["injection"]
    resampler, augmented = RESAMPLERS[setting["resample"]], injection == "augmented"
    M, Q = filter_noise(setting["motion_noise"], setting["sensor_noise"])  # the odometry noise, the reading noise
    T = len(world.t)
    cloud, weights = np.empty((T, N, 3), dtype=np.float32), np.empty((T, N), dtype=np.float32)
    ess, resampled, injected = np.empty(T), np.zeros(T, dtype=bool), np.zeros(T, dtype=int)
    mu, Sig = np.empty((T, 3)), np.empty((T, 3, 3))
    log_w = np.zeros(N)  # log-weights carried from step to step: all equal after resampling
    w_slow = w_fast = None  # augmented MCL: long- and short-term averages of how well the readings fit
    for k in range(T):
        x = pf_predict(x, world.odometry[k], world.dt, M, rng)  # (1)-(2)
        seen, before = world.visible[k], log_w
        marks = world.landmarks[seen] if labelled else world.landmarks  # each reading's landmark, or the whole map
        log_w = pf_weight(x, world.z[k, seen], marks, Q, log_w, labelled)  # (3), unlabelled (3')
        if augmented and seen.any():  # the readings' average likelihood sum_i w_i p(z | x_i), per reading
            fit = np.exp((np.logaddexp.reduce(log_w) - np.logaddexp.reduce(before)) / seen.sum())
            w_slow = fit if w_slow is None else w_slow + ALPHA_SLOW * (fit - w_slow)
            w_fast = fit if w_fast is None else w_fast + ALPHA_FAST * (fit - w_fast)
        w = normalise(log_w)  # (4)
        cloud[k], weights[k], ess[k] = x, w, effective_sample_size(w)  # (5)
        mu[k], Sig[k] = pf_estimate(x, w)  # (7)
        if ess[k] < N / 2:
            x, log_w, resampled[k] = x[resampler(w, rng)], np.zeros(N), True  # (6): every weight 1/N
            share = injection
            if augmented:  # the readings fit worse lately than in the long run: the robot may be lost
                share = min(1.0, max(0.0, 1.0 - w_fast / w_slow)) if w_slow else 0.0
            if share > 0:
                x, injected[k] = inject_random(x, share, box, rng), round(share * N)  # (8)
        else:
            log_w = log_w - log_w.max()  # keep the weights (the largest as 0, so the sum never drifts off)

    return {
        "particles": cloud,
        "w": weights,
        "ess": ess,
        "resampled": resampled,
        "injected": injected,
        "mu": mu,
        "Sig": Sig,
    }


def _particle_run(world, box, lap: dict, **setting) -> ParticleRun:
    """The record of one lap: the world, the cloud's lap (:func:`_follow_cloud`), the truth measured against it,
    and the settings."""
    mu, Sig = lap["mu"], lap["Sig"]
    err = world.truth[:, :2] - mu[:, :2]
    position_nees = nees(world.truth[:, :2], mu[:, :2], Sig[:, :2, :2])
    return ParticleRun(
        t=world.t,
        dt=world.dt,
        truth=world.truth,
        odometry=world.odometry,
        landmarks=world.landmarks,
        z=world.z,
        visible=world.visible,
        start=world.start,
        bounds=box,
        **lap,
        error=np.linalg.norm(err, axis=1),
        inside=position_nees <= 9.0,
        nees=position_nees,
        kidnap=world.kidnap,
        dropout=world.dropout,
        **setting,
    )
