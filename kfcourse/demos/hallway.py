"""Chapter 1: the histogram (discrete Bayes) filter in a hallway with doors."""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from matplotlib.ticker import FormatStrFormatter, MaxNLocator

from ..filters.bayes import bayes_predict, bayes_update
from ..plots import palette
from ..plots.artists import belief_bars, update_belief_bars
from ..plots.style import FigureRenderer, new_figure
from ..sim.hallway import (
    BOUNDARY,
    MOTION_RELIABILITY,
    N_CELLS,
    SENSOR_RELIABILITY,
    door_likelihood,
    hallway_doors,
    motion_kernel,
    move,
    read_door,
    start_cell,
)
from ._base import Demo, button, slider

DOORS = hallway_doors()  # (2, N_CELLS): doors on the left (row 0) and right (row 1) wall
DOORS.flags.writeable = False
DOOR_COLOUR = "#b07a4a"  # brown: a door in the hallway map


class HallwayModel:
    """Model: the belief, the hidden true cell and the last reading.

    Predict and Update draw from one seeded generator in the same order as
    :func:`kfcourse.sim.hallway.simulate_hallway`, so alternating them replays that run.
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
        self.motion_reliability = p

    def set_sensor_reliability(self, p: float) -> None:
        """A new reliability also changes the likelihood of the last reading."""
        self.sensor_reliability = p
        self.likelihood = door_likelihood(self.doors, self.saw_door, p)

    def set_boundary(self, boundary: str) -> None:
        self.boundary = boundary


def _status(model: HallwayModel) -> str:
    """The text at the top right: what the last button did, and the belief's total."""
    left, right = ("door" if seen else "no door" for seen in model.saw_door)
    if model.phase == "predicted":
        moves = f"{model.steps} move{'s' if model.steps != 1 else ''} since Reset"
        text = rf"after Predict ({moves}): $\overline{{bel}}$ is shifted and blurred"
    else:
        text = f"after Update: left “{left}”, right “{right}”, η = {model.eta:.2f}"
        if model.likelihood_is_stale():
            text = f"{text}\norange: at the new reliability, not used yet"
    return f"{text}\nΣ bel = {model.belief.sum():.3f}"


def _setup(model: HallwayModel) -> str:
    """The text at the top left: the motion kernel, the sensor's reliability and the corridor's ends."""
    k = motion_kernel(model.motion_reliability)
    ends = "loop (wrap)" if model.boundary == "wrap" else "walls"
    return (
        f"motion: one cell right {k[1]:.2f}, stall {k[0]:.2f}\n"
        f"each wall read right {model.sensor_reliability:.2f} of the time\nends: {ends}"
    )


def _hallway_map(ax_map, model: HallwayModel) -> tuple[list, Line2D]:
    """The hallway map: the upper wall is on the robot's left (it drives right), the lower wall on its right.

    Returns
    -------
    (end_walls, robot)
        The walls at both ends (shown when the corridor has walls) and the true robot's marker.
    """
    ax_map.set_ylim(0, 1)
    ax_map.set_yticks([0.9, 0.1], ["left wall", "right wall"], fontsize=8)
    ax_map.tick_params(axis="y", length=0)
    ax_map.grid(False)
    cells = np.arange(N_CELLS)
    for side, y in ((0, 0.8), (1, 0.0)):
        ax_map.axhline(y + 0.1, color=palette.INK, lw=1.2, zorder=1)
        for c in cells[model.doors[side]]:
            ax_map.add_patch(Rectangle((c - 0.35, y), 0.7, 0.2, color=DOOR_COLOUR, lw=0, zorder=2))
    end_walls = [ax_map.axvline(x, color=palette.INK, lw=4, zorder=2) for x in (-0.5, N_CELLS - 0.5)]
    (robot,) = ax_map.plot([model.true_cell], [0.5], marker=">", ms=13, color=palette.TRUTH, zorder=3)
    robot.set_markeredgecolor("#666666")
    return end_walls, robot


def _picture(model: HallwayModel) -> tuple[FigureRenderer, Callable[[], None]]:
    """The belief's bars over the hallway map, and the sensor's likelihood under it.

    Returns
    -------
    (renderer, draw)
        ``draw()`` shows the model's belief, true cell, likelihood and settings.
    """
    fig, (ax, ax_map, ax_lik) = new_figure(8.0, 4.8, nrows=3, sharex=True, gridspec_kw={"height_ratios": [3, 0.7, 1.1]})
    ax.set_xlim(-0.6, N_CELLS - 0.4)
    ax.set_ylim(0, 1.0)
    ax.set_ylabel("belief  bel(x)")
    ax.yaxis.set_major_formatter(FormatStrFormatter("%.2f"))  # labels of one width: the layout, found once, fits all
    bars = belief_bars(ax, model.belief)
    status = ax.text(0.99, 0.97, "", transform=ax.transAxes, ha="right", va="top", fontsize=10)
    setup = ax.text(0.01, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9, color=palette.INK)
    end_walls, robot = _hallway_map(ax_map, model)
    ax_lik.set_ylim(0, 1.05)
    ax_lik.set_ylabel("p(z | x)")
    ax_lik.set_xlabel("cell   (brown: doors on the left and right wall; grey arrow: the true robot)")
    ax_lik.set_xticks(np.arange(N_CELLS))
    lik_bars = belief_bars(ax_lik, model.likelihood, color=palette.MEASUREMENT)
    dynamic = [*bars, robot, status, setup, *lik_bars, *end_walls]
    renderer = FigureRenderer(fig, dynamic)

    def draw() -> None:
        # The bars fill at most the lower 70 %, the two text blocks the rest; the top moves in steps
        # of 0.25 (few full redraws), and the ticks stop at 1, as a probability does.
        top = 0.25 * np.ceil(float(model.belief.max()) / 0.7 / 0.25)
        if ax.get_ylim()[1] != top:
            ax.set_yticks([t for t in MaxNLocator(6).tick_values(0, top) if t <= 1.0 + 1e-9])
            ax.set_ylim(0, top)  # after the ticks, which may reach a rounding past the top and widen it
        update_belief_bars(bars, model.belief)
        colour = palette.PREDICTION if model.phase == "predicted" else palette.ESTIMATE
        for bar in bars:
            bar.set_color(colour)
        robot.set_data([model.true_cell], [0.5])
        for wall in end_walls:  # the corridor's ends: walls, or open on a loop
            wall.set_visible(model.boundary == "wall")
        update_belief_bars(lik_bars, model.likelihood)
        for bar in lik_bars:
            bar.set_alpha(0.35 if model.phase == "predicted" else 1.0)
        status.set_text(_status(model))
        setup.set_text(_setup(model))

    return renderer, draw


def hallway(seed: int = 0) -> Demo:
    """Demo "histogram hallway" (chapter 1): Predict shifts and blurs the bars,
    Update multiplies by the door sensor's likelihood and renormalises.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = HallwayModel(seed)
    renderer, draw = _picture(model)
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
        renderer=renderer,
        draw=draw,
        controls={
            "predict": (button("Predict", icon="arrow-right", tooltip="Move one cell right"), model.predict),
            "update": (button("Update", icon="eye", tooltip="Read the door sensor on both walls"), model.update),
            "reset": (button("Reset", icon="undo", tooltip="Flat belief and a first look"), model.reset),
            "motion_reliability": (
                slider(widgets.FloatSlider, "motion reliability", MOTION_RELIABILITY, 0.5, 1.0, 0.01),
                model.set_motion_reliability,
            ),
            "sensor_reliability": (
                slider(widgets.FloatSlider, "sensor reliability", SENSOR_RELIABILITY, 0.5, 0.99, 0.01),
                model.set_sensor_reliability,
            ),
            "boundary": (boundary, model.set_boundary),
        },
        layout=[["predict", "update", "reset", "boundary"], ["motion_reliability", "sensor_reliability"]],
    )
