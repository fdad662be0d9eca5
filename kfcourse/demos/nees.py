"""Chapter 6, beyond the lesson: is the filter's ellipse honest?  The average NEES
of a few hundred tracks against its 95 % chi-square band."""

from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..plots.style import FigureRenderer
from ..plots.tracking import nees_view, update_nees_view
from ..sim.scores import nees, nees_band
from ..sim.target import filter_tracks, simulate_tracks
from ._base import Demo, button, shown, slider

N_TRACKS = 200
N_STEPS = 60
DOF = 4  # the state [px, py, vx, vy]
LEVEL = 0.95
Y_RANGE = (0.5, 500.0)  # log axis: from timid to badly over-confident
DISPLAY_WIDTH = 848  # CSS px: a laptop's notebook width
FACTOR_FORMAT = ".3g"  # the factor slider's readout
NOISE_NAMES = {"R": "process noise", "Q": "measurement noise"}


@dataclass(frozen=True)
class NeesFacts:
    """What the description and the readout say, computed once by :meth:`NeesPanel.facts`."""

    seed: int  # the run: which batch of tracks
    which: str  # "R" or "Q": the noise the filter gets wrong
    factor: float  # the filter assumes factor times the true one
    mean_nees: float  # the mean over the steps of the average NEES
    band: tuple[float, float]  # where the average NEES lies 95 % of the time if the filter is honest
    below: float  # share of the steps with the average NEES below the band
    inside: float  # inside it
    above: float  # above it
    verdict: str  # "honest: ...", "timid: ..." or "over-confident: ..."


class NeesPanel:
    """Model: a fixed batch of constant-velocity tracks and a filter whose R or Q is off by ``factor``.

    Attributes
    ----------
    batch : TrackBatch
        The world (true noise ``batch.R``, ``batch.Q``); mistuning never changes it, ``new_run`` draws another.
    which : str
        ``"R"`` or ``"Q"``: the noise the filter gets wrong.
    factor : float
        The filter assumes ``factor`` times the true ``which`` (1 = tuned).
    avg_nees : ndarray, shape (T,)
        The NEES averaged over the tracks at each time step.
    band : (float, float)
        Where ``avg_nees`` lies 95 % of the time if the filter is honest.
    """

    def __init__(self, seed: int):
        self.batch = simulate_tracks(N_TRACKS, N_STEPS, seed=seed)
        self.band = nees_band(N_TRACKS, DOF, LEVEL)
        self.which = "Q"
        self.factor = 1.0
        self._refilter()

    def new_run(self) -> None:
        """New tracks (the next seed), the same mistuning."""
        self.batch = simulate_tracks(N_TRACKS, N_STEPS, seed=self.batch.seed + 1)
        self._refilter()

    def assumed(self) -> tuple[np.ndarray, np.ndarray]:
        """The R and Q the filter uses."""
        R, Q = self.batch.R, self.batch.Q
        return (self.factor * R, Q) if self.which == "R" else (R, self.factor * Q)

    def _refilter(self) -> None:
        mu, Sig = filter_tracks(self.batch, *self.assumed())
        self.avg_nees = nees(self.batch.truth, mu, Sig).mean(axis=0)  # average over the tracks

    def set_which(self, which: str) -> None:
        self.which = which
        self._refilter()

    def set_factor(self, factor: float) -> None:
        self.factor = float(factor)
        self._refilter()

    def fractions(self) -> tuple[float, float, float]:
        """Fraction of time steps with the average NEES below, inside and above the band."""
        low, high = self.band
        below, above = np.mean(self.avg_nees < low), np.mean(self.avg_nees > high)
        return float(below), float(1.0 - below - above), float(above)

    def verdict(self) -> str:
        below, _, above = self.fractions()
        if above > 0.5:
            return "over-confident: the ellipse is too small for the real errors"
        if below > 0.5:
            return "timid: the ellipse is larger than the real errors"
        return "honest: the ellipse matches the real errors"

    def facts(self) -> NeesFacts:
        """The mistuning, the mean, the shares of the steps below, inside and above the band, and the verdict:
        what the description and the readout both say."""
        below, inside, above = self.fractions()
        return NeesFacts(
            seed=self.batch.seed,
            which=self.which,
            factor=self.factor,
            mean_nees=float(self.avg_nees.mean()),
            band=self.band,
            below=below,
            inside=inside,
            above=above,
            verdict=self.verdict(),
        )

    def describe(self) -> str:
        """What the picture shows in two sentences: the mistuning as the controls show it, the mean of the
        average NEES against its expected value, the shares of the steps below, inside and above the band
        (the readout's numbers); the verdict."""
        f = self.facts()
        below, inside, above = (f"{100 * share:.0f} %" for share in (f.below, f.inside, f.above))
        return (
            f"With the filter assuming {shown(f.factor, FACTOR_FORMAT)} × the true {f.which} "
            f"({NOISE_NAMES[f.which]}), the average NEES of {N_TRACKS} tracks (run {f.seed}) has a mean of "
            f"{f.mean_nees:.2f} ({DOF} expected) and is below, inside and above the 95 % band at {below}, {inside} "
            f"and {above} of the steps. The filter is {f.verdict}."
        )


def _readout(model: NeesPanel) -> str:
    """The three lines under the picture: the mistuning and the mean, the shares of steps below, inside and
    above the band, and the verdict."""
    f = model.facts()
    low, high = f.band
    return (
        f"<div style='font-size:13px;line-height:1.5'>run {f.seed}: filter assumes "
        f"{shown(f.factor, FACTOR_FORMAT)} × the true {f.which}: mean NEES = {f.mean_nees:.2f} "
        f"(band {low:.2f} to {high:.2f})<br>"
        f"time steps below / inside / above the band: {f.below:.0%} / {f.inside:.0%} / {f.above:.0%}<br>"
        f"<b>{f.verdict}</b></div>"
    )


def nees_panel(seed: int = 0) -> Demo:
    """Demo "is the ellipse honest?" (chapter 6): the average NEES of many tracks
    over time against its 95 % band; a factor slider mistunes R or Q.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = NeesPanel(seed)
    view = nees_view(model.batch.dt * np.arange(N_STEPS), model.band, DOF, N_TRACKS, Y_RANGE)
    readout = widgets.HTML()  # text under the picture: no glyphs to render into the PNG
    readout.add_class("kf-readout")

    def draw() -> None:
        update_nees_view(view, model)
        readout.value = _readout(model)

    caption = (
        f"<b>Is the ellipse honest?</b> {N_TRACKS} targets moving exactly as the constant-velocity model says, each "
        "tracked by its own filter. Teal: their average NEES = (x − μ)ᵀ Σ⁻¹ (x − μ) at each step (log scale); grey: "
        f"where it stays 95 % of the time if every Σ is honest; dashed: {DOF}, its expected value. The filter assumes "
        "<i>factor</i> × the true R (process) or Q (measurement), as <i>mistune</i> picks; <i>New run</i> draws new "
        "tracks."
    )
    tips = [f"{NOISE_NAMES[name]} {name}" for name in ("R", "Q")]
    which = widgets.ToggleButtons(
        options=["R", "Q"], value=model.which, description="mistune", tooltips=tips, style={"button_width": "60px"}
    )
    # Every factor reruns all the tracks: the slider reports where it is let go, not every value on the way.
    factor = slider(widgets.FloatLogSlider, "factor", 1.0, -2, 2, 0.1, FACTOR_FORMAT, continuous_update=False, base=10)
    demo = Demo(
        name="nees",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=draw,
        describe=model.describe,
        controls={
            "which": (which, model.set_which),
            "factor": (factor, model.set_factor),
            "new": (button("New run", "refresh", "new tracks, same mistuning"), model.new_run),
        },
        layout=[readout, ["which", "factor", "new"]],
        display_width=DISPLAY_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
