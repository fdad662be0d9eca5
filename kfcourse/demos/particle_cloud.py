"""Chapter 11: a particle filter localizing the robot of chapter 10's loop, one weighted cloud per step."""

from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.loop_strips import NSIG
from ..plots.particles import cloud_view, update_cloud_view
from ..plots.style import FigureRenderer
from ..sim.particle_lap import RESAMPLERS, particle_loop
from ._base import Demo, button, slider

FIRST_FRAME = 60  # the step shown first, as in chapter 10: on the top straight, two landmarks in view
PARTICLES = 2000  # the particle count at first
COUNT_RANGE = (2.0, 4.0)  # log10 of the particle counts the slider reaches: 100 to 10 000
INJECTION = 0.05  # share of the particles replaced by random poses after each resampling, when on
IMAGE_WIDTH = 500  # CSS px at most: beside the column, within a laptop's 848 px
COLUMN_WIDTH = 340  # CSS px: the controls and the readout beside the picture
SCHEME_BUTTON = 106  # CSS px: one resampling scheme's button, its whole name readable ("multinomial")


@dataclass(frozen=True)
class CloudFacts:
    """What the description and the readout say about the step shown, computed once by :meth:`CloudModel.facts`."""

    step: int
    t: float  # s
    n_particles: int
    seen: int  # readings at this step
    error: float  # distance of the cloud's mean from the truth (m)
    inside: bool  # the truth is inside the cloud's drawn 2σ ellipse
    ess: float  # the effective sample size N_eff
    resampled: bool  # N_eff fell under N/2 and the cloud was resampled
    injected: int  # random particles injected after the resampling
    kidnapped: bool  # the true robot has been carried off, at this step or before


class CloudModel:
    """Model: the settings of one particle-filter lap, the run, and the step shown.

    Attributes
    ----------
    seed : int
        The world's noise and the filter's draws; *New run* takes the next one.
    n_particles : int
        N, from 100 to 10 000.
    resample : {"multinomial", "stratified", "systematic"}
    global_start : bool
        The cloud starts spread over the whole map (the start unknown), not round the true start.
    injection : bool
        After each resampling, :data:`INJECTION` of the particles are replaced by random poses.
    kidnap : int or None
        The step at which the true robot is carried half a lap on, or None.
    run : ParticleRun
        ``kf.sim.particle_loop`` with these settings; recomputed once per change.
    frame : int
        The step shown.
    """

    def __init__(self, seed: int = 0):
        self.seed, self.n_particles, self.resample = seed, PARTICLES, "systematic"
        self.global_start = self.injection = False
        self.kidnap = None
        self.frame = FIRST_FRAME
        self._rerun()

    def _rerun(self) -> None:
        self.run = particle_loop(
            self.seed,
            n_particles=self.n_particles,
            resample=self.resample,
            global_start=self.global_start,
            kidnap=self.kidnap,
            injection=INJECTION if self.injection else 0.0,
        )

    def set_particles(self, n: float) -> None:
        self.n_particles = round(n)
        self._rerun()

    def set_resample(self, name: str) -> None:
        self.resample = name
        self._rerun()

    def set_global_start(self, on: bool) -> None:
        self.global_start = bool(on)
        self._rerun()

    def set_injection(self, on: bool) -> None:
        self.injection = bool(on)
        self._rerun()

    def toggle_kidnap(self) -> None:
        """Carry the true robot off at the step shown, or undo a kidnap."""
        self.kidnap = self.frame if self.kidnap is None else None
        self._rerun()

    def new_run(self) -> None:
        """New noise: the next seed, every setting kept."""
        self.seed += 1
        self._rerun()

    def spread(self) -> tuple[float, float]:
        """How far the dots of the step shown spread, in x and in y (m): the width of the middle 95 % of
        the particles each way, their weights aside (a cloud that covers the map spans nearly all of it)."""
        low, high = np.percentile(self.run.particles[self.frame, :, :2], [2.5, 97.5], axis=0)
        width, height = high - low
        return float(width), float(height)

    def facts(self) -> CloudFacts:
        """The facts of the step shown, which the description and the readout both say."""
        run, k = self.run, self.frame
        return CloudFacts(
            step=k,
            t=float(run.t[k]),
            n_particles=int(run.n_particles),
            seen=int(np.count_nonzero(run.visible[k])),
            error=float(run.error[k]),
            inside=bool(run.nees[k] <= NSIG**2),  # the drawn ellipse: a Mahalanobis distance of NSIG
            ess=float(run.ess[k]),
            resampled=bool(run.resampled[k]),
            injected=int(run.injected[k]),
            kidnapped=self.kidnap is not None and k >= self.kidnap,
        )

    def describe(self) -> str:
        """What the picture shows: how far the cloud spreads, its error and whether the truth is inside its
        drawn ellipse, the effective sample size and whether the step resampled; then the settings of this lap."""
        f, run = self.facts(), self.run
        inside = "inside" if f.inside else "outside"
        if f.resampled:
            after = "under N/2, so the cloud is resampled"
            after += f" and {f.injected} random particles injected" if f.injected else ""
        else:
            after = "at or over N/2, so the weights are kept"
        width, height = self.spread()
        box = ""
        if self.global_start and run.bounds is not None:  # the cloud started anywhere: how much of the map it holds
            (x_min, x_max), (y_min, y_max) = run.bounds
            box = f" of the {x_max - x_min:g} m by {y_max - y_min:g} m map"
        now = (
            f"Step {f.step}: the {f.n_particles} particles spread over {width:.2f} m by {height:.2f} m{box} (the "
            f"middle 95 %), their mean {f.error:.2f} m from the truth, which is {inside} their 2σ ellipse; "
            f"the effective sample size {f.ess:.0f} is {after}."
        )
        settings = [f"{run.resample} resampling", "a global start" if self.global_start else "a known start"]
        if self.injection:
            settings.append(f"{100 * INJECTION:.0f} % injected")
        if self.kidnap is not None:
            settings.append(f"{'a kidnap at' if f.kidnapped else 'a kidnap to come at'} step {self.kidnap}")
        return f"{now} Run {self.seed}, with {', '.join(settings[:-1])} and {settings[-1]}."


def _readout(model: CloudModel) -> str:
    """The lines beside the picture: the step, the error, the ESS, and what happened after weighing."""
    f = model.facts()
    if f.resampled:
        after = f"<b>resampled</b> ({model.run.resample}): N<sub>eff</sub> under N/2"
    else:
        after = "weights kept: N<sub>eff</sub> at or over N/2"
    injected = f", {f.injected} particles injected" if f.injected else ""
    kidnapped = ""
    if model.kidnap is not None:
        kidnapped = f"<br>{'<b>kidnapped</b>' if f.kidnapped else 'a kidnap comes'} at step {model.kidnap}"
    inside = "inside" if f.inside else "<b>outside</b>"
    return (
        f"<div style='font-size:13px;line-height:1.5'>step {f.step}, t = {f.t:.1f} s, run {model.seed}: "
        f"{f.n_particles} particles, {f.seen} reading{'s' if f.seen != 1 else ''}{kidnapped}<br>"
        f"<span style='color:{palette.ESTIMATE_TEXT}'>position error {f.error:.2f} m</span>, "
        f"truth {inside} the 2σ ellipse<br>"
        f"N<sub>eff</sub> = {f.ess:.0f} ({f.ess / f.n_particles:.1%} of N)<br>{after}{injected}</div>"
    )


def _draw(view, model: CloudModel, readout: widgets.HTML, kidnap: widgets.Button) -> None:
    update_cloud_view(view, model)
    readout.value = _readout(model)
    kidnap.description = "Undo kidnap" if model.kidnap is not None else "Kidnap"


def _controls(model: CloudModel, kidnap: widgets.Button) -> dict:
    """The particle count, the resampling scheme, the start, injection, kidnap and a new run, bound to the model.

    Each change reruns the whole lap (0.1 s at 2 000 particles, 0.5 s at 10 000): the count once, where it is let go.
    """
    lo, hi = COUNT_RANGE
    count = slider(widgets.FloatLogSlider, "particles", PARTICLES, lo, hi, 0.1, ".0f", False, base=10)
    scheme = widgets.ToggleButtons(  # the three resampling schemes, by name: room for the whole word in each
        options=list(RESAMPLERS),
        value=model.resample,
        tooltips=[f"Resample with the {name} scheme" for name in RESAMPLERS],
        tooltip="resampling scheme",  # the group's name for a screen reader: it has no label
        style={"button_width": f"{SCHEME_BUTTON}px"},
    )
    start = widgets.ToggleButton(
        description="Global start", icon="globe", tooltip="Start anywhere on the map", layout={"width": "120px"}
    )
    inject = widgets.ToggleButton(
        description=f"inject {INJECTION:.0%}",
        icon="random",
        tooltip=f"After each resampling, replace {INJECTION:.0%} of the particles by random poses",
        layout={"width": "110px"},
    )
    new = button("New run", icon="refresh", tooltip="New noise: the next seed")
    new.layout.width, kidnap.layout.width = "100px", "125px"  # room for "Undo kidnap"
    return {
        "particles": (count, model.set_particles),
        "resample": (scheme, model.set_resample),
        "global_start": (start, model.set_global_start),
        "injection": (inject, model.set_injection),
        "kidnap": (kidnap, model.toggle_kidnap),
        "new": (new, model.new_run),
    }


CAPTION = (
    "<b>Particle cloud.</b> The loop of chapter 10, followed by a particle filter. Dots: the particles after "
    "the step's prediction, shaded by their weight (dark purple: heavy). Grey: true path (dotted) and robot. Teal: the "
    "cloud's mean, trail, 2σ ellipse and beams to the readings. Strip: the effective sample size N<sub>eff</sub>/N; "
    "under the dashed N/2 line the filter resamples. <i>Global start</i>: the start unknown, particles everywhere. "
    "<i>inject</i>: random particles after each resampling. <i>Kidnap</i> moves the true robot half a lap on."
)


def particle_cloud(seed: int = 0) -> Demo:
    """Demo "particle cloud" (chapter 11): a particle filter localizing the robot round chapter 10's loop.

    Run animates the lap, the step slider scrubs it.  A log slider sets the particle count
    (100 to 10 000), three buttons the resampling scheme; *Global start* spreads the first
    cloud over the whole map; *inject* replaces 5 % of the particles by random poses after each
    resampling; *Kidnap* carries the true robot half a lap on at the step shown; *New run*
    draws new noise.  Every change reruns the whole lap once; moving in time only redraws.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = CloudModel(seed)
    view = cloud_view(model)
    readout = widgets.HTML(layout=widgets.Layout(width=f"{COLUMN_WIDTH}px"))
    readout.add_class("kf-readout")
    kidnap = button("Kidnap", icon="user-secret", tooltip="Carry the true robot half a lap on at this step")
    demo = Demo(
        name="particle-cloud",
        caption=CAPTION,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=lambda: _draw(view, model, readout, kidnap),
        describe=model.describe,
        frames=model.run.t.size,
        controls=_controls(model, kidnap),
        beside=[["play", "frame"], "particles", "resample", ["global_start", "injection"], ["kidnap", "new"], readout],
        display_width=IMAGE_WIDTH,
    )
    demo.controls["frame"].layout.width = f"{COLUMN_WIDTH - 90}px"  # beside Run (90 px), in the column's width
    return demo
