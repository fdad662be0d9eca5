"""Chapter 7: a Gaussian pushed through a nonlinear function, and the EKF's tangent-line answer."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..plots.ekf_figures import linearization_view, update_linearization_view
from ..plots.style import FigureRenderer
from ..sim.curve_functions import FUNCTIONS, GaussianThroughCurve
from ._base import Demo, shown, slider

X_RANGE = (-4.0, 4.0)
N_SAMPLES = 4000  # fixed standard-normal draws, rescaled by the sliders
# The output axis of each function: x² is cut at 9, so that its bottom shows (wide inputs reach far above).
OUTPUT_LIMITS = {"x²": (-1.0, 9.0), "sin x": (-1.25, 1.25), "range √(x² + 1)": (0.5, 5.5)}
DISPLAY_WIDTH = 848  # CSS px: a laptop's notebook width, where the picture and its controls fit the screen
SLIDER_FORMAT = ".2f"  # the readout of the m and s sliders; the description writes them the same way
CLOSE = 0.1  # the EKF "matches": its mean within 0.1 true standard deviations, its variance within 10 %
NEAR = 0.01  # or its mean and standard deviation within 0.01 of the true ones (chapter 7: "agrees to 0.01")
FLAT = 0.01  # a variance under 1 % of the true one: the tangent sees (almost) no spread


class LinearizationModel(GaussianThroughCurve):
    """Chapter 7's input N(m, s²) through f, with its samples and the EKF's Gaussian, and a
    sentence that says how well the tangent did."""

    def describe(self) -> str:
        """What the picture shows: the true output's mean and variance against the EKF's, and what that says."""
        mean_y, var_y = self.sampled()
        mean_e, var_e = self.ekf()
        slope = float(self.df(self.m))
        m, s = shown(self.m, SLIDER_FORMAT), shown(self.s, SLIDER_FORMAT)
        numbers = (
            f"With f = {self.function}, m = {m} and s = {s}, the true output has mean {shown(mean_y, '.3f')} "
            f"and variance {shown(var_y, '.3g')}; the EKF's tangent (slope {shown(slope, '.3f')}) gives mean "
            f"{shown(mean_e, '.3f')} and variance {shown(var_e, '.3g')}."
        )
        off = abs(mean_e - mean_y) / np.sqrt(var_y)  # the EKF's mean error in true standard deviations
        ratio = var_e / var_y
        if slope == 0.0:
            verdict = f"The tangent is flat at m: the EKF says variance 0; the true output's is {shown(var_y, '.3g')}."
        elif ratio < FLAT:
            verdict = "The tangent is nearly flat at m: the EKF's variance is under 1 % of the true output's."
        elif off < CLOSE and abs(ratio - 1) < CLOSE:
            verdict = "Over the input's width f is nearly straight, and the EKF's Gaussian matches the true output."
        elif abs(mean_e - mean_y) <= NEAR and abs(np.sqrt(var_e) - np.sqrt(var_y)) <= NEAR:  # narrow, near a flat slope
            verdict = (
                "Over the input's width f is nearly straight: the EKF's mean and standard deviation are within "
                "0.01 of the true ones."
            )
        else:
            verdict = (
                f"The curve bends within the input's width: the EKF's mean is {off:.2f} true standard deviations off, "
                f"its variance {ratio:.2f} times the true one."
            )
        return f"{numbers} {verdict}"


def linearization(seed: int = 0) -> Demo:
    """Demo "linearization" (chapter 7): a Gaussian through x², sin x or a range,
    the sampled truth against the EKF's tangent-line Gaussian.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = LinearizationModel(seed=seed, m=1.0, s=0.5, function="x²", n_samples=N_SAMPLES)
    view = linearization_view(OUTPUT_LIMITS, X_RANGE)
    caption = (
        "<b>Linearization.</b> Purple: the input N(m, s²). Black: f; teal dashed: its tangent at m (the EKF). "
        f"Right, on the output axis: grey, the true output ({N_SAMPLES} seeded draws through f); teal, the EKF's "
        "N(f(m), f'(m)² s²); thin lines, their means (grey dotted, teal solid). Pick f, drag m and s, compare "
        "the numbers."
    )
    demo = Demo(
        name="linearization",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=lambda: update_linearization_view(view, model),
        describe=model.describe,
        controls={
            "function": (
                widgets.ToggleButtons(options=list(FUNCTIONS), value=model.function, description="f(x)"),
                model.set_function,
            ),
            "m": (slider(widgets.FloatSlider, "input mean m", model.m, -2.0, 2.0, 0.05, SLIDER_FORMAT), model.set_m),
            "s": (slider(widgets.FloatSlider, "input width s", model.s, 0.05, 1.5, 0.05, SLIDER_FORMAT), model.set_s),
        },
        layout=["function", ["m", "s"]],
        display_width=DISPLAY_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
