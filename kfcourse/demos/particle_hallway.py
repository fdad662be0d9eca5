"""Chapter 11: chapter 1's hallway with a particle filter beside the histogram filter."""

from __future__ import annotations

from functools import partial

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..filters.bayes import bayes_predict, bayes_update
from ..filters.particle import effective_sample_size, resample_systematic
from ..plots.particle_hallway_view import particle_hallway_view, update_particle_hallway
from ..plots.style import FigureRenderer
from ..sim.hallway_world import (
    BOUNDARY,
    MOTION_RELIABILITY,
    N_CELLS,
    SENSOR_RELIABILITY,
    door_likelihood,
    hallway_doors,
    motion_kernel,
    move,
    peak_cells,
    read_door,
    start_cell,
)
from ..sim.particle_hallway_run import (
    hallway_particles_predict,
    hallway_particles_weight,
    particle_histogram,
    total_variation,
)
from ..sim.particle_lap import PF_STREAM
from ._base import Demo, button, slider

DOORS = hallway_doors()
DOORS.flags.writeable = False
N_PARTICLES = 200  # where the slider starts: close to the bars, not yet on them
N_MIN, N_MAX = 10, 5000


class ParticleHallwayModel:
    """Model: chapter 1's hallway (truth, readings, bars) and a particle cloud on the same readings.

    The world draws from ``default_rng(seed)`` in the order of
    :func:`kfcourse.sim.hallway_world.simulate_hallway`, the particles from
    ``default_rng([seed, PF_STREAM])``: alternating Update and Predict replays
    :func:`kfcourse.sim.particle_hallway_run.simulate_particle_hallway`.  A new particle count
    replays every press since the last Reset with the new cloud, on the same readings.

    Attributes
    ----------
    belief, cloud : ndarray, shape (N_CELLS,)
        The histogram filter's bars; the particle histogram (after resampling, after an Update).
    cells : ndarray of int, shape (n_particles,)
        Each particle's cell.
    dots, weights : ndarray, shape (n_particles,)
        The particles as drawn: after an Update, their cells and weights before resampling.
    tv, n_eff : float
        Total variation between ``cloud`` and ``belief``; effective sample size of the weights.
    actions : list of str
        The presses since the last Reset, ``"predict"`` or ``"update"``.
    """

    def __init__(self, seed: int, n_particles: int = N_PARTICLES):
        self.seed = seed
        self.n_particles = n_particles
        self.doors = DOORS
        self.motion_reliability = MOTION_RELIABILITY
        self.sensor_reliability = SENSOR_RELIABILITY
        self.boundary = BOUNDARY
        self.reset()

    def reset(self) -> None:
        """Flat bars, a uniform cloud, the same (seeded) true cell, and a first look."""
        self.world = np.random.default_rng(self.seed)
        self.rng = np.random.default_rng([self.seed, PF_STREAM])
        self.true_cell = start_cell(self.world, N_CELLS)
        self.belief = np.full(N_CELLS, 1.0 / N_CELLS)
        self.cells = self.rng.integers(N_CELLS, size=self.n_particles)
        self.steps = 0
        self.actions = []
        self.update()

    def predict(self) -> None:
        """Command "one cell right": the truth moves, the bars shift and blur, every particle samples a move."""
        kernel = motion_kernel(self.motion_reliability)
        self.true_cell = move(self.true_cell, kernel, self.world, N_CELLS, self.boundary)
        self.belief = bayes_predict(self.belief, kernel, self.boundary)
        self.cells = hallway_particles_predict(self.cells, self.motion_reliability, self.rng, N_CELLS, self.boundary)
        self.dots, self.weights = self.cells, np.full(self.cells.size, 1.0 / self.cells.size)
        self._compare("predicted")
        self.steps += 1
        self.actions.append("predict")

    def update(self) -> None:
        """Read the doors; Bayes' rule on the bars; weight, then resample (systematic) the particles."""
        self.saw_door = read_door(self.true_cell, self.doors, self.sensor_reliability, self.world)
        self.belief = bayes_update(self.belief, door_likelihood(self.doors, self.saw_door, self.sensor_reliability))
        self.dots = self.cells
        self.weights = hallway_particles_weight(self.cells, self.doors, self.saw_door, self.sensor_reliability)
        self.cells = self.cells[resample_systematic(self.weights, self.rng)]
        self._compare("updated")
        self.actions.append("update")

    def _compare(self, phase: str) -> None:
        """After a step: the particle histogram, its distance to the bars, N_eff."""
        self.phase = phase
        self.cloud = particle_histogram(self.cells, N_CELLS)
        self.tv = total_variation(self.cloud, self.belief)
        self.n_eff = effective_sample_size(self.weights)

    def set_n_particles(self, n: float) -> None:
        """A new cloud of ``n`` particles (rounded) through every press since Reset, on the same readings."""
        self.n_particles = int(np.clip(round(n), N_MIN, N_MAX))
        presses = self.actions[1:]  # the first is Reset's own look
        self.reset()
        for press in presses:
            getattr(self, press)()

    def new_run(self) -> None:
        """The next seed: a new start, new readings, a new cloud."""
        self.seed += 1
        self.reset()

    def describe(self) -> str:
        """What the picture shows: the last press, how far the particles' histogram is from the bars
        (TV), the effective sample size N_eff, and where the bars and the particles peak against the robot's cell."""
        moves = f"{self.steps} move{'s' if self.steps != 1 else ''}"
        if self.phase == "predicted":
            last = f"After Predict ({moves})"
        else:
            left, right = self.saw_door  # the reading: a door on the left wall, on the right
            seen = "doors on both sides" if left and right else "a door on the left" if left else "a door on the right"
            last = f"After an Update that saw {seen if left or right else 'no door'} ({moves})"
        return (
            f"{last}, the {self.n_particles} particles' histogram lies TV = {self.tv:.2f} from the bars "
            f"(total variation: 0 the same, 1 no overlap), effective sample size {self.n_eff:.0f}. "
            f"The bars peak at {peak(self.belief)}, the particles at {peak(self.cloud)}; "
            f"the robot is in cell {self.true_cell}."
        )


def peak(histogram: np.ndarray) -> str:
    """Where a histogram over the cells peaks, in words: "42 % on cells 0 and 10".

    Every cell of :func:`~kfcourse.sim.hallway_world.peak_cells` is named, up to four, else their number.  A share that
    rounds to 100 % without being 1 is "over 99 %"."""
    top = float(histogram.max())
    cells = [str(c) for c in peak_cells(histogram)]
    if len(cells) == 1:
        where = f"cell {cells[0]}"
    elif len(cells) <= 4:
        where = f"cells {', '.join(cells[:-1])} and {cells[-1]}"
    else:
        where = f"{len(cells)} cells"
    share = "over 99 %" if round(100 * top) == 100 and top < 1.0 else f"{100 * top:.0f} %"
    return f"{share} on {where}"


def particle_hallway(seed: int = 0) -> Demo:
    """Demo "particle hallway" (chapter 11): chapter 1's bars and a particle cloud on the same readings.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = ParticleHallwayModel(seed)
    view = particle_hallway_view(model.doors)
    caption = (
        f"<b>Particles in chapter 1's hallway.</b> Bars: the histogram filter over {N_CELLS} cells "
        "(purple after <i>Predict</i>, teal after <i>Update</i>); black outlines: the share of the "
        "particles in each cell. Below the hallway, every particle as a purple dot, darker the heavier. "
        "TV is the total variation distance between outlines and bars: move the particle count."
    )
    return Demo(
        name="particle-hallway",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=partial(update_particle_hallway, view, model),
        describe=model.describe,
        controls={
            "new_run": (button("New run", icon="random", tooltip="The next seed"), model.new_run),
            "predict": (button("Predict", icon="arrow-right", tooltip="Move one cell right"), model.predict),
            "update": (button("Update", icon="eye", tooltip="Read the doors; weight and resample"), model.update),
            "reset": (button("Reset", icon="undo", tooltip="Flat bars, a uniform cloud, a first look"), model.reset),
            "n_particles": (
                slider(
                    widgets.FloatLogSlider,
                    "particles N",
                    N_PARTICLES,
                    np.log10(N_MIN),
                    np.log10(N_MAX),
                    0.01,
                    readout_format=".0f",
                    base=10,
                ),
                model.set_n_particles,
            ),
        },
        layout=[["predict", "update", "reset", "new_run"], ["n_particles"]],
    )
