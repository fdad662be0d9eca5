"""Chapter 4: the Kalman gain as a trust slider between prediction and measurement."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..filters.gaussian import fuse
from ..filters.kalman_1d import kf_1d_gain
from ..plots import palette
from ..plots.artists import gain_gauge, gaussian_curve, update_gain_gauge, update_gaussian_curve
from ..plots.style import FigureRenderer, fixed_width_ticks, new_figure, nice_limit
from ._base import Demo, slider

X_RANGE = (-6.0, 6.0)


class TrustModel:
    """Model: a prediction N(mu_pred, var_pred) and a measurement N(z, var_meas)."""

    # Variances start on the log sliders' grid (10^k, k a multiple of 0.05), so the readouts match the model.
    def __init__(self, mu_pred: float = -1.0, var_pred: float = 1.0, z: float = 1.5, var_meas: float = 10**-0.5):
        self.mu_pred, self.var_pred, self.z, self.var_meas = mu_pred, var_pred, z, var_meas

    @property
    def K(self) -> float:
        return kf_1d_gain(self.var_pred, Q=self.var_meas)  # K = var_bar / (var_bar + var_Q), c = 1

    def set_mu_pred(self, mu_pred: float) -> None:
        self.mu_pred = mu_pred

    def set_var_pred(self, var_pred: float) -> None:
        self.var_pred = var_pred

    def set_z(self, z: float) -> None:
        self.z = z

    def set_var_meas(self, var_meas: float) -> None:
        self.var_meas = var_meas

    def fused(self) -> tuple[float, float]:
        return fuse(self.mu_pred, self.var_pred, self.z, self.var_meas)


def trust_slider(seed: int = 0) -> Demo:
    """Demo "trust slider" (chapter 4): drag the two variances (and means) and
    watch K move between "trust the prediction" and "trust the measurement".
    ``seed`` is accepted for a uniform demo signature; this demo draws no noise.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = TrustModel()
    fig, (ax, ax_k) = new_figure(8.0, 4.0, nrows=2, gridspec_kw={"height_ratios": [5, 1]})
    x = np.linspace(*X_RANGE, 800)
    ax.set_xlim(*X_RANGE)
    ax.set_xlabel("position x")
    ax.set_ylabel("density")
    fixed_width_ticks(ax.yaxis)  # the layout is found once: keep the density labels one width
    pred = gaussian_curve(ax, x, model.mu_pred, model.var_pred, palette.PREDICTION, "prediction")
    meas = gaussian_curve(ax, x, model.z, model.var_meas, palette.MEASUREMENT, "measurement")
    fused = gaussian_curve(ax, x, *model.fused(), palette.ESTIMATE, "fused")
    fused[0].set_linewidth(3)
    ax.legend(loc="upper left", fontsize=9)
    ax.set_title("\u00a0\n\u00a0", fontsize=10)  # reserves room above the axes for the readout
    info = ax.text(0.0, 1.02, "", transform=ax.transAxes, ha="left", va="bottom", fontsize=10)
    gauge = gain_gauge(ax_k, model.K)
    renderer = FigureRenderer(fig, [*pred, *meas, *fused, info, *gauge])

    def draw() -> None:
        mu_f, var_f = model.fused()
        update_gaussian_curve(pred, model.mu_pred, model.var_pred)
        update_gaussian_curve(meas, model.z, model.var_meas)
        peak = float(update_gaussian_curve(fused, mu_f, var_f).max())
        top = nice_limit(1.1 * peak)
        if ax.get_ylim()[1] != top:
            ax.set_ylim(0, top)
        update_gain_gauge(gauge, model.K)
        narrowest = min(model.var_pred, model.var_meas)
        if var_f < narrowest:
            verdict = f"σ² = {var_f:.3g} < min({model.var_pred:.3g}, {model.var_meas:.3g}): narrower than both inputs"
        else:
            verdict = (
                f"σ² = {var_f:.3g} ≥ min({model.var_pred:.3g}, {model.var_meas:.3g}): not narrower than both inputs"
            )
        info.set_text(
            f"K = {model.var_pred:.3g} / ({model.var_pred:.3g} + {model.var_meas:.3g}) = {model.K:.3f}"
            f"      fused: μ = {mu_f:.3f}, σ² = {var_f:.3g}\n{verdict}"
        )

    caption = (
        "<b>The gain as a trust slider.</b> Purple: the prediction; orange: the measurement; "
        "teal: the fused belief, always narrower than both. The bar shows K from 0 (trust the "
        "prediction) to 1 (trust the measurement). Drag the variances and the means."
    )
    m = model
    return Demo(
        name="trust-slider",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={
            "mu_pred": (slider(widgets.FloatSlider, "prediction mean", m.mu_pred, -4.0, 4.0, 0.1), m.set_mu_pred),
            "var_pred": (log_slider("prediction variance", m.var_pred), m.set_var_pred),
            "z": (slider(widgets.FloatSlider, "measurement z", m.z, -4.0, 4.0, 0.1), m.set_z),
            "var_meas": (log_slider("measurement variance", m.var_meas), m.set_var_meas),
        },
        layout=[["mu_pred", "var_pred"], ["z", "var_meas"]],
    )


def log_slider(description: str, value: float) -> widgets.FloatLogSlider:
    """A variance slider from 0.01 to 10 on a log scale."""
    return slider(widgets.FloatLogSlider, description, value, -2, 1, 0.05, ".3f", base=10)
