"""Chapter 3: one predict / update cycle at a time, on Gaussian curves."""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets
import numpy as np

from ..filters.kalman_1d import kf_1d_gain, kf_1d_predict, kf_1d_update
from ..plots import palette
from ..plots.artists import gaussian_curve, update_gaussian_curve
from ..plots.style import FigureRenderer, fixed_width_ticks, new_figure, nice_limit
from ._base import Demo, button, slider

MU0, VAR0 = 2.0, 0.40  # the worked example's prior at time step 0 (chapter 3): m, m^2
U = 1.0  # m commanded each step
WORKED_Z = (3.6, 4.7)  # the worked cycles' readings at time steps 1 and 2 (m)
SENSOR_VAR = 0.1  # m^2: noise of the simulated readings after step 2 (the worked example's Q)
HALF_WIDTH = 3.5  # m shown either side of the belief


class StepThroughModel:
    """Model: the buttons pressed so far, replayed with the current R and Q.

    Readings belong to time steps.  The robot starts at time step 0; the k-th
    Predict moves it to time step k, and an Update reads the sensor there
    (:meth:`reading`).  Each time step has one reading, so an Update is refused,
    with a note, before the first Predict and once this step's reading is in
    the belief: using it again would count the same evidence twice and make
    the filter overconfident.
    """

    def __init__(self, seed: int, R: float = 0.2, Q: float = 0.1):
        self.seed = seed
        self.R, self.Q = R, Q
        self.actions: list[str] = []
        self.replay()

    def reading(self, k: int) -> float:
        """The sensor reading at time step ``k >= 1`` (m): the worked cycles' 3.6 and 4.7, then
        seeded readings of a robot that is at ``MU0 + k U`` metres."""
        if k <= len(WORKED_Z):
            return WORKED_Z[k - 1]
        noise = np.random.default_rng([self.seed, k]).standard_normal()  # the same for a seed and step
        return MU0 + k * U + float(np.sqrt(SENSOR_VAR) * noise)

    def predict(self) -> None:
        self.actions.append("predict")
        self.replay()

    def update(self) -> None:
        if self.fresh:
            self.actions.append("update")
            self.replay()
        elif self.k == 0:
            self.note = "No reading at step 0: press Predict first."
        else:
            self.note = f"Step {self.k}'s reading is already used:\nusing it again would count it twice. Press Predict."

    def reset(self) -> None:
        self.actions = []
        self.replay()

    def set_R(self, R: float) -> None:
        self.R = R
        self.replay()

    def set_Q(self, Q: float) -> None:
        self.Q = Q
        self.replay()

    def replay(self) -> None:
        """Recompute every step from the prior with the current R and Q."""
        mu, var = MU0, VAR0
        self.k = 0  # the time step the robot is at
        self.fresh = False  # whether step k's reading is still unused
        self.before = (mu, var)
        self.predicted = None
        self.z = None
        self.K = None
        self.phase = "prior"
        self.note = ""
        self.rows = []
        for action in self.actions:
            self.before = (mu, var)
            if action == "predict":
                self.k += 1
                self.fresh = True
                mu, var = kf_1d_predict(mu, var, U, R=self.R)  # equations (1), (2)
                self.predicted = (mu, var)
                self.z, self.K, self.phase = None, None, "predicted"
            else:
                z = self.reading(self.k)
                self.fresh = False
                K = kf_1d_gain(var, Q=self.Q)  # equation (3)
                mu_new, var_new = kf_1d_update(mu, var, z, Q=self.Q)  # equations (4), (5)
                self.predicted = (mu, var)
                self.z, self.K, self.phase = z, K, "updated"
                self.rows.append((self.k, mu, var, z, z - mu, K, mu_new, var_new))
                mu, var = mu_new, var_new
        self.mu, self.var = mu, var


def _table(rows) -> str:
    """The last few completed updates as a hand table (one row per update, as in chapter 3)."""
    cell = "style='padding:0 8px;text-align:right'"
    bar = "<span style='text-decoration:overline'>{}</span>"
    names = ("step", bar.format("μ"), bar.format("σ") + "²", "z", "z − " + bar.format("μ"), "K", "μ", "σ²")
    head = "".join(f"<th {cell}>{h}</th>" for h in names)
    body = "".join(
        f"<tr><td {cell}>{row[0]}</td>" + "".join(f"<td {cell}>{c:.3f}</td>" for c in row[1:]) + "</tr>"
        for row in rows[-4:]
    )
    if not rows:
        return (
            "<i style='font-size:12px'>Each Update adds a row here for its time step, as in the hand tables above.</i>"
        )
    return f"<table style='font-family:monospace;font-size:12px'><tr>{head}</tr>{body}</table>"


def _status(m: StepThroughModel) -> str:
    """The text at the top right: what the last button did (or why an Update was refused), and R and Q."""
    if m.note:
        text = m.note
    elif m.phase == "prior":
        text = f"step 0, prior  μ = {m.mu:.3f}, σ² = {m.var:.3f}\npress Predict"
    elif m.phase == "predicted":
        text = rf"Predict to step {m.k}: $\bar\mu$ = {m.mu:.3f}, $\bar\sigma^2$ = {m.var:.3f} (grew by R)"
    else:
        text = f"Update with step {m.k}'s reading z = {m.z:.2f}: K = {m.K:.3f}\nμ = {m.mu:.3f}, σ² = {m.var:.3f}"
    return f"{text}\nR = {m.R:.3g}, Q = {m.Q:.3g}"


def _picture(model: StepThroughModel) -> tuple[FigureRenderer, Callable[[], None]]:
    """The four Gaussians of a step (the belief before it, the prediction, the measurement, the
    updated belief) on an axis that follows the belief, with the status in the corner.

    Returns
    -------
    (renderer, draw)
        ``draw()`` shows the curves of the model's last step, faded in the legend where not shown.
    """
    fig, ax = new_figure(8.0, 3.4)
    ax.set_xlabel("position x (m)")
    ax.set_ylabel("density")
    fixed_width_ticks(ax.yaxis)  # the layout is found once: keep the density labels one width
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
        status.set_text(_status(m))

    return renderer, draw


def step_through(seed: int = 0) -> Demo:
    """Demo "step through" (chapter 3): press Predict and Update to walk the
    scalar Kalman filter one half-step at a time, starting from the worked
    example's prior N(2.0, 0.40) at time step 0.  The k-th Predict moves the robot to
    time step k; an Update uses that step's reading (the worked cycles' 3.6 and 4.7
    at steps 1 and 2) and is refused if the step has none left.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = StepThroughModel(seed)
    renderer, draw_picture = _picture(model)
    table = widgets.HTML()

    def draw() -> None:
        draw_picture()
        table.value = _table(model.rows)

    caption = (
        "<b>Step through the 1-D Kalman filter.</b> Dashed teal: the belief before the step; "
        "purple: the prediction; orange: the measurement N(z, Q); teal: the updated belief. "
        "Each <i>Predict</i> moves the robot +1 m to the next time step; <i>Update</i> reads the sensor at the step "
        "the robot is at (3.6 m at step 1, 4.7 m at step 2, then simulated readings). A step has one reading: a "
        "second Update in a row is refused, since using the same reading twice would count it twice. "
        "The sliders replay every step with new R and Q."
    )
    return Demo(
        name="step-through",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={
            "predict": (button("Predict", icon="arrow-right", tooltip="Move +1 m: shift and widen"), model.predict),
            "update": (
                button("Update", icon="eye", tooltip="Read the sensor at this time step: blend and narrow"),
                model.update,
            ),
            "reset": (button("Reset", icon="undo", tooltip="Back to the prior N(2.0, 0.40)"), model.reset),
            "R": (log_slider("process noise R", model.R), model.set_R),
            "Q": (log_slider("measurement noise Q", model.Q), model.set_Q),
        },
        layout=[["predict", "update", "reset"], ["R", "Q"], table],
    )


def log_slider(description: str, value: float) -> widgets.FloatLogSlider:
    """A noise slider from 0.001 to 10 on a log scale."""
    return slider(widgets.FloatLogSlider, description, value, -3, 1, 0.1, readout_format=".3g", base=10)
