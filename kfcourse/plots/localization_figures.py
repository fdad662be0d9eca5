"""Pictures of EKF localization on a known map (chapter 8): readings and gates in the plane,
the data-association picture, one update's ellipses, and runs with and without the bearing wrap."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib import patheffects
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.figure import Figure
from matplotlib.patches import Ellipse, Polygon, Rectangle
from matplotlib.text import Text

from .. import _validate as v
from . import palette
from .artists import covariance_ellipse, landmarks, robot, update_covariance_ellipse, update_robot
from .style import new_figure

ASSOCIATION_X, ASSOCIATION_Y = (-4.9, 5.6), (-4.6, 5.1)  # m: room for every gate up to 6 sigma on chapter 8's map
ASSOCIATION_ROBOT = 0.2  # m, centre to nose
# The close-up of the robots: the window it shows (m) and where it sits (a fraction of the map's axes), in the
# corner that no gate reaches up to the slider's 6 sigma.
CLOSE_UP_X, CLOSE_UP_Y = (-0.3, 0.65), (-0.75, 0.2)
CLOSE_UP_AT = (0.69, 0.015, 0.3, 0.3)
CLOSE_UP_ROBOT = 0.1  # m: smaller robots in the close-up, so that a few centimetres between them show
CLOSE_UP_ZOOM = CLOSE_UP_AT[2] * (ASSOCIATION_X[1] - ASSOCIATION_X[0]) / (CLOSE_UP_X[1] - CLOSE_UP_X[0])


def reading_points(pose, z) -> np.ndarray:
    r"""Where readings put their objects in the plane, seen from ``pose``.

    A reading :math:`(r, \phi)` taken at pose :math:`(x, y, \theta)` points at
    :math:`(x + r\cos(\theta + \phi),\; y + r\sin(\theta + \phi))`.  Drawn from the
    predicted pose, a reading lands on its landmark exactly when it equals the
    landmark's predicted reading.  Introduced in chapter 8.

    Parameters
    ----------
    pose : array_like, shape (3,)
        ``[x, y, theta]``.
    z : array_like, shape (K, 2) or (2,)
        Readings ``[r, phi]``, one a row.

    Returns
    -------
    ndarray, shape (K, 2)
    """
    x, y, theta = v.vector(pose, "pose", 3)
    z = np.empty((0, 2)) if np.size(z) == 0 else v.matrix(z, "z", cols=2)
    r, phi = z[:, 0], z[:, 1]
    return np.column_stack([x + r * np.cos(theta + phi), y + r * np.sin(theta + phi)])


def gate_outline(pose, z_hat, S, gate: float, n: int = 90) -> np.ndarray:
    r"""A landmark's validation gate drawn in the plane.

    The gate is the ellipse :math:`(z - \hat z)^\top S^{-1} (z - \hat z) = \gamma^2` in
    reading space :math:`(r, \phi)`.  Each of its ``n`` boundary readings is drawn
    with :func:`reading_points` from ``pose``, so a reading lies inside the gate
    exactly when its point lies inside the outline.  Ranges below 0 do not exist
    and are clipped to 0.  Introduced in chapter 8.

    Parameters
    ----------
    pose : array_like, shape (3,)
        The pose the readings are drawn from (the predicted pose).
    z_hat : array_like, shape (2,)
        The landmark's predicted reading ``[r, phi]``.
    S : array_like, shape (2, 2)
        Its innovation covariance.
    gate : float
        :math:`\gamma` (> 0), in standard deviations.
    n : int
        Boundary points (>= 8).

    Returns
    -------
    ndarray, shape (n, 2)
        A closed outline (the last point repeats the first).
    """
    z_hat = v.vector(z_hat, "z_hat", 2)
    S = v.covariance(S, "S", 2)
    gate = v.positive(gate, "gate", "a distance", "standard deviations")
    n = v.whole(n, "n", 8)
    t = np.linspace(0.0, 2 * np.pi, n)
    L = np.linalg.cholesky(S)  # S = L L^T: the unit circle through L is the 1-sigma ellipse
    boundary = z_hat + gate * (L @ np.vstack([np.cos(t), np.sin(t)])).T  # z = z_hat + gamma L [cos t, sin t]
    boundary[:, 0] = np.maximum(boundary[:, 0], 0.0)  # no negative ranges
    return reading_points(pose, boundary)


@dataclass(frozen=True)
class AssociationView:
    """What :func:`association_view` drew; :func:`update_association` moves it.

    The map, the true pose, the predicted pose and its 2-sigma ellipse are drawn once:
    they are the scan's, and a new gate, an extra reading or a new scan does not move them.
    The close-up (an inset in the map's empty corner) shows the robots ``CLOSE_UP_ZOOM``
    times larger, where the estimate's ellipse and its distance from the truth are visible.
    """

    fig: Figure
    close_up: Axes  #: the inset around the robots
    gates: LineCollection  #: each landmark's gate, drawn like the readings (purple, dashed)
    beams: LineCollection  #: from the predicted pose to each reading (faint orange)
    links: LineCollection  #: from each accepted reading to its landmark
    used: PathCollection  #: accepted readings (filled orange)
    unused: PathCollection  #: rejected readings (hollow orange)
    leg_label: Text  #: "leg", beside the leg's reading (hidden without one)
    estimate: Polygon  #: the robot after the updates (teal)
    ellipse: Ellipse  #: the estimate's 2-sigma ellipse (teal, white edge)
    close_estimate: Polygon  #: the same robot in the close-up
    close_ellipse: Ellipse  #: the same ellipse in the close-up

    @property
    def moving(self) -> list:
        """Every artist that changes with the gate or the scan, bottom to top (all above the truth)."""
        return [
            self.gates,
            self.beams,
            self.links,
            self.used,
            self.unused,
            self.leg_label,
            self.estimate,
            self.ellipse,
            self.close_estimate,
            self.close_ellipse,
        ]


def _robots(ax, scan, size: float) -> tuple[Polygon, Ellipse]:
    """The predicted pose (purple) and its 2-sigma ellipse, the true pose (grey dotted outline), and the
    estimate (teal, returned with its 2-sigma ellipse: the update moves them)."""
    robot(ax, scan.mu_bar, color=palette.PREDICTION, size=size, alpha=0.6, zorder=3)
    covariance_ellipse(ax, scan.mu_bar, scan.Sig_bar[:2, :2], nsig=2.0, color=palette.PREDICTION, lw=1.5)
    robot(ax, scan.truth, color=palette.TRUTH, size=size, facecolor="none", lw=1.5, ls=palette.TRUTH_LINE, zorder=4)
    estimate = robot(ax, scan.mu_bar, color=palette.ESTIMATE, size=size, alpha=0.9, zorder=5)
    halo = [patheffects.withStroke(linewidth=3.5, foreground="white")]  # shows on the teal robot too
    ellipse = covariance_ellipse(ax, scan.mu_bar, scan.Sig_bar[:2, :2], nsig=2.0, lw=1.6, path_effects=halo)
    return estimate, ellipse


def association_view(model) -> AssociationView:
    """The chapter 8 map, the predicted pose, the gates, a scan's readings and the estimate after them,
    with a close-up of the robots.

    Introduced in chapter 8.

    Parameters
    ----------
    model : object
        Anything with a scan ``scan`` (:class:`kfcourse.sim.AssociationScan`) and its
        gated update ``result`` (:class:`kfcourse.sim.GatedUpdate`).

    Returns
    -------
    AssociationView
    """
    scan = model.scan
    fig, ax = new_figure(6.2, 5.4)
    ax.set_xlim(*ASSOCIATION_X)
    ax.set_ylim(*ASSOCIATION_Y)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    landmarks(ax, scan.landmarks, labels=True, zorder=2)
    estimate, ellipse = _robots(ax, scan, ASSOCIATION_ROBOT)
    (x0, x1), (y0, y1) = CLOSE_UP_X, CLOSE_UP_Y
    box = {"fill": False, "edgecolor": palette.INK, "lw": 0.8, "zorder": 1}
    ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, **box))  # what the close-up shows
    close_up = ax.inset_axes(CLOSE_UP_AT, xlim=CLOSE_UP_X, ylim=CLOSE_UP_Y, xticks=[], yticks=[])
    close_up.set_aspect("equal")
    close_up.grid(False)
    close_up.set_title(f"close-up of the box, ×{CLOSE_UP_ZOOM:.0f}", fontsize=8, pad=2)
    for side in ("top", "right"):
        close_up.spines[side].set_visible(True)
    close_estimate, close_ellipse = _robots(close_up, scan, CLOSE_UP_ROBOT)

    def lines(**style) -> LineCollection:
        return ax.add_collection(LineCollection([], **style), autolim=False)

    gates = lines(colors=palette.PREDICTION, lw=1.0, linestyles="--", alpha=0.8, zorder=1)
    beams = lines(colors=palette.MEASUREMENT, lw=0.8, alpha=0.3, zorder=1)
    links = lines(colors=palette.MEASUREMENT, lw=1.2, alpha=0.9, zorder=3)
    used = ax.scatter([], [], s=40, color=palette.MEASUREMENT, zorder=4)
    unused = ax.scatter([], [], s=60, facecolors="white", edgecolors=palette.MEASUREMENT, linewidths=2.0, zorder=4)
    leg_label = ax.text(0, 0, "leg", color=palette.MEASUREMENT_TEXT, fontsize=9, ha="left", va="bottom", zorder=5)
    view = AssociationView(
        fig, close_up, gates, beams, links, used, unused, leg_label, estimate, ellipse, close_estimate, close_ellipse
    )
    update_association(view, model)
    return view


def update_association(view: AssociationView, model) -> None:
    """Show the model's gate, readings and estimate on a picture made by :func:`association_view`.

    Each reading is drawn where it points from the predicted pose (:func:`reading_points`),
    each gate with :func:`gate_outline`, so a reading's point lies inside a gate exactly
    when the reading passes it.
    """
    scan, res = model.scan, model.result
    gates = [gate_outline(scan.mu_bar, z_hat, S, res.gate) for z_hat, S in zip(scan.z_hat, scan.S, strict=True)]
    view.gates.set_segments(gates)
    points = reading_points(scan.mu_bar, scan.z)
    accepted = res.accepted
    view.beams.set_segments([np.array([scan.mu_bar[:2], p]) for p in points])
    matched = [(p, scan.landmarks[j]) for p, j in zip(points, res.match, strict=True) if j >= 0]
    view.links.set_segments([np.array(pair) for pair in matched])
    view.used.set_offsets(points[accepted].reshape(-1, 2))
    view.unused.set_offsets(points[~accepted].reshape(-1, 2))
    leg = np.flatnonzero(np.asarray(scan.source) < 0)  # the reading that no landmark made, if any
    view.leg_label.set_visible(leg.size > 0)
    if leg.size:
        view.leg_label.set_position(points[leg[0]] + [0.12, 0.05])
    for estimate, ellipse in ((view.estimate, view.ellipse), (view.close_estimate, view.close_ellipse)):
        update_robot(estimate, res.mu)
        update_covariance_ellipse(ellipse, res.mu, res.Sig[:2, :2])


def update_ellipse_chart(mu_bar, Sig_bar, mu, Sig, landmark, nsig: float = 2.0):
    """Chapter 8: one EKF update from a single landmark, before and after.

    The predicted pose and its ``nsig``-sigma position ellipse (purple), the
    updated pose and its ellipse (teal), the landmark (purple square) and the
    line of sight from the predicted pose to it (dotted).  The update moves the
    pose toward the landmark and shrinks the ellipse along the line of sight.

    Introduced in chapter 8.

    Parameters
    ----------
    mu_bar, mu : array_like, shape (3,)
        Pose before and after the update.
    Sig_bar, Sig : array_like, shape (3, 3)
        Their covariances.
    landmark : array_like, shape (2,)
    nsig : float
        Size of the ellipses in standard deviations (> 0).

    Returns
    -------
    matplotlib.figure.Figure
    """
    mu_bar, mu = v.vector(mu_bar, "mu_bar", 3), v.vector(mu, "mu", 3)
    Sig_bar, Sig = v.covariance(Sig_bar, "Sig_bar", 3), v.covariance(Sig, "Sig", 3)
    m = v.vector(landmark, "landmark", 2)
    nsig = v.positive(nsig, "nsig", "a size", "standard deviations")
    fig, ax = new_figure(6.0, 5.0)
    ax.plot([mu_bar[0], m[0]], [mu_bar[1], m[1]], color=palette.INK, lw=1, ls=":", label="line of sight")
    covariance_ellipse(ax, mu_bar, Sig_bar[:2, :2], nsig=nsig, color=palette.PREDICTION, label="before (predicted)")
    covariance_ellipse(ax, mu, Sig[:2, :2], nsig=nsig, color=palette.ESTIMATE, label="after the update")
    robot(ax, mu_bar, color=palette.PREDICTION, size=0.12, alpha=0.7)
    robot(ax, mu, color=palette.ESTIMATE, size=0.12)
    ax.annotate(
        "", xy=mu[:2], xytext=mu_bar[:2], arrowprops={"arrowstyle": "->", "color": palette.INK, "lw": 1.5}, zorder=5
    )
    landmarks(ax, [m], labels=["landmark"])
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{nsig:g}-sigma position ellipses, before and after one reading", fontsize=10)
    ax.legend(loc="upper left", fontsize=8)
    return fig


def wrap_runs_chart(wrapped, unwrapped):
    r"""Chapter 8: the same drive filtered with the bearing innovation wrapped and not wrapped.

    Left and middle: the map (purple squares), the true path (grey) and the
    estimate (teal), one panel per run, titled with its largest and final error;
    a cross marks the true pose at the first step where the two runs part.
    Right: the position error of both runs over time (teal; solid: wrapped,
    dashed: not wrapped) and how far each run's 3-sigma position ellipse reaches
    from its estimate, :math:`3\sqrt{\lambda_{\max}(\Sigma_{xy})}` (grey).  Where a
    run's error is above its reach, the truth lies outside its 3-sigma ellipse.
    The ellipses themselves are a few centimetres across, too small to see on
    the map, so they are shown by their reach.

    Introduced in chapter 8.

    Parameters
    ----------
    wrapped, unwrapped : object with ``t, truth, landmarks, mu, Sig, error``
        Run records such as the ones :func:`kfcourse.sim.landmark_loop` returns,
        of the same drive.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax_a, ax_b, ax_e) = new_figure(11.0, 3.9, ncols=3, gridspec_kw={"width_ratios": [1, 1, 1.1]})
    parted = np.flatnonzero(np.any(np.asarray(wrapped.mu) != np.asarray(unwrapped.mu), axis=1))
    for ax, run, name in ((ax_a, wrapped, "bearing innovation wrapped"), (ax_b, unwrapped, "not wrapped")):
        ax.plot(run.truth[:, 0], run.truth[:, 1], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=2.5, label="truth")
        ax.plot(run.mu[:, 0], run.mu[:, 1], color=palette.ESTIMATE, lw=1.5, label="EKF estimate")
        landmarks(ax, run.landmarks)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x (m)")
        ax.set_title(f"{name}\nlargest error {run.error.max():.2f} m, final {run.error[-1]:.2f} m", fontsize=10)
    if parted.size:
        k0 = parted[0]
        (mark,) = ax_b.plot(*unwrapped.truth[k0, :2], "x", color=palette.INK, ms=9, mew=2, label="where the runs part")
        ax_b.legend(handles=[mark], loc="lower left", fontsize=8)
    ax_a.set_ylabel("y (m)")
    ax_a.legend(loc="upper left", fontsize=8)
    for run, ls, name in ((wrapped, "-", "wrapped"), (unwrapped, "--", "not wrapped")):
        reach = 3.0 * np.sqrt(np.linalg.eigvalsh(np.asarray(run.Sig)[:, :2, :2])[:, -1])  # 3 sqrt(largest eigenvalue)
        ax_e.plot(run.t, run.error, color=palette.ESTIMATE, lw=2, ls=ls, label=f"error, {name}")
        ax_e.plot(run.t, reach, color=palette.INK, lw=1, ls=ls, alpha=0.6, label=f"3σ ellipse's reach, {name}")
    ax_e.set_xlabel("time (s)")
    ax_e.set_ylabel("distance (m)")
    ax_e.legend(loc="upper left", fontsize=8)
    return fig
