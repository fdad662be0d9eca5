"""Chapter 0: a robot on a line: raw readings and dead reckoning against the filtered estimate."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.style import FigureRenderer, new_figure, nice_limit
from ..sim.line import simulate_line
from ._base import Demo, button, slider

N_STEPS = 150
STEP_STD = 0.05  # m of disturbance per step
SENSOR_STD = 0.4  # m, the slider's starting point
SENSOR_MAX = 3.0  # m


class RawVsFiltered:
    """Model: one seeded run and the frame being shown (the first frame shows the whole run)."""

    def __init__(self, seed: int, sensor_std: float = SENSOR_STD):
        self.seed = seed
        self.run = simulate_line(N_STEPS, STEP_STD, sensor_std, seed=seed)
        self.frame = N_STEPS - 1

    def set_sensor_std(self, sensor_std: float) -> None:
        self.run = simulate_line(N_STEPS, STEP_STD, sensor_std, seed=self.seed)

    def new_noise(self) -> None:
        self.seed += 1
        self.run = simulate_line(N_STEPS, STEP_STD, self.run.sensor_std, seed=self.seed)

    def errors(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Distance from the truth at every step of the whole run (m): raw, dead reckoning, filtered."""
        r = self.run
        return np.abs(r.z - r.truth), np.abs(r.dead_reckoning - r.truth), np.abs(r.mu - r.truth)

    def view_limits(self) -> tuple[tuple[float, float], float]:
        """Axis limits that hold the whole run: the position axis (m) and the top of the error axis (m).

        The margins are powers of two (:func:`nice_limit`), so they change only now and then as the
        sensor-noise slider moves, and every reading and every error stays in view.
        """
        r = self.run
        lo, hi = float(r.truth.min()), float(r.truth.max())
        seen = np.concatenate([r.z, r.mu, r.dead_reckoning])
        margin = nice_limit(max(0.25 * (hi - lo), lo - seen.min(), seen.max() - hi))  # m beyond the truth's range
        top = nice_limit(1.05 * max(e.max() for e in self.errors()))
        return (lo - margin, hi + margin), top

    def rms_errors(self) -> tuple[float, float]:
        """RMS error up to the current frame of the raw readings and the filter."""
        raw, _, filt = self.rms_errors_all()
        return raw, filt

    def rms_errors_all(self) -> tuple[float, float, float]:
        """RMS error up to the current frame: raw readings, dead reckoning, filter."""
        k = self.frame + 1
        return tuple(float(np.sqrt(np.mean(e[:k] ** 2))) for e in self.errors())


def raw_vs_filtered(seed: int = 0) -> Demo:
    """Demo "raw vs filtered" (chapter 0): the first frame shows a whole run and each
    estimate's distance from the truth; Run replays time, the sensor-noise slider makes
    the raw trace explode while the filter holds, "New noise" draws a fresh run.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = RawVsFiltered(seed)
    fig, (ax, ax_err) = new_figure(8.0, 4.6, nrows=2, sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    ax.set_xlim(0, N_STEPS - 1)
    ax.set_ylabel("position (m)")
    (truth,) = ax.plot([], [], color=palette.TRUTH, lw=5, alpha=0.55, label="truth (unknown)")
    pings = ax.scatter([], [], s=14, color=palette.MEASUREMENT, alpha=0.75, label="sensor pings", zorder=3)
    (raw,) = ax.plot([], [], color=palette.MEASUREMENT, lw=1.0, alpha=0.8, label="raw: trust each ping")
    (dr,) = ax.plot([], [], "--", color=palette.PREDICTION, lw=1.6, label="dead reckoning")
    band = ax.fill_between([], [], [], color=palette.ESTIMATE, alpha=0.18, lw=0)
    (est,) = ax.plot([], [], color=palette.ESTIMATE, lw=2.4, label="filtered (Kalman)")
    (robot,) = ax.plot([], [], "o", color=palette.ESTIMATE, ms=8, zorder=4)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=3, fontsize=9)
    ax_err.set_xlabel("time step")
    ax_err.set_ylabel("distance from truth (m)")
    (err_raw,) = ax_err.plot([], [], color=palette.MEASUREMENT, lw=0.9, alpha=0.8)
    (err_dr,) = ax_err.plot([], [], "--", color=palette.PREDICTION, lw=1.6)
    (err_est,) = ax_err.plot([], [], color=palette.ESTIMATE, lw=2.0)
    readout = ax_err.text(0.0, 1.03, "", transform=ax_err.transAxes, ha="left", va="bottom", fontsize=9.5)
    dynamic = [truth, pings, raw, dr, band, est, robot, err_raw, err_dr, err_est, readout]
    renderer = FigureRenderer(fig, dynamic)

    def draw() -> None:
        run, k = model.run, model.frame + 1
        t = run.t[:k]
        truth.set_data(t, run.truth[:k])
        pings.set_offsets(np.column_stack([t, run.z[:k]]))
        raw.set_data(t, run.z[:k])
        dr.set_data(t, run.dead_reckoning[:k])
        sd = np.sqrt(run.var[:k])
        lo, hi = run.mu[:k] - sd, run.mu[:k] + sd
        band.set_verts([np.concatenate([np.column_stack([t, lo]), np.column_stack([t[::-1], hi[::-1]])])])
        est.set_data(t, run.mu[:k])
        robot.set_data([t[-1]], [run.mu[k - 1]])
        e_raw, e_dr, e_est = model.errors()
        view, top = model.view_limits()
        if ax.get_ylim() != view or ax_err.get_ylim()[1] != top:
            ax.set_ylim(*view)
            ax_err.set_ylim(0, top)
        err_raw.set_data(t, e_raw[:k])
        err_dr.set_data(t, e_dr[:k])
        err_est.set_data(t, e_est[:k])
        rms_raw, rms_dr, rms_est = model.rms_errors_all()
        readout.set_text(
            f"RMS error so far: raw {100 * rms_raw:.0f} cm   dead reckoning {100 * rms_dr:.0f} cm   "
            f"filtered {100 * rms_est:.0f} cm"
        )

    caption = (
        "<b>Raw vs filtered.</b> Grey: the true position (the robot never sees it). "
        "Orange dots: noisy sensor pings; orange line: trusting each ping. "
        "Purple dashes: dead reckoning, counting the commanded moves only. "
        "Teal: the Kalman filter's estimate (band = ±1σ). Lower panel: how far each one is from the truth. "
        "Press <i>Run</i> to replay time, drag <i>sensor noise</i>, or draw <i>New noise</i>."
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
