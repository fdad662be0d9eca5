"""Chapter 10: a robot localizing itself round a loop of landmarks, and how to break it."""

from __future__ import annotations

import html
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.loop import loop_view, update_loop_view
from ..plots.loop_strips import NSIG
from ..plots.style import FigureRenderer
from ..sim.landmark_lap import landmark_loop as run_loop
from ..sim.scores import HONEST_NEES
from ._base import Demo, button, shown, slider

FIRST_FRAME = 60  # the step shown first: on the top straight, two landmarks in view
NOISE_RANGE = (-1.0, 1.0)  # log10 of the world's noise scales the sliders reach: 0.1x to 10x
TRUST_RANGE = (-2.0, 2.0)  # log10 of the filter's R and Q against the world's: 0.01x to 100x
FILTERS = ("EKF", "UKF")  # the course's filters; the run takes them in lower case
YOURS = "yours"  # the choice that runs the student's own step
IMAGE_WIDTH = 500  # CSS px at most: beside the column, within a laptop's 848 px; 1.2 times as tall as wide
COLUMN_WIDTH = 340  # CSS px: the controls and the readout beside the picture
BUTTONS = ["dropout", "kidnap", "new"]  # one row of the column: 105 + 125 + 100 px
GATE = 4.0  # the filter rejects a reading more than 4 standard deviations from its prediction (chapter 8)
SLIDER_FORMAT = ".2g"  # the readout of the four log sliders; the description writes their values the same way


@dataclass(frozen=True)
class LoopFacts:
    """What the description and the readout say about the step shown, computed once by :meth:`LoopModel.facts`.

    "Inside" is always the drawn 2σ ellipse (a squared Mahalanobis distance, the position NEES, of at most
    ``NSIG**2``); the share inside the 3σ ellipse is named as such."""

    step: int
    t: float  # s
    blind: bool  # the sensor is blind at this step
    sight_back: bool  # the first step after a blind stretch: the nearest landmark only
    used: int  # readings the filter used
    rejected: int  # readings the gate rejected
    kidnapped: bool  # the true robot has been carried off, at this step or before
    error: float  # distance of the estimate from the truth (m)
    prediction_error: float  # the same before this step's readings (m)
    area_before: float  # the 1σ area before the readings (m²)
    area_after: float  # and after them (m²)
    shrink: float | None  # area_after / area_before when readings were used, else None
    inside: bool  # the truth is inside the drawn 2σ ellipse
    share_inside: float  # share of the steps so far (0 to this one) with the truth inside the 2σ ellipse
    share_inside_3sigma: float  # the same for the 3σ ellipse
    mean_nees: float  # the position NEES averaged over the whole lap
    verdict: str  # "honest", "timid" or "over-confident", from ``mean_nees``


class LoopModel:
    """Model: the settings of one landmark-loop run, the run, and the step shown.

    Attributes
    ----------
    seed : int
        The world's noise; *New run* takes the next one.
    filter : {"ekf", "ukf", "yours"}
    step : callable or None
        The student's own step function, run when ``filter`` is "yours".
    motion_noise, sensor_noise : float
        Scales of the world's odometry noise and reading noise (standard deviations).
    trust_motion, trust_sensor : float
        The R and the Q the filter assumes, as multiples of the world's true ones (1: honest).
    blind : (int, int) or None
        The sensor is blind for steps t0 <= k < t1; the step after, it reads the nearest landmark only.
    kidnap : int or None
        The step at which the true robot is carried off, or None.
    run : LoopRun
        ``kf.sim.landmark_loop`` with these settings; recomputed once per change, from the first step
        the change affects (a kidnap or a dropout at the step shown leaves the steps before it).
    ran : {"ekf", "ukf", "yours"}
        The filter that made ``run``.
    failure : str or None
        What went wrong in the student's step; the run is then the course's EKF.
    frame : int
        The step shown.
    """

    def __init__(self, seed: int = 0, step=None):
        if step is not None and not callable(step):
            raise ValueError(f"filter must be your step function (or None for the course's EKF), got {step!r}")
        self.seed, self.step = seed, step
        self.filter = YOURS if step is not None else "ekf"
        self.motion_noise = self.sensor_noise = self.trust_motion = self.trust_sensor = 1.0
        self.blind = self.kidnap = None
        self.frame = FIRST_FRAME
        self.run, self.ran = None, None
        self._rerun()

    def _rerun(self) -> None:
        settings = {
            "dropout": self.blind,
            "one_back": True,
            "motion_noise": self.motion_noise,
            "sensor_noise": self.sensor_noise,
            "filter_motion_noise": self.motion_noise * np.sqrt(self.trust_motion),  # R scales as its std squared
            "filter_sensor_noise": self.sensor_noise * np.sqrt(self.trust_sensor),
            "kidnap": self.kidnap,
            "gate": GATE,
        }
        since = self.run if self.ran != YOURS else None  # the course's filter: the steps it shares are copied
        self.failure = None
        if self.filter != YOURS:
            self.run, self.ran = run_loop(self.seed, filter=self.filter, since=since, **settings), self.filter
            return
        try:
            self.run, self.ran = run_loop(self.seed, filter=self.step, **settings), YOURS
        except ValueError as err:  # the student's step broke: say how, and show the course's EKF meanwhile
            self.failure = str(err)
            self.run, self.ran = run_loop(self.seed, filter="ekf", since=since, **settings), "ekf"

    def set_filter(self, name: str) -> None:
        self.filter = name if name == YOURS else name.lower()
        self._rerun()

    def set_motion_noise(self, scale: float) -> None:
        self.motion_noise = float(scale)
        self._rerun()

    def set_sensor_noise(self, scale: float) -> None:
        self.sensor_noise = float(scale)
        self._rerun()

    def set_trust_motion(self, ratio: float) -> None:
        self.trust_motion = float(ratio)
        self._rerun()

    def set_trust_sensor(self, ratio: float) -> None:
        self.trust_sensor = float(ratio)
        self._rerun()

    def set_dropout(self, on: bool) -> None:
        """On: the sensor goes blind at the step shown, until turned off.  Off: sight comes back at the
        step shown, the nearest landmark first (nothing stays blind if that is not after the start)."""
        if on:
            self.blind = (self.frame, self.run.t.size)
        elif self.blind is not None:
            self.blind = (self.blind[0], self.frame) if self.frame > self.blind[0] else None
        self._rerun()

    def toggle_kidnap(self) -> None:
        """Carry the true robot off at the step shown, or undo a kidnap."""
        self.kidnap = self.frame if self.kidnap is None else None
        self._rerun()

    def new_run(self) -> None:
        """New noise: the next seed, every setting kept."""
        self.seed += 1
        self._rerun()

    def is_blind(self) -> bool:
        """True if the sensor is blind at the step shown."""
        return self.blind is not None and self.blind[0] <= self.frame < self.blind[1]

    def areas(self) -> tuple[float, float]:
        """Area of the 1-sigma position ellipse before and after the readings of the step shown (m²)."""
        before = np.pi * np.sqrt(max(np.linalg.det(self.run.Sig_bar[self.frame, :2, :2]), 0.0))  # pi sqrt(det)
        return float(before), float(self.run.area[self.frame])

    def facts(self) -> LoopFacts:
        """The facts of the step shown, which the description and the readout both say."""
        run, k = self.run, self.frame
        used, rejected = int(np.count_nonzero(run.used[k])), int(np.count_nonzero(run.rejected[k]))
        before, after = self.areas()
        nees_so_far = run.nees[: k + 1]
        mean_nees, verdict = run.honesty()
        return LoopFacts(
            step=k,
            t=float(run.t[k]),
            blind=self.is_blind(),
            sight_back=self.blind is not None and k == self.blind[1],
            used=used,
            rejected=rejected,
            kidnapped=self.kidnap is not None and k >= self.kidnap,
            error=float(run.error[k]),
            prediction_error=self.prediction_error(),
            area_before=before,
            area_after=after,
            shrink=after / before if used and before > 0 else None,
            inside=bool(run.nees[k] <= NSIG**2),  # the drawn ellipse: a Mahalanobis distance of NSIG
            share_inside=float(np.mean(nees_so_far <= NSIG**2)),
            share_inside_3sigma=float(np.mean(run.inside[: k + 1])),  # the run record's inside: the 3σ ellipse
            mean_nees=mean_nees,
            verdict=verdict,
        )

    def describe(self) -> str:
        """What the picture shows: the run and step, what the filter saw and did, its error (and the
        prediction's, when it used readings), its 1σ area, whether the truth is inside the drawn 2σ ellipse;
        then the settings that differ from an honest filter in the usual world, and whether the lap's NEES
        calls it honest."""
        f = self.facts()
        name = "your filter" if self.filter == YOURS and self.failure is None else f"the {self.run.filter.upper()}"
        notes = ["your filter failed: the course's EKF is shown"] if self.failure else []
        if self.kidnap is not None:
            notes.append(f"{'robot kidnapped' if f.kidnapped else 'a kidnap comes'} at step {self.kidnap}")
        if f.blind:
            did = f"{name} sees nothing (the sensor is blind)"
        else:
            did = f"{name} uses {f.used or 'no'} reading{'s' if f.used != 1 else ''}"
            did += f", rejects {f.rejected}" if f.rejected else ""
            did += " (sight back: the nearest landmark only)" if f.sight_back else ""
        off = f"is {metres(f.error, '.3f')} m off"
        if f.used:  # the readings moved the estimate: from where
            off += f" ({metres(f.prediction_error, '.3f')} m before the reading{'s' if f.used != 1 else ''})"
        area = f"its 1σ area {f.area_after:.3g} m²" + (f" ({shrink(f.shrink)})" if f.shrink is not None else "")
        inside = "inside" if f.inside else "outside"
        said = f" ({'; '.join(notes)})" if notes else ""
        now = f"Run {self.seed}, step {f.step}{said}: {did} and {off}; {area}, the truth {inside} its 2σ ellipse."
        lap = f"over this lap the filter is {f.verdict} (mean NEES {nees_text(f.mean_nees)})."
        changed = self.changed()
        return f"{now} With {changed}, {lap}" if changed else f"{now} {lap[0].upper()}{lap[1:]}"

    def prediction_error(self) -> float:
        """Distance between the predicted and the true position at the step shown, before its readings (m)."""
        k = self.frame
        return float(np.linalg.norm(self.run.truth[k, :2] - self.run.mu_bar[k, :2]))

    def changed(self) -> str:
        """The settings that differ from 1 as their sliders show them, each owner named once: "the world's
        process noise ×3.2, its measurement noise ×10, the filter's R ×1.0e+2 and Q ×1.0e+2" ("" if none)."""
        honest = shown(1.0, SLIDER_FORMAT)
        world = [
            f"{label} ×{shown(value, SLIDER_FORMAT)}"
            for label, value in (("process noise", self.motion_noise), ("measurement noise", self.sensor_noise))
            if shown(value, SLIDER_FORMAT) != honest
        ]
        trust = [
            f"{label} ×{shown(value, SLIDER_FORMAT)}"
            for label, value in (("R", self.trust_motion), ("Q", self.trust_sensor))
            if shown(value, SLIDER_FORMAT) != honest
        ]
        if world:
            world = [f"the world's {world[0]}"] + [f"its {rest}" for rest in world[1:]]
        if trust:
            trust[0] = f"the filter's {trust[0]}"
        parts = world + trust
        return ", ".join(parts[:-1]) + f" and {parts[-1]}" if len(parts) > 1 else "".join(parts)


def metres(value: float, fmt: str) -> str:
    """A distance as the description writes it: ``fmt`` digits, or "over 1000" (a student's step may fly off)."""
    return shown(value, fmt) if value < 1e3 else "over 1000"


def shrink(factor: float) -> str:
    """How the readings scaled the 1σ area, in two digits however small: "×0.065", "×0.0022"."""
    return f"×{factor:#.2g}"


def nees_text(nees: float) -> str:
    """A mean NEES as the description and the readout write it: two digits, written out (2.2, 170, 160,000),
    or "unbounded" (a flat ellipse the truth left)."""
    if not np.isfinite(nees):
        return "unbounded"
    return f"{nees:.2g}" if nees < 100 else f"{float(f'{nees:.2g}'):,.0f}"


def _readout(model: LoopModel) -> str:
    """The lines beside the picture: what the filter did at the step shown, its error, its doubt, its honesty."""
    f = model.facts()
    if f.blind:
        sight = "<b>sensor blind</b>"
    else:
        back = " (sight back: the nearest landmark only)" if f.sight_back else ""
        sight = f"uses {f.used} reading{'s' if f.used != 1 else ''}{back}"
        if f.rejected:
            sight += (
                f", <span style='color:{palette.MEASUREMENT_TEXT}'><b>rejects {f.rejected}</b></span> "
                "(outside the gate)"
            )
    shrink_text = f" ({shrink(f.shrink)})" if f.shrink is not None else ""
    inside = "inside" if f.inside else "<b>outside</b>"
    kidnapped = ""
    if model.kidnap is not None:
        kidnapped = f"<br>{'<b>kidnapped</b>' if f.kidnapped else 'a kidnap comes'} at step {model.kidnap}"
    nees = nees_text(f.mean_nees) + ("" if np.isfinite(f.mean_nees) else " (a flat ellipse the truth left)")
    failure = html.escape(model.failure or "")  # the student's own message, shown as text
    failed = f"<b>Your filter failed</b>: {failure}. Shown: the course's EKF.<br>" if failure else ""
    return (
        f"<div style='font-size:13px;line-height:1.5'>{failed}step {f.step}, t = {f.t:.1f} s, run {model.seed}: "
        f"{sight}{kidnapped}<br>"
        f"<span style='color:{palette.ESTIMATE_TEXT}'>position error {metres(f.error, '.3f')} m</span><br>"
        f"1σ area: <span style='color:{palette.PREDICTION_TEXT}'>{f.area_before:.3g}</span> before the readings → "
        f"<span style='color:{palette.ESTIMATE_TEXT}'>{f.area_after:.3g} m²</span>{shrink_text}<br>"
        f"truth {inside} the 2σ ellipse; so far inside it at {f.share_inside:.0%} of steps, "
        f"inside 3σ at {f.share_inside_3sigma:.0%}<br>"
        f"this lap, the filter is <b>{f.verdict}</b>: mean NEES {nees} "
        f"(honest: {HONEST_NEES[0]:g} to {HONEST_NEES[1]:g}, 2 on average)</div>"
    )


def _draw(view, model: LoopModel, readout: widgets.HTML, kidnap: widgets.Button) -> None:
    update_loop_view(view, model)
    readout.value = _readout(model)
    kidnap.description = "Undo kidnap" if model.kidnap is not None else "Kidnap"


def _controls(model: LoopModel, kidnap: widgets.Button) -> dict:
    """The world's noise, the filter's trust, dropout, kidnap, new run and the filter's choice, bound to the model.

    Each change reruns the whole lap (30 to 80 ms): a slider once, where it is let go.
    """
    lo, hi = NOISE_RANGE
    tlo, thi = TRUST_RANGE
    log = {"readout_format": SLIDER_FORMAT, "continuous_update": False, "base": 10}
    motion = slider(widgets.FloatLogSlider, "process noise ×", 1.0, lo, hi, 0.05, **log)
    sensor = slider(widgets.FloatLogSlider, "measurement noise ×", 1.0, lo, hi, 0.05, **log)
    R, Q = (slider(widgets.FloatLogSlider, f"filter's {x} ×", 1.0, tlo, thi, 0.1, **log) for x in "RQ")
    for noise in (motion, sensor, R, Q):
        noise.style.description_width = "145px"  # the four tracks line up
    dropout = widgets.ToggleButton(
        description="dropout",
        icon="eye-slash",
        tooltip="On: the sensor is blind from the step shown. Off: sight comes back at the step shown.",
        layout=widgets.Layout(width="105px"),
    )
    new = button("New run", icon="refresh", tooltip="New noise: the next seed")
    new.layout.width, kidnap.layout.width = "100px", "125px"  # room for "Undo kidnap"
    choice = widgets.ToggleButtons(
        options=[YOURS, *FILTERS] if model.step is not None else list(FILTERS),
        value=YOURS if model.filter == YOURS else model.filter.upper(),
        description="filter",
        style={"button_width": "60px", "description_width": "40px"},
    )
    return {
        "motion": (motion, model.set_motion_noise),
        "sensor": (sensor, model.set_sensor_noise),
        "trust_motion": (R, model.set_trust_motion),
        "trust_sensor": (Q, model.set_trust_sensor),
        "dropout": (dropout, model.set_dropout),
        "kidnap": (kidnap, model.toggle_kidnap),
        "new": (new, model.new_run),
        "filter": (choice, model.set_filter),
    }


CAPTION = (
    "<b>Landmark loop.</b> Purple squares: landmarks. Grey: true path (dotted) and robot. Teal: the filter's estimate, "
    "trail, 2σ ellipse (dashed purple: before this step's readings) and beams to the readings it uses; dash-dot "
    "orange: readings it rejects (over 4σ off). Strips: x and y error (truth − estimate, m) in the filter's ±2σ "
    "band; grey: blind steps; dotted: the kidnap. <i>process</i> / <i>measurement noise</i>: the world's odometry "
    "and sensor noise. <i>filter's R</i> / <i>Q</i>: the noise the filter assumes, times the true one (1: honest). "
    "<i>dropout</i>: the sensor is blind from the step shown until pressed again; sight returns one landmark first. "
    "<i>Kidnap</i> moves the true robot half a lap on; <i>New run</i>: new noise."
)


def landmark_loop(seed: int = 0, filter=None) -> Demo:
    """Demo "landmark loop" (chapter 10): localization round a map of landmarks, by the course's EKF or UKF
    or by your own step ``filter(mu, Sig, u, z, landmarks, dt, M, Q, gate) -> (mu, Sig, used)``.

    Run animates the lap, the step slider scrubs it.  Two log sliders scale the world's
    odometry and reading noise, two more the R and Q the filter assumes; *dropout*
    blinds the sensor from the step shown until it is pressed again; *Kidnap* carries the
    true robot half a lap on at the step shown; *New run* draws new noise.  A step
    function that fails is named in the readout, and the course's EKF is shown meanwhile.
    Every change reruns the whole lap once; moving in time only redraws.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = LoopModel(seed, filter)
    view = loop_view(model)
    readout = widgets.HTML(layout=widgets.Layout(width=f"{COLUMN_WIDTH}px"))
    readout.add_class("kf-readout")
    kidnap = button("Kidnap", icon="random", tooltip="Carry the true robot half a lap on at this step")
    demo = Demo(
        name="landmark-loop",
        caption=CAPTION,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=lambda: _draw(view, model, readout, kidnap),
        describe=model.describe,
        frames=model.run.t.size,
        controls=_controls(model, kidnap),
        beside=[["play", "frame"], "motion", "sensor", "trust_motion", "trust_sensor", BUTTONS, "filter", readout],
        display_width=IMAGE_WIDTH,
    )
    demo.controls["frame"].layout.width = f"{COLUMN_WIDTH - 90}px"  # beside Run (90 px), in the column's width
    return demo
