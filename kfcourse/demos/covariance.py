"""Chapter 2: a 2-D Gaussian, its samples and its 1/2/3-sigma ellipses."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..filters.gaussian import mass_inside
from ..plots import palette
from ..plots.artists import covariance_ellipse as ellipse_artist
from ..plots.artists import update_covariance_ellipse
from ..plots.style import FigureRenderer, new_figure
from ._base import Demo, slider

N_SAMPLES = 1000
LIMIT = 7.5  # half-width of the view, both ways: the 3σ contour (at most ±6) and its label fit at every slider position
SIGMAS = (1, 2, 3)


class CovarianceModel:
    """Model: Σ from two variances and a correlation, and fixed standard-normal draws."""

    def __init__(self, seed: int, var_x: float = 2.0, var_y: float = 1.0, rho: float = 0.6):
        self.white = np.random.default_rng(seed).standard_normal((N_SAMPLES, 2))
        self.var_x, self.var_y, self.rho = var_x, var_y, rho

    @property
    def Sig(self) -> np.ndarray:
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


def covariance_ellipse(seed: int = 0) -> Demo:
    """Demo "covariance ellipse" (chapter 2): sliders for σx², σy² and ρ tilt and
    stretch the ellipses; the share of samples inside each is compared with theory.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = CovarianceModel(seed)
    fig, (ax, ax_text) = new_figure(7.6, 4.4, ncols=2, gridspec_kw={"width_ratios": [3, 1.1]})
    ax_text.set_axis_off()
    ax.set_xlim(-LIMIT, LIMIT)
    ax.set_ylim(-LIMIT, LIMIT)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    dots = ax.scatter(*model.samples().T, s=5, color=palette.INK, alpha=0.35, lw=0)
    rings = [
        ellipse_artist(ax, (0, 0), model.Sig, k, palette.ESTIMATE, lw=2.4 - 0.6 * i, alpha=1.0 - 0.25 * i)
        for i, k in enumerate(SIGMAS)
    ]
    labels = [ax.text(0, 0, f"{k}σ", color=palette.ESTIMATE, fontsize=9, weight="bold") for k in SIGMAS]
    (shadow,) = ax.plot([], [], "--", color=palette.INK, lw=1.0, label="1σ shadow: ±σx, ±σy")
    ax_text.legend(handles=[shadow], loc="lower left", fontsize=8)  # beside the plot: never over a contour
    info = ax_text.text(
        0.0, 0.95, "", transform=ax_text.transAxes, ha="left", va="top", fontsize=10, family="monospace"
    )
    theory = mass_inside(np.array(SIGMAS), dim=2)
    renderer = FigureRenderer(fig, [dots, *rings, *labels, shadow, info])

    def draw() -> None:
        Sig = model.Sig
        dots.set_offsets(model.samples())
        w, V = np.linalg.eigh(Sig)
        for ring, label, k in zip(rings, labels, SIGMAS, strict=True):
            update_covariance_ellipse(ring, (0, 0), Sig)
            axis = V[:, 1] if V[0, 1] >= 0 else -V[:, 1]  # the major axis, pointing right
            label.set_position(k * np.sqrt(w[1]) * axis * 1.03)  # at its right end
        sx, sy = np.sqrt(Sig[0, 0]), np.sqrt(Sig[1, 1])  # the 1σ ellipse's shadow: ±sigma_x, ±sigma_y
        shadow.set_data([-sx, sx, sx, -sx, -sx], [-sy, -sy, sy, sy, -sy])
        frac = model.fractions()
        rows = "\n".join(
            f" {k}σ   {100 * f:5.1f}% {100 * t:5.1f}%" for k, f, t in zip(SIGMAS, frac, theory, strict=True)
        )
        info.set_text(
            "Σ =\n"
            f" [{Sig[0, 0]:5.2f} {Sig[0, 1]:5.2f}]\n"
            f" [{Sig[1, 0]:5.2f} {Sig[1, 1]:5.2f}]\n\n"
            f"inside samples theory\n{rows}"
        )

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
        renderer=renderer,
        draw=draw,
        controls={
            "var_x": (slider(widgets.FloatSlider, "σx²", model.var_x, 0.1, 4.0, 0.1), model.set_var_x),
            "var_y": (slider(widgets.FloatSlider, "σy²", model.var_y, 0.1, 4.0, 0.1), model.set_var_y),
            "rho": (slider(widgets.FloatSlider, "ρ", model.rho, -0.95, 0.95, 0.05), model.set_rho),
        },
        layout=[["var_x", "var_y"], "rho"],
    )
