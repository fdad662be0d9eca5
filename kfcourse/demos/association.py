"""Chapter 8: which reading belongs to which landmark?  Mahalanobis distance and the validation gate."""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets
import numpy as np
from matplotlib.collections import LineCollection

from ..plots import palette
from ..plots.artists import covariance_ellipse, landmarks, robot, update_covariance_ellipse, update_robot
from ..plots.localization import gate_outline, reading_points
from ..plots.style import FigureRenderer, new_figure
from ..sim.association import association_scan, gated_update
from ._base import Demo, slider

GATE = 3.0  # standard deviations: the default validation gate
GATE_RANGE = (1.0, 6.0)
LEG_OPTIONS = ("none", "a pedestrian's leg")
X_LIM, Y_LIM = (-4.9, 5.6), (-4.6, 5.1)  # m: wide enough for every gate up to the slider's 6 sigma
ROBOT_SIZE = 0.2  # m, centre to nose: small enough that the 2-sigma ellipse after the update shows


class AssociationModel:
    """Model: one scan on the chapter 8 map, the gate, and the EKF estimate after the accepted readings.

    Attributes
    ----------
    scan : AssociationScan
        The predicted belief, the map and the readings (with the leg's when ``leg``).
    gate : float
        The validation gate gamma (standard deviations).
    leg : bool
        The sensor also sees a pedestrian's leg.
    result : GatedUpdate
        Every reading matched or rejected at ``gate``, and the estimate after the updates.
    """

    def __init__(self, seed: int = 0, gate: float = GATE, leg: bool = False):
        self.seed, self.gate, self.leg = seed, float(gate), bool(leg)
        self.scan = association_scan(seed, leg=self.leg)
        self.result = gated_update(self.scan, self.gate)

    def set_gate(self, gate: float) -> None:
        self.gate = float(gate)
        self.result = gated_update(self.scan, self.gate)

    def set_leg(self, option: str) -> None:
        self.leg = option == LEG_OPTIONS[1]
        self.scan = association_scan(self.seed, leg=self.leg)
        self.result = gated_update(self.scan, self.gate)

    def kept(self) -> float:
        """Share of true readings a gate of this size keeps: P(chi^2 with 2 dof <= gamma^2)."""
        return 1.0 - float(np.exp(-0.5 * self.gate**2))


CELL = "<td style='padding:0 12px 0 0'>{}</td>"


def _readout(model: AssociationModel) -> str:
    """The readout under the picture: each reading's nearest landmark, its distance, the verdict; the errors."""
    scan, res = model.scan, model.result
    rows = [CELL.format("reading") + CELL.format("nearest landmark") + CELL.format("d (σ)") + CELL.format("")]
    for k, (d, j) in enumerate(zip(res.distances, res.match, strict=True)):
        nearest = int(np.argmin(d))
        name = "the leg" if scan.source[k] < 0 else f"reading {k}"
        verdict = f"accepted as landmark {j}" if j >= 0 else "<b>rejected</b>"
        rows.append("".join(CELL.format(x) for x in (name, nearest, f"{d[nearest]:.2f}", verdict)))
    table = "<table style='font-size:12px'>" + "".join(f"<tr>{row}</tr>" for row in rows) + "</table>"
    return (
        f"<div style='font-size:13px;line-height:1.5'>gate γ = {model.gate:.1f}σ: a true reading falls outside it "
        f"{100 * (1 - model.kept()):.2g} % of the time. {table}"
        f"Position error: predicted <b>{res.error_bar:.2f} m</b>, corrected with {int(res.accepted.sum())} of "
        f"{res.match.size} readings <b style='color:{palette.ESTIMATE}'>{res.error:.2f} m</b>.</div>"
    )


def _picture(model: AssociationModel) -> tuple[FigureRenderer, Callable[[], None]]:
    """The map, the predicted pose, the gates, the scan's readings and the estimate after them.

    Returns
    -------
    (renderer, draw)
        ``draw()`` moves the gates, readings and estimate to the model's gate and scan.
    """
    scan = model.scan
    fig, ax = new_figure(6.2, 5.4)
    ax.set_xlim(*X_LIM)
    ax.set_ylim(*Y_LIM)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")

    # Static: the map, the truth, the predicted pose and its 2-sigma ellipse.
    landmarks(ax, scan.landmarks, labels=True, zorder=2)
    robot(ax, scan.mu_bar, color=palette.PREDICTION, size=ROBOT_SIZE, alpha=0.8, zorder=3)
    covariance_ellipse(ax, scan.mu_bar, scan.Sig_bar[:2, :2], nsig=2.0, color=palette.PREDICTION, lw=1.5)

    # Dynamic: gates, links reading -> landmark, readings, the leg's label, the estimate.
    gates = LineCollection([], colors=palette.PREDICTION, lw=1.0, linestyles="--", alpha=0.8, zorder=1)
    ax.add_collection(gates, autolim=False)
    beams = LineCollection([], colors=palette.MEASUREMENT, lw=0.8, alpha=0.3, zorder=1)
    ax.add_collection(beams, autolim=False)
    links = LineCollection([], colors=palette.MEASUREMENT, lw=1.2, alpha=0.9, zorder=3)
    ax.add_collection(links, autolim=False)
    used = ax.scatter([], [], s=40, color=palette.MEASUREMENT, zorder=4)
    unused = ax.scatter([], [], s=60, facecolors="white", edgecolors=palette.MEASUREMENT, linewidths=2.0, zorder=4)
    leg_label = ax.text(0, 0, "leg", color=palette.MEASUREMENT, fontsize=9, ha="left", va="bottom", zorder=5)
    estimate = robot(ax, scan.mu_bar, color=palette.ESTIMATE, size=ROBOT_SIZE, alpha=0.5, zorder=5)
    # The truth is drawn over the estimate (as a dynamic artist, though it never moves) so the estimate never
    # hides it, and the estimate's ellipse over both, so it shows even when it is smaller than the triangle.
    truth = robot(ax, scan.truth, color=palette.TRUTH, size=ROBOT_SIZE, facecolor="none", lw=2.0, zorder=6)
    estimate_ellipse = covariance_ellipse(ax, scan.mu_bar, scan.Sig_bar[:2, :2], nsig=2.0, lw=2.0, zorder=7)
    renderer = FigureRenderer(fig, [gates, beams, links, used, unused, leg_label, estimate, truth, estimate_ellipse])

    def draw() -> None:
        scan, res = model.scan, model.result
        gates.set_segments(
            [gate_outline(scan.mu_bar, z_hat, S, res.gate) for z_hat, S in zip(scan.z_hat, scan.S, strict=True)]
        )
        points = reading_points(scan.mu_bar, scan.z)  # each reading drawn from the predicted pose
        accepted = res.accepted
        beams.set_segments([np.array([scan.mu_bar[:2], p]) for p in points])
        links.set_segments([np.array([p, scan.landmarks[j]]) for p, j in zip(points, res.match, strict=True) if j >= 0])
        used.set_offsets(points[accepted] if accepted.any() else np.empty((0, 2)))
        unused.set_offsets(points[~accepted] if (~accepted).any() else np.empty((0, 2)))
        leg_label.set_visible(model.leg)
        if model.leg:
            leg_label.set_position(points[-1] + [0.12, 0.05])
        update_robot(estimate, res.mu)
        update_covariance_ellipse(estimate_ellipse, res.mu, res.Sig[:2, :2])

    return renderer, draw


def data_association(seed: int = 0) -> Demo:
    """Demo "data association" (chapter 8): a scan of unlabelled readings, the map, and a
    validation gate that decides which readings are landmarks.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = AssociationModel(seed=seed)
    renderer, draw_picture = _picture(model)
    readout = widgets.HTML()  # text under the picture: no glyphs to render into the PNG
    readout.add_class("kf-readout")

    def draw() -> None:
        draw_picture()
        readout.value = _readout(model)

    caption = (
        "<b>Data association.</b> Purple: the map (numbered squares) and the predicted pose with its 2σ ellipse; "
        "purple dashed: each landmark's gate, the readings within γ standard deviations (Mahalanobis) of its "
        "predicted reading, drawn like the readings. Orange: this scan's readings, each drawn where it points from "
        "the predicted pose; filled and joined to a landmark if accepted, hollow if rejected. Teal: the EKF estimate "
        "after the accepted readings, with its 2σ ellipse (drawn on top). Grey outline: the true pose. "
        "Slider: the gate γ; toggle: add a pedestrian's leg to the scan."
    )
    gate_slider = slider(widgets.FloatSlider, "gate γ (σ)", model.gate, *GATE_RANGE, 0.1, readout_format=".1f")
    leg_toggle = widgets.ToggleButtons(
        options=list(LEG_OPTIONS),
        value=LEG_OPTIONS[0],
        description="extra reading",
        style={"description_width": "initial", "button_width": "auto"},
    )
    controls_row = widgets.HBox([gate_slider, leg_toggle], layout=widgets.Layout(flex_flow="row wrap"))  # wraps
    return Demo(
        name="data-association",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={"gate": (gate_slider, model.set_gate), "leg": (leg_toggle, model.set_leg)},
        layout=[readout, controls_row],
    )
