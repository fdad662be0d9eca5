"""Chapter 0: a robot on a line, raw readings against the filtered estimate."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.style import FigureRenderer, new_figure
from ..sim.line import simulate_line
from ._base import Demo, button, slider

N_STEPS = 150
STEP_STD = 0.05  # m of disturbance per step
SENSOR_STD = 0.4  # m, the slider's starting point
SENSOR_MAX = 3.0  # m


class RawVsFiltered:
    """Model: one seeded run and the frame being shown."""

    def __init__(self, seed: int, sensor_std: float = SENSOR_STD):
        self.seed = seed
        self.run = simulate_line(N_STEPS, STEP_STD, sensor_std, seed=seed)
        self.frame = N_STEPS // 3

    def set_sensor_std(self, sensor_std: float) -> None:
        self.run = simulate_line(N_STEPS, STEP_STD, sensor_std, seed=self.seed)

    def new_noise(self) -> None:
        self.seed += 1
        self.run = simulate_line(N_STEPS, STEP_STD, self.run.sensor_std, seed=self.seed)

    def rms_errors(self) -> tuple[float, float]:
        """RMS error up to the current frame of the raw readings and the filter."""
        k = self.frame + 1
        r = self.run
        raw = np.sqrt(np.mean((r.z[:k] - r.truth[:k]) ** 2))
        filt = np.sqrt(np.mean((r.mu[:k] - r.truth[:k]) ** 2))
        return float(raw), float(filt)


def raw_vs_filtered(seed: int = 0) -> Demo:
    """Demo "raw vs filtered" (chapter 0): Run animates time, the sensor-noise
    slider makes the raw trace explode while the filter holds, "New noise"
    draws a fresh run.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = RawVsFiltered(seed)
    fig, ax = new_figure(8.0, 3.6)
    r = model.run
    span = r.truth.max() - r.truth.min()
    ax.set_xlim(0, N_STEPS - 1)
    ax.set_ylim(r.truth.min() - 0.25 * span, r.truth.max() + 0.25 * span)
    ax.set_xlabel("time step")
    ax.set_ylabel("position along the line (m)")
    (truth,) = ax.plot([], [], color=palette.TRUTH, lw=5, alpha=0.55, label="truth (unknown)")
    pings = ax.scatter([], [], s=14, color=palette.MEASUREMENT, alpha=0.75, label="sensor pings", zorder=3)
    (raw,) = ax.plot([], [], color=palette.MEASUREMENT, lw=1.0, alpha=0.8, label="raw: trust each ping")
    band = ax.fill_between([], [], [], color=palette.ESTIMATE, alpha=0.18, lw=0)
    (est,) = ax.plot([], [], color=palette.ESTIMATE, lw=2.4, label="filtered (Kalman)")
    (robot,) = ax.plot([], [], "o", color=palette.ESTIMATE, ms=8, zorder=4)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=4, fontsize=9)
    readout = ax.text(
        0.99,
        0.03,
        "",
        transform=ax.transAxes,
        ha="right",
        va="bottom",
        fontsize=10,
        bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "none"},
    )
    renderer = FigureRenderer(fig, [truth, pings, raw, band, est, robot, readout])

    def draw() -> None:
        run, k = model.run, model.frame + 1
        t = run.t[:k]
        truth.set_data(t, run.truth[:k])
        pings.set_offsets(np.column_stack([t, run.z[:k]]))
        raw.set_data(t, run.z[:k])
        sd = np.sqrt(run.var[:k])
        lo, hi = run.mu[:k] - sd, run.mu[:k] + sd
        band.set_verts([np.concatenate([np.column_stack([t, lo]), np.column_stack([t[::-1], hi[::-1]])])])
        est.set_data(t, run.mu[:k])
        robot.set_data([t[-1]], [run.mu[k - 1]])
        e_raw, e_filt = model.rms_errors()
        readout.set_text(f"RMS error so far: raw {100 * e_raw:.0f} cm   filtered {100 * e_filt:.0f} cm")

    caption = (
        "<b>Raw vs filtered.</b> Grey: the true position (the robot never sees it). "
        "Orange dots: noisy sensor pings; orange line: trusting each ping. "
        "Teal: the Kalman filter's estimate (band = ±1σ). "
        "Press <i>Run</i> to run time, drag <i>sensor noise</i>, or draw <i>New noise</i>."
    )
    return Demo(
        name="raw-vs-filtered",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        frames=N_STEPS,
        controls={
            "sensor_noise": (
                slider(widgets.FloatSlider, "sensor noise σ (m)", SENSOR_STD, 0.05, SENSOR_MAX, 0.05),
                model.set_sensor_std,
            ),
            "new_noise": (button("New noise", icon="refresh", tooltip="Draw a new random run"), model.new_noise),
        },
        layout=[["play", "frame"], ["sensor_noise", "new_noise"]],
    )
