"""A hallway of cells with doors, for the histogram filter (chapter 1)."""

from __future__ import annotations

import numpy as np

from .. import _validate as v
from ..filters.bayes import BOUNDARIES


def motion_kernel(reliability: float) -> dict[int, float]:
    """Kernel for "move one cell right": lands right with ``reliability``, else
    stalls or overshoots by one, each half the remaining probability."""
    p = v.probability(reliability, "reliability")
    return {1: p, 0: (1 - p) / 2, 2: (1 - p) / 2}


def move(cell: int, kernel: dict[int, float], rng: np.random.Generator, n_cells: int, boundary: str = "wall") -> int:
    """Sample where the true robot lands after one commanded move."""
    k = v.kernel(kernel, "kernel")
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}, got {boundary!r}")
    offsets = list(k)
    step = offsets[rng.choice(len(offsets), p=np.array(list(k.values())) / sum(k.values()))]
    dst = cell + step
    return int(dst % n_cells if boundary == "wrap" else min(max(dst, 0), n_cells - 1))


def read_door(cell: int, doors, reliability: float, rng: np.random.Generator) -> bool:
    """The door sensor: reports the truth (door or no door) with ``reliability``."""
    p = v.probability(reliability, "reliability")
    truth = bool(np.asarray(doors, bool)[cell])
    return truth if rng.random() < p else not truth


def door_likelihood(doors, saw_door: bool, reliability: float) -> np.ndarray:
    r"""Measurement model :math:`p(z \mid x)` of the door sensor for every cell.

    ``reliability`` where the cell agrees with the reading, ``1 - reliability``
    where it does not: the likelihood peaks at every cell that fits the reading.
    Introduced in chapter 1.

    Returns
    -------
    ndarray, shape (n_cells,)
    """
    p = v.probability(reliability, "reliability")
    is_door = np.asarray(doors, bool)
    return np.where(is_door == bool(saw_door), p, 1.0 - p)
