r"""The particle filter on the landmark loop (chapter 11): the cloud on chapter 10's map, and its ESS strip.

The map is chapter 10's (:mod:`kfcourse.plots.loop`): the landmarks (purple squares), the
true path (grey, dotted) and robot (grey), the estimate's trail and robot (teal) with its 2-sigma
position ellipse, and teal beams from the estimate to the landmarks read at that step.  On
it, the particles as small purple dots (:data:`palette.PARTICLE_WEIGHTS`, as in every picture of
particles), after the step's prediction, shaded by their weight before resampling: pale where a
particle explains the readings badly, dark purple where it explains them best, the heaviest
drawn on top.

Under the map, a strip shows the effective sample size over the whole run as a share of
the particle count, :math:`N_{\text{eff}} / N`, with the :math:`N/2` line under which the
filter resamples and a cursor at the step shown.

:func:`cloud_view` draws the picture for a demo's model (anything with a run record ``run``
and a step ``frame``); :func:`update_cloud_view` shows the model's run and step on it again,
moving the artists in place (10 000 dots are one scatter whose offsets are replaced).
:func:`cloud_chart` is the same picture, of one run at one step, for a figure in the chapter.
Every function takes a run record with the fields of :class:`kfcourse.sim.ParticleRun`.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Polygon
from matplotlib.text import Text

from . import palette
from .artists import beams, covariance_ellipse, landmarks, robot, update_beams, update_covariance_ellipse, update_robot
from .loop import MAP_MARGIN, ROBOT_FILL, ROBOT_SIZE, TRUTH_SIZE
from .loop_strips import NSIG, kidnap_step, run_step
from .style import new_figure

__all__ = ["CloudView", "cloud_chart", "cloud_view", "update_cloud_view", "weight_shades"]

DOT_SIZE = 4.0  # points squared: 10 000 dots still leave the map readable
STRIP_HEIGHT = 1.0  # inches: the ESS strip
LEGEND_HEIGHT = 0.45  # inches above the map for its legend (two rows)
RESAMPLE_LINE = 0.5  # the filter resamples when N_eff < N/2


def weight_shades(w) -> tuple[np.ndarray, np.ndarray]:
    """The drawing order and shade of each particle: lightest first, shades ``w / max(w)`` from 0 to 1.

    Introduced in chapter 11.

    Parameters
    ----------
    w : array_like, shape (N,)
        Normalised weights.

    Returns
    -------
    (order, shade) : ndarray, shape (N,) each
        The particles' indices, lightest first, and their shades in that order.
    """
    w = np.asarray(w, float)
    order = np.argsort(w, kind="stable")
    return order, w[order] / w.max()


@dataclass(frozen=True)
class CloudView:
    """What :func:`cloud_view` drew; :func:`update_cloud_view` moves it."""

    fig: Figure
    truth_before: Line2D  #: true path (up to a kidnap)
    truth_after: Line2D  #: true path after a kidnap (empty without one)
    cloud: PathCollection  #: the particles, purple shaded by weight (palette.PARTICLE_WEIGHTS)
    beams: LineCollection  #: teal, to the landmarks read at the step
    trail: Line2D  #: the estimate's path up to the step shown
    truth_robot: Polygon
    robot: Polygon
    ring: Ellipse  #: 2-sigma position ellipse of the weighted cloud
    note: Text  #: "kidnapped", or nothing
    past: Line2D  #: N_eff / N up to the step shown
    future: Line2D  #: the rest of the run, faint
    cursor: Line2D  #: the step shown
    kidnap: Line2D  #: the kidnap step on the strip (hidden without one)

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the run, bottom to top."""
        return [
            self.truth_before,
            self.truth_after,
            self.cloud,
            self.beams,
            self.trail,
            self.truth_robot,
            self.robot,
            self.ring,
            self.note,
            self.kidnap,
            self.future,
            self.past,
            self.cursor,
        ]


def _map_extent(run) -> tuple[np.ndarray, np.ndarray]:
    points = np.vstack([np.asarray(run.landmarks, float).reshape(-1, 2), np.asarray(run.truth)[:, :2]])
    return points.min(axis=0) - MAP_MARGIN, points.max(axis=0) + MAP_MARGIN


def cloud_view(model, width: float = 6.4, dot_size: float = DOT_SIZE) -> CloudView:
    """The map with the particle cloud, and the ESS strip under it, at the model's run and step.

    Introduced in chapter 11.

    Parameters
    ----------
    model : object
        Anything with a run record ``run`` (fields of :class:`kfcourse.sim.ParticleRun`) and the
        step shown, ``frame``.  The map's extent comes from this run's map and true path; later
        runs must drive the same loop.
    width : float
        Inches.
    dot_size : float
        Area of each particle's dot (points squared): small for a cloud of thousands, larger
        to see a tight cloud of a few centimetres on the whole map.

    Returns
    -------
    CloudView
    """
    run = model.run
    lo, hi = _map_extent(run)
    map_height = (width - 0.8) * (hi[1] - lo[1]) / (hi[0] - lo[0]) + 0.5  # metres square, room for the x label
    fig, (ax, strip) = new_figure(
        width,
        map_height + STRIP_HEIGHT + LEGEND_HEIGHT,
        nrows=2,
        gridspec_kw={"height_ratios": [map_height, STRIP_HEIGHT]},
    )
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    landmarks(ax, np.asarray(run.landmarks, float).reshape(-1, 2), zorder=2)
    path = {"color": palette.TRUTH, "ls": palette.TRUTH_LINE, "lw": 3}
    (truth_before,) = ax.plot([], [], **path)
    (truth_after,) = ax.plot([], [], **path)
    cloud = ax.scatter(
        np.zeros(1),
        np.zeros(1),
        s=dot_size,
        c=[1.0],
        cmap=palette.PARTICLE_WEIGHTS,
        vmin=0.0,
        vmax=1.0,
        linewidths=0,
        zorder=4.5,
    )
    lines = beams(ax)
    (trail,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.6, alpha=0.9)
    start = np.asarray(run.start, float)
    truth_robot = robot(ax, start, color=palette.TRUTH, size=TRUTH_SIZE, alpha=0.8, zorder=3)
    fill = to_rgba(palette.ESTIMATE, ROBOT_FILL)
    est = robot(ax, start, color=palette.ESTIMATE, facecolor=fill, size=ROBOT_SIZE, zorder=4)
    ring = covariance_ellipse(ax, start, np.eye(2), nsig=NSIG, lw=2.0, zorder=6)
    note = ax.text(
        0.5, 0.97, "", transform=ax.transAxes, ha="center", va="top", fontsize=11, weight="bold", color=palette.INK
    )
    handles = [
        ax.scatter([], [], marker="s", color=palette.LANDMARK, s=40),
        Line2D([], [], **path),
        Line2D([], [], ls="", marker="o", ms=4, color=palette.PARTICLE_WEIGHTS(0.15)),
        Line2D([], [], ls="", marker="o", ms=4, color=palette.PARTICLE_WEIGHTS(1.0)),
        Line2D([], [], color=palette.ESTIMATE, lw=1.6),
        Ellipse((0, 0), 1, 1, fill=False, edgecolor=palette.ESTIMATE, lw=2),
        Line2D([], [], color=palette.ESTIMATE, lw=1.2),
    ]
    labels = ["landmark", "truth", "light particle", "heavy particle", "estimate", "2σ estimate", "reading"]
    ax.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=4, fontsize=8.5, columnspacing=1.2)

    t = np.asarray(run.t, float)
    strip.set_xlim(t[0], t[-1])
    strip.set_ylim(0.0, 1.05)
    strip.set_yticks([0.0, 0.5, 1.0])
    strip.set_ylabel("N$_{\\mathrm{eff}}$ / N")
    strip.set_xlabel("time (s)")
    strip.axhline(RESAMPLE_LINE, color=palette.INK, lw=1.2, ls="--", label="resample below N/2")
    kidnap = strip.axvline(t[0], color=palette.INK, lw=1.2, ls=":", visible=False)
    (future,) = strip.plot([], [], color=palette.ESTIMATE, lw=1.2, alpha=0.35)
    (past,) = strip.plot([], [], color=palette.ESTIMATE, lw=1.8)
    cursor = strip.axvline(t[0], color=palette.INK, lw=1.0, alpha=0.6)
    strip.legend(loc="lower right", fontsize=8.5)
    view = CloudView(
        fig, truth_before, truth_after, cloud, lines, trail, truth_robot, est, ring, note, past, future, cursor, kidnap
    )
    update_cloud_view(view, model)
    return view


def cloud_chart(run, k: int | None = None, width: float = 6.4, dot_size: float = DOT_SIZE) -> Figure:
    """The particle cloud of a run at step ``k``, with the ESS strip: the demo's picture, standing still.

    Introduced in chapter 11.

    Parameters
    ----------
    run : ParticleRun
    k : int, optional
        The step shown; by default the last.
    width : float
        Inches.
    dot_size : float
        Area of each particle's dot (points squared), as in :func:`cloud_view`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    return cloud_view(SimpleNamespace(run=run, frame=run_step(run, k)), width, dot_size).fig


def update_cloud_view(view: CloudView, model) -> None:
    """Show the model's run at its step ``frame`` on a picture made by :func:`cloud_view`.

    Only the artists in :attr:`CloudView.moving` change: the cloud's offsets and shades are
    replaced in place, whatever its size.
    """
    run = model.run
    k = run_step(run, model.frame)
    truth = np.asarray(run.truth)[:, :2]
    k0 = kidnap_step(run)
    split = truth.shape[0] if k0 is None else k0
    view.truth_before.set_data(truth[:split, 0], truth[:split, 1])
    view.truth_after.set_data(truth[split:, 0], truth[split:, 1])
    order, shade = weight_shades(run.w[k])
    view.cloud.set_offsets(np.asarray(run.particles[k], float)[order, :2])
    view.cloud.set_array(shade)
    mu = np.asarray(run.mu)
    update_beams(view.beams, mu[k], np.asarray(run.landmarks)[np.asarray(run.visible[k], bool)])
    view.trail.set_data(mu[: k + 1, 0], mu[: k + 1, 1])
    update_robot(view.truth_robot, run.truth[k])
    update_robot(view.robot, mu[k])
    update_covariance_ellipse(view.ring, mu[k], np.asarray(run.Sig[k])[:2, :2])
    view.note.set_text("kidnapped: the truth jumped, the filter was not told" if k0 is not None and k >= k0 else "")
    t = np.asarray(run.t, float)
    share = np.asarray(run.ess, float) / run.n_particles
    view.past.set_data(t[: k + 1], share[: k + 1])
    view.future.set_data(t[k:], share[k:])
    view.cursor.set_xdata([t[k], t[k]])
    view.kidnap.set_visible(k0 is not None)
    if k0 is not None:
        view.kidnap.set_xdata([t[k0], t[k0]])
