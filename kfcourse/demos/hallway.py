"""Chapter 1: the histogram (discrete Bayes) filter in a hallway with doors."""

from __future__ import annotations

from functools import partial

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..filters.bayes import bayes_predict, bayes_update
from ..plots.hallway_view import hallway_view, update_hallway
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
from ._base import Demo, button, shown, slider

DOORS = hallway_doors()  # (2, N_CELLS): doors on the left (row 0) and right (row 1) wall
DOORS.flags.writeable = False
RELIABILITY_FORMAT = ".2f"  # the reliability sliders' readouts


class HallwayModel:
    """Model: the belief, the hidden true cell and the last reading.

    Predict and Update draw from one seeded generator in the same order as
    :func:`kfcourse.sim.hallway_world.simulate_hallway`, so alternating them replays that run.

    Attributes
    ----------
    belief : ndarray, shape (N_CELLS,)
        bel(x) after the last step.
    true_cell : int
        Where the robot really is (hidden from the filter).
    phase : str
        What the last step was: ``"predicted"`` or ``"updated"``.
    steps : int
        Moves since the last Reset.
    saw_door : ndarray of bool, shape (2,)
        The last reading: a door on the left wall, on the right wall.
    likelihood : ndarray, shape (N_CELLS,)
        p(z | x) of the last reading, at the sensor reliability set now.
    eta : float
        The last update's normaliser.
    motion_reliability, sensor_reliability : float
    boundary : str
        ``"wrap"`` (a loop) or ``"wall"`` (walls at both ends).
    """

    def __init__(
        self,
        seed: int,
        motion_reliability: float = MOTION_RELIABILITY,
        sensor_reliability: float = SENSOR_RELIABILITY,
        boundary: str = BOUNDARY,
    ):
        self.seed = seed
        self.doors = DOORS
        self.motion_reliability = motion_reliability
        self.sensor_reliability = sensor_reliability
        self.boundary = boundary
        self.reset()

    def reset(self) -> None:
        """Flat belief, the same (seeded) true cell, and a first look."""
        self.rng = np.random.default_rng(self.seed)
        self.true_cell = start_cell(self.rng, N_CELLS)
        self.belief = np.full(N_CELLS, 1.0 / N_CELLS)
        self.steps = 0
        self.update()

    def predict(self) -> None:
        """Command "one cell right": the truth moves (or stalls), the belief shifts and blurs."""
        kernel = motion_kernel(self.motion_reliability)
        self.true_cell = move(self.true_cell, kernel, self.rng, N_CELLS, self.boundary)
        self.belief = bayes_predict(self.belief, kernel, self.boundary)
        self.phase = "predicted"
        self.steps += 1

    def update(self) -> None:
        """Read the door sensor on both walls and apply Bayes' rule."""
        self.saw_door = read_door(self.true_cell, self.doors, self.sensor_reliability, self.rng)
        self.likelihood = door_likelihood(self.doors, self.saw_door, self.sensor_reliability)
        self.belief, self.eta = bayes_update(self.belief, self.likelihood, return_eta=True)
        self.used_reliability = self.sensor_reliability
        self.phase = "updated"

    def likelihood_is_stale(self) -> bool:
        """True once the sensor slider has moved since the last Update: the orange bars then show the
        last reading at the new reliability, which the belief has not used yet."""
        return self.sensor_reliability != self.used_reliability

    def set_motion_reliability(self, p: float) -> None:
        """Used from the next Predict on."""
        self.motion_reliability = p

    def set_sensor_reliability(self, p: float) -> None:
        """A new reliability also changes the likelihood of the last reading."""
        self.sensor_reliability = p
        self.likelihood = door_likelihood(self.doors, self.saw_door, p)

    def set_boundary(self, boundary: str) -> None:
        """``"wrap"`` or ``"wall"``, used from the next Predict on."""
        self.boundary = boundary

    def update_was_flat(self) -> bool:
        """True when the last Update's likelihood was the same in every cell (a sensor reliability of 0.5,
        a coin flip): Bayes' rule then multiplies every cell by the same number and the belief is unchanged."""
        likelihood = door_likelihood(self.doors, self.saw_door, self.used_reliability)
        return bool(np.allclose(likelihood, likelihood[0], rtol=1e-9, atol=0.0))

    def describe(self) -> str:
        """What the picture shows in two sentences: what the last step did to the belief (on the loop, where
        the last cell's share went; with a coin-flip sensor, nothing), where it peaks against the true cell,
        and the settings."""
        peak = self.belief.max()
        cells = peak_cells(self.belief)
        if cells.size == 1:
            where = f"cell {cells[0]}"
        elif cells.size <= 4:
            where = f"{cells.size} cells ({', '.join(str(c) for c in cells)})"
        else:
            where = f"{cells.size} cells"
        if self.phase == "predicted":
            moves = f"{self.steps} move{'s' if self.steps != 1 else ''} since Reset"
            blurred = " and blurred" if self.motion_reliability < 1.0 else ""
            last = N_CELLS - 1
            if self.boundary == "wrap":
                ends = f", cell {last}'s share carried round the loop to cell 0, which now holds {self.belief[0]:.2f}"
            else:
                ends = f", cell {last} keeping its share at the wall, now holding {self.belief[last]:.2f}"
            step = f"After Predict ({moves}: shifted right{blurred}{ends})"
            still = ""
        else:
            left, right = ("a door" if seen else "no door" for seen in self.saw_door)
            flat = self.update_was_flat()
            coin = "; a coin-flip sensor: the likelihood is flat, the belief unchanged" if flat else ""
            step = f"After Update (the sensor read {left} on the left, {right} on the right{coin})"
            still = " still" if flat else ""
        p_motion, p_sensor = (shown(p, RELIABILITY_FORMAT) for p in (self.motion_reliability, self.sensor_reliability))
        later = ", from the next Update on" if self.likelihood_is_stale() else ""
        return (
            f"{step}, the belief{still} peaks at {peak:.2f} on {where}; the robot is truly at cell {self.true_cell}. "
            f"Motion reliability {p_motion}, sensor reliability {p_sensor}{later}, ends: {self.boundary}."
        )


def hallway(seed: int = 0) -> Demo:
    """Demo "histogram hallway" (chapter 1): Predict shifts and blurs the bars,
    Update multiplies by the door sensor's likelihood and renormalises.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = HallwayModel(seed)
    view = hallway_view(model.doors)
    boundary = widgets.ToggleButtons(options=["wrap", "wall"], value=model.boundary, description="ends:")
    boundary.style.button_width = "60px"
    caption = (
        f"<b>Histogram hallway.</b> Bars: the belief bel(x) over a corridor of {N_CELLS} cells "
        "(purple after <i>Predict</i>, teal after <i>Update</i>); brown: doors on the left and right wall; "
        "orange: the door sensor's likelihood p(z | x); the grey arrow is the true robot. "
        "Sliders set how reliable motion and sensing are; <i>ends</i> chooses a loop (wrap) "
        "or end walls (drawn as thick black bars at both ends of the map)."
    )
    return Demo(
        name="hallway",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=partial(update_hallway, view, model),
        describe=model.describe,
        controls={
            "predict": (button("Predict", icon="arrow-right", tooltip="Move one cell right"), model.predict),
            "update": (button("Update", icon="eye", tooltip="Read the door sensor on both walls"), model.update),
            "reset": (button("Reset", icon="undo", tooltip="Flat belief and a first look"), model.reset),
            "motion_reliability": (
                slider(
                    widgets.FloatSlider, "motion reliability", MOTION_RELIABILITY, 0.5, 1.0, 0.01, RELIABILITY_FORMAT
                ),
                model.set_motion_reliability,
            ),
            "sensor_reliability": (
                slider(
                    widgets.FloatSlider, "sensor reliability", SENSOR_RELIABILITY, 0.5, 0.99, 0.01, RELIABILITY_FORMAT
                ),
                model.set_sensor_reliability,
            ),
            "boundary": (boundary, model.set_boundary),
        },
        layout=[["predict", "update", "reset", "boundary"], ["motion_reliability", "sensor_reliability"]],
    )
