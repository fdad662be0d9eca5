r"""The real run (chapter 12): a filter over a Plaza log, on the plaza at the scale of the data.

The map shows the four beacons (purple squares), the true path (grey, dotted, the whole run) and the
true robot (grey), the ranges that arrived in the second shown as orange arcs of their circles about
their beacons (dash-dot: used; dotted and thin: refused by the gate), and the filter's estimate (teal):
its trail over the last :data:`TRAIL` seconds, the estimated robot and its 3-sigma position ellipse.  The smoother's
path, when shown, is the whole run at once, a wide pale teal band.  The legend names only what is drawn: the
refused ranges when the run refused some, the estimate once its run is ready, the smoother's path when shown.
Under the map a strip shows the position NEES of every pose on a log scale, with a cursor at the time shown,
against the band where an honest filter's NEES lies at 95 % of its poses (:data:`~kfcourse.sim.NEES_BAND`,
chi-square with 2 degrees of freedom: 0.05 to 7.4) and its average, 2 (dotted).

:func:`real_run_view` draws the whole picture for a demo's model, :func:`update_real_run_view` shows the
model's run and time on it again.  The model is anything with

- ``log``: the :class:`~kfcourse.data.PlazaLog` (its beacons and ground truth set the map);
- ``run``: a record with ``t, mu, Sig, nees`` (:class:`~kfcourse.sim.RangeRun` or
  :class:`~kfcourse.sim.RangeParticleRun`), or ``None`` while the filter is still running;
- ``smooth``: such a record of the smoother, or ``None`` when the smoother is not shown;
- ``row``: the pose shown (a row of ``run``);
- ``arrivals()``: the ranges of the second shown, as ``(beacons (R, 2), ranges (R,), used (R,))``;
- ``busy()``: what the filter is doing when ``run`` is ``None`` (a short text), else "".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Polygon
from matplotlib.text import Text

from ..sim.scores import NEES_BAND
from . import palette
from .artists import covariance_ellipse, landmarks, robot, update_covariance_ellipse, update_robot
from .style import new_figure

__all__ = ["RealRunView", "range_arcs", "real_run_view", "update_real_run_view"]

NSIG = 3.0  # the map's ellipse is 3-sigma: the truth inside it is a position NEES of at most 9 (kf.sim.RangeRun.inside)
MAP_MARGIN = 6.0  # m of room around the beacons and the true path
ROBOT_SIZE = 1.6  # m from the robot's centre to its nose: the plaza is 80 m across
TRUTH_SIZE = 2.2  # m: the true robot is drawn larger, so it shows round an estimate on top of it
ARC_LENGTH = 12.0  # m: each range's arc, centred on the true robot as seen from its beacon
TRAIL = 30.0  # s of the estimate's path drawn behind it: the whole run is in the strip
ARC_POINTS = 24
NEES_LIMITS = (1e-2, 1e4)  # the strip's fixed log scale: a change of run never redraws its axes
WIDTH = 5.75  # inches: 460 px at the figure's 80 dpi
STRIP_HEIGHT = 1.05  # inches
LEGEND_HEIGHT = 0.45  # inches above the map for its legend


def range_arcs(beacons, ranges, centre) -> np.ndarray:
    """(R, ARC_POINTS, 2) an arc of each range's circle (radius the range, about its beacon), :data:`ARC_LENGTH`
    long about the direction from the beacon to ``centre`` (x, y): where the range says the robot is."""
    b = np.asarray(beacons, float).reshape(-1, 2)
    r = np.asarray(ranges, float).reshape(-1)
    bearing = np.arctan2(centre[1] - b[:, 1], centre[0] - b[:, 0])
    half = 0.5 * ARC_LENGTH / np.maximum(r, ARC_LENGTH)  # rad; at most half a radian for a short range
    angles = bearing[:, None] + half[:, None] * np.linspace(-1.0, 1.0, ARC_POINTS)
    return np.stack([b[:, :1] + r[:, None] * np.cos(angles), b[:, 1:] + r[:, None] * np.sin(angles)], axis=-1)


@dataclass(frozen=True)
class RealRunView:
    """What :func:`real_run_view` drew; :func:`update_real_run_view` moves it."""

    fig: Figure
    smooth: Line2D  #: the smoother's path, the whole run (empty when not shown)
    used: LineCollection  #: arcs of the ranges of the second shown that the filter used
    refused: LineCollection  #: arcs of those the gate refused
    trail: Line2D  #: the estimate's path over the last TRAIL seconds
    truth_robot: Polygon
    robot: Polygon
    ring: Ellipse  #: NSIG-sigma
    note: Text  #: what the filter is doing while its run is not ready, else nothing
    nees: Line2D  #: the position NEES of every pose
    smooth_nees: Line2D  #: the smoother's (empty when not shown)
    cursor: Line2D  #: the time shown, on the strip
    keys: dict  #: the legend's entries by label, in their order: only those drawn are shown (:func:`_legend`)

    @property
    def moving(self) -> list:
        """Every artist that changes with the time shown or the run, bottom to top."""
        return [
            self.smooth,
            self.used,
            self.refused,
            self.trail,
            self.truth_robot,
            self.robot,
            self.ring,
            self.note,
            self.smooth_nees,
            self.nees,
            self.cursor,
        ]


def real_run_view(model) -> RealRunView:
    """The plaza above, the NEES strip under it, at the model's run and time (see the module's docstring).

    Introduced in chapter 12.
    """
    log = model.log
    points = np.vstack([log.beacons, log.truth[:, :2]])
    lo, hi = points.min(axis=0) - MAP_MARGIN, points.max(axis=0) + MAP_MARGIN
    map_height = (WIDTH - 0.8) * (hi[1] - lo[1]) / (hi[0] - lo[0]) + 0.4  # metres square, room for the x label
    fig, (ax, strip) = new_figure(
        WIDTH,
        map_height + STRIP_HEIGHT + LEGEND_HEIGHT,
        nrows=2,
        gridspec_kw={"height_ratios": [map_height, STRIP_HEIGHT]},
    )
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)", labelpad=1)
    ax.set_ylabel("y (m)")
    landmarks(ax, log.beacons, labels=True, zorder=2)
    truth_style = {"color": palette.TRUTH, "ls": palette.TRUTH_LINE, "lw": palette.TRUTH_WIDTH}
    ax.plot(log.truth[:, 0], log.truth[:, 1], **truth_style)
    (smooth,) = ax.plot([], [], color=palette.ESTIMATE, lw=5, alpha=0.3, solid_capstyle="round")
    used = LineCollection([], colors=palette.MEASUREMENT, linestyles=palette.MEASUREMENT_LINE, lw=1.6, zorder=3)
    refused = LineCollection([], colors=palette.MEASUREMENT, linestyles=":", lw=1.0, zorder=3)
    for arcs in (used, refused):
        ax.add_collection(arcs, autolim=False)
    (trail,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.3, zorder=4)
    pose = log.truth[0]
    edged = {"edgecolor": palette.TRUTH_TEXT, "lw": 1.0}  # the grey robot shows on its own grey path
    truth_robot = robot(ax, pose, color=palette.TRUTH, size=TRUTH_SIZE, alpha=0.8, zorder=5, **edged)
    est = robot(ax, pose, color=palette.ESTIMATE, facecolor=to_rgba(palette.ESTIMATE, 0.3), size=ROBOT_SIZE, zorder=6)
    ring = covariance_ellipse(ax, pose, np.eye(2), nsig=NSIG, lw=1.8, zorder=7)
    note = ax.text(
        0.5, 0.5, "", transform=ax.transAxes, ha="center", va="center", fontsize=11, weight="bold", color=palette.INK
    )
    keys = {
        "beacon": ax.scatter([], [], marker="s", color=palette.LANDMARK, s=40),
        "truth": Line2D([], [], **truth_style),
        "range used": Line2D([], [], color=palette.MEASUREMENT, ls=palette.MEASUREMENT_LINE, lw=1.6),
        "range refused": Line2D([], [], color=palette.MEASUREMENT, ls=":", lw=1.0),
        f"estimate, last {TRAIL:g} s": Line2D([], [], color=palette.ESTIMATE, lw=1.3),
        f"{NSIG:g}σ": Ellipse((0, 0), 1, 1, fill=False, edgecolor=palette.ESTIMATE, lw=1.8),
        "smoothed": Line2D([], [], color=palette.ESTIMATE, lw=5, alpha=0.3),
    }
    strip.set_yscale("log")
    strip.set_ylim(*NEES_LIMITS)
    strip.set_xlim(0.0, float(log.t_truth[-1]))
    strip.set_xlabel("t (s)", labelpad=1)
    strip.set_ylabel("NEES")
    strip.axhspan(*NEES_BAND, color=palette.ESTIMATE, alpha=0.12, lw=0)  # one pose's NEES, 95 % of the time
    strip.axhline(2.0, color=palette.ESTIMATE, lw=0.8, ls=":")  # an honest filter's average
    (smooth_nees,) = strip.plot([], [], color=palette.ESTIMATE, lw=2.5, alpha=0.3)
    (nees,) = strip.plot([], [], color=palette.ESTIMATE, lw=0.9)
    cursor = strip.axvline(0.0, color=palette.INK, lw=1.0)
    view = RealRunView(fig, smooth, used, refused, trail, truth_robot, est, ring, note, nees, smooth_nees, cursor, keys)
    update_real_run_view(view, model)
    return view


def _clipped(values: np.ndarray) -> np.ndarray:
    """A NEES inside the strip's limits (an infinite one, a flat ellipse the truth left, at the top)."""
    return np.clip(np.nan_to_num(values, nan=NEES_LIMITS[1], posinf=NEES_LIMITS[1]), *NEES_LIMITS)


def _legend(view: RealRunView, run, smooth) -> None:
    """The map's legend with an entry for each thing drawn: the refused ranges only when the run refused some
    (in any second: the legend stays as the time moves), the estimate and its ellipse once the run is ready, the
    smoother's path when shown.  Made again only when its entries change (a change of run): a new legend is a
    change to the picture's background, which is drawn again in full."""
    ax = view.trail.axes
    hidden = set()
    if run is None:
        hidden |= {label for label in view.keys if label.startswith("estimate") or label.endswith("σ")}
    if run is None or not hasattr(run, "used") or run.used.all():
        hidden.add("range refused")
    if smooth is None:
        hidden.add("smoothed")
    labels = [label for label in view.keys if label not in hidden]
    legend = ax.get_legend()
    if legend is not None and [text.get_text() for text in legend.get_texts()] == labels:
        return
    handles = [view.keys[label] for label in labels]
    ax.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=4, fontsize=8, columnspacing=1.0)


def update_real_run_view(view: RealRunView, model) -> None:
    """Show the model's run at its pose ``row`` on a picture made by :func:`real_run_view`."""
    log, run, k = model.log, model.run, model.row
    truth = log.truth[k]
    update_robot(view.truth_robot, truth)
    beacons, ranges, used = model.arrivals()
    arcs = range_arcs(beacons, ranges, truth)
    view.used.set_segments(list(arcs[used]))
    view.refused.set_segments(list(arcs[~used]))
    view.cursor.set_xdata([log.t_truth[k]] * 2)
    estimate = (view.trail, view.robot, view.ring, view.nees)
    for artist in estimate:
        artist.set_visible(run is not None)
    view.note.set_text(model.busy())
    if run is not None:
        first = int(np.searchsorted(run.t, run.t[k] - TRAIL))
        view.trail.set_data(run.mu[first : k + 1, 0], run.mu[first : k + 1, 1])
        update_robot(view.robot, run.mu[k, :3])
        update_covariance_ellipse(view.ring, run.mu[k], np.asarray(run.Sig[k])[:2, :2])
        view.nees.set_data(run.t, _clipped(run.nees))
    smooth = model.smooth
    for artist in (view.smooth, view.smooth_nees):
        artist.set_visible(smooth is not None)
    if smooth is not None:
        view.smooth.set_data(smooth.mu[:, 0], smooth.mu[:, 1])
        view.smooth_nees.set_data(smooth.t, _clipped(smooth.nees))
    _legend(view, run, smooth)
