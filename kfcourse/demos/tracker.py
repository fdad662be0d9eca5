"""Chapter 6: a constant-velocity Kalman filter tracking a turning target in the plane."""

from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..plots import palette
from ..plots.style import FigureRenderer
from ..plots.tracking import tracker_view, update_tracker_view
from ..sim.scores import nees
from ..sim.target import (
    SENSOR_STD,
    START_STEPS,
    Honesty,
    TargetRun,
    filter_target,
    process_noise,
    simulate_target,
)
from ._base import Demo, button, shown, slider

ACCEL_TUNED = 10.0  # m²/s⁴, the filter's assumed acceleration variance to start with
K_JITTERY = 0.9  # position gain above which the filter copies the readings
K_COASTING = 0.05  # position gain below which the filter coasts on its motion model
SENSOR_FORMAT = ".1f"  # the sensor σ slider's readout
TUNING_FORMAT = ".3g"  # the readouts of the log sliders Q and σₐ²
DISPLAY_WIDTH = 848  # CSS px: a laptop's notebook width, where the picture and its controls fit the screen
REGIMES = {  # each mode of Tracker.mode, explained in the readout
    "starting guess": "starting guess: the first reading, velocity unknown",
    "start-up": "start-up: fitting a straight line through the readings so far",
    "jittery": "K → 1: jittery, copies every reading (R huge or Q tiny)",
    "coasting": "K → 0: coasting on the motion model, lags the turns (Q huge or R tiny)",
    "balanced": "balanced: follows the turns, smooths the noise",
}
CAPTION = (
    "<b>2-D tracker.</b> Grey, dotted: the true path, position and velocity (the line reaches where the target is 1 s "
    "later). Orange: readings. Teal: the estimate, its trail, velocity and 2σ ellipse; pale thin line: where it "
    "goes next. <i>sensor σ</i> and <i>New run</i> change the world (the readings); <i>Q</i> (× the true one) and "
    "<i>σₐ²</i> (which sets R) change only what the filter <i>assumes</i>."
)


@dataclass(frozen=True)
class TrackerFacts:
    """What the description and the readout say about the step shown, computed once by :meth:`Tracker.facts`."""

    step: int
    t: float  # s
    mode: str  # "starting guess", "start-up", "jittery", "coasting" or "balanced"
    gain: float | None  # the position gain K; None at step 0, where the estimate is the first reading
    error: float  # distance of the estimate from the truth (m)
    inside: bool  # the truth is inside the drawn 2σ ellipse
    radius: float  # how far that ellipse reaches: half its long axis (m)
    honesty: Honesty  # the run's NEES test: its verdict, mean NEES and band


class Tracker:
    """Model: one turning target seen by a sensor of tunable noise (the world), and the
    filter's assumed noise (its belief), tuned apart from the world.

    Attributes
    ----------
    run : TargetRun
        The world: the true path and the readings, with sensor noise ``sensor_std``.
    sensor_std : float
        The world's sensor noise per axis (m); the true Q is ``sensor_std**2 * I``.
    q_factor : float
        The filter assumes ``q_factor`` times the true Q (1: it is told the truth).
    accel_var : float
        Assumed acceleration variance per axis; R = :func:`process_noise` (m²/s⁴).
    est : TargetEstimates
        The filter run over the whole of ``run`` with these assumptions.
    frame : int
        The time step shown.
    """

    def __init__(self, seed: int):
        self.seed = seed
        self.sensor_std = SENSOR_STD
        self.q_factor = 1.0
        self.accel_var = ACCEL_TUNED
        self.frame = 95  # in the middle of the U-turn
        self._simulate()

    @property
    def q_var(self) -> float:
        """The sensor variance per axis the filter assumes, Q = q_var I (m²)."""
        return self.q_factor * self.sensor_std**2

    def _simulate(self) -> None:
        self.run: TargetRun = simulate_target(self.seed, self.sensor_std)
        self._refilter()

    def _refilter(self) -> None:
        R = process_noise(self.run.dt, self.accel_var)
        self.est = filter_target(self.run, R=R, Q=self.q_var * np.eye(2))

    def set_sensor_std(self, sensor_std: float) -> None:
        """Change the world's sensor noise; the filter's Q follows it (times ``q_factor``)."""
        self.sensor_std = float(sensor_std)
        self._simulate()

    def set_q_factor(self, q_factor: float) -> None:
        self.q_factor = float(q_factor)
        self._refilter()

    def set_accel_var(self, accel_var: float) -> None:
        self.accel_var = float(accel_var)
        self._refilter()

    def new_run(self) -> None:
        """The same path and settings, new sensor noise."""
        self.seed += 1
        self._simulate()

    def gain(self) -> float:
        """The position gain at the frame shown: how far the estimate moves towards a reading."""
        return float(self.est.K[self.frame, 0, 0])

    def mode(self) -> str:
        """Where the filter is on the trust slider at the frame shown, in one or two words."""
        if self.frame == 0:
            return "starting guess"
        if self.frame < START_STEPS:
            return "start-up"
        K = self.gain()
        if K >= K_JITTERY:
            return "jittery"
        if K <= K_COASTING:
            return "coasting"
        return "balanced"

    def regime(self) -> str:
        """The mode at the frame shown, explained."""
        return REGIMES[self.mode()]

    def truth_inside(self) -> bool:
        """Is the true position inside the estimate's 2σ ellipse at the frame shown?"""
        k = self.frame
        p_true, p_est, Sig = self.run.truth[k, :2], self.est.mu[k, :2], self.est.Sig[k, :2, :2]
        return bool(nees(p_true, p_est, Sig) <= 2.0**2)  # on the 2σ ellipse NEES = 2²

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

    def facts(self) -> TrackerFacts:
        """The facts of the step shown, which the description and the readout both say."""
        k = self.frame
        return TrackerFacts(
            step=k,
            t=float(self.run.t[k]),
            mode=self.mode(),
            gain=self.gain() if k > 0 else None,  # no gain yet: the estimate is the first reading
            error=float(self.est.position_error()[k]),
            inside=self.truth_inside(),
            radius=self.est.ellipse_radius(k),
            honesty=self.est.honesty(),
        )

    def describe(self) -> str:
        """What the picture shows in one short sentence (one line of the output, so that the picture and its
        controls fit a laptop's screen): the step and the settings as their sliders show them; the mode and
        the gain K; how far the estimate is off and whether the truth is inside its 2σ ellipse, of which
        radius; and the run's honesty verdict.  The numbers are the readout's (which a screen reader does not
        announce); the readout adds the velocities, the mean errors and the mean NEES."""
        f = self.facts()
        sensor = shown(self.sensor_std, SENSOR_FORMAT)
        q, accel = shown(self.q_factor, TUNING_FORMAT), shown(self.accel_var, TUNING_FORMAT)
        gain = f", K = {f.gain:.3f}" if f.gain is not None else ""
        inside = "inside" if f.inside else "outside"
        return (
            f"Step {f.step}, σ {sensor} m, Q × {q}, σₐ² {accel}: {f.mode}{gain}; "
            f"{f.error:.2f} m off, {inside} the 2σ ellipse ({f.radius:.2f} m); {f.honesty.verdict}."
        )


def _readout(model: Tracker, lo, hi) -> str:
    """The four lines under the picture: the velocities; the errors and the ellipse (said to reach past the
    map ``lo``-``hi`` where it does); the gain and its regime; the honesty test of the run."""
    f = model.facts()
    v_est, v_true = model.velocities()
    e_est, e_raw = model.errors()
    p = model.est.mu[f.step, :2]
    past = ", past the edge" if np.any(p - f.radius < lo) or np.any(p + f.radius > hi) else ""
    inside = "inside" if f.inside else "<b>outside</b>"
    gain = f"K = {f.gain:.3f} &nbsp; " if f.gain is not None else ""
    h = f.honesty
    return (
        f"<div style='font-size:13px;line-height:1.45'>t = {f.t:.1f} s &nbsp; velocity (m/s): "
        f"<span style='color:{palette.ESTIMATE_TEXT}'>estimated ({v_est[0]:+.2f}, {v_est[1]:+.2f})</span>, "
        f"true ({v_true[0]:+.2f}, {v_true[1]:+.2f}) &nbsp; run {model.seed}<br>"
        f"estimate {f.error:.2f} m off, {inside} the 2σ ellipse ({f.radius:.2f} m{past}); "
        f"mean off so far: estimate {e_est:.2f} m, readings {e_raw:.2f} m<br>"
        f"<b>{gain}{REGIMES[f.mode]}</b><br>"
        f"<b>{h.verdict}</b>: mean position NEES over the run {h.mean_nees:.3g}, honest from {h.low:.2f} to "
        f"{h.high:.2f} &nbsp; (filter's Q = {model.q_var:.3g} m², true {model.sensor_std**2:.3g} m²)</div>"
    )


def tracker(seed: int = 0) -> Demo:
    """Demo "2-D tracker" (chapter 6): a constant-velocity filter follows a turning
    target.  Run animates time, the step slider scrubs; the world's sensor noise and
    New run change the readings, two log sliders retune the filter's assumed Q and R.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = Tracker(seed)
    view = tracker_view(model.run)
    readout = widgets.HTML()  # text under the picture: no glyphs to render into the PNG
    readout.add_class("kf-readout")

    def draw() -> None:
        update_tracker_view(view, model)
        readout.value = _readout(model, view.lo, view.hi)

    demo = Demo(
        name="tracker",
        caption=CAPTION,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=draw,
        describe=model.describe,
        frames=model.run.t.size,
        controls={
            "sigma": (
                slider(widgets.FloatSlider, "sensor σ (m)", SENSOR_STD, 0.1, 5.0, 0.1, SENSOR_FORMAT),
                model.set_sensor_std,
            ),
            "new": (button("New run", "refresh", "new sensor noise, same path"), model.new_run),
            "Q": (
                slider(widgets.FloatLogSlider, "filter's Q (× true)", 1.0, -3, 4, 0.1, TUNING_FORMAT, base=10),
                model.set_q_factor,
            ),
            "R": (
                slider(widgets.FloatLogSlider, "filter's σₐ² (m²/s⁴)", ACCEL_TUNED, -3, 7, 0.1, TUNING_FORMAT, base=10),
                model.set_accel_var,
            ),
        },
        layout=[readout, ["play", "frame"], ["sigma", "new"], ["Q", "R"]],
        display_width=DISPLAY_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
