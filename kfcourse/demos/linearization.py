"""Chapter 7: a Gaussian pushed through a nonlinear function, and the EKF's tangent-line answer."""

from __future__ import annotations

import ipywidgets as widgets

from ..plots.ekf import linearization_view, update_linearization_view
from ..plots.style import FigureRenderer
from ..sim.curves import FUNCTIONS, GaussianThroughCurve
from ._base import Demo, slider

X_RANGE = (-4.0, 4.0)
N_SAMPLES = 4000  # fixed standard-normal draws, rescaled by the sliders
# The output axis of each function: x² is cut at 9, so that its bottom shows (wide inputs reach far above).
OUTPUT_LIMITS = {"x²": (-1.0, 9.0), "sin x": (-1.25, 1.25), "range √(x² + 1)": (0.5, 5.5)}
DISPLAY_WIDTH = 848  # CSS px: a laptop's notebook width, where the picture and its controls fit the screen


def linearization(seed: int = 0) -> Demo:
    """Demo "linearization" (chapter 7): a Gaussian through x², sin x or a range,
    the sampled truth against the EKF's tangent-line Gaussian.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = GaussianThroughCurve(seed=seed, m=1.0, s=0.5, function="x²", n_samples=N_SAMPLES)
    view = linearization_view(OUTPUT_LIMITS, X_RANGE)
    caption = (
        "<b>Linearization.</b> Purple: the input N(m, s²). Black: f; teal dashed: its tangent at m (the EKF). "
        f"Right, on the output axis: grey, the true output ({N_SAMPLES} seeded draws through f); teal, the EKF's "
        "N(f(m), f'(m)² s²); dotted, their means. Pick f, drag m and s, compare the numbers."
    )
    demo = Demo(
        name="linearization",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=lambda: update_linearization_view(view, model),
        controls={
            "function": (
                widgets.ToggleButtons(options=list(FUNCTIONS), value=model.function, description="f(x)"),
                model.set_function,
            ),
            "m": (slider(widgets.FloatSlider, "input mean m", model.m, -2.0, 2.0, 0.05), model.set_m),
            "s": (slider(widgets.FloatSlider, "input width s", model.s, 0.05, 1.5, 0.05), model.set_s),
        },
        layout=["function", ["m", "s"]],
        display_width=DISPLAY_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
