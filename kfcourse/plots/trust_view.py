r"""Chapter 4's picture: the Kalman gain as a trust slider between two Gaussians.

On top, the prediction :math:`\mathcal N(\bar\mu, \bar\sigma^2)` (purple), the
measurement :math:`\mathcal N(z, \sigma_Q^2)` (orange) and their fusion (teal, thicker),
with a readout above the axes: the gain :math:`K = \bar\sigma^2 / (\bar\sigma^2 + \sigma_Q^2)`
as a sum, the fused mean and variance, and whether the fused variance is below both
inputs.  Underneath, :math:`K` as a 0-1 gauge (:func:`~kfcourse.plots.artists.gain_gauge`).
The density axis's top is a power of two (:func:`~kfcourse.plots.style.nice_limit`).

:func:`trust_view` builds the figure; :func:`update_trust` shows a model's two inputs
and their fusion on it.  Introduced in chapter 4.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from matplotlib.text import Text

from . import palette
from .artists import gain_gauge, gaussian_curve, update_gain_gauge, update_gaussian_curve
from .style import fixed_width_ticks, new_figure, nice_limit, set_limits

X_RANGE = (-6.0, 6.0)  # the position axis
GRID_POINTS = 800  # points along each curve


@dataclass(frozen=True)
class TrustView:
    """What :func:`trust_view` drew; :func:`update_trust` moves it."""

    fig: Figure
    ax: Axes  #: the three densities
    ax_gain: Axes  #: the gauge
    prediction: tuple[Line2D, PolyCollection]
    measurement: tuple[Line2D, PolyCollection]
    fused: tuple[Line2D, PolyCollection]
    readout: Text  #: above the axes: K, the fused mean and variance, and the verdict
    gauge: tuple[Rectangle, Text]  #: the gain's bar and its label

    @property
    def moving(self) -> list:
        """Every artist that changes with the model (the gauge's bar and label last)."""
        return [*self.prediction, *self.measurement, *self.fused, self.readout, *self.gauge]


def trust_view() -> TrustView:
    """The densities' axes with their three curves and readout, and the gain's gauge, all to be placed.

    Returns
    -------
    TrustView
    """
    fig, (ax, ax_gain) = new_figure(8.0, 4.0, nrows=2, gridspec_kw={"height_ratios": [5, 1]})
    x = np.linspace(*X_RANGE, GRID_POINTS)
    ax.set_xlim(*X_RANGE)
    ax.set_xlabel("position x")
    ax.set_ylabel("density")
    fixed_width_ticks(ax.yaxis)  # the layout is found once: keep the density labels one width
    prediction = gaussian_curve(ax, x, 0.0, 1.0, palette.PREDICTION, "prediction")
    measurement = gaussian_curve(ax, x, 0.0, 1.0, palette.MEASUREMENT, "measurement")
    fused = gaussian_curve(ax, x, 0.0, 1.0, palette.ESTIMATE, "fused")
    fused[0].set_linewidth(3)
    ax.legend(loc="upper left", fontsize=9)
    ax.set_title("\u00a0\n\u00a0", fontsize=10)  # reserves room above the axes for the readout
    readout = ax.text(0.0, 1.02, "", transform=ax.transAxes, ha="left", va="bottom", fontsize=10)
    gauge = gain_gauge(ax_gain)
    return TrustView(fig, ax, ax_gain, prediction, measurement, fused, readout, gauge)


def update_trust(view: TrustView, model) -> None:
    r"""Show the model's prediction, measurement, their fusion and the gain.

    Parameters
    ----------
    view : TrustView
    model
        Anything with ``mu_pred``, ``var_pred`` (the prediction), ``z``, ``var_meas`` (the
        measurement), ``K`` (the gain) and ``fused()`` (the fused mean and variance), such
        as :class:`kfcourse.demos.trust.TrustModel`.
    """
    m = model
    mu_f, var_f = m.fused()
    update_gaussian_curve(view.prediction, m.mu_pred, m.var_pred)
    update_gaussian_curve(view.measurement, m.z, m.var_meas)
    peak = float(update_gaussian_curve(view.fused, mu_f, var_f).max())
    top = nice_limit(1.1 * peak)
    set_limits(view.ax, ylim=(0.0, top))
    update_gain_gauge(view.gauge, m.K)
    inputs = f"min({m.var_pred:.3g}, {m.var_meas:.3g})"
    if var_f < min(m.var_pred, m.var_meas):
        verdict = f"σ² = {var_f:.3g} < {inputs}: narrower than both inputs"
    else:
        verdict = f"σ² = {var_f:.3g} ≥ {inputs}: not narrower than both inputs"
    view.readout.set_text(
        f"K = {m.var_pred:.3g} / ({m.var_pred:.3g} + {m.var_meas:.3g}) = {m.K:.3f}"
        f"      fused: μ = {mu_f:.3f}, σ² = {var_f:.3g}\n{verdict}"
    )
