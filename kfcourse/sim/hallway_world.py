"""A hallway of cells with doors, for the histogram filter (chapter 1).

The chapter's hallway is a loop corridor of ``N_CELLS`` cells with doors on both
sides.  The robot is told "move one cell right" before every look; it obeys with
the motion reliability and otherwise stalls.  Its door sensor looks at both walls
of the cell it is in and reports, for each side, door or no door; each report is
right with the sensor reliability.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.bayes import BOUNDARIES, bayes_predict, bayes_update
from .records import Record

N_CELLS = 12
LEFT_DOORS = (0, 3, 5, 8, 10)  #: cells with a door on the robot's left (drawn on the upper wall)
RIGHT_DOORS = (0, 2, 4, 6, 9, 10)  #: cells with a door on the robot's right (drawn on the lower wall)
MOTION_RELIABILITY = 0.9  #: the chapter's default: one cell right 90 % of the time, else a stall
SENSOR_RELIABILITY = 0.95  #: the chapter's default: each side read right 95 % of the time
BOUNDARY = "wrap"  #: the chapter's default: a loop corridor, no end walls


def hallway_doors(n_cells: int = N_CELLS, left=LEFT_DOORS, right=RIGHT_DOORS) -> np.ndarray:
    """The door map: ``doors[0, i]`` is a door on the left of cell ``i``, ``doors[1, i]`` on its right.

    Introduced in chapter 1.

    Returns
    -------
    ndarray of bool, shape (2, n_cells)
    """
    n = v.whole(n_cells, "n_cells", 1)
    doors = np.zeros((2, n), bool)
    for side, (name, cells) in enumerate((("left", left), ("right", right))):
        idx = v.vector(cells, name)
        if not ((idx == np.round(idx)) & (idx >= 0) & (idx < n)).all():
            raise ValueError(f"{name} must hold door cells, whole numbers in 0..{n - 1}, got {cells!r}")
        doors[side, idx.astype(int)] = True
    return doors


def _door_map(doors) -> np.ndarray:
    """A checked door map: one wall (n_cells,) or one row per wall (2, n_cells), True where there is a door."""
    is_door = v.flags(doors, "doors")
    if is_door.ndim not in (1, 2) or is_door.shape[-1] == 0:
        raise ValueError(f"doors must have shape (n_cells,) or (2, n_cells), a door map; got {is_door.shape}")
    return is_door


def _inside(cell: int, n_cells: int) -> int:
    """``cell``, a whole number >= 0, if the hallway of ``n_cells`` has it."""
    if cell >= n_cells:
        raise ValueError(f"cell must be a cell of the hallway, 0 to {n_cells - 1}, got {cell}")
    return cell


def motion_kernel(reliability: float) -> dict[int, float]:
    """Kernel for "move one cell right": lands one cell right with ``reliability``, else stalls.

    The same kind of motion model as the chapter's hand calculation, ``{1: 0.8, 0: 0.2}``.
    """
    p = v.probability(reliability, "reliability")
    return {1: p, 0: 1.0 - p}


def move(cell: int, kernel: dict[int, float], rng: np.random.Generator, n_cells: int, boundary: str = "wall") -> int:
    """Sample where the true robot lands after one commanded move."""
    cell = v.whole(cell, "cell")
    k = v.kernel(kernel, "kernel")
    rng = v.generator(rng, "rng")
    n_cells = v.whole(n_cells, "n_cells", 1)
    cell = _inside(cell, n_cells)
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}, got {boundary!r}")
    offsets = list(k)
    step = offsets[rng.choice(len(offsets), p=np.array(list(k.values())) / sum(k.values()))]
    dst = cell + step
    return int(dst % n_cells if boundary == "wrap" else min(max(dst, 0), n_cells - 1))


def read_door(cell: int, doors, reliability: float, rng: np.random.Generator):
    """The door sensor: reports the truth (door or no door) with ``reliability``.

    With ``doors`` of shape ``(n_cells,)`` it returns one bool; with a door map of
    shape ``(2, n_cells)`` (left and right wall) it reads each side in turn and
    returns an array of two bools.
    """
    cell = v.whole(cell, "cell")
    is_door = _door_map(doors)
    cell = _inside(cell, is_door.shape[-1])
    p = v.probability(reliability, "reliability")
    rng = v.generator(rng, "rng")
    if is_door.ndim == 1:
        truth = bool(is_door[cell])
        return truth if rng.random() < p else not truth
    truth = is_door[:, cell]
    right = np.array([rng.random() < p for _ in truth])  # one independent look per side
    return np.where(right, truth, ~truth)


def door_likelihood(doors, saw_door, reliability: float) -> np.ndarray:
    r"""Measurement model :math:`p(z \mid x)` of the door sensor for every cell.

    ``reliability`` where the cell agrees with the reading, ``1 - reliability``
    where it does not: the likelihood peaks at every cell that fits the reading.
    With a door map of shape ``(2, n_cells)`` the reading is a pair (left, right);
    the two looks are independent, so their likelihoods multiply.
    Introduced in chapter 1.

    Returns
    -------
    ndarray, shape (n_cells,)
    """
    is_door = _door_map(doors)
    saw = v.flags(saw_door, "saw_door")
    p = v.probability(reliability, "reliability")
    if is_door.ndim == 1:
        if saw.size != 1:
            raise ValueError(f"saw_door must be one reading, True or False, for the door map of one wall; got {saw!r}")
        return np.where(is_door == bool(saw), p, 1.0 - p)
    if saw.shape != is_door.shape[:1]:
        raise ValueError(f"saw_door must hold one reading per side ({is_door.shape[0]}), got {saw_door!r}")
    return np.prod(np.where(is_door == saw[:, None], p, 1.0 - p), axis=0)  # p(z_left | x) * p(z_right | x)


def start_cell(rng: np.random.Generator, n_cells: int = N_CELLS) -> int:
    """Where the true robot starts: any cell, equally likely (the filter is not told)."""
    rng = v.generator(rng, "rng")
    return int(rng.integers(v.whole(n_cells, "n_cells", 1)))


def peak_cells(histogram) -> np.ndarray:
    """The cells where a histogram over the hallway peaks: every cell within rounding (a relative
    1e-9) of the tallest.  A mirrored or flat belief peaks on several cells, and the first of them
    is no likelier than the others.

    Parameters
    ----------
    histogram : array_like, shape (n_cells,)
        A belief or a particle histogram: probabilities summing to 1.

    Returns
    -------
    np.ndarray of int, in increasing order
    """
    p = v.probabilities(histogram, "histogram")
    return np.flatnonzero(np.isclose(p, p.max(), rtol=1e-9, atol=0.0))


@dataclass(frozen=True)
class HallwayRun(Record):
    """One run of the hallway filter: a first look, then ``n_cycles`` of predict and update.

    Row ``k`` of every array is the state after the ``k``-th update (row 0: the first look).
    """

    doors: np.ndarray  #: (2, n_cells) bool, the door map
    true_cell: np.ndarray  #: (n_cycles + 1,) int, where the robot really is
    saw_door: np.ndarray  #: (n_cycles + 1, 2) bool, each reading (left, right)
    belief: np.ndarray  #: (n_cycles + 1, n_cells), bel(x) after each update
    motion_reliability: float
    sensor_reliability: float
    boundary: str
    seed: int

    def peak_on_truth(self) -> np.ndarray:
        """``(n_cycles + 1,)`` bool: is the tallest bar on the true cell after each update?"""
        return self.belief.argmax(axis=1) == self.true_cell


def simulate_hallway(
    n_cycles: int = 10,
    motion_reliability: float = MOTION_RELIABILITY,
    sensor_reliability: float = SENSOR_RELIABILITY,
    boundary: str = BOUNDARY,
    doors=None,
    seed: int = 0,
) -> HallwayRun:
    """Run the histogram filter in the hallway, the way the chapter's demo does when you alternate
    Predict and Update.

    The robot starts in a random cell (:func:`start_cell`) with a flat belief and takes a first look.
    Each cycle it is told "one cell right": the truth moves (:func:`move`), the belief is pushed
    through :func:`motion_kernel` (:func:`~kfcourse.filters.bayes.bayes_predict`), the sensor reads
    both walls (:func:`read_door`) and Bayes' rule folds the reading in
    (:func:`~kfcourse.filters.bayes.bayes_update`).  Introduced in chapter 1.

    Parameters
    ----------
    n_cycles : int
        Predict/update cycles after the first look (>= 0).
    motion_reliability, sensor_reliability : float
        Probabilities in [0, 1].
    boundary : {"wall", "wrap"}
    doors : array_like of bool, shape (2, n_cells), optional
        The door map; :func:`hallway_doors` by default.
    seed : int

    Returns
    -------
    HallwayRun
    """
    seed = v.whole(seed, "seed", 0)
    n_cycles = v.whole(n_cycles, "n_cycles", 0)
    pm = v.probability(motion_reliability, "motion_reliability")
    ps = v.probability(sensor_reliability, "sensor_reliability")
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}, got {boundary!r}")
    door_map = hallway_doors() if doors is None else _door_map(doors)
    if door_map.ndim != 2 or door_map.shape[0] != 2:
        raise ValueError(f"doors must have shape (2, n_cells), got {door_map.shape}")
    n = door_map.shape[1]
    rng = np.random.default_rng(seed)
    kernel = motion_kernel(pm)
    cell = start_cell(rng, n)
    belief = np.full(n, 1.0 / n)  # the robot knows nothing yet
    cells, readings, beliefs = [], [], []
    for k in range(n_cycles + 1):
        if k > 0:
            cell = move(cell, kernel, rng, n, boundary)  # the truth moves ...
            belief = bayes_predict(belief, kernel, boundary)  # ... and the belief follows: shift and blur
        saw = read_door(cell, door_map, ps, rng)
        belief = bayes_update(belief, door_likelihood(door_map, saw, ps))  # multiply and renormalise
        cells.append(cell)
        readings.append(saw)
        beliefs.append(belief)
    return HallwayRun(
        door_map, np.array(cells, dtype=int), np.array(readings), np.array(beliefs, dtype=float), pm, ps, boundary, seed
    )
