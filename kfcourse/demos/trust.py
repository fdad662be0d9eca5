"""Chapter 4: the Kalman gain as a trust slider between prediction and measurement."""

from __future__ import annotations

from functools import partial

import ipywidgets as widgets

from .. import _validate as v
from ..filters.gaussian import fuse
from ..filters.kalman_1d import kf_1d_gain
from ..plots.style import FigureRenderer
from ..plots.trust_view import trust_view, update_trust
from ._base import Demo, shown, slider

MEAN_FORMAT = ".2f"  # the mean sliders' readouts
VARIANCE_FORMAT = ".3f"  # the variance sliders' readouts


class TrustModel:
    """Model: a prediction N(mu_pred, var_pred) and a measurement N(z, var_meas).

    The sliders set the four numbers; :attr:`K` and :meth:`fused` follow from them.
    """

    # Variances start on the log sliders' grid (10^k, k a multiple of 0.05), so the readouts match the model.
    def __init__(self, mu_pred: float = -1.0, var_pred: float = 1.0, z: float = 1.5, var_meas: float = 10**-0.5):
        self.mu_pred, self.var_pred, self.z, self.var_meas = mu_pred, var_pred, z, var_meas

    @property
    def K(self) -> float:
        """The Kalman gain: the share of the way from the prediction to the measurement."""
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
        """The fused mean and variance (inverse-variance weighting, the same as the Kalman update)."""
        return fuse(self.mu_pred, self.var_pred, self.z, self.var_meas)

    def describe(self) -> str:
        """What the picture shows in one sentence: the gain K as the share of the way from the prediction
        to the measurement, which of the two is surer, and the fused variance, narrower than both."""
        mu_f, var_f = self.fused()
        prediction = f"mean {shown(self.mu_pred, MEAN_FORMAT)}, variance {shown(self.var_pred, VARIANCE_FORMAT)}"
        measurement = f"z = {shown(self.z, MEAN_FORMAT)}, variance {shown(self.var_meas, VARIANCE_FORMAT)}"
        if shown(self.var_pred, VARIANCE_FORMAT) != shown(self.var_meas, VARIANCE_FORMAT):  # one is surer
            if self.K < 0.5:
                prediction += ", the surer one"
            else:
                measurement += ", the surer one"
        share = 100 * self.K
        share = f"{share:.0f}" if 1 <= share <= 99 else f"{share:.1f}"  # never "0 %" or "100 %" of the way
        variance = shown(var_f, VARIANCE_FORMAT)  # as the variance sliders write theirs
        surer = min(self.var_pred, self.var_meas)
        if var_f >= surer:
            narrower = "not narrower than both"
        elif variance == shown(surer, VARIANCE_FORMAT):  # narrower by less than the readouts show
            narrower = "only just narrower than both"
        else:
            narrower = "narrower than both"
        return (
            f"K = {self.K:.3f}: the fused mean {shown(mu_f, '.3f')} lies {share} % of the way from the prediction "
            f"({prediction}) to the measurement ({measurement}); its variance {variance} is {narrower}."
        )


def trust_slider(seed: int = 0) -> Demo:
    """Demo "trust slider" (chapter 4): drag the two variances (and means) and
    watch K move between "trust the prediction" and "trust the measurement".
    ``seed`` is accepted for a uniform demo signature; this demo draws no noise.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = TrustModel()
    view = trust_view()
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
        renderer=FigureRenderer(view.fig, view.moving),
        draw=partial(update_trust, view, model),
        describe=model.describe,
        controls={
            "mu_pred": (
                slider(widgets.FloatSlider, "prediction mean", m.mu_pred, -4.0, 4.0, 0.1, MEAN_FORMAT),
                m.set_mu_pred,
            ),
            "var_pred": (log_slider("prediction variance", m.var_pred), m.set_var_pred),
            "z": (slider(widgets.FloatSlider, "measurement z", m.z, -4.0, 4.0, 0.1, MEAN_FORMAT), m.set_z),
            "var_meas": (log_slider("measurement variance", m.var_meas), m.set_var_meas),
        },
        layout=[["mu_pred", "var_pred"], ["z", "var_meas"]],
    )


def log_slider(description: str, value: float) -> widgets.FloatLogSlider:
    """A variance slider from 0.01 to 10 on a log scale."""
    return slider(widgets.FloatLogSlider, description, value, -2, 1, 0.05, VARIANCE_FORMAT, base=10)
