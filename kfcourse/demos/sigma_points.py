"""Chapter 9: sigma points pushed through a curve, the UKF's Gaussian against the EKF's tangent guess."""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.patches import Polygon

from ..filters.gaussian import gaussian_pdf
from ..filters.ukf import sigma_points as make_sigma_points
from ..filters.ukf import unscented_1d
from ..plots import palette
from ..plots.style import FigureRenderer
from ._base import Demo, slider
from .linearization import FUNCTIONS, LinearizationModel, function_panels, show_output_axis, sideways_histogram

N_SAMPLES = 20_000  # fixed standard-normal draws, rescaled by the sliders
X_RANGE = (-5.0, 5.0)  # the sigma points reach m +- sqrt(1 + lam) s = 2 + 2 * 1.5 at the sliders' extremes
N_BINS = 60
DENSITY_CAP = 1.5  # output densities are cut at 1.5 times the sampled peak, inside the panel's 1.6
ARROW = 0.3  # length of the arrow drawn for a variance of 0: all the probability at one value
# Output-axis ticks for this demo's wider input range (the functions themselves are chapter 7's).
Y_TICKS = {
    "x²": (0.0, 6.0, 12.0, 18.0, 24.0),
    "sin x": (-1.0, -0.5, 0.0, 0.5, 1.0),
    "range √(x² + 1)": (1.0, 2.0, 3.0, 4.0, 5.0),
}


class SigmaPointsModel(LinearizationModel):
    """Chapter 7's model (input N(m, s^2), a function f, its samples and the EKF's Gaussian)
    plus the spread parameter lam and the UKF's answer.  Introduced in chapter 9."""

    def __init__(self, seed: int = 0, m: float = 2.0, s: float = 1.0, lam: float = 0.0, function: str = "x²"):
        super().__init__(seed=seed, m=m, s=s, function=function)
        self.lam = lam
        self.draws = np.random.default_rng(seed).standard_normal(N_SAMPLES)  # e ~ N(0, 1), fixed; more than chapter 7

    def set_lam(self, lam: float) -> None:
        self.lam = float(lam)

    def sigma_points(self) -> tuple[np.ndarray, np.ndarray]:
        """The three sigma points of N(m, s^2) and their (mean) weights, shapes (3,), (3,)."""
        chi, wm, _wc = make_sigma_points(np.array([self.m]), np.array([[self.s * self.s]]), self.lam)
        return chi[:, 0], wm

    def ukf(self) -> tuple[float, float]:
        """The UKF's output Gaussian: the unscented transform of N(m, s^2) through f."""
        return unscented_1d(self.m, self.s * self.s, FUNCTIONS[self.function][0], self.lam)

    def exact(self) -> tuple[float, float] | None:
        """The exact output mean and variance, known in closed form for y = x² only (None otherwise):
        m² + s² and 4 m² s² + 2 s⁴."""
        if self.function != "x²":
            return None
        m2, s2 = self.m * self.m, self.s * self.s
        return m2 + s2, 4 * m2 * s2 + 2 * s2 * s2  # E[x²], Var[x²] for x ~ N(m, s²)


def _sigma_dots(ax, colour: str):
    """Three dots, one per sigma point (placed, sized and filled by ``draw``)."""
    return ax.scatter([0, 0, 0], [0, 0, 0], s=40, color=colour, edgecolor=colour, lw=1.5, zorder=3)


def _output_density(line, mean: float, var: float, top: float, lo: float, hi: float, grid) -> None:
    """Show N(mean, var) sideways on ``line``, divided by the sampled peak ``top`` and cut at DENSITY_CAP."""
    if var > 1e-12 * (hi - lo) ** 2:
        line.set_data(np.minimum(gaussian_pdf(grid, mean, var) / top, DENSITY_CAP), grid)
        line.set_marker("None")
    else:  # no spread at all: a short arrow at the mean, all the probability at one value
        line.set_data([0.0, 0.0, ARROW, 0.0, 0.0], [lo, mean, mean, mean, hi])
        line.set_marker(">")
        line.set_markevery([2])


def _readout(chi, w, moments) -> str:
    """The text panel: the sigma points and their weights, then each answer's mean and variance."""
    order = [2, 0, 1]  # the points are made as m, m + spread, m - spread; shown left to right
    return (
        f"{'sigma points':12}"
        + "".join(f"{chi[i]:6.2f}" for i in order)
        + f"\n{'weights':12}"
        + "".join(f"{w[i]:6.2f}" for i in order)
        + f"\n\n{'':12}mean{'':7}var\n"
        + "\n".join(f"{name:7}{mean:9.3f} {var:9.4f}" for name, mean, var in moments)
    )


def _picture(model: SigmaPointsModel) -> tuple[FigureRenderer, Callable[[], None]]:
    """The curve f with the sigma points climbing it from the input density, the output densities
    (sampled, UKF, EKF) beside it, and the numbers under those.

    Returns
    -------
    (renderer, draw)
        ``draw()`` shows the model's function, input, sigma points and outputs.
    """
    fig, ax_f, ax_out, ax_in, ax_txt, y_labels = function_panels(
        8.4, 6.0, X_RANGE, Y_TICKS[model.function], width_ratio=1.4, height_ratio=1.3
    )

    x = np.linspace(*X_RANGE, 500)
    (curve,) = ax_f.plot(x, x, color=palette.INK, lw=1.5, label="f(x)")
    (tangent,) = ax_f.plot(x, x, color=palette.MEASUREMENT, lw=1.6, ls="--", label="EKF: tangent at m")
    guides = LineCollection([], colors=palette.PREDICTION, lw=0.9, linestyles=":")
    ax_f.add_collection(guides)
    on_curve = _sigma_dots(ax_f, palette.PREDICTION)
    ax_f.legend(loc="upper center", fontsize=9)  # the middle top: empty above all three curves
    (inp,) = ax_in.plot(x, x, color=palette.PREDICTION, lw=2)
    on_input = _sigma_dots(ax_in, palette.PREDICTION)
    hist = Polygon([[0, 0], [1, 1], [0, 1]], closed=True, facecolor=palette.TRUTH, alpha=0.45, lw=0, label="sampled")
    ax_out.add_patch(hist)
    (ukf,) = ax_out.plot([0, 1], [0, 1], color=palette.ESTIMATE, lw=2.2, label="UKF")
    (ekf,) = ax_out.plot([0, 1], [0, 1], color=palette.MEASUREMENT, lw=1.8, ls="--", label="EKF")
    on_output = _sigma_dots(ax_out, palette.ESTIMATE)
    # Above the panel, where no output density can reach it.
    ax_out.legend(
        loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, fontsize=8, frameon=False, handlelength=1.4,
        columnspacing=0.8, handletextpad=0.4,
    )  # fmt: skip
    # The readout: row names and numbers in one monospace grid (only x² has the row "exact").
    text_style = {"transform": ax_txt.transAxes, "ha": "left", "va": "top", "fontsize": 8.5, "family": "monospace"}
    info = ax_txt.text(-0.12, 1.0, "", **text_style)
    moving = [curve, tangent, guides, on_curve, inp, on_input, hist, ukf, ekf, on_output, info, *y_labels]
    renderer = FigureRenderer(fig, moving)

    def draw() -> None:
        f, df, _ = FUNCTIONS[model.function]
        lo, hi = show_output_axis(ax_f, y_labels, Y_TICKS[model.function])
        curve.set_ydata(f(x))
        m, s = model.m, model.s
        fm, slope = float(f(m)), float(df(m))
        tangent.set_ydata(fm + slope * (x - m))  # f(m) + f'(m) (x - m)
        inp.set_ydata(np.exp(-0.5 * (x - m) ** 2 / (s * s)))  # N(m, s^2) divided by its peak
        chi, w = model.sigma_points()
        Y = f(chi)  # the sigma points through the true f
        on_input.set_offsets(np.column_stack([chi, np.exp(-0.5 * (chi - m) ** 2 / (s * s))]))
        on_curve.set_offsets(np.column_stack([chi, Y]))
        on_output.set_offsets(np.column_stack([np.full(3, 0.04), Y]))
        sizes = 30.0 + 90.0 * np.abs(w)  # dot area grows with the weight
        for dots, colour in (
            (on_input, palette.PREDICTION),
            (on_curve, palette.PREDICTION),
            (on_output, palette.ESTIMATE),
        ):
            dots.set_sizes(sizes)
            dots.set_facecolors([colour if wi > 0 else "white" for wi in w])  # a weight-0 point: an empty ring
        guides.set_segments([[(c, lo), (c, y), (X_RANGE[1], y)] for c, y in zip(chi, Y, strict=True)])
        y = model.samples()
        hist_x, hist_y, top = sideways_histogram(y, lo, hi, N_BINS)  # every output density is divided by top
        hist.set_xy(np.column_stack([hist_x, hist_y]))
        grid = np.linspace(lo, hi, 600)
        mean_y, var_y = float(y.mean()), float(y.var())
        mean_u, var_u = model.ukf()
        mean_e, var_e = model.ekf()
        moments = [("sampled", mean_y, var_y), ("UKF", mean_u, var_u), ("EKF", mean_e, var_e)]
        if model.exact() is not None:
            moments.append(("exact", *model.exact()))
        _output_density(ukf, mean_u, var_u, top, lo, hi, grid)
        _output_density(ekf, mean_e, var_e, top, lo, hi, grid)
        info.set_text(_readout(chi, w, moments))

    return renderer, draw


def sigma_points(seed: int = 0) -> Demo:
    """Demo "sigma points on y = x²" (chapter 9): three sigma points of the input Gaussian
    climb the curve; their images give the UKF's Gaussian, beside the EKF's tangent guess
    and the sampled truth.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = SigmaPointsModel(seed=seed)
    renderer, draw = _picture(model)
    caption = (
        "<b>Sigma points.</b> Purple: the input N(m, s²) and its three sigma points m, m ± √(1+λ)·s "
        "(dot size: weight; a ring: weight 0), carried up the curve f (black) along dotted paths. Right: teal, the "
        "UKF's Gaussian from their images; orange dashed, the EKF's tangent at m and its Gaussian; grey, the sampled "
        "true output (20 000 draws; for x² the readout also gives the exact moments). An arrow: variance 0. "
        "Controls: the function f, the input mean m and width s, the spread λ."
    )
    return Demo(
        name="sigma-points",
        caption=caption,
        model=model,
        renderer=renderer,
        draw=draw,
        controls={
            "function": (
                widgets.ToggleButtons(options=list(FUNCTIONS), value=model.function, description="f(x)"),
                model.set_function,
            ),
            "m": (slider(widgets.FloatSlider, "input mean m", model.m, -2.0, 2.0, 0.05), model.set_m),
            "s": (slider(widgets.FloatSlider, "input width s", model.s, 0.05, 1.5, 0.05), model.set_s),
            "lam": (
                slider(widgets.FloatSlider, "spread λ", model.lam, 0.0, 3.0, 0.1, readout_format=".1f"),
                model.set_lam,
            ),
        },
        layout=["function", ["m", "s"], "lam"],
    )
