"""Chapter 6: a constant-velocity Kalman filter tracking a turning target in the plane."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..plots import palette
from ..plots.style import FigureRenderer
from ..plots.tracking import tracker_view, update_tracker_view
from ..sim.target import START_STEPS, TargetRun, filter_target, process_noise, simulate_target
from ._base import Demo, slider

Q_TUNED = 1.0  # m², the filter's assumed sensor variance to start with (the world's is 1 m²)
ACCEL_TUNED = 10.0  # m²/s⁴, the filter's assumed acceleration variance to start with
K_JITTERY = 0.9  # position gain above which the filter copies the readings
K_COASTING = 0.05  # position gain below which the filter coasts on its motion model
DISPLAY_WIDTH = 848  # CSS px: a laptop's notebook width, where the picture and its controls fit the screen


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


def _readout(model: Tracker) -> str:
    """The three lines under the picture: both velocities, the mean errors so far, and the gain with its regime."""
    k, run = model.frame, model.run
    v_est, v_true = model.velocities()
    e_est, e_raw = model.errors()
    return (
        f"<div style='font-size:13px;line-height:1.5'>t = {run.t[k]:.1f} s &nbsp; velocity (m/s): "
        f"<span style='color:{palette.ESTIMATE}'>estimated ({v_est[0]:+.2f}, {v_est[1]:+.2f})</span>, "
        f"true ({v_true[0]:+.2f}, {v_true[1]:+.2f})<br>"
        f"mean distance from the truth so far: estimate {e_est:.2f} m, readings {e_raw:.2f} m<br>"
        f"<b>K = {model.gain():.3f} &nbsp; {model.regime()}</b></div>"
    )


def tracker(seed: int = 0) -> Demo:
    """Demo "2-D tracker" (chapter 6): a constant-velocity filter follows a turning
    target.  Run animates time, the step slider scrubs, and two log sliders retune
    the filter's assumed Q and R while the target stays the same.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = Tracker(seed)
    view = tracker_view(model.run)
    readout = widgets.HTML()  # text under the picture: no glyphs to render into the PNG
    readout.add_class("kf-readout")

    def draw() -> None:
        update_tracker_view(view, model)
        readout.value = _readout(model)

    caption = (
        "<b>2-D tracker.</b> Grey: the true path, position and velocity (the line reaches where the target is "
        "1 s later). Orange: readings (σ = 1 m). Teal: the estimate, its trail, velocity and 2σ ellipse; dotted: "
        "where these settings take it next. <i>Q</i> and <i>σₐ²</i> (which sets R) are the noises the filter "
        "<i>assumes</i>: they retune the filter, not the target."
    )
    demo = Demo(
        name="tracker",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=draw,
        frames=model.run.t.size,
        controls={
            "Q": (
                slider(widgets.FloatLogSlider, "assumed Q (m²)", Q_TUNED, -3, 4, 0.1, ".3g", base=10),
                model.set_q_var,
            ),
            "R": (
                slider(widgets.FloatLogSlider, "assumed σₐ² (m²/s⁴)", ACCEL_TUNED, -3, 7, 0.1, ".3g", base=10),
                model.set_accel_var,
            ),
        },
        layout=[readout, ["play", "frame"], ["Q", "R"]],
        display_width=DISPLAY_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
