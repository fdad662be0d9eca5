"""GTSAM's batch solution over a real robot's log (chapter 12): the whole run as one factor graph.

:func:`factor_graph` puts every pose of a :class:`~kfcourse.data.PlazaLog` into one nonlinear least-squares problem
and solves it at once, with GTSAM (Georgia Tech Smoothing And Mapping): a prior on the first pose, one
odometry factor between each two poses, one range factor per range, and Levenberg–Marquardt over them all.  It
is what the RTS smoother of :mod:`~kfcourse.sim.range_run` computes by linearising once along the filter's path,
but relinearised until it settles, and with a robust loss on the ranges if asked: the door to SLAM, where the
beacons would be unknowns too.  The record, :class:`FactorGraphRun`, measures the solution against the log's
ground truth, as :class:`~kfcourse.sim.RangeRun` measures the filter.

GTSAM's compiled module is imported only when the function runs: the rest of the course never needs it.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .. import _validate as v
from .range_run import DATA_SHEET, START_STD, AgainstTruth, against_truth, log_steps
from .records import Record

if TYPE_CHECKING:
    from ..data import PlazaLog

# The odometry's noise per second of a step, in the robot's frame: along its heading and across it (m/s), and in
# its turn (rad/s).  Along and turn are the data sheet's speed and turn-rate noise, as the EKF is told; across, as
# much as along (the EKF's motion model has none: a graph's odometry factor needs some in every direction).
ODOMETRY_STD = (DATA_SHEET["speed_std"], DATA_SHEET["speed_std"], DATA_SHEET["turn_std"])
HUBER_K = 1.345  # the robust loss: squared within k standard deviations of a range, linear beyond (Huber)
BEACON_STD = 1e-3  # the beacons are GTSAM variables held at their surveyed positions by priors this tight (m)


@dataclass(frozen=True)
class FactorGraphRun(AgainstTruth, Record):
    """GTSAM's batch solution over a log, measured against its ground truth.

    Rows ``k = 0 .. K`` are poses as in :class:`~kfcourse.sim.RangeRun`: row 0 the start, row k after odometry
    step k-1.  Ranges ``i = 0 .. M-1`` are the log's, in time order, each a factor on the pose ``step[i]``.
    """

    log: str  #: the log's name ("Plaza1", "Plaza2")
    t: np.ndarray  #: (K + 1,) time of each pose (s)
    truth: np.ndarray  #: (K + 1, 3) the log's ground truth [x, y, heading]
    mu: np.ndarray  #: (K + 1, 3) the solution: the pose of each row
    Sig: np.ndarray  #: (K + 1, 3, 3) its marginal covariance, in the world's axes (x, y, heading)
    step: np.ndarray  #: (M,) the pose row each range is a factor on
    beacon: np.ndarray  #: (M,) the beacon of each range (a row of ``beacons``)
    z: np.ndarray  #: (M,) the range read (m)
    distance: np.ndarray  #: (M,) the distance from the solution's pose to the beacon (m)
    beacons: np.ndarray  #: (B, 2) the beacons (m)
    error: np.ndarray  #: (K + 1,) distance between the solution's and the true position (m)
    nees: np.ndarray  #: (K + 1,) position NEES: 2 on average when the covariance is honest
    iterations: int  #: Levenberg–Marquardt's iterations
    initial_error: float  #: the graph's error at the initial values: half the sum of squared whitened residuals
    final_error: float  #: the graph's error at the solution
    seconds: float  #: wall time to build the graph, solve it and compute the covariances (s)
    scale: float  #: the radio's scale assumed: each range is divided by it
    range_std: float  #: the range noise assumed (m)
    odometry_std: tuple  #: the odometry noise assumed per second: along, across (m/s), turn (rad/s)
    robust: bool  #: whether the ranges had Huber's robust loss (:data:`HUBER_K`)

    @property
    def residual(self) -> np.ndarray:
        """(M,) each range over the scale, minus the distance at the solution (m)."""
        return self.z / self.scale - self.distance


def _settings(log, scale, range_std, odometry_std, robust, steps, initial) -> tuple:
    steps = log_steps(log, steps)
    scale = v.positive(scale, "scale", "a scale")
    range_std = v.positive(range_std, "range_std", "a standard deviation", "m")
    odometry_std = v.vector(odometry_std, "odometry_std", 3)
    if not np.all(odometry_std > 0):
        raise ValueError(f"odometry_std must be standard deviations > 0 (m/s, m/s, rad/s), got {odometry_std}")
    robust = v.flag(robust, "robust")
    if initial is not None:
        initial = v.matrix(initial, "initial")
        if initial.shape[0] < steps + 1 or initial.shape[1] != 3:
            raise ValueError(
                f"initial must have shape (n, 3), a pose [x, y, heading] for each of at least the {steps + 1} "
                f"rows, got {initial.shape}"
            )
    return scale, range_std, tuple(odometry_std.tolist()), robust, steps, initial


def _gtsam():
    """GTSAM's module, or the course's message on how to install it."""
    from ..data.plaza import GTSAM_VERSION, NO_GTSAM

    try:
        import gtsam
    except ImportError:
        raise ModuleNotFoundError(NO_GTSAM.format(version=GTSAM_VERSION), name="gtsam") from None
    return gtsam


def factor_graph(
    log: PlazaLog,
    *,
    scale: float = 1.07,
    range_std: float = DATA_SHEET["range_std"],
    odometry_std=ODOMETRY_STD,
    robust: bool = True,
    steps: int | None = None,
    initial=None,
) -> FactorGraphRun:
    r"""GTSAM's batch solution over a real robot's log: every pose at once, as a factor graph.

    The graph has one ``Pose2`` variable per row of the log (``steps + 1`` of them) and these factors:

    - a prior on the first pose: the true start, with the EKF's doubt :data:`~kfcourse.sim.range_run.START_STD`;
    - per odometry step, a ``BetweenFactorPose2``: the step's motion seen from the pose it starts at, the chord
      of :func:`~kfcourse.unicycle` (length :math:`d\,\mathrm{sinc}(\Delta\theta/2)` at angle
      :math:`\Delta\theta/2`, then the turn :math:`\Delta\theta`), so that composing the steps is the log's
      dead reckoning; its standard deviations ``odometry_std`` times the step's duration;
    - per range, a ``RangeFactor2D`` from the pose at or after it in time (where
      :func:`~kfcourse.sim.range_localize` uses it) to its beacon, a ``Point2`` held at its surveyed position by a
      prior of :data:`BEACON_STD`: the range over ``scale``, with standard deviation ``range_std / scale`` (the
      EKF's :math:`z = s\,\lVert p - b\rVert + v` divided by s); if ``robust``, under Huber's loss (:data:`HUBER_K`).

    Levenberg–Marquardt (GTSAM's defaults) starts from the dead reckoning, or from ``initial``, and GTSAM's
    ``Marginals`` give each pose's covariance, turned from the pose's own axes into the world's.  The whole run
    takes about 2 s on Plaza2 and 3 s on Plaza1.  Introduced in chapter 12.

    Parameters
    ----------
    log : PlazaLog
        :func:`kfcourse.data.load_plaza`.
    scale, range_std : float
        The radio's scale (> 0: a range reads ``scale`` times the distance) and noise (m, :data:`DATA_SHEET`'s).
    odometry_std : array_like, shape (3,)
        The odometry noise per second of a step, along the heading and across it (m/s), and in the turn (rad/s):
        :data:`ODOMETRY_STD`.
    robust : bool
        Huber's loss on the ranges, or (``False``) plain least squares.
    steps : int, optional
        Only the first ``steps`` odometry steps (>= 1) and the ranges up to them; by default the whole log.
    initial : array_like, shape (n, 3), optional
        Where the optimiser starts, a pose per row (its first ``steps + 1`` used), e.g. an EKF's ``mu``; by
        default the log's dead reckoning.

    Returns
    -------
    FactorGraphRun
    """
    scale, range_std, odometry_std, robust, steps, initial = _settings(
        log, scale, range_std, odometry_std, robust, steps, initial
    )
    gtsam = _gtsam()
    start = time.perf_counter()
    found = _solve(gtsam, log, steps, initial, scale, range_std, odometry_std, robust)
    seconds = time.perf_counter() - start
    mu, Sig, step, ranges = found["mu"], found["Sig"], found["step"], found["ranges"]
    truth, b = log.truth[: steps + 1], log.beacons[log.beacon[ranges]]
    return FactorGraphRun(
        log=log.name,
        t=log.t_truth[: steps + 1],
        truth=truth,
        mu=mu,
        Sig=Sig,
        step=step,
        beacon=log.beacon[ranges],
        z=log.range[ranges],
        distance=np.hypot(*(mu[step, :2] - b).T),
        beacons=log.beacons,
        **against_truth(truth, mu, Sig),
        iterations=found["iterations"],
        initial_error=found["initial_error"],
        final_error=found["final_error"],
        seconds=seconds,
        scale=scale,
        range_std=range_std,
        odometry_std=odometry_std,
        robust=robust,
    )


def _solve(gtsam, log, steps: int, initial, *settings) -> dict:
    """Build the graph of the first ``steps`` odometry steps of ``log`` (``settings``: scale, range_std,
    odometry_std, robust), solve it with Levenberg–Marquardt from ``initial`` or the dead reckoning, and compute
    the covariances: the solution, which ranges it used and on which pose, and how the optimiser went."""
    ranges, step = log.range_steps(steps)  # the ranges of these steps, on the poses range_localize uses them at
    graph = _graph(gtsam, log, steps, ranges, step, *settings)
    poses = log.dead_reckoning(steps=steps) if initial is None else initial[: steps + 1]
    values = _initial_values(gtsam, poses, log.beacons)
    optimizer = gtsam.LevenbergMarquardtOptimizer(graph, values, gtsam.LevenbergMarquardtParams())
    solution = optimizer.optimize()
    mu = gtsam.utilities.extractPose2(solution)  # (steps + 1, 3) in key order: the rows
    return {"mu": mu, "Sig": _covariances(gtsam, graph, solution, mu), "ranges": ranges, "step": step,
            "iterations": int(optimizer.iterations()), "initial_error": float(graph.error(values)),
            "final_error": float(graph.error(solution))}  # fmt: skip


def _graph(gtsam, log, steps: int, ranges, step, scale: float, range_std: float, odometry_std: tuple, robust: bool):
    """The factor graph of the first ``steps`` odometry steps of ``log`` and of its ``ranges``, each a factor on
    the pose row ``step`` of it: the prior on the start, the odometry, the beacons' priors, the ranges."""
    X, L = gtsam.symbol_shorthand.X, gtsam.symbol_shorthand.L  # pose k is X(k), beacon j is L(j)
    graph = gtsam.NonlinearFactorGraph()
    graph.add(gtsam.PriorFactorPose2(X(0), gtsam.Pose2(*log.truth[0]), gtsam.noiseModel.Diagonal.Sigmas(START_STD)))
    d, turn, dt = log.distance[:steps], log.turn[:steps], log.dt[:steps]
    chord = d * np.sinc(turn / (2 * np.pi))  # the unicycle's chord: d sin(turn / 2) / (turn / 2)
    sigmas = np.outer(dt, odometry_std)  # (steps, 3): the noise of each step grows with its duration
    for k in range(steps):
        moved = gtsam.Pose2(chord[k] * np.cos(turn[k] / 2), chord[k] * np.sin(turn[k] / 2), turn[k])
        graph.add(gtsam.BetweenFactorPose2(X(k), X(k + 1), moved, gtsam.noiseModel.Diagonal.Sigmas(sigmas[k])))
    held = gtsam.noiseModel.Isotropic.Sigma(2, BEACON_STD)
    for j, b in enumerate(log.beacons):
        graph.add(gtsam.PriorFactorPoint2(L(j), b, held))
    noise = gtsam.noiseModel.Isotropic.Sigma(1, range_std / scale)
    if robust:
        noise = gtsam.noiseModel.Robust.Create(gtsam.noiseModel.mEstimator.Huber.Create(HUBER_K), noise)
    for i, k in zip(ranges.tolist(), step.tolist(), strict=True):
        graph.add(gtsam.RangeFactor2D(X(k), L(int(log.beacon[i])), float(log.range[i] / scale), noise))
    return graph


def _initial_values(gtsam, poses: np.ndarray, beacons: np.ndarray):
    """GTSAM's ``Values`` to start from: pose k at ``poses[k]``, beacon j at ``beacons[j]``."""
    X, L = gtsam.symbol_shorthand.X, gtsam.symbol_shorthand.L
    values = gtsam.Values()
    for k, pose in enumerate(poses.tolist()):
        values.insert(X(k), gtsam.Pose2(*pose))
    for j, b in enumerate(beacons):
        values.insert(L(j), np.asarray(b, dtype=float))
    return values


def _covariances(gtsam, graph, solution, mu: np.ndarray) -> np.ndarray:
    """(K + 1, 3, 3) each pose's marginal covariance, in the world's axes.

    GTSAM gives a ``Pose2``'s covariance in the pose's own axes (forward, left, heading): a perturbation of
    the pose is composed on its right.  Turned by the heading, ``J Σ J^T`` with ``J = diag(R(θ), 1)``, it is
    in the world's (x, y, heading), as the EKF's.  About half a second for Plaza2's 4 091 poses.
    """
    X = gtsam.symbol_shorthand.X
    marginals = gtsam.Marginals(graph, solution)
    local = np.array([marginals.marginalCovariance(X(k)) for k in range(len(mu))])
    c, s = np.cos(mu[:, 2]), np.sin(mu[:, 2])
    J = np.zeros_like(local)
    J[:, 0, 0], J[:, 0, 1], J[:, 1, 0], J[:, 1, 1], J[:, 2, 2] = c, -s, s, c, 1.0
    return J @ local @ J.transpose(0, 2, 1)
