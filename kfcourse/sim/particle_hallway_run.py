"""Chapter 1's hallway with a particle filter beside the histogram filter (chapter 11).

The same corridor, doors, motion and door sensor as :mod:`kfcourse.sim.hallway_world`, and the same
readings for the same seed.  Beside the histogram's bars runs a cloud of particles, each one a
guess of the cell the robot is in: it moves by sampling the motion model, is weighted by the
door sensor's likelihood of the reading, and is resampled.  Counting the particles in each cell
gives a histogram that should match the bars; the total variation distance says how far it is.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.bayes import BOUNDARIES
from ..filters.particle import effective_sample_size, normalise, resample_systematic
from .hallway_world import MOTION_RELIABILITY, SENSOR_RELIABILITY, door_likelihood, simulate_hallway
from .particle_lap import PF_STREAM
from .records import Record


def hallway_particles_predict(
    cells, reliability: float, rng: np.random.Generator, n_cells: int, boundary: str = "wall"
) -> np.ndarray:
    """Sample "move one cell right" for every particle: the kernel of chapter 1, one draw each.

    Each particle moves one cell right with ``reliability`` and otherwise stalls; at the ends
    it stops at the wall (``"wall"``) or comes round the loop (``"wrap"``), as the histogram's
    predict does.  Introduced in chapter 11.

    Returns
    -------
    ndarray of int, shape (N,)
    """
    p = v.probability(reliability, "reliability")
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}, got {boundary!r}")
    cells = np.asarray(cells, int)
    dst = cells + (rng.random(cells.size) < p)  # one cell right with probability p, else stall
    return dst % n_cells if boundary == "wrap" else np.clip(dst, 0, n_cells - 1)


def hallway_particles_weight(cells, doors, saw_door, reliability: float) -> np.ndarray:
    r"""Normalised weights :math:`w^{[i]} \propto p(z \mid x^{[i]})`: the door likelihood at each particle's cell.

    Works in log space (:func:`~kfcourse.filters.particle.normalise`), so a sensor that is
    never wrong (likelihood 0 where the cell does not fit) still gives weights, as long as one
    particle fits the reading.  Introduced in chapter 11.
    """
    with np.errstate(divide="ignore"):  # log 0 = -inf: a weight of 0
        log_lik = np.log(door_likelihood(doors, saw_door, reliability))
    return normalise(log_lik[np.asarray(cells, int)])


def particle_histogram(cells, n_cells: int, weights=None) -> np.ndarray:
    """The share of the particles (or of their weight) in each cell: the cloud drawn as bars.

    Returns
    -------
    ndarray, shape (n_cells,)
        Sums to 1.
    """
    counts = np.bincount(np.asarray(cells, int), weights=weights, minlength=n_cells)
    return counts / counts.sum()


def total_variation(p, q) -> float:
    r"""Total variation distance between two distributions over the same cells.

    .. math:: \mathrm{TV}(p, q) = \tfrac12 \sum_x |p(x) - q(x)|

    0 when they agree, 1 when they share no cell: the largest difference in probability the
    two give to any set of cells.
    """
    return float(0.5 * np.abs(np.asarray(p, float) - np.asarray(q, float)).sum())


@dataclass(frozen=True)
class ParticleHallwayRun(Record):
    """One run of the hallway with the histogram filter and a particle filter on the same readings.

    Row ``k`` of every array is the state after the ``k``-th update (row 0: the first look);
    the particles are the cloud after resampling.
    """

    doors: np.ndarray  #: (2, n_cells) bool, the door map
    true_cell: np.ndarray  #: (n_cycles + 1,) int
    saw_door: np.ndarray  #: (n_cycles + 1, 2) bool, the readings both filters use
    belief: np.ndarray  #: (n_cycles + 1, n_cells), the histogram filter's bars
    particles: np.ndarray  #: (n_cycles + 1, N) int, each particle's cell after resampling
    cloud: np.ndarray  #: (n_cycles + 1, n_cells), the particle histogram
    tv: np.ndarray  #: (n_cycles + 1,), total variation between the cloud and the bars
    n_eff: np.ndarray  #: (n_cycles + 1,), effective sample size of the weights before resampling
    motion_reliability: float
    sensor_reliability: float
    boundary: str
    seed: int


def simulate_particle_hallway(
    n_particles: int = 500,
    n_cycles: int = 10,
    motion_reliability: float = MOTION_RELIABILITY,
    sensor_reliability: float = SENSOR_RELIABILITY,
    boundary: str = "wrap",
    seed: int = 0,
) -> ParticleHallwayRun:
    """The hallway run of :func:`~kfcourse.sim.hallway_world.simulate_hallway`, with a particle filter beside it.

    The world (start cell, moves, readings) and the bars are that run's, draw for draw.  The
    particles start spread uniformly over the cells (the flat belief) and, on every reading:
    predict by sampling (:func:`hallway_particles_predict`, not before the first look), weight
    (:func:`hallway_particles_weight`), resample systematically
    (:func:`~kfcourse.filters.particle.resample_systematic`).  Their draws come from
    ``np.random.default_rng([seed, PF_STREAM])``, apart from the world's.  Introduced in chapter 11.

    Returns
    -------
    ParticleHallwayRun
    """
    seed = v.whole(seed, "seed", 0)
    n = v.whole(n_particles, "n_particles", 1)
    hall = simulate_hallway(n_cycles, motion_reliability, sensor_reliability, boundary, seed=seed)
    n_cells = hall.doors.shape[1]
    rng = np.random.default_rng([seed, PF_STREAM])
    cells = rng.integers(n_cells, size=n)  # the flat belief, as a cloud
    clouds, particles, tv, n_eff = [], [], [], []
    for k, saw in enumerate(hall.saw_door):
        if k > 0:
            cells = hallway_particles_predict(cells, hall.motion_reliability, rng, n_cells, boundary)
        w = hallway_particles_weight(cells, hall.doors, saw, hall.sensor_reliability)
        n_eff.append(effective_sample_size(w))
        cells = cells[resample_systematic(w, rng)]
        particles.append(cells)
        clouds.append(particle_histogram(cells, n_cells))
        tv.append(total_variation(clouds[-1], hall.belief[k]))
    return ParticleHallwayRun(
        hall.doors,
        hall.true_cell,
        hall.saw_door,
        hall.belief,
        np.array(particles),
        np.array(clouds),
        np.array(tv),
        np.array(n_eff),
        hall.motion_reliability,
        hall.sensor_reliability,
        boundary,
        seed,
    )
