"""Chapter 0: a robot on a line: raw readings and dead reckoning against the filtered estimate."""

from __future__ import annotations

from functools import partial

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..plots.raw_vs_filtered_view import raw_vs_filtered_view, update_raw_vs_filtered
from ..plots.style import FigureRenderer
from ..sim.line import simulate_line
from ._base import Demo, button, shown, slider

N_STEPS = 150
STEP_STD = 0.05  # m of disturbance per step
SENSOR_STD = 0.4  # m, the slider's starting point
SENSOR_MAX = 3.0  # m
SENSOR_FORMAT = ".2f"  # the sensor-noise slider's readout


class RawVsFiltered:
    """Model: one seeded run and the frame being shown (the first frame shows the whole run).

    Attributes
    ----------
    seed : int
        The run's seed; "New noise" moves on to the next one.
    run : LineRun
        Truth, readings, dead reckoning and the filter's estimates over ``N_STEPS`` steps.
    frame : int
        The step shown (Run and the step slider set it).
    """

    def __init__(self, seed: int, sensor_std: float = SENSOR_STD):
        self.seed = seed
        self.run = simulate_line(N_STEPS, STEP_STD, sensor_std, seed=seed)
        self.frame = N_STEPS - 1

    def set_sensor_std(self, sensor_std: float) -> None:
        """The same run (same seed) with another sensor noise (m)."""
        self.run = simulate_line(N_STEPS, STEP_STD, sensor_std, seed=self.seed)

    def new_noise(self) -> None:
        """A fresh run: the next seed, the same sensor noise."""
        self.seed += 1
        self.run = simulate_line(N_STEPS, STEP_STD, self.run.sensor_std, seed=self.seed)

    def errors(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Distance from the truth at every step of the whole run (m): raw, dead reckoning, filtered."""
        r = self.run
        return np.abs(r.z - r.truth), np.abs(r.dead_reckoning - r.truth), np.abs(r.mu - r.truth)

    def rms_errors(self) -> tuple[float, float]:
        """RMS error up to the current frame of the raw readings and the filter."""
        raw, _, filt = self.rms_errors_all()
        return raw, filt

    def rms_errors_all(self) -> tuple[float, float, float]:
        """RMS error up to the current frame: raw readings, dead reckoning, filter."""
        k = self.frame + 1
        return tuple(float(np.sqrt(np.mean(e[:k] ** 2))) for e in self.errors())

    def describe(self) -> str:
        """What the picture shows in one sentence: the run and the step, the sensor noise, how far each
        estimate has been from the truth so far (RMS, in cm as the picture writes it), and which is the closest."""
        raw, dead, filtered = (round(100 * e) for e in self.rms_errors_all())  # cm, as the picture writes them
        errors = {"the filter": filtered, "the raw pings": raw, "dead reckoning": dead}
        closest = [name for name, cm in errors.items() if cm == min(errors.values())]
        if len(closest) == 1:
            verdict = f"{closest[0]} is the closest"
        else:
            verdict = f"{', '.join(closest[:-1])} and {closest[-1]} are equally close"
        sensor = shown(self.run.sensor_std, SENSOR_FORMAT)
        return (
            f"Run {self.seed}, step {self.frame}, sensor noise σ = {sensor} m: so far the filtered estimate has been "
            f"{filtered} cm from the truth (RMS), the raw pings {raw} cm and dead reckoning {dead} cm, so {verdict}."
        )


def raw_vs_filtered(seed: int = 0) -> Demo:
    """Demo "raw vs filtered" (chapter 0): the first frame shows a whole run and each
    estimate's distance from the truth; Run replays time, the sensor-noise slider makes
    the raw trace explode while the filter holds, "New noise" draws a fresh run.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = RawVsFiltered(seed)
    view = raw_vs_filtered_view(N_STEPS)
    caption = (
        "<b>Raw vs filtered.</b> Grey dotted line: the true position (the robot never sees it). "
        "Orange dots: noisy sensor pings; orange dash-dot line: trusting each ping. "
        "Purple dashes: dead reckoning, counting the commanded moves only. "
        "Teal: the Kalman filter's estimate (band = ±1σ). Lower panel: how far each one is from the truth. "
        "Press <i>Run</i> to replay time, drag <i>sensor noise</i>, or draw <i>New noise</i>."
    )
    return Demo(
        name="raw-vs-filtered",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=partial(update_raw_vs_filtered, view, model),
        describe=model.describe,
        frames=N_STEPS,
        controls={
            "sensor_noise": (
                slider(widgets.FloatSlider, "sensor noise σ (m)", SENSOR_STD, 0.05, SENSOR_MAX, 0.05, SENSOR_FORMAT),
                model.set_sensor_std,
            ),
            "new_noise": (button("New noise", icon="refresh", tooltip="Draw a new random run"), model.new_noise),
        },
        layout=[["play", "frame"], ["sensor_noise", "new_noise"]],
    )
