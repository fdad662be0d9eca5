"""Chapter 3: one predict / update cycle at a time, on Gaussian curves."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..filters.kalman_1d import kf_1d_gain, kf_1d_predict, kf_1d_update
from ..plots.step_through_view import step_through_view, update_step_through
from ..plots.style import FigureRenderer
from ._base import Demo, button, shown, slider

MU0, VAR0 = 2.0, 0.40  # the worked example's prior at time step 0 (chapter 3): m, m^2
U = 1.0  # m commanded each step
WORKED_Z = (3.6, 4.7)  # the worked cycles' readings at time steps 1 and 2 (m)
SENSOR_VAR = 0.1  # m^2: noise of the simulated readings after step 2 (the worked example's Q)
NOISE_FORMAT = ".3g"  # the R and Q sliders' readouts


class StepThroughModel:
    """Model: the buttons pressed so far, replayed with the current R and Q.

    Readings belong to time steps.  The robot starts at time step 0; the k-th
    Predict moves it to time step k, and an Update reads the sensor there
    (:meth:`reading`).  Each time step has one reading, so an Update is refused,
    with a note, before the first Predict and once this step's reading is in
    the belief: using it again would count the same evidence twice and make
    the filter overconfident.

    Attributes
    ----------
    R, Q : float
        Process and measurement noise variances (m²).
    k : int
        The time step the robot is at.
    phase : str
        What the last press did: ``"prior"`` (nothing yet), ``"predicted"`` or ``"updated"``.
    before : (float, float)
        Mean and variance before the last half-step.
    predicted : (float, float) or None
        The last prediction (mean, variance); None before the first Predict.
    z, K : float or None
        The reading and the gain of the last Update, if the last press was one.
    mu, var : float
        The belief now.
    rows : list of tuple
        One row per Update: step, predicted mean and variance, z, innovation, K, mean, variance.
    note : str
        Why the last Update was refused, or empty.
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

    def describe(self) -> str:
        """What the picture shows in a sentence: what the last press did (or why an Update was refused),
        the belief now, and R and Q as their sliders show them."""
        noise = f"R = {shown(self.R, NOISE_FORMAT)}, Q = {shown(self.Q, NOISE_FORMAT)}"
        belief = f"mean {self.mu:.3f}, variance {self.var:.3f}"
        if self.note:
            why = "no reading at step 0" if self.k == 0 else f"step {self.k}'s reading is already used, once is enough"
            return f"Update refused ({why}): the belief stays at {belief}; {noise}."
        if self.phase == "prior":
            return f"Step 0, the prior: {belief}; press Predict. {noise}."
        mu_bar, var_bar = self.predicted
        mu_before, var_before = self.before
        if self.phase == "predicted":
            return (
                f"Predict to step {self.k}: the mean moved +{U:.0f} m from {mu_before:.3f} to {self.mu:.3f} and "
                f"the variance grew by R from {var_before:.3f} to {self.var:.3f}; {noise}."
            )
        return (
            f"Update with step {self.k}'s reading z = {self.z:.2f}: K = {self.K:.3f}, so the mean moved {self.K:.3f} "
            f"of the way from the prediction {mu_bar:.3f} towards z, to {self.mu:.3f}, and the variance shrank "
            f"from {var_bar:.3f} to {self.var:.3f}; {noise}."
        )


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
    seed = v.whole(seed, "seed", 0)
    model = StepThroughModel(seed)
    view = step_through_view()
    table = widgets.HTML()

    def draw() -> None:
        update_step_through(view, model)
        table.value = _table(model.rows)

    caption = (
        "<b>Step through the 1-D Kalman filter.</b> Thin teal: the belief before the step; "
        "dashed purple: the prediction; dash-dot orange: the measurement N(z, Q); teal: the updated belief. "
        "Each <i>Predict</i> moves the robot +1 m to the next time step; <i>Update</i> reads the sensor at the step "
        "the robot is at (3.6 m at step 1, 4.7 m at step 2, then simulated readings). A step has one reading: a "
        "second Update in a row is refused, since using the same reading twice would count it twice. "
        "The sliders replay every step with new R and Q."
    )
    return Demo(
        name="step-through",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=draw,
        describe=model.describe,
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
    return slider(widgets.FloatLogSlider, description, value, -3, 1, 0.1, readout_format=NOISE_FORMAT, base=10)
