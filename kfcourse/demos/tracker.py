"""Chapter 6: a constant-velocity Kalman filter tracking a turning target in the plane."""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.artists import covariance_ellipse, update_covariance_ellipse
from ..plots.style import FigureRenderer, new_figure
from ..sim.target import START_STEPS, TargetRun, filter_target, process_noise, simulate_target
from ._base import Demo, slider

Q_TUNED = 1.0  # m², the filter's assumed sensor variance to start with (the world's is 1 m²)
ACCEL_TUNED = 10.0  # m²/s⁴, the filter's assumed acceleration variance to start with
K_JITTERY = 0.9  # position gain above which the filter copies the readings
K_COASTING = 0.05  # position gain below which the filter coasts on its motion model
ARROW_TIME = 1.0  # s: velocity arrows show where the target would be this much later


class Tracker:
    """Model: one turning target (fixed) and the filter's assumed noise (tunable).

    Attributes
    ----------
    run : TargetRun
        The world; it never changes when the filter is retuned.
    q_var : float
        Assumed sensor variance per axis, Q = q_var I (m²).
    accel_var : float
        Assumed acceleration variance per axis; R = :func:`process_noise` (m²/s⁴).
    est : TargetEstimates
        The filter run over the whole of ``run`` with these assumptions.
    frame : int
        The time step shown.
    """

    def __init__(self, seed: int):
        self.run: TargetRun = simulate_target(seed)
        self.q_var = Q_TUNED
        self.accel_var = ACCEL_TUNED
        self.frame = 95  # in the middle of the U-turn
        self._refilter()

    def _refilter(self) -> None:
        R = process_noise(self.run.dt, self.accel_var)
        self.est = filter_target(self.run, R=R, Q=self.q_var * np.eye(2))

    def set_q_var(self, q_var: float) -> None:
        self.q_var = float(q_var)
        self._refilter()

    def set_accel_var(self, accel_var: float) -> None:
        self.accel_var = float(accel_var)
        self._refilter()

    def gain(self) -> float:
        """The position gain at the frame shown: how far the estimate moves towards a reading."""
        return float(self.est.K[self.frame, 0, 0])

    def regime(self) -> str:
        """Which end of the trust slider the filter is at, in words."""
        if self.frame == 0:
            return "starting guess: the first reading, velocity unknown"
        if self.frame < START_STEPS:
            return "start-up: fitting a straight line through the readings so far"
        K = self.gain()
        if K >= K_JITTERY:
            return "K → 1: jittery, copies every reading (R huge or Q tiny)"
        if K <= K_COASTING:
            return "K → 0: coasting on the motion model, lags the turns (Q huge or R tiny)"
        return "balanced: follows the turns, smooths the noise"

    def velocities(self) -> tuple[np.ndarray, np.ndarray]:
        """Estimated and true velocity [vx, vy] (m/s) at the frame shown."""
        return self.est.mu[self.frame, 2:], self.run.truth[self.frame, 2:]

    def errors(self) -> tuple[float, float]:
        """Mean distance (m) from the truth up to the frame, of the estimate and of the raw readings."""
        k = self.frame + 1
        truth = self.run.truth[:k, :2]
        est = np.linalg.norm(self.est.mu[:k, :2] - truth, axis=1).mean()
        raw = np.linalg.norm(self.run.z[:k] - truth, axis=1).mean()
        return float(est), float(raw)


def _velocity_tip(p, vel, lo, hi):
    """Where the velocity line from ``p`` ends: ARROW_TIME ahead, cut short at the edge ``lo``, ``hi`` of the view."""
    d = ARROW_TIME * vel
    room = np.where(d > 0, hi - p, p - lo)  # distance to the edge the line heads for, per axis
    with np.errstate(divide="ignore"):
        fits = np.where(d != 0, room / np.abs(d), np.inf).min()  # fraction of the line inside the view
    return p + float(np.clip(fits, 0.0, 1.0)) * d


def _readout(model: Tracker) -> str:
    """The lines under the picture: both velocities, the mean errors so far, and the gain with its regime."""
    k, run = model.frame, model.run
    v_est, v_true = model.velocities()
    e_est, e_raw = model.errors()
    return (
        f"<div style='font-size:13px;line-height:1.5'>t = {run.t[k]:.1f} s &nbsp; velocity (m/s): "
        f"<span style='color:{palette.ESTIMATE}'>estimated ({v_est[0]:+.2f}, {v_est[1]:+.2f})</span>, "
        f"true ({v_true[0]:+.2f}, {v_true[1]:+.2f}) &nbsp; mean distance from the truth so far: "
        f"estimate {e_est:.2f} m, readings {e_raw:.2f} m<br>"
        f"<b>K = {model.gain():.3f} &nbsp; {model.regime()}</b></div>"
    )


def _picture(model: Tracker) -> tuple[FigureRenderer, Callable[[], None]]:
    """The true path, the readings so far, the estimate's trail and the rest of the run, the true and
    the estimated position with their velocities, and the estimate's 2-sigma ellipse.

    Returns
    -------
    (renderer, draw)
        ``draw()`` shows the model's run and estimates up to the frame shown.
    """
    run = model.run
    fig, ax = new_figure(8.0, 5.6)
    lo, hi = run.truth[:, :2].min(axis=0) - 3.0, run.truth[:, :2].max(axis=0) + 3.0
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.plot(run.truth[:, 0], run.truth[:, 1], color=palette.TRUTH, lw=5, alpha=0.45, label="true path")
    (truth_dot,) = ax.plot([], [], "o", color=palette.TRUTH, ms=9, zorder=3)
    (truth_vel,) = ax.plot([], [], color=palette.TRUTH, lw=2.5, zorder=3)
    pings = ax.scatter([], [], s=12, color=palette.MEASUREMENT, alpha=0.7, label="readings", zorder=2)
    (trail,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.6, alpha=0.8, label="estimate")
    (ahead,) = ax.plot([], [], ":", color=palette.ESTIMATE, lw=1.2, alpha=0.5, label="estimate ahead")
    (est_dot,) = ax.plot([], [], "o", color=palette.ESTIMATE, ms=8, zorder=4)
    (est_vel,) = ax.plot([], [], color=palette.ESTIMATE, lw=2.5, zorder=4)
    ring = covariance_ellipse(ax, run.z[0], np.eye(2), nsig=2.0, label="2σ ellipse", zorder=4)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=5, fontsize=9)
    renderer = FigureRenderer(fig, [pings, trail, ahead, truth_vel, truth_dot, est_vel, est_dot, ring])

    def draw() -> None:
        k, est = model.frame, model.est
        pings.set_offsets(run.z[: k + 1])
        trail.set_data(est.mu[: k + 1, 0], est.mu[: k + 1, 1])
        ahead.set_data(est.mu[k:, 0], est.mu[k:, 1])  # the rest of the run with these settings
        p_true, p_est = run.truth[k, :2], est.mu[k, :2]
        v_est, v_true = model.velocities()
        truth_dot.set_data([p_true[0]], [p_true[1]])
        truth_vel.set_data(*np.column_stack([p_true, p_true + ARROW_TIME * v_true]))
        est_dot.set_data([p_est[0]], [p_est[1]])
        est_vel.set_data(*np.column_stack([p_est, _velocity_tip(p_est, v_est, lo, hi)]))
        update_covariance_ellipse(ring, p_est, est.Sig[k, :2, :2])

    return renderer, draw


def tracker(seed: int = 0) -> Demo:
    """Demo "2-D tracker" (chapter 6): a constant-velocity filter follows a turning
    target.  Run animates time, the step slider scrubs, and two log sliders retune
    the filter's assumed Q and R while the target stays the same.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = Tracker(seed)
    renderer, draw_picture = _picture(model)
    readout = widgets.HTML()  # text under the picture: no glyphs to render into the PNG
    readout.add_class("kf-readout")

    def draw() -> None:
        draw_picture()
        readout.value = _readout(model)

    caption = (
        "<b>2-D tracker.</b> Grey: the target's true path, its position now and its true velocity (the line "
        "shows where it would be 1 s later). Orange dots: noisy position readings (σ = 1 m). "
        "Teal: the filter's estimate, its trail, its estimated velocity and its 2σ ellipse; dotted teal: where "
        "these settings take the estimate for the rest of the run. "
        "<i>Run</i> plays time, <i>step</i> scrubs it. <i>Q</i> is the sensor noise the filter "
        "<i>assumes</i>; <i>σₐ²</i> is the random acceleration it assumes, which sets its process noise R: "
        "they retune the filter, the target and the readings stay the same. "
        "The lines under the picture give both velocities, the mean errors so far, and the position gain K "
        "with its regime: jittery (K → 1), balanced, or coasting (K → 0)."
    )
    return Demo(
        name="tracker",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        frames=model.run.t.size,
        controls={
            "Q": (
                slider(widgets.FloatLogSlider, "assumed Q (m²)", Q_TUNED, -3, 4, 0.1, ".3g", base=10),
                model.set_q_var,
            ),
            "R": (
                slider(
                    widgets.FloatLogSlider,
                    "assumed σₐ² (m²/s⁴)",
                    ACCEL_TUNED,
                    -3,
                    7,
                    0.1,
                    ".3g",
                    base=10,
                ),
                model.set_accel_var,
            ),
        },
        layout=[readout, ["play", "frame"], ["Q", "R"]],
    )
