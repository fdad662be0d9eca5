"""Chapter 10: a robot localizing itself round a loop of landmarks, and how to break it."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.loop import loop_view, update_loop_view
from ..plots.style import FigureRenderer
from ..sim.localization import landmark_loop as run_loop
from ._base import Demo, button, slider

DROPOUT = (40, 70)  # steps k with t0 <= k < t1 without readings when dropout is on (6 s of a 24 s lap)
FIRST_FRAME = 60  # the step shown first: on the top straight, two landmarks in view
NOISE_RANGE = (-1.0, 1.0)  # log10 of the noise scales the sliders reach: 0.1x to 10x
FILTERS = ("EKF", "UKF")  # the choices shown; the run takes them in lower case
IMAGE_WIDTH = 500  # CSS px at most: beside the column, within a laptop's 848 px; 1.2 times as tall as wide
COLUMN_WIDTH = 340  # CSS px: the controls and the readout beside the picture
GATE = 4.0  # the filter rejects a reading more than 4 standard deviations from its prediction (chapter 8)


class LoopModel:
    """Model: the settings of one landmark-loop run, the run, and the step shown.

    Attributes
    ----------
    seed : int
    filter : {"ekf", "ukf"}
    motion_noise, sensor_noise : float
        Scales of the odometry noise and its R, and of the reading noise and its Q.
    dropout : bool
        Blind the sensor for the steps ``DROPOUT``.
    kidnap : int or None
        The step at which the true robot is carried off, or None.
    run : LoopRun
        ``kf.sim.landmark_loop`` with these settings; recomputed once per change.
    frame : int
        The step shown.
    """

    def __init__(self, seed: int = 0):
        self.seed = seed
        self.filter = "ekf"
        self.motion_noise = 1.0
        self.sensor_noise = 1.0
        self.dropout = False
        self.kidnap = None
        self.frame = FIRST_FRAME
        self._rerun()

    def _rerun(self) -> None:
        self.run = run_loop(
            self.seed,
            filter=self.filter,
            dropout=DROPOUT if self.dropout else None,
            motion_noise=self.motion_noise,
            sensor_noise=self.sensor_noise,
            kidnap=self.kidnap,
            gate=GATE,
        )

    def set_filter(self, name: str) -> None:
        self.filter = name.lower()
        self._rerun()

    def set_motion_noise(self, scale: float) -> None:
        self.motion_noise = float(scale)
        self._rerun()

    def set_sensor_noise(self, scale: float) -> None:
        self.sensor_noise = float(scale)
        self._rerun()

    def set_dropout(self, on: bool) -> None:
        self.dropout = bool(on)
        self._rerun()

    def toggle_kidnap(self) -> None:
        """Carry the true robot off at the step shown, or undo a kidnap."""
        self.kidnap = self.frame if self.kidnap is None else None
        self._rerun()

    def blind(self) -> bool:
        """True if the sensor is blinded at the step shown."""
        return self.dropout and DROPOUT[0] <= self.frame < DROPOUT[1]

    def areas(self) -> tuple[float, float]:
        """Area of the 1-sigma position ellipse before and after the readings of the step shown (m²)."""
        before = np.pi * np.sqrt(max(np.linalg.det(self.run.Sig_bar[self.frame, :2, :2]), 0.0))  # pi sqrt(det)
        return float(before), float(self.run.area[self.frame])

    def share_inside(self) -> float:
        """Share of the steps so far with the true position inside the 3-sigma ellipse (0 to 1)."""
        return float(np.mean(self.run.inside[: self.frame + 1]))


def _readout(model: LoopModel) -> str:
    """The lines beside the picture: what the filter did at the step shown, its error and its doubt."""
    run, k = model.run, model.frame
    used, rejected = int(np.count_nonzero(run.used[k])), int(np.count_nonzero(run.rejected[k]))
    if model.blind():
        sight = "<b>sensor blind</b>"
    else:
        sight = f"uses {used} reading{'s' if used != 1 else ''}"
        if rejected:
            sight += f", <span style='color:{palette.MEASUREMENT}'><b>rejects {rejected}</b></span> (outside the gate)"
    before, after = model.areas()
    shrink = f" (×{after / before:#.2g})" if before > 0 else ""  # two digits however small: ×0.10, ×0.0022
    inside = "inside" if run.inside[k] else "<b>outside</b>"
    kidnapped = f"<br><b>kidnapped</b> at step {model.kidnap}" if model.kidnap is not None else ""
    return (
        f"<div style='font-size:13px;line-height:1.5'>step {k}, t = {run.t[k]:.1f} s: {sight}{kidnapped}<br>"
        f"<span style='color:{palette.ESTIMATE}'>position error {run.error[k]:.3f} m</span><br>"
        f"1σ area: <span style='color:{palette.PREDICTION}'>{before:.3g}</span> before the readings → "
        f"<span style='color:{palette.ESTIMATE}'>{after:.3g} m²</span>{shrink}<br>"
        f"truth {inside} the 3σ ellipse ({model.share_inside():.0%} of steps so far)</div>"
    )


def _controls(model: LoopModel, kidnap: widgets.Button) -> dict:
    """The noise sliders, the dropout toggle, the filter's choice and the ``kidnap`` button, bound to the model.

    Each noise change reruns the whole lap (30 to 60 ms): once, where the slider is let go.
    """
    lo, hi = NOISE_RANGE
    return {
        "motion": (
            slider(widgets.FloatLogSlider, "process noise ×", 1.0, lo, hi, 0.05, ".2g", False, base=10),
            model.set_motion_noise,
        ),
        "sensor": (
            slider(widgets.FloatLogSlider, "measurement noise ×", 1.0, lo, hi, 0.05, ".2g", False, base=10),
            model.set_sensor_noise,
        ),
        "dropout": (
            widgets.ToggleButton(
                value=False,
                description="sensor dropout",
                icon="eye-slash",
                tooltip=f"Blind the sensor for steps {DROPOUT[0]} to {DROPOUT[1] - 1}",
                layout=widgets.Layout(width="150px"),
            ),
            model.set_dropout,
        ),
        "filter": (
            widgets.ToggleButtons(
                options=list(FILTERS),
                tooltips=["extended Kalman filter: Jacobians", "unscented Kalman filter: sigma points"],
                value=model.filter.upper(),
                description="filter",
                style={"button_width": "60px", "description_width": "40px"},
            ),
            model.set_filter,
        ),
        "kidnap": (kidnap, model.toggle_kidnap),
    }


CAPTION = (
    "<b>Landmark loop.</b> Purple squares: landmarks. Grey: true path and robot. Teal: the filter's estimate, "
    "trail, 2σ ellipse (dashed purple: before this step's readings) and beams to the readings it uses; dashed "
    "orange: readings it rejects (over 4σ off). Strips: x and y error (truth − estimate, m) in the filter's ±2σ "
    "band; grey: blind steps; dotted: the kidnap. <i>process</i> / <i>measurement noise</i> scale the odometry's "
    f"noise and R / the readings' noise and Q; <i>sensor dropout</i> blinds steps {DROPOUT[0]}–{DROPOUT[1] - 1}; "
    "<i>Kidnap</i> moves the true robot half a lap on."
)


def landmark_loop(seed: int = 0) -> Demo:
    """Demo "landmark loop" (chapter 10): EKF (or UKF) localization round a map of landmarks.

    Run animates the lap, the step slider scrubs it; two log sliders scale the
    odometry noise (and the filter's R) and the reading noise (and its Q); a
    toggle blinds the sensor for a fixed stretch of steps; another picks the
    filter; *Kidnap* carries the true robot half a lap on at the step shown.
    Every change reruns the whole lap once; moving in time only redraws.
    The controls and the readout stand beside the picture, so that a laptop
    shows them and the whole map at once.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = LoopModel(seed)
    view = loop_view(model)
    readout = widgets.HTML(layout=widgets.Layout(width=f"{COLUMN_WIDTH}px"))
    readout.add_class("kf-readout")
    kidnap = button("Kidnap", icon="random", tooltip="Carry the true robot half a lap on at this step")

    def draw() -> None:
        update_loop_view(view, model)
        readout.value = _readout(model)
        kidnap.description = "Undo kidnap" if model.kidnap is not None else "Kidnap"

    demo = Demo(
        name="landmark-loop",
        caption=CAPTION,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=draw,
        frames=model.run.t.size,
        controls=_controls(model, kidnap),
        beside=[["play", "frame"], "motion", "sensor", ["dropout", "kidnap"], "filter", readout],
        display_width=IMAGE_WIDTH,
    )
    demo.controls["frame"].layout.width = f"{COLUMN_WIDTH - 90}px"  # beside Run (90 px), in the column's width
    return demo
