"""Chapter 3: one predict / update cycle at a time, on Gaussian curves."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..filters.kalman import kf_1d_cycle
from ..plots import palette
from ..plots.artists import gaussian_curve, update_gaussian_curve
from ..plots.style import FigureRenderer, new_figure, nice_limit
from ._base import Demo, button, slider

MU0, VAR0 = 2.0, 0.40  # the lesson's prior: m, m^2
U = 1.0  # m commanded each step
LESSON_Z = (3.6, 4.7)  # the lesson's first two readings (m)
HALF_WIDTH = 3.5  # m shown either side of the belief


class StepThroughModel:
    """Model: the actions pressed so far, replayed with the current R and Q."""

    def __init__(self, seed: int, R: float = 0.2, Q: float = 0.1):
        rng = np.random.default_rng(seed)
        k = np.arange(len(LESSON_Z), 200)
        later = MU0 + (k + 1) * U + np.sqrt(0.1) * rng.standard_normal(k.size)  # true walk + sensor noise
        self.readings = np.concatenate([LESSON_Z, later])
        self.R, self.Q = R, Q
        self.actions: list[str] = []
        self.replay()

    def press(self, action: str) -> None:
        if action == "reset":
            self.actions = []
        else:
            self.actions.append(action)
        self.replay()

    def predict(self) -> None:
        self.press("predict")

    def update(self) -> None:
        self.press("update")

    def reset(self) -> None:
        self.press("reset")

    def set_R(self, R: float) -> None:
        self.R = R
        self.replay()

    def set_Q(self, Q: float) -> None:
        self.Q = Q
        self.replay()

    def replay(self) -> None:
        """Recompute every step from the prior with the current R and Q."""
        mu, var = MU0, VAR0
        self.before = (mu, var)
        self.predicted = None
        self.z = None
        self.K = None
        self.phase = "prior"
        self.rows = []
        n_updates = 0
        for action in self.actions:
            self.before = (mu, var)
            if action == "predict":
                cyc = kf_1d_cycle(mu, var, U, None, R=self.R, Q=self.Q)
                self.predicted = (cyc.mu_bar, cyc.var_bar)
                self.z, self.K, self.phase = None, None, "predicted"
            else:
                z = float(self.readings[n_updates % self.readings.size])
                n_updates += 1
                cyc = kf_1d_cycle(mu, var, 0.0, z, b=0.0, R=0.0, Q=self.Q)  # update only
                self.predicted = (mu, var)
                self.z, self.K, self.phase = z, cyc.K, "updated"
                self.rows.append((len(self.rows) + 1, mu, var, z, cyc.innovation, cyc.K, cyc.mu, cyc.var))
            mu, var = cyc.mu, cyc.var
        self.mu, self.var = mu, var


def _table(rows) -> str:
    """The last few completed updates as the lesson's table."""
    cell = "style='padding:0 8px;text-align:right'"
    bar = "<span style='text-decoration:overline'>{}</span>"
    names = ("update", bar.format("μ"), bar.format("σ") + "²", "z", "z − " + bar.format("μ"), "K", "μ", "σ²")
    head = "".join(f"<th {cell}>{h}</th>" for h in names)
    body = "".join(
        f"<tr><td {cell}>{row[0]}</td>" + "".join(f"<td {cell}>{c:.3f}</td>" for c in row[1:]) + "</tr>"
        for row in rows[-4:]
    )
    if not rows:
        return "<i style='font-size:12px'>Each completed Update adds a row here, as in the lesson's table.</i>"
    return f"<table style='font-family:monospace;font-size:12px'><tr>{head}</tr>{body}</table>"


def step_through(seed: int = 0) -> Demo:
    """Demo "step through" (chapter 3): press Predict and Update to walk the
    scalar Kalman filter one half-step at a time, starting from the lesson's
    prior N(2.0, 0.40) and readings 3.6, 4.7.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = StepThroughModel(seed)
    fig, ax = new_figure(8.0, 3.4)
    ax.set_xlabel("position x (m)")
    ax.set_ylabel("density")
    x = np.linspace(0.0, 10.0, 600)
    before = gaussian_curve(ax, x, MU0, VAR0, palette.ESTIMATE, "belief before this step", fill=False)
    before[0].set_linestyle("--")
    before[0].set_linewidth(1.4)
    pred = gaussian_curve(ax, x, MU0, VAR0, palette.PREDICTION, r"prediction  $\overline{bel}$")
    meas = gaussian_curve(ax, x, MU0, VAR0, palette.MEASUREMENT, "measurement  N(z, Q)")
    post = gaussian_curve(ax, x, MU0, VAR0, palette.ESTIMATE, "belief  bel")
    zline = ax.axvline(MU0, color=palette.MEASUREMENT, lw=1, ls=":")
    legend = ax.legend(loc="upper left", fontsize=9)
    status = ax.text(0.99, 0.97, "", transform=ax.transAxes, ha="right", va="top", fontsize=10)
    curves = (before, pred, meas, post)
    dynamic = [a for c in curves for a in c if a is not None] + [zline, status, legend]
    renderer = FigureRenderer(fig, dynamic)
    table = widgets.HTML()

    def draw() -> None:
        m = model
        centre = round(m.mu)
        lo, hi = centre - HALF_WIDTH, centre + HALF_WIDTH
        grid = np.linspace(lo, hi, 600)
        shown = {
            "prior": (False, False, False, True),
            "predicted": (True, True, False, False),
            "updated": (False, True, True, True),
        }[m.phase]
        params = (m.before, m.predicted or m.before, (m.z or 0.0, m.Q), (m.mu, m.var))
        peak = 0.0
        for handle, label, visible in zip(legend.legend_handles, legend.get_texts(), shown, strict=True):
            handle.set_alpha(1.0 if visible else 0.25)  # fade the entries of curves not shown now
            label.set_alpha(1.0 if visible else 0.4)
        for curve, visible, (mu, var) in zip(curves, shown, params, strict=True):
            for artist in curve:
                if artist is not None:
                    artist.set_visible(visible)
            curve[0].set_xdata(grid)
            if visible:
                peak = max(peak, float(update_gaussian_curve(curve, mu, max(var, 1e-9)).max()))
        zline.set_visible(m.phase == "updated")
        zline.set_xdata([m.z or 0.0] * 2)
        top = nice_limit(1.1 * peak)
        if ax.get_xlim() != (lo, hi) or ax.get_ylim()[1] != top:
            ax.set_xlim(lo, hi)
            ax.set_ylim(0, top)
            renderer.invalidate()
        if m.phase == "prior":
            text = f"prior  μ = {m.mu:.3f}, σ² = {m.var:.3f}\npress Predict"
        elif m.phase == "predicted":
            text = rf"Predict: $\bar\mu$ = {m.mu:.3f}, $\bar\sigma^2$ = {m.var:.3f} (grew by R)"
        else:
            text = f"Update with z = {m.z:.2f}: K = {m.K:.3f}\nμ = {m.mu:.3f}, σ² = {m.var:.3f}"
        status.set_text(f"{text}\nR = {m.R:.3g}, Q = {m.Q:.3g}")
        table.value = _table(m.rows)

    caption = (
        "<b>Step through the 1-D Kalman filter.</b> Dashed teal: the belief before the step; "
        "purple: the prediction; orange: the measurement N(z, Q); teal: the updated belief. "
        "Press <i>Predict</i> and <i>Update</i> in turn; the sliders replay every step with new R and Q."
    )
    return Demo(
        name="step-through",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={
            "predict": (button("Predict", icon="arrow-right", tooltip="Move +1 m: shift and widen"), model.predict),
            "update": (button("Update", icon="eye", tooltip="Read the sensor: blend and narrow"), model.update),
            "reset": (button("Reset", icon="undo", tooltip="Back to the prior N(2.0, 0.40)"), model.reset),
            "R": (log_slider("process noise R", model.R), model.set_R),
            "Q": (log_slider("measurement noise Q", model.Q), model.set_Q),
        },
        layout=[["predict", "update", "reset"], ["R", "Q"], table],
    )


def log_slider(description: str, value: float) -> widgets.FloatLogSlider:
    """A noise slider from 0.001 to 10 on a log scale."""
    return slider(widgets.FloatLogSlider, description, value, -3, 1, 0.1, readout_format=".3g", base=10)
