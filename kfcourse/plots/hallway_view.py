r"""Chapter 1's picture: the histogram filter's belief over a hallway with doors.

Three panels share the cell axis.  On top, the belief :math:`\mathrm{bel}(x)` as one bar
per cell (purple after a prediction, teal after an update), with the filter's settings
written at the top left and what the last step did at the top right.  In the middle,
the hallway's map: doors (brown) on the left and right wall, the true robot (a grey
arrow) and, when the corridor is not a loop, its end walls.  At the bottom, the door
sensor's likelihood :math:`p(z \mid x)` of the last reading (orange, faded after a
prediction, which does not use it).

:func:`hallway_view` builds the figure; :func:`update_hallway` shows a model's state
on it.  Introduced in chapter 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.container import BarContainer
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from matplotlib.text import Text
from matplotlib.ticker import FormatStrFormatter, MaxNLocator

from . import palette
from .artists import belief_bars, update_belief_bars
from .style import new_figure

DOOR_COLOUR = "#b07a4a"  # brown: a door in the hallway map
BARS_SHARE = 0.7  # the bars fill at most this share of the belief axis; the two text blocks the rest
TOP_STEP = 0.25  # the belief axis's top moves in steps of this much


@dataclass(frozen=True)
class HallwayView:
    """What :func:`hallway_view` drew; :func:`update_hallway` moves it."""

    fig: Figure
    ax: Axes  #: the belief
    ax_map: Axes  #: the hallway's map
    ax_likelihood: Axes  #: the sensor's likelihood
    status: Text  #: top right: what the last step did
    setup: Text  #: top left: the motion and sensor settings and the corridor's ends
    bars: BarContainer  #: the belief, one bar per cell
    robot: Line2D  #: the true robot
    end_walls: tuple[Line2D, Line2D]  #: drawn when the corridor has walls at its ends
    likelihood: BarContainer  #: the likelihood of the last reading, one bar per cell

    @property
    def moving(self) -> list:
        """Every artist that changes with the model."""
        return [*self.bars, self.robot, self.status, self.setup, *self.likelihood, *self.end_walls]


def hallway_view(doors) -> HallwayView:
    """The three panels for a hallway with ``doors``; the bars start flat.

    Parameters
    ----------
    doors : array_like of bool, shape (2, n_cells)
        ``doors[0, i]``: a door on the left wall of cell ``i`` (the upper wall in the map,
        the robot drives right); ``doors[1, i]``: a door on the right wall.

    Returns
    -------
    HallwayView
    """
    doors = np.asarray(doors)
    if doors.ndim != 2 or doors.shape[0] != 2 or doors.shape[1] < 1 or doors.dtype != bool:
        raise ValueError(f"doors must be booleans of shape (2, n_cells), got {doors.dtype} of shape {doors.shape}")
    n = doors.shape[1]
    fig, (ax, ax_map, ax_lik) = new_figure(8.0, 4.5, nrows=3, sharex=True, gridspec_kw={"height_ratios": [3, 0.7, 1.1]})
    ax.set_xlim(-0.6, n - 0.4)
    ax.set_ylim(0, 1.0)
    ax.set_ylabel("belief  bel(x)")
    ax.yaxis.set_major_formatter(FormatStrFormatter("%.2f"))  # labels of one width: the layout, found once, fits all
    flat = np.full(n, 1.0 / n)
    bars = belief_bars(ax, flat)
    status = ax.text(0.99, 0.97, "", transform=ax.transAxes, ha="right", va="top", fontsize=10)
    clear = {"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 1.0}  # over the grid lines
    style = {"transform": ax.transAxes, "ha": "left", "va": "top", "fontsize": 9, "color": palette.INK, "bbox": clear}
    setup = ax.text(0.01, 0.97, "", **style)
    end_walls, robot = hallway_map(ax_map, doors)
    ax_lik.set_ylim(0, 1.05)
    ax_lik.set_ylabel("p(z | x)")
    ax_lik.set_xlabel("cell   (brown: doors on the left and right wall; grey arrow: the true robot)")
    ax_lik.set_xticks(np.arange(n))
    likelihood = belief_bars(ax_lik, flat, color=palette.MEASUREMENT)
    return HallwayView(fig, ax, ax_map, ax_lik, status, setup, bars, robot, end_walls, likelihood)


def hallway_map(ax_map: Axes, doors: np.ndarray) -> tuple[tuple[Line2D, Line2D], Line2D]:
    """The hallway's map: the upper wall is on the robot's left (it drives right), the lower wall on its right.

    Returns
    -------
    (end_walls, robot)
        The walls at both ends (hidden until a corridor with walls is shown) and the true robot's marker.
    """
    n = doors.shape[1]
    ax_map.set_ylim(0, 1)
    ax_map.set_yticks([0.9, 0.1], ["left wall", "right wall"], fontsize=8)
    ax_map.tick_params(axis="y", length=0)
    ax_map.grid(False)
    cells = np.arange(n)
    for side, y in ((0, 0.8), (1, 0.0)):
        ax_map.axhline(y + 0.1, color=palette.INK, lw=1.2, zorder=1)
        for c in cells[doors[side]]:
            ax_map.add_patch(Rectangle((c - 0.35, y), 0.7, 0.2, color=DOOR_COLOUR, lw=0, zorder=2))
    end_walls = tuple(ax_map.axvline(x, color=palette.INK, lw=4, zorder=2, visible=False) for x in (-0.5, n - 0.5))
    (robot,) = ax_map.plot([0], [0.5], marker=">", ms=13, color=palette.TRUTH, zorder=3)
    robot.set_markeredgecolor("#666666")
    return end_walls, robot


def update_hallway(view: HallwayView, model) -> None:
    r"""Show the model's belief, true cell, last likelihood and settings.

    The belief axis's top moves in steps of ``TOP_STEP``, so that the tallest bar fills at
    most ``BARS_SHARE`` of it and the texts above stay clear; its ticks stop at 1, as a
    probability does.

    Parameters
    ----------
    view : HallwayView
    model
        Anything with ``belief`` and ``likelihood`` (one value per cell), ``true_cell``,
        ``phase`` (``"predicted"`` or ``"updated"``: what the last step was), ``boundary``
        (``"wrap"`` or ``"wall"``), ``motion_reliability``, ``sensor_reliability``, ``steps``
        (moves since the reset), ``saw_door`` (the last reading, left and right), ``eta``
        (the last update's normaliser :math:`\eta`) and ``likelihood_is_stale()``, such as
        :class:`kfcourse.demos.hallway.HallwayModel`.
    """
    top = TOP_STEP * np.ceil(float(model.belief.max()) / BARS_SHARE / TOP_STEP)
    if view.ax.get_ylim() != (0.0, top):  # a limit set again, even unchanged, redraws the background
        view.ax.set_yticks([t for t in MaxNLocator(6).tick_values(0, top) if t <= 1.0 + 1e-9])
        view.ax.set_ylim(0, top)  # after the ticks, which may reach a rounding past the top and widen it
    update_belief_bars(view.bars, model.belief)
    colour = palette.PREDICTION if model.phase == "predicted" else palette.ESTIMATE
    for bar in view.bars:
        bar.set_color(colour)
    view.robot.set_data([model.true_cell], [0.5])
    for wall in view.end_walls:  # the corridor's ends: walls, or open on a loop
        wall.set_visible(model.boundary == "wall")
    update_belief_bars(view.likelihood, model.likelihood)
    for bar in view.likelihood:
        bar.set_alpha(0.35 if model.phase == "predicted" else 1.0)
    view.status.set_text(_status(model))
    view.setup.set_text(_setup(model))


def _status(model) -> str:
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


def _setup(model) -> str:
    """The text at the top left: the motion model, the sensor's reliability and the corridor's ends."""
    p = model.motion_reliability
    ends = "loop (wrap)" if model.boundary == "wrap" else "walls"
    return (
        f"motion: one cell right {p:.2f}, stall {1.0 - p:.2f}\n"
        f"each wall read right {model.sensor_reliability:.2f} of the time\nends: {ends}"
    )
