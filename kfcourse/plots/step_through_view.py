r"""Chapter 3's picture: one half-step of the 1-D Kalman filter on Gaussian curves.

Four curves, of which each half-step shows some: the belief before the step (thin
teal), the prediction :math:`\overline{bel}` (purple, dashed), the measurement
:math:`\mathcal N(z, Q)` around the reading (orange, dash-dot, as is the line at the reading) and
the belief after the update (teal, solid).  The legend fades the entries of the curves not shown.
The x axis follows the belief, a whole number of metres at its centre; the density
axis's top is a power of two (:func:`~kfcourse.plots.style.nice_limit`), so that both
move in coarse steps.  A text at the top right says what the last button did.

:func:`step_through_view` builds the figure; :func:`update_step_through` shows a
model's last half-step on it.  Introduced in chapter 3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.text import Text

from . import palette
from .artists import gaussian_curve, update_gaussian_curve
from .style import fixed_width_ticks, new_figure, nice_limit, set_limits

HALF_WIDTH = 3.5  # m shown either side of the belief's centre
GRID_POINTS = 600  # points along each curve

# Which of (before, prediction, measurement, belief) each phase shows.
SHOWN = {
    "prior": (False, False, False, True),
    "predicted": (True, True, False, False),
    "updated": (False, True, True, True),
}


@dataclass(frozen=True)
class StepThroughView:
    """What :func:`step_through_view` drew; :func:`update_step_through` moves it."""

    fig: Figure
    ax: Axes
    before: tuple[Line2D, None]  #: the belief before this step (thin, unfilled)
    prediction: tuple[Line2D, PolyCollection]
    measurement: tuple[Line2D, PolyCollection]
    belief: tuple[Line2D, PolyCollection]
    reading: Line2D  #: the reading z, a dash-dot vertical line
    legend: Legend  #: background: its entries fade when their curves are hidden
    status: Text  #: top right: what the last button did, and R and Q

    @property
    def curves(self) -> tuple:
        """The four curves, in the order of :data:`SHOWN`."""
        return self.before, self.prediction, self.measurement, self.belief

    @property
    def moving(self) -> list:
        """Every artist that moves with the model.  The legend is not one: it changes only with
        the phase, and a change to it redraws the background."""
        return [a for curve in self.curves for a in curve if a is not None] + [self.reading, self.status]


def step_through_view() -> StepThroughView:
    """The axes, the four curves, the reading's line, the legend and the status, all to be placed.

    Returns
    -------
    StepThroughView
    """
    fig, ax = new_figure(8.0, 3.4)
    ax.set_xlabel("position x (m)")
    ax.set_ylabel("density")
    fixed_width_ticks(ax.yaxis)  # the layout is found once: keep the density labels one width
    x = np.linspace(-HALF_WIDTH, HALF_WIDTH, GRID_POINTS)
    before = gaussian_curve(ax, x, 0.0, 1.0, palette.ESTIMATE, "belief before this step", fill=False)
    before[0].set_linewidth(1.4)  # the last estimate: thin, solid as an estimate is, without fill
    prediction = gaussian_curve(ax, x, 0.0, 1.0, palette.PREDICTION, r"prediction  $\overline{bel}$")
    measurement = gaussian_curve(ax, x, 0.0, 1.0, palette.MEASUREMENT, "measurement  N(z, Q)")
    belief = gaussian_curve(ax, x, 0.0, 1.0, palette.ESTIMATE, "belief  bel")
    reading = ax.axvline(0.0, color=palette.MEASUREMENT, lw=1, ls=palette.MEASUREMENT_LINE)
    legend = ax.legend(loc="upper left", fontsize=9)
    status = ax.text(0.99, 0.97, "", transform=ax.transAxes, ha="right", va="top", fontsize=10)
    return StepThroughView(fig, ax, before, prediction, measurement, belief, reading, legend, status)


def update_step_through(view: StepThroughView, model) -> None:
    """Show the curves of the model's last half-step, on an x axis centred near its belief.

    Parameters
    ----------
    view : StepThroughView
    model
        Anything with ``phase`` (``"prior"``, ``"predicted"`` or ``"updated"``), ``before``,
        ``predicted`` (or None before the first Predict) and ``(mu, var)``, each a mean and a
        variance, ``z`` (the reading used, or None), ``K``, ``k`` (the time step), ``R``,
        ``Q`` and ``note`` (why an Update was refused, or empty), such as
        :class:`kfcourse.demos.step_through.StepThroughModel`.
    """
    m = model
    centre = round(m.mu)
    lo, hi = centre - HALF_WIDTH, centre + HALF_WIDTH
    grid = np.linspace(lo, hi, GRID_POINTS)
    shown = SHOWN[m.phase]
    params = (m.before, m.predicted or m.before, (m.z or 0.0, m.Q), (m.mu, m.var))
    for handle, label, visible in zip(view.legend.legend_handles, view.legend.get_texts(), shown, strict=True):
        _set_alpha(handle, 1.0 if visible else 0.25)  # fade the entries of curves not shown now
        _set_alpha(label, 1.0 if visible else 0.4)
    peak = 0.0
    for curve, visible, (mu, var) in zip(view.curves, shown, params, strict=True):
        for artist in curve:
            if artist is not None:
                artist.set_visible(visible)
        curve[0].set_xdata(grid)
        if visible:
            peak = max(peak, float(update_gaussian_curve(curve, mu, max(var, 1e-9)).max()))
    view.reading.set_visible(m.phase == "updated")
    view.reading.set_xdata([m.z or 0.0] * 2)
    top = nice_limit(1.1 * peak)
    set_limits(view.ax, xlim=(lo, hi), ylim=(0.0, top))
    view.status.set_text(_status(m))


def _set_alpha(artist, alpha: float) -> None:
    """Set the alpha of a legend entry if it differs: the legend is part of the background,
    and setting an alpha, even the same one, marks the figure for a full redraw."""
    if artist.get_alpha() != alpha:
        artist.set_alpha(alpha)


def _status(m) -> str:
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
