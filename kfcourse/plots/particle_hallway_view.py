r"""Chapter 11's hallway picture: the histogram filter's bars and a particle cloud on the same readings.

Three panels share chapter 1's cell axis.  On top, the belief :math:`\mathrm{bel}(x)` as bars
(purple after a prediction, teal after an update) with the particle histogram over them as
black outlines, and a readout of the particle count, the total variation distance between the
two and the effective sample size.  In the middle, chapter 1's map of the hallway.  At the
bottom, the particles themselves: one purple dot each at its cell, jittered so that the dots of a
cell spread out, darker the heavier its weight (:data:`palette.PARTICLE_WEIGHTS`, as in every
picture of particles).

:func:`particle_hallway_view` builds the figure; :func:`update_particle_hallway` shows a model's
state on it.  Introduced in chapter 11.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PathCollection
from matplotlib.container import BarContainer
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.text import Text
from matplotlib.ticker import FormatStrFormatter, MaxNLocator

from . import palette
from .artists import belief_bars, update_belief_bars
from .hallway_view import BARS_SHARE, TOP_STEP, hallway_map
from .style import new_figure

JITTER_DOTS = 5000  # jitter positions made once; a larger cloud reuses them


@dataclass(frozen=True)
class ParticleHallwayView:
    """What :func:`particle_hallway_view` drew; :func:`update_particle_hallway` moves it."""

    fig: Figure
    ax: Axes  #: the bars and the particle histogram
    ax_map: Axes  #: chapter 1's hallway map
    ax_cloud: Axes  #: the particles as dots
    bars: BarContainer  #: the histogram filter's belief
    cloud: BarContainer  #: the particle histogram, outlines
    dots: PathCollection  #: one dot per particle, purple shaded by weight (palette.PARTICLE_WEIGHTS)
    jitter: np.ndarray  #: (JITTER_DOTS, 2): where in its cell each dot sits
    robot: Line2D
    end_walls: tuple[Line2D, Line2D]
    readout: Text  #: top right: N, the total variation, N_eff
    legend: Text  #: top left: what the bars and outlines are

    @property
    def moving(self) -> list:
        """Every artist that changes with the model."""
        return [*self.bars, *self.cloud, self.dots, self.robot, *self.end_walls, self.readout, self.legend]


def particle_hallway_view(doors) -> ParticleHallwayView:
    """The three panels for a hallway with ``doors`` (shape (2, n_cells), bool); the bars start flat."""
    doors = np.asarray(doors)
    if doors.ndim != 2 or doors.shape[0] != 2 or doors.shape[1] < 1 or doors.dtype != bool:
        raise ValueError(f"doors must be booleans of shape (2, n_cells), got {doors.dtype} of shape {doors.shape}")
    n = doors.shape[1]
    ratios = {"height_ratios": [3, 0.7, 1.2]}
    fig, (ax, ax_map, ax_cloud) = new_figure(8.0, 4.6, nrows=3, sharex=True, gridspec_kw=ratios)
    ax.set_xlim(-0.6, n - 0.4)
    ax.set_ylim(0, 1.0)
    ax.set_ylabel("bel(x) and particles")
    ax.yaxis.set_major_formatter(FormatStrFormatter("%.2f"))
    flat = np.full(n, 1.0 / n)
    bars = belief_bars(ax, flat)
    cloud = belief_bars(ax, flat, fill=False, edgecolor=palette.INK, lw=1.4)
    clear = {"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 1.0}
    style = {"transform": ax.transAxes, "va": "top", "fontsize": 9, "color": palette.INK, "bbox": clear}
    readout = ax.text(0.99, 0.97, "", ha="right", **style)
    legend = ax.text(0.01, 0.97, "", ha="left", **style)
    end_walls, robot = hallway_map(ax_map, doors)
    ax_cloud.set_ylim(0, 1)
    ax_cloud.set_yticks([])
    ax_cloud.grid(False)
    ax_cloud.set_ylabel("particles")
    ax_cloud.set_xticks(np.arange(n))
    ax_cloud.set_xlabel("cell   (purple dots: one per particle, darker = heavier; grey arrow: the true robot)")
    jitter = np.random.default_rng(0).uniform([-0.38, 0.06], [0.38, 0.94], size=(JITTER_DOTS, 2))
    dots = ax_cloud.scatter(
        jitter[:1, 0], jitter[:1, 1], s=5, c=[1.0], cmap=palette.PARTICLE_WEIGHTS, vmin=0, vmax=1, lw=0
    )
    return ParticleHallwayView(fig, ax, ax_map, ax_cloud, bars, cloud, dots, jitter, robot, end_walls, readout, legend)


def update_particle_hallway(view: ParticleHallwayView, model) -> None:
    """Show the model's bars, particle histogram, particles, true cell and readout.

    Parameters
    ----------
    view : ParticleHallwayView
    model
        Anything with ``belief`` and ``cloud`` (one value per cell), ``dots`` and ``weights``
        (each particle's cell and weight as drawn), ``true_cell``, ``phase`` (``"predicted"``
        or ``"updated"``), ``boundary``, ``n_particles``, ``tv`` and ``n_eff``, such as
        :class:`kfcourse.demos.particle_hallway.ParticleHallwayModel`.
    """
    tallest = max(float(model.belief.max()), float(model.cloud.max()))
    top = TOP_STEP * np.ceil(tallest / BARS_SHARE / TOP_STEP)
    if view.ax.get_ylim() != (0.0, top):  # a limit set again, even unchanged, redraws the background
        view.ax.set_yticks([t for t in MaxNLocator(6).tick_values(0, top) if t <= 1.0 + 1e-9])
        view.ax.set_ylim(0, top)
    update_belief_bars(view.bars, model.belief)
    colour = palette.PREDICTION if model.phase == "predicted" else palette.ESTIMATE
    for bar in view.bars:
        bar.set_color(colour)
    update_belief_bars(view.cloud, model.cloud)
    place = view.jitter[np.arange(model.dots.size) % len(view.jitter)]
    view.dots.set_offsets(np.column_stack([model.dots + place[:, 0], place[:, 1]]))
    view.dots.set_array(model.weights / model.weights.max())
    view.dots.set_sizes([float(np.clip(300 / np.sqrt(model.dots.size), 4, 30))])  # a few particles: bigger dots
    view.robot.set_data([model.true_cell], [0.5])
    for wall in view.end_walls:
        wall.set_visible(model.boundary == "wall")
    step = "after Predict" if model.phase == "predicted" else "after Update (weights before resampling)"
    view.readout.set_text(f"N = {model.n_particles} particles, {step}\nTV(cloud, bars) = {model.tv:.2f}")
    view.legend.set_text(f"bars: histogram filter\noutlines: particle histogram\nN_eff = {model.n_eff:.0f}")
