"""Chapter 2: a 2-D Gaussian, its samples and its 1/2/3-sigma ellipses."""

from __future__ import annotations

from functools import partial

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..filters.gaussian import mass_inside
from ..plots.covariance_view import covariance_view, update_covariance
from ..plots.style import FigureRenderer
from ._base import Demo, shown, slider

N_SAMPLES = 1000
SIGMAS = (1, 2, 3)  # the contours drawn, in standard deviations
SLIDER_FORMAT = ".2f"  # the readouts of the sliders σx², σy² and ρ


class CovarianceModel:
    """Model: Σ from two variances and a correlation, and fixed standard-normal draws.

    Attributes
    ----------
    white : ndarray, shape (N_SAMPLES, 2)
        Standard-normal draws, fixed by the seed; :meth:`samples` reshapes them by Σ.
    var_x, var_y : float
        The variances on the diagonal of Σ.
    rho : float
        The correlation, in (-1, 1).
    """

    def __init__(self, seed: int, var_x: float = 2.0, var_y: float = 1.0, rho: float = 0.6):
        self.white = np.random.default_rng(seed).standard_normal((N_SAMPLES, 2))
        self.var_x, self.var_y, self.rho = var_x, var_y, rho

    @property
    def Sig(self) -> np.ndarray:
        """Σ = [[σx², ρ σx σy], [ρ σx σy, σy²]]."""
        c = self.rho * np.sqrt(self.var_x * self.var_y)  # covariance = rho sigma_x sigma_y
        return np.array([[self.var_x, c], [c, self.var_y]])

    def set_var_x(self, var_x: float) -> None:
        self.var_x = var_x

    def set_var_y(self, var_y: float) -> None:
        self.var_y = var_y

    def set_rho(self, rho: float) -> None:
        self.rho = rho

    def samples(self) -> np.ndarray:
        """x = L w with L L^T = Σ: the same draws reshaped by the current Σ."""
        return self.white @ np.linalg.cholesky(self.Sig).T

    def fractions(self) -> np.ndarray:
        """Share of samples inside the 1, 2, 3-sigma ellipses."""
        d2 = np.sum(self.white**2, axis=1)  # squared Mahalanobis distance of each sample
        return np.array([np.mean(d2 <= k * k) for k in SIGMAS])

    def axes(self) -> tuple[float, float]:
        """The ellipses' long axis: its angle above the x axis, θ = ½ atan2(2 Σxy, Σxx − Σyy) in degrees,
        and how many times the short axis it is, √(λmax / λmin) from the eigenvalues of Σ."""
        Sig = self.Sig
        angle = 0.5 * np.degrees(np.arctan2(2.0 * Sig[0, 1], Sig[0, 0] - Sig[1, 1]))
        small, large = np.linalg.eigvalsh(Sig)
        return float(angle), float(np.sqrt(large / small))

    def describe(self) -> str:
        """What the picture shows in two sentences: how Σ stretches and tilts the ellipses, and the
        share of the samples inside each contour against theory."""
        angle, ratio = self.axes()
        sliders = {"σx²": self.var_x, "σy²": self.var_y, "ρ": self.rho}
        values = ", ".join(f"{name} = {shown(value, SLIDER_FORMAT)}" for name, value in sliders.items())
        shape = f"the long axis is {ratio:.1f} times the short one"
        if f"{ratio:.1f}" == "1.0":
            round_ = self.var_x == self.var_y and self.rho == 0.0
            shape = "the ellipses are circles" if round_ else "the ellipses are nearly circles"
        elif self.rho == 0.0:
            shape += f", along the {'x' if self.var_x > self.var_y else 'y'} axis"
        else:
            degrees = f"{abs(angle):.0f}" if abs(angle) >= 1.0 else f"{abs(angle):.1f}"
            shape += f", {degrees}° {'above' if angle > 0 else 'below'} the x axis"
        inside = ", ".join(f"{100 * f:.1f} %" for f in self.fractions())
        theory = ", ".join(f"{100 * t:.1f} %" for t in mass_inside(np.array(SIGMAS), dim=2))
        return f"With {values}, {shape}. The 1σ, 2σ, 3σ contours hold {inside} of the samples (theory: {theory})."


def covariance_ellipse(seed: int = 0) -> Demo:
    """Demo "covariance ellipse" (chapter 2): sliders for σx², σy² and ρ tilt and
    stretch the ellipses; the share of samples inside each is compared with theory.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = CovarianceModel(seed)
    view = covariance_view(SIGMAS)
    caption = (
        "<b>Covariance ellipse.</b> Dots: 1000 samples of N(0, Σ); teal: the 1σ, 2σ, 3σ contours; dashed: the box "
        "±σx, ±σy that the 1σ contour fits in (its shadow on the axes). σx² and σy² stretch the ellipse, "
        "ρ tilts it; the table compares the share of samples inside each contour with theory "
        "(1 − e<sup>−k²/2</sup> in 2-D)."
    )
    return Demo(
        name="covariance-ellipse",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=partial(update_covariance, view, model),
        describe=model.describe,
        controls={
            "var_x": (slider(widgets.FloatSlider, "σx²", model.var_x, 0.1, 4.0, 0.1, SLIDER_FORMAT), model.set_var_x),
            "var_y": (slider(widgets.FloatSlider, "σy²", model.var_y, 0.1, 4.0, 0.1, SLIDER_FORMAT), model.set_var_y),
            "rho": (slider(widgets.FloatSlider, "ρ", model.rho, -0.95, 0.95, 0.05, SLIDER_FORMAT), model.set_rho),
        },
        layout=[["var_x", "var_y"], "rho"],
    )
