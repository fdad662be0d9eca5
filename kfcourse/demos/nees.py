"""Chapter 6, beyond the lesson: is the filter's ellipse honest?  The average NEES
of a few hundred tracks against its 95 % chi-square band."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.style import FigureRenderer, new_figure
from ..sim.target import filter_tracks, nees, nees_band, simulate_tracks
from ._base import Demo, slider

N_TRACKS = 200
N_STEPS = 60
DOF = 4  # the state [px, py, vx, vy]
LEVEL = 0.95
Y_RANGE = (0.5, 500.0)  # log axis: from timid to badly over-confident


class NeesPanel:
    """Model: a fixed batch of constant-velocity tracks and a filter whose R or Q is off by ``factor``.

    Attributes
    ----------
    batch : TrackBatch
        The world (true noise ``batch.R``, ``batch.Q``); it never changes.
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


def nees_panel(seed: int = 0) -> Demo:
    """Demo "is the ellipse honest?" (chapter 6): the average NEES of many tracks
    over time against its 95 % band; a factor slider mistunes R or Q.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = NeesPanel(seed)
    t = model.batch.dt * np.arange(N_STEPS)
    low, high = model.band
    fig, ax = new_figure(8.0, 3.8)
    ax.set_yscale("log")
    ax.set_xlim(t[0], t[-1])
    ax.set_ylim(*Y_RANGE)
    ax.set_xlabel("time (s)")
    ax.set_ylabel(r"average NEES  $\bar\epsilon$")
    ax.axhspan(low, high, color=palette.TRUTH, alpha=0.35, lw=0, label=f"95 % band for {N_TRACKS} honest runs")
    ax.axhline(DOF, color=palette.INK, lw=1.0, ls="--", label=f"{DOF} = state dimension")
    (curve,) = ax.plot([], [], color=palette.ESTIMATE, lw=2.2, label="average NEES of the filter")
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=3, fontsize=9)
    readout = widgets.HTML()  # text under the picture: no glyphs to render into the PNG
    readout.add_class("kf-readout")
    renderer = FigureRenderer(fig, [curve])

    def draw() -> None:
        curve.set_data(t, np.clip(model.avg_nees, *Y_RANGE))  # off-scale values sit on the edge
        below, inside, above = model.fractions()
        readout.value = (
            f"<div style='font-size:13px;line-height:1.5'>filter assumes {model.factor:.3g} × the true "
            f"{model.which}: mean ε̄ = {model.avg_nees.mean():.2f} (band {low:.2f} to {high:.2f}); "
            f"time steps below / inside / above the band: {below:.0%} / {inside:.0%} / {above:.0%}<br>"
            f"<b>{model.verdict()}</b></div>"
        )

    caption = (
        f"<b>Is the ellipse honest?</b> {N_TRACKS} targets that move exactly as the constant-velocity model says, "
        f"each tracked by its own filter. Teal: the normalised estimation error squared "
        f"ε = (x − μ)ᵀ Σ⁻¹ (x − μ), averaged over the tracks, at each time step (log scale). Grey band: where that "
        f"average stays 95 % of the time if every Σ is honest; dashed: {DOF}, its expected value. "
        "<i>mistune</i> picks the noise the filter gets wrong, <i>factor</i> how far: the filter assumes "
        "factor × the true R (process) or Q (measurement). Above the band: over-confident; below: timid."
    )
    return Demo(
        name="nees",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={
            "which": (
                widgets.ToggleButtons(
                    options=["R", "Q"],
                    value=model.which,
                    description="mistune",
                    tooltips=["process noise R", "measurement noise Q"],
                    style={"button_width": "60px"},
                ),
                model.set_which,
            ),
            "factor": (slider(widgets.FloatLogSlider, "factor", 1.0, -2, 2, 0.1, ".3g", base=10), model.set_factor),
        },
        layout=[readout, ["which", "factor"]],
    )
