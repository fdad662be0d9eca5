"""CMU's Plaza logs: a real robot's wheel odometry and radio ranges to four beacons (chapter 12).

A robot drove a planar plaza carrying wheel odometry and a radio that ranges to four beacons at surveyed
positions; a survey-grade GPS and the robot's own fused estimate give the ground truth.  Two runs:

- ``"Plaza1"``: 9 657 odometry steps and 3 529 ranges over 1 933 s and 1.86 km;
- ``"Plaza2"``: 4 090 odometry steps and 1 816 ranges over 410 s and 1.35 km.

The data are those of J. Djugash, S. Singh, G. Kantor and W. Zhang, "Range-only SLAM for robots operating
cooperatively with sensor networks", IEEE International Conference on Robotics and Automation (ICRA), 2006.
They ship in the wheel of GTSAM (Georgia Tech Smoothing And Mapping, BSD licence) on PyPI, as
``gtsam/Data/Plaza1_.mat`` and ``Plaza2_.mat``; :func:`load_plaza` finds them through the package's installed
files and reads them with ``scipy.io.loadmat``, without importing gtsam's compiled module.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

import numpy as np

from .. import _validate as v
from ..models import unicycle, wrap_angle
from ..sim.records import Record

PLAZA_RUNS = ("Plaza1", "Plaza2")
GTSAM_VERSION = "4.3.0"  # the wheel the course pins: its Data/ holds both logs

# What the log's ground-truth angle means.  In Plaza1 it is the direction the robot drives in; in Plaza2 it
# points the other way: the direction of travel differs from it by pi at 99.7 % of the moving steps, and the
# log's own dead-reckoning start (``DRp``) is its angle plus pi.  The record's heading is the direction of
# travel in both runs: the log's angle plus this offset.
HEADING_OFFSET = {"Plaza1": 0.0, "Plaza2": math.pi}

NO_GTSAM = (
    "The Plaza logs come in the gtsam wheel: pip install gtsam=={version} (wheels for Linux and macOS, "
    "Python 3.11 to 3.13). There is no Windows wheel: on Windows, open the course on Binder or in WSL."
)


@dataclass(frozen=True)
class PlazaLog(Record):
    """One Plaza run, times in seconds from its first ground-truth pose.

    Odometry step ``k`` moves the robot from ``truth[k]`` to ``truth[k + 1]``: it drove ``distance[k]``
    and turned by ``turn[k]``.  A range ``range[i]`` to beacon ``beacon[i]`` (a row of ``beacons``) arrives
    at ``t_range[i]``, between odometry steps.
    """

    name: str  #: "Plaza1" or "Plaza2"
    t0: float  #: the log's clock at the first ground-truth pose (s)
    t_truth: np.ndarray  #: (K + 1,) time of each ground-truth pose (s)
    truth: np.ndarray  #: (K + 1, 3) ground-truth pose [x, y, heading] (m, m, rad), heading in (-pi, pi]
    t_odometry: np.ndarray  #: (K,) time at the end of each odometry step (s): t_truth[1:]
    distance: np.ndarray  #: (K,) distance driven in each odometry step (m)
    turn: np.ndarray  #: (K,) change of heading in each odometry step (rad)
    t_range: np.ndarray  #: (M,) time of each range, increasing (s)
    beacon: np.ndarray  #: (M,) which beacon each range is to: a row of ``beacons``
    range: np.ndarray  #: (M,) the radio's range (m)
    beacons: np.ndarray  #: (B, 2) beacon positions [x, y] (m)
    beacon_ids: np.ndarray  #: (B,) each beacon's id in the log

    @property
    def duration(self) -> float:
        """Length of the run (s)."""
        return float(self.t_truth[-1] - self.t_truth[0])

    @property
    def path_length(self) -> float:
        """Distance the robot drove, by its ground truth (m)."""
        return float(np.hypot(*np.diff(self.truth[:, :2], axis=0).T).sum())

    @property
    def dt(self) -> np.ndarray:
        """(K,) duration of each odometry step (s)."""
        return np.diff(self.t_truth)

    def controls(self) -> np.ndarray:
        """(K, 2) the odometry as the unicycle's controls ``[V, omega]`` (m/s, rad/s): each step's distance
        and turn over its duration, for :func:`~kfcourse.unicycle` with that step's ``dt``."""
        return np.column_stack([self.distance, self.turn]) / self.dt[:, None]

    def dead_reckoning(self, start=None, steps: int | None = None) -> np.ndarray:
        """(steps + 1, 3) the poses the odometry alone gives, step by step through :func:`~kfcourse.unicycle`
        (chapter 8's motion model), from ``start`` ``[x, y, heading]``, by default the true start, over the first
        ``steps`` odometry steps (by default all K)."""
        pose = self.truth[0] if start is None else v.vector(start, "start", 3)
        steps = self.step_count(steps)
        poses = [pose]
        for u, dt in zip(self.controls()[:steps], self.dt[:steps], strict=True):
            poses.append(unicycle(poses[-1], u, dt))
        return np.array(poses)

    def step_count(self, steps: int | None = None) -> int:
        """``steps``, checked as a count of this log's odometry steps (1 to K); None is all K of them."""
        K = len(self.distance)
        steps = K if steps is None else v.whole(steps, "steps", 1)
        if steps > K:
            raise ValueError(f"steps must be at most {K}, the log's odometry steps; got {steps}")
        return steps

    def range_steps(self, steps: int) -> tuple[np.ndarray, np.ndarray]:
        """The ranges a filter over the first ``steps`` odometry steps uses, and when: their indices (those that
        arrived by pose ``steps``), and for each the pose (1 to ``steps``) after whose prediction it is used,
        the first whose time is not before the range's."""
        ranges = np.flatnonzero(self.t_range <= self.t_truth[steps])
        return ranges, np.searchsorted(self.t_truth, self.t_range[ranges], side="left").clip(1, steps)

    def only(self, beacons) -> PlazaLog:
        """The same log with the ranges to ``beacons`` (rows of :attr:`beacons`) alone, the others left out: what a
        robot that hears fewer beacons would have had (none, ``[]``: a filter over it dead-reckons).  Introduced in
        chapter 12 (two beacons: a mirror image)."""
        rows = np.unique(v.vector(beacons, "beacons"))
        if not np.all((rows == np.round(rows)) & (rows >= 0) & (rows < len(self.beacons))):
            raise ValueError(f"beacons must be rows of the log's {len(self.beacons)} beacons, got {beacons!r}")
        keep = np.isin(self.beacon, rows.astype(int))
        fields = {name: getattr(self, name) for name in self.__dataclass_fields__}
        fields.update(t_range=self.t_range[keep], beacon=self.beacon[keep], range=self.range[keep])
        return PlazaLog(**fields)

    def mirrored_start(self, beacons) -> np.ndarray:
        """The true start reflected across the line through two beacons (rows of :attr:`beacons`): its position
        and its heading.  Two circles round those beacons meet there as well as at the start, so ranges to them
        alone cannot tell the two apart.  Introduced in chapter 12."""
        rows = v.vector(beacons, "beacons", 2)
        if not np.all((rows == np.round(rows)) & (rows >= 0) & (rows < len(self.beacons))) or rows[0] == rows[1]:
            raise ValueError(
                f"beacons must be two different rows of the log's {len(self.beacons)} beacons, got {beacons!r}"
            )
        a, b = self.beacons[rows.astype(int)]
        d = (b - a) / np.hypot(*(b - a))  # the line's direction
        p = self.truth[0, :2] - a
        position = a + 2.0 * (p @ d) * d - p  # p reflected: 2 (p . d) d - p, about a
        heading = 2.0 * np.arctan2(d[1], d[0]) - self.truth[0, 2]  # a direction reflected: 2 phi - theta
        return np.array([*position, wrap_angle(heading)])

    def true_distance(self) -> np.ndarray:
        """(M,) the true distance from the robot to the beacon of each range, the ground truth's position
        interpolated in time to the range's (m)."""
        x = np.interp(self.t_range, self.t_truth, self.truth[:, 0])
        y = np.interp(self.t_range, self.t_truth, self.truth[:, 1])
        b = self.beacons[self.beacon]
        return np.hypot(x - b[:, 0], y - b[:, 1])


def _data_file(name: str) -> Path:
    """Where the installed gtsam wheel keeps the log ``name``."""
    try:
        dist = metadata.distribution("gtsam")
    except metadata.PackageNotFoundError:
        raise ModuleNotFoundError(NO_GTSAM.format(version=GTSAM_VERSION), name="gtsam") from None
    path = Path(dist.locate_file(f"gtsam/Data/{name}_.mat"))
    if not path.is_file():
        raise FileNotFoundError(
            f"gtsam {dist.version} has no gtsam/Data/{name}_.mat; the course reads the logs of gtsam=={GTSAM_VERSION}"
        )
    return path


def _columns(mat: dict, key: str, width: int, name: str) -> np.ndarray:
    """The log's table ``key``, checked: a finite float array of ``width`` columns."""
    a = np.asarray(mat.get(key, np.empty((0, 0))), dtype=float)
    if a.ndim != 2 or a.shape[1] != width or a.shape[0] == 0 or not np.isfinite(a).all():
        raise ValueError(f"{name}_.mat: {key} must be a finite table of {width} columns, got shape {a.shape}")
    return a


def load_plaza(name: str = "Plaza1") -> PlazaLog:
    """Read one of CMU's Plaza logs from the installed gtsam wheel (chapter 12).

    The log's tables become the record's arrays: ``GT`` (time, x, y, angle) the ground truth, its angle turned
    to the direction of travel (:data:`HEADING_OFFSET`); ``DR`` (time, distance, change of heading) the
    odometry; ``TD`` (time, robot, beacon id, range) the ranges, sorted by time (Plaza1 stores two blocks out of
    order); ``TL`` (id, x, y) the beacons.  Introduced in chapter 12.

    Parameters
    ----------
    name : {"Plaza1", "Plaza2"}

    Returns
    -------
    PlazaLog

    Raises
    ------
    ModuleNotFoundError
        If gtsam is not installed (it has no Windows wheel: use Binder or WSL).
    """
    if not isinstance(name, str) or name not in PLAZA_RUNS:
        raise ValueError(f"name must be one of {PLAZA_RUNS}, got {name!r}")
    from scipy.io import loadmat  # only here: the rest of the course does not need scipy

    mat = loadmat(_data_file(name))
    GT, DR = _columns(mat, "GT", 4, name), _columns(mat, "DR", 3, name)
    TD, TL = _columns(mat, "TD", 4, name), _columns(mat, "TL", 3, name)
    if len(DR) != len(GT) - 1 or not np.array_equal(DR[:, 0], GT[1:, 0]):
        raise ValueError(f"{name}_.mat: DR must hold one odometry step between each two poses of GT")
    order = np.argsort(TD[:, 0], kind="stable")
    TD = TD[order]
    ids = TL[:, 0].astype(int)
    row = {beacon_id: i for i, beacon_id in enumerate(ids)}
    unknown = set(TD[:, 2].astype(int).tolist()) - set(row)
    if unknown:
        raise ValueError(f"{name}_.mat: TD ranges to beacons {sorted(unknown)} that TL does not place")
    t0 = float(GT[0, 0])
    return PlazaLog(
        name=name,
        t0=t0,
        t_truth=GT[:, 0] - t0,
        truth=np.column_stack([GT[:, 1], GT[:, 2], wrap_angle(GT[:, 3] + HEADING_OFFSET[name])]),
        t_odometry=DR[:, 0] - t0,
        distance=DR[:, 1],
        turn=DR[:, 2],
        t_range=TD[:, 0] - t0,
        beacon=np.array([row[int(i)] for i in TD[:, 2]]),
        range=TD[:, 3],
        beacons=TL[:, 1:3],
        beacon_ids=ids,
    )
