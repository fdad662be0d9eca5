"""The pictures of chapter 6's demos: the 2-D tracker and the NEES panel.

:func:`tracker_view` draws the turning target's map, :func:`update_tracker_view`
shows a filter's run up to a step on it; :func:`nees_view` draws the average-NEES
axes with the honest band, :func:`update_nees_view` a filter's average NEES on them.
Every limit is fixed when the picture is made, so the updates move only the
artists listed in each view's ``moving``.  Introduced in chapter 6.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.collections import PathCollection
from matplotlib.colors import to_rgb
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse

from .. import _validate as v
from . import palette
from .artists import covariance_ellipse, update_covariance_ellipse
from .curve_panels import axis_range
from .style import new_figure

__all__ = ["NeesView", "TrackerView", "nees_view", "tracker_view", "update_nees_view", "update_tracker_view"]

ARROW_TIME = 1.0  # s: velocity lines show where the target would be this much later
MAP_MARGIN = 3.0  # m of room around the true path: three sensor standard deviations


# --------------------------------------------------------------------------- the 2-D tracker


@dataclass(frozen=True)
class TrackerView:
    """What :func:`tracker_view` drew; :func:`update_tracker_view` moves it."""

    fig: Figure
    readings: PathCollection  #: orange, the readings so far
    trail: Line2D  #: teal, the estimate so far
    ahead: Line2D  #: thin pale teal, the estimate for the rest of the run
    truth_velocity: Line2D  #: grey, from the true position to where it would be ARROW_TIME later
    truth_dot: Line2D  #: grey, the true position
    velocity: Line2D  #: teal, the same for the estimate, cut at the edge of the map
    dot: Line2D  #: teal, the estimated position
    ring: Ellipse  #: teal, the estimate's 2-sigma position ellipse, lightly filled
    lo: np.ndarray  #: (2,) lower-left corner of the map (m)
    hi: np.ndarray  #: (2,) upper-right corner of the map (m)

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the filter, bottom to top."""
        return [
            self.readings,
            self.trail,
            self.ahead,
            self.truth_velocity,
            self.truth_dot,
            self.velocity,
            self.dot,
            self.ring,
        ]


def tracker_view(run, width: float = 8.0, height: float = 4.25) -> TrackerView:
    """The map of a turning target's run: its true path, and the artists a filter's run moves.

    The map spans the true path with a margin of ``MAP_MARGIN``, at one scale along both
    axes, with the legend on its right.  Nothing of the filter is shown until
    :func:`update_tracker_view`.  Introduced in chapter 6.

    Parameters
    ----------
    run : TargetRun
        With ``truth`` (T, 4) and ``z`` (T, 2), as :func:`kfcourse.sim.simulate_target` makes.
    width, height : float
        Figure size (inches).

    Returns
    -------
    TrackerView
    """
    fig, ax = new_figure(width, height)
    lo, hi = run.truth[:, :2].min(axis=0) - MAP_MARGIN, run.truth[:, :2].max(axis=0) + MAP_MARGIN
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.plot(run.truth[:, 0], run.truth[:, 1], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=3.5, label="true path")
    (truth_dot,) = ax.plot([], [], "o", color=palette.TRUTH, ms=9, zorder=3, label="true position")
    (truth_velocity,) = ax.plot(
        [], [], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=3, zorder=3, label="true velocity (1 s)"
    )
    readings = ax.scatter([], [], s=12, color=palette.MEASUREMENT, alpha=0.7, label="readings", zorder=2)
    (trail,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.6, alpha=0.8, label="estimate so far")
    (ahead,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.0, alpha=0.35, label="estimate ahead")  # solid, pale
    (dot,) = ax.plot([], [], "o", color=palette.ESTIMATE, ms=8, zorder=4, label="estimated position")
    (velocity,) = ax.plot([], [], color=palette.ESTIMATE, lw=2.5, zorder=4, label="estimated velocity")
    # Lightly filled: an ellipse larger than the map still shows, as a tint over all of it.
    fill = (*to_rgb(palette.ESTIMATE), 0.1)
    ring = covariance_ellipse(
        ax, run.z[0], np.eye(2), nsig=2.0, label="2σ ellipse", zorder=4, fill=True, facecolor=fill
    )
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=9, frameon=False)
    return TrackerView(fig, readings, trail, ahead, truth_velocity, truth_dot, velocity, dot, ring, lo, hi)


def velocity_tip(p, vel, lo, hi) -> np.ndarray:
    """Where the velocity line from ``p`` ends: ``ARROW_TIME`` ahead, cut short at the edge ``lo``, ``hi`` of the map.

    An estimate off the map draws no line into it (the tip is ``p`` itself).
    """
    d = ARROW_TIME * np.asarray(vel, float)
    room = np.where(d > 0, hi - p, p - lo)  # distance to the edge the line heads for, per axis
    with np.errstate(divide="ignore"):
        fits = np.where(d != 0, room / np.abs(d), np.inf).min()  # fraction of the line inside the map
    return p + float(np.clip(fits, 0.0, 1.0)) * d


def update_tracker_view(view: TrackerView, model) -> None:
    """Show a filter's run up to a step on a map made by :func:`tracker_view`.

    ``model`` needs ``run`` (the :class:`~kfcourse.sim.TargetRun`), ``est`` (the filter's
    :class:`~kfcourse.sim.TargetEstimates` over it) and ``frame`` (the step shown).
    """
    k, run, est = model.frame, model.run, model.est
    view.readings.set_offsets(run.z[: k + 1])
    view.trail.set_data(est.mu[: k + 1, 0], est.mu[: k + 1, 1])
    view.ahead.set_data(est.mu[k:, 0], est.mu[k:, 1])  # the rest of the run with these settings
    p_true, v_true = run.truth[k, :2], run.truth[k, 2:]
    p_est, v_est = est.mu[k, :2], est.mu[k, 2:]
    view.truth_dot.set_data([p_true[0]], [p_true[1]])
    view.truth_velocity.set_data(*np.column_stack([p_true, p_true + ARROW_TIME * v_true]))
    view.dot.set_data([p_est[0]], [p_est[1]])
    view.velocity.set_data(*np.column_stack([p_est, velocity_tip(p_est, v_est, view.lo, view.hi)]))
    update_covariance_ellipse(view.ring, p_est, est.Sig[k, :2, :2])


# --------------------------------------------------------------------------- the NEES panel


@dataclass(frozen=True)
class NeesView:
    """What :func:`nees_view` drew; :func:`update_nees_view` moves it."""

    fig: Figure
    curve: Line2D  #: teal, the average NEES over time
    y_range: tuple  #: (low, high) of the log axis; values beyond sit on its edge

    @property
    def moving(self) -> list:
        return [self.curve]


def nees_view(t, band, dof: int, n_tracks: int, y_range=(0.5, 500.0), width: float = 8.0, height: float = 3.8):
    """The average NEES over time on a log axis, with the 95 % band of honest filters and the state dimension.

    Introduced in chapter 6.

    Parameters
    ----------
    t : array_like, shape (T,)
        Time of each step (s).
    band : (float, float)
        Where an honest filter's average NEES lies 95 % of the time (:func:`kfcourse.sim.nees_band`).
    dof : int
        The state dimension, the honest average.
    n_tracks : int
        Tracks averaged over (for the legend).
    y_range : (float, float)
        The log axis, > 0.

    Returns
    -------
    NeesView
    """
    t = v.vector(t, "t")
    if t.size < 2:
        raise ValueError(f"t must hold at least 2 times, got {t.size}")
    low, high = axis_range(band, "band")
    y_range = axis_range(y_range, "y_range")
    if y_range[0] <= 0:
        raise ValueError(f"y_range must be positive (a log axis), got {y_range}")
    fig, ax = new_figure(width, height)
    ax.set_yscale("log")
    ax.set_xlim(t[0], t[-1])
    ax.set_ylim(*y_range)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("average NEES")
    ax.axhspan(low, high, color=palette.TRUTH, alpha=0.45, lw=0, label=f"95 % band for {n_tracks} honest runs")
    ax.axhline(dof, color=palette.INK, lw=1.0, ls="--", label=f"{dof} = state dimension")
    (curve,) = ax.plot(
        t, np.full(t.size, float(dof)), color=palette.ESTIMATE, lw=2.2, label="average NEES of the filter"
    )
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=3, fontsize=9)
    return NeesView(fig, curve, y_range)


def update_nees_view(view: NeesView, model) -> None:
    """Show ``model.avg_nees`` (one average per step) on a panel made by :func:`nees_view`.

    Values beyond the axis are drawn on its edge.
    """
    view.curve.set_ydata(np.clip(model.avg_nees, *view.y_range))
