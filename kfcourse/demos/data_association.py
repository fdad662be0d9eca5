"""Chapter 8: which reading belongs to which landmark?  Mahalanobis distance and the validation gate."""

from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.localization_figures import association_view, update_association
from ..plots.style import FigureRenderer
from ..sim.scan import association_scan, gated_update
from ._base import Demo, button, slider

GATE = 3.0  # standard deviations: the default validation gate
GATE_RANGE = (1.0, 6.0)
LEG_OPTIONS = ("none", "a pedestrian's leg")
IMAGE_WIDTH = 500  # CSS px at most: the picture beside its controls fits a laptop's notebook (848 px wide)
COLUMN_WIDTH = 340  # CSS px: the controls and the readout beside the picture


@dataclass(frozen=True)
class ReadingFacts:
    """One reading of the scan: where the gate put it."""

    index: int  # its place in the scan
    leg: bool  # the pedestrian's leg, not a landmark's reading
    landmark: int  # the landmark it was matched to; if rejected, its nearest
    distance: float  # its Mahalanobis distance from that landmark's predicted reading (σ)
    accepted: bool  # inside the gate: used in the update


@dataclass(frozen=True)
class ScanFacts:
    """What the description and the readout say about the scan, computed once by :meth:`AssociationModel.facts`."""

    seed: int
    gate: float  # γ (σ)
    readings: tuple[ReadingFacts, ...]
    passed: int  # readings inside the gate
    error_before: float  # position error of the prediction (m)
    error_after: float  # of the estimate after the accepted readings (m)
    outside: float  # share of true readings the gate rejects: P(chi^2 with 2 dof > gamma^2)


class AssociationModel:
    """Model: one scan on the chapter 8 map, the gate, and the EKF estimate after the accepted readings.

    Attributes
    ----------
    seed : int
        Seed of the scan's reading noise; "New scan" moves on to the next one.
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

    def new_scan(self) -> None:
        """The next seed: the same robot, map and gate, new noise on every reading."""
        self.seed += 1
        self.scan = association_scan(self.seed, leg=self.leg)
        self.result = gated_update(self.scan, self.gate)

    def kept(self) -> float:
        """Share of true readings a gate of this size keeps: P(chi^2 with 2 dof <= gamma^2)."""
        return 1.0 - float(np.exp(-0.5 * self.gate**2))

    def nearest(self, k: int) -> tuple[int, float]:
        """The landmark reading ``k`` was matched to (if rejected: its nearest) and its distance from it (σ)."""
        d, j = self.result.distances[k], int(self.result.match[k])
        j = j if j >= 0 else int(np.argmin(d))
        return j, float(d[j])

    def facts(self) -> ScanFacts:
        """Every reading's landmark, distance and verdict, the count that passes, and the errors before and
        after: what the description and the readout both say."""
        res, source = self.result, self.scan.source
        readings = []
        for k in range(res.match.size):
            landmark, distance = self.nearest(k)
            leg, accepted = bool(source[k] < 0), bool(res.accepted[k])
            readings.append(ReadingFacts(k, leg, landmark, distance, accepted))
        return ScanFacts(
            seed=self.seed,
            gate=self.gate,
            readings=tuple(readings),
            passed=int(res.accepted.sum()),
            error_before=res.error_bar,
            error_after=res.error,
            outside=1.0 - self.kept(),
        )

    def describe(self) -> str:
        """What the picture shows: how many readings pass the gate, what became of the leg's reading,
        and how far the accepted ones move the estimate from the truth."""
        f = self.facts()
        notes = []
        lost = [r for r in f.readings if not r.leg and not r.accepted]  # landmarks' own readings turned away
        if len(lost) > 2:
            notes.append(f"{len(lost)} landmark readings rejected")
        else:  # one or two: which, and how far outside the gate
            for r in lost:
                notes.append(f"reading {r.index} rejected at {r.distance:.2f}σ from landmark {r.landmark}")
        for r in f.readings:
            if r.leg:
                taken = (
                    f"taken for landmark {r.landmark} at {r.distance:.2f}σ"
                    if r.accepted
                    else f"rejected at {r.distance:.2f}σ from landmark {r.landmark}"
                )
                notes.append(f"the pedestrian's leg {taken}")
        said = f" ({', '.join(notes)})" if notes else ""
        if f.passed == 0:
            effect = f"the estimate stays the prediction, {f.error_before:.2f} m from the truth"
        else:
            effect = f"the update takes the position error from {f.error_before:.2f} m to {f.error_after:.2f} m"
        return (
            f"Scan {f.seed}, gate γ = {f.gate:.1f}σ: {f.passed} of {len(f.readings)} readings pass{said}, and {effect}."
        )


CELL = "<td style='padding:0 10px 0 0'>{}</td>"


def _readout(model: AssociationModel) -> str:
    """The readout beside the picture: each reading's nearest landmark, its distance, the verdict; the errors."""
    f = model.facts()
    rows = ["".join(CELL.format(x) for x in ("reading", "nearest", "d (σ)", ""))]
    for r in f.readings:
        name = "the leg" if r.leg else f"reading {r.index}"
        verdict = f"→ landmark {r.landmark}" if r.accepted else "<b>rejected</b>"
        rows.append("".join(CELL.format(x) for x in (name, r.landmark, f"{r.distance:.2f}", verdict)))
    table = "<table style='font-size:12px;margin:4px 0'>" + "".join(f"<tr>{row}</tr>" for row in rows) + "</table>"
    return (
        f"<div style='font-size:13px;line-height:1.5'>Scan {f.seed}. Gate γ = {f.gate:.1f}σ: a true reading "
        f"falls outside it {100 * f.outside:.2g} % of the time. {table}"
        f"Position error: predicted <b>{f.error_before:.2f} m</b>; corrected with {f.passed} of "
        f"{len(f.readings)} readings <b style='color:{palette.ESTIMATE_TEXT}'>{f.error_after:.2f} m</b>.</div>"
    )


CAPTION = (
    "<b>Data association.</b> Purple: the map (numbered squares), the predicted pose and its 2σ ellipse, and each "
    "landmark's gate (dashed): the readings within γ standard deviations of its predicted reading. Orange: the "
    "scan's readings, drawn from the predicted pose; filled and joined to a landmark if accepted, hollow if "
    "rejected. Teal: the EKF estimate after the accepted readings and its 2σ ellipse, drawn on top; grey dotted "
    "outline: the true pose. The box around the robots is shown enlarged bottom right. Slider: the gate γ; toggle: "
    "a pedestrian's leg in the scan; <i>New scan</i>: the same scene with new reading noise."
)


def data_association(seed: int = 0) -> Demo:
    """Demo "data association" (chapter 8): a scan of unlabelled readings, the map, and a
    validation gate that decides which readings are landmarks.

    The slider sets the gate γ, the toggle adds a pedestrian's leg to the scan, "New
    scan" draws new reading noise; the readout beside the picture lists each reading's
    nearest landmark and verdict.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = AssociationModel(seed=seed)
    view = association_view(model)
    readout = widgets.HTML(layout=widgets.Layout(width=f"{COLUMN_WIDTH}px"))  # text, not glyphs in the picture
    readout.add_class("kf-readout")

    def draw() -> None:
        update_association(view, model)
        readout.value = _readout(model)

    gate = slider(widgets.FloatSlider, "gate γ (σ)", model.gate, *GATE_RANGE, 0.1, readout_format=".1f")
    leg = widgets.ToggleButtons(
        options=list(LEG_OPTIONS),
        value=LEG_OPTIONS[0],
        description="extra reading",
        style={"description_width": "initial", "button_width": "auto"},
    )
    demo = Demo(
        name="data-association",
        caption=CAPTION,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=draw,
        describe=model.describe,
        controls={
            "gate": (gate, model.set_gate),
            "leg": (leg, model.set_leg),
            "new_scan": (button("New scan", icon="refresh", tooltip="New noise on every reading"), model.new_scan),
        },
        beside=["gate", "leg", "new_scan", readout],
        display_width=IMAGE_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
