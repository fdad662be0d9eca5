"""Chapter 9: sigma points pushed through a curve, the UKF's Gaussian against the EKF's tangent guess."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..filters.ukf import sigma_points as make_sigma_points
from ..filters.ukf import unscented_1d
from ..plots.style import FigureRenderer
from ..plots.ukf_figures import sigma_points_view, update_sigma_points_view
from ..sim.curve_functions import FUNCTIONS, GaussianThroughCurve
from ._base import Demo, shown, slider

N_SAMPLES = 20_000  # fixed standard-normal draws, rescaled by the sliders
M_RANGE = (-2.5, 2.5)  # the input mean: the worked example's m = 2 has room on both sides
X_RANGE = (-5.5, 5.5)  # the sigma points reach m +- sqrt(1 + lam) s = 2.5 + 2 * 1.5 at the sliders' extremes
# The output axis of each function (chapter 7's functions over this wider input range).
OUTPUT_LIMITS = {"x²": (-3.0, 31.0), "sin x": (-1.25, 1.25), "range √(x² + 1)": (0.5, 6.0)}
DISPLAY_WIDTH = 848  # CSS px: a laptop's notebook width, where the picture and its controls fit the screen
SLIDER_FORMAT = ".2f"  # the readout of the m and s sliders; the description writes them the same way
LAM_FORMAT = ".1f"  # the readout of the lambda slider
SAME_MEAN = 0.001  # two means this close count as equally close to the truth (the readout's last digit)
SAME_VARIANCE = 0.01  # two variances whose errors differ by under 1 % of the true variance: equally close
AGREE = 0.1  # all three agree: both means within 0.1 true standard deviations, both variances within 10 %


def closer(ukf_error: float, ekf_error: float, tie: float) -> str:
    """Which answer is nearer the truth, "UKF", "EKF" or "tie", given their errors."""
    if abs(ukf_error - ekf_error) < tie:
        return "tie"
    return "UKF" if ukf_error < ekf_error else "EKF"


class SigmaPointsModel(GaussianThroughCurve):
    """Chapter 7's input N(m, s²) through f, with its samples and the EKF's Gaussian,
    plus the spread parameter lam and the UKF's answer.  Introduced in chapter 9."""

    def __init__(self, seed: int = 0, m: float = 2.0, s: float = 1.0, lam: float = 0.0, function: str = "x²"):
        super().__init__(seed=seed, m=m, s=s, function=function, n_samples=N_SAMPLES)
        self.lam = lam

    def set_lam(self, lam: float) -> None:
        self.lam = float(lam)

    def sigma_points(self) -> tuple[np.ndarray, np.ndarray]:
        """The three sigma points of N(m, s²) and their (mean) weights, shapes (3,), (3,)."""
        chi, wm, _wc = make_sigma_points(np.array([self.m]), np.array([[self.s * self.s]]), self.lam)
        return chi[:, 0], wm

    def ukf(self) -> tuple[float, float]:
        """The UKF's output Gaussian: the unscented transform of N(m, s²) through f."""
        return unscented_1d(self.m, self.s * self.s, self.f, self.lam)

    def exact(self) -> tuple[float, float] | None:
        """The exact output mean and variance, known in closed form for y = x² only (None otherwise):
        m² + s² and 4 m² s² + 2 s⁴."""
        if self.function != "x²":
            return None
        m2, s2 = self.m * self.m, self.s * self.s
        return m2 + s2, 4 * m2 * s2 + 2 * s2 * s2  # E[x²], Var[x²] for x ~ N(m, s²)

    def describe(self) -> str:
        """What the picture shows: where the sigma points sit, and which answer, the UKF's or the EKF's,
        is nearer the true output's mean and variance (the exact ones for x², else the sampled ones), or
        that all three agree (a narrow input)."""
        chi, w = self.sigma_points()
        left, right = sorted(chi[1:])
        (mean_u, var_u), (mean_e, var_e) = self.ukf(), self.ekf()
        truth = "exact" if self.exact() is not None else "sampled"
        mean_t, var_t = self.exact() if truth == "exact" else self.sampled()
        x = [shown(value, SLIDER_FORMAT) for value in (left, self.m, right)]
        weight = shown(w[0], ".2f")
        points = (
            f"With f = {self.function}, m = {shown(self.m, SLIDER_FORMAT)}, s = {shown(self.s, SLIDER_FORMAT)} "
            f"and λ = {shown(self.lam, LAM_FORMAT)}, the sigma points sit at {x[0]}, {x[1]} and {x[2]} "
            f"(the middle one weighs {'0' if float(weight) == 0 else weight})."
        )
        sd_t = np.sqrt(var_t)
        if all(
            abs(mean - mean_t) < AGREE * sd_t and abs(var / var_t - 1) < AGREE
            for mean, var in ((mean_u, var_u), (mean_e, var_e))
        ):
            verdict = "all three agree"
        else:
            by_mean = closer(abs(mean_u - mean_t), abs(mean_e - mean_t), SAME_MEAN)
            by_var = closer(abs(var_u - var_t) / var_t, abs(var_e - var_t) / var_t, SAME_VARIANCE)
            if by_mean == by_var != "tie":
                verdict = f"the {by_mean} is closer in both"
            else:
                verdict = "; ".join(
                    [
                        _nearer(by_mean, "mean", shown(mean_u, ".3f"), shown(mean_e, ".3f")),
                        _nearer(by_var, "variance", shown(var_u, ".4g"), shown(var_e, ".4g")),
                    ]
                )
        answers = (
            f"Against the {truth} output's mean {shown(mean_t, '.3f')} and variance {shown(var_t, '.4g')}, the UKF "
            f"gives {shown(mean_u, '.3f')} and {shown(var_u, '.4g')}, the EKF {shown(mean_e, '.3f')} and "
            f"{shown(var_e, '.4g')}: {verdict}."
        )
        return f"{points} {answers}"


def _nearer(who: str, what: str, ukf: str, ekf: str) -> str:
    """One clause of the verdict: which answer is closer in ``what`` ("mean" or "variance"), given
    the two answers as shown; equally close ones that read the same are named once."""
    if who != "tie":
        return f"the {who} is closer in the {what}"
    return f"both give the {what} {ukf}" if ukf == ekf else f"neither is closer in the {what}"


def sigma_points(seed: int = 0) -> Demo:
    """Demo "sigma points on y = x²" (chapter 9): three sigma points of the input Gaussian
    climb the curve; their images give the UKF's Gaussian, beside the EKF's tangent guess
    and the sampled truth.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    seed = v.whole(seed, "seed", 0)
    model = SigmaPointsModel(seed=seed)
    view = sigma_points_view(OUTPUT_LIMITS, X_RANGE)
    caption = (
        "<b>Sigma points.</b> Purple: the input N(m, s²) and its sigma points m, m ± √(1+λ)·s (dot size: weight; "
        "a ring: weight 0), carried up the curve f (black). Right: teal solid, the UKF's Gaussian from their images; "
        "teal dashed, the EKF's tangent and its Gaussian; grey, the true output (20 000 draws). "
        "An arrow: variance 0."
    )
    demo = Demo(
        name="sigma-points",
        caption=caption,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=lambda: update_sigma_points_view(view, model),
        describe=model.describe,
        controls={
            "function": (
                widgets.ToggleButtons(options=list(FUNCTIONS), value=model.function, description="f(x)"),
                model.set_function,
            ),
            "m": (slider(widgets.FloatSlider, "input mean m", model.m, *M_RANGE, 0.05, SLIDER_FORMAT), model.set_m),
            "s": (slider(widgets.FloatSlider, "input width s", model.s, 0.05, 1.5, 0.05, SLIDER_FORMAT), model.set_s),
            "lam": (
                slider(widgets.FloatSlider, "spread λ", model.lam, 0.0, 3.0, 0.1, readout_format=LAM_FORMAT),
                model.set_lam,
            ),
        },
        layout=["function", ["m", "s"], "lam"],
        display_width=DISPLAY_WIDTH,
    )
    demo.view = view  # the artists by name, for tests
    return demo
