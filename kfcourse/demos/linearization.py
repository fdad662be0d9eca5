"""Chapter 7: a Gaussian pushed through a nonlinear function, and the EKF's tangent-line answer."""

from __future__ import annotations

from collections.abc import Callable

import ipywidgets as widgets
import numpy as np

from ..filters.gaussian import gaussian_pdf
from ..plots import palette
from ..plots.style import FigureRenderer, moving_tick_labels, new_figure, tick_text
from ._base import Demo, slider

X_RANGE = (-4.0, 4.0)
N_SAMPLES = 4000  # fixed standard-normal draws, rescaled by the sliders
N_BINS = 60
OFFSET = 1.0  # m: the landmark sits this far off the robot's line


def square(x):
    return x * x  # f(x) = x^2


def d_square(x):
    return 2.0 * x  # f'(x) = 2x


def rng_range(x):
    return np.sqrt(x * x + OFFSET**2)  # r = sqrt(x^2 + d^2)


def d_range(x):
    return x / np.sqrt(x * x + OFFSET**2)  # dr/dx = x / r


# name: (f, f', the ticks of the output axis: five, evenly spaced, for every function)
FUNCTIONS = {
    "x²": (square, d_square, (0.0, 2.0, 4.0, 6.0, 8.0)),
    "sin x": (np.sin, np.cos, (-1.0, -0.5, 0.0, 0.5, 1.0)),
    "range √(x² + 1)": (rng_range, d_range, (1.0, 2.0, 3.0, 4.0, 5.0)),
}


def output_limits(ticks) -> tuple[float, float]:
    """The output axis for evenly spaced ``ticks``: half a spacing of room beyond the end ones.

    When every function has as many ticks, they sit at the same heights whichever
    function is shown, so a new function changes the ticks' labels (moving text) and
    not the picture's background, which would take a full redraw.
    """
    step = ticks[1] - ticks[0]
    return ticks[0] - 0.5 * step, ticks[-1] + 0.5 * step


class LinearizationModel:
    """Model: an input N(m, s^2), a function f, the sampled output and the EKF's Gaussian."""

    def __init__(self, seed: int = 0, m: float = 1.0, s: float = 0.5, function: str = "x²"):
        self.seed, self.m, self.s, self.function = seed, m, s, function
        self.draws = np.random.default_rng(seed).standard_normal(N_SAMPLES)  # e ~ N(0, 1), fixed

    def set_m(self, m: float) -> None:
        self.m = float(m)

    def set_s(self, s: float) -> None:
        self.s = float(s)

    def set_function(self, name: str) -> None:
        self.function = name

    def samples(self) -> np.ndarray:
        """The input samples x = m + s e pushed through f."""
        f = FUNCTIONS[self.function][0]
        return f(self.m + self.s * self.draws)

    def sampled(self) -> tuple[float, float]:
        """Mean and variance of the true (sampled) output."""
        y = self.samples()
        return float(y.mean()), float(y.var())

    def ekf(self) -> tuple[float, float]:
        """The EKF's output Gaussian: N(f(m), f'(m)^2 s^2)."""
        f, df, _ = FUNCTIONS[self.function]
        slope = float(df(self.m))
        return float(f(self.m)), slope * slope * self.s * self.s  # mean f(m), variance f'(m)^2 s^2


def function_panels(width: float, height: float, x_range, y_ticks, width_ratio: float, height_ratio: float):
    """The four panels of the demos of chapters 7 and 9: the curve f (top left) over the input
    density (bottom left, same x), the output density sideways on f's own y axis (top right) and
    a text panel (bottom right).  Both densities are drawn relative to a peak, so their axes
    never rescale while a slider is dragged; the output axis starts with the ticks ``y_ticks``
    (see :func:`output_limits`), whose labels are moving text.

    Returns
    -------
    (fig, ax_f, ax_out, ax_in, ax_txt, y_labels)
    """
    fig, axes = new_figure(
        width,
        height,
        nrows=2,
        ncols=2,
        gridspec_kw={"width_ratios": [3, width_ratio], "height_ratios": [3, height_ratio]},
    )
    (ax_f, ax_out), (ax_in, ax_txt) = axes
    ax_in.sharex(ax_f)
    ax_out.sharey(ax_f)
    ax_f.tick_params(labelbottom=False)  # the input panel under it labels x
    ax_out.tick_params(labelleft=False)  # f's panel beside it labels y
    ax_f.set_xlim(*x_range)
    ax_f.set_ylim(*output_limits(y_ticks))
    y_labels = moving_tick_labels(ax_f, y_ticks, 5)
    ax_f.set_ylabel("output y = f(x)")
    ax_in.set_xlabel("input x")
    ax_in.set_ylabel("density\n(peak = 1)")
    ax_out.set_xlabel("density (sampled peak = 1)")
    ax_in.set_ylim(0.0, 1.15)
    ax_out.set_xlim(0.0, 1.6)
    ax_txt.axis("off")
    return fig, ax_f, ax_out, ax_in, ax_txt, y_labels


def show_output_axis(ax_f, y_labels, ticks) -> tuple[float, float]:
    """Give the output axis of :func:`function_panels` a function's ``ticks``; returns its limits."""
    lo, hi = output_limits(ticks)
    ax_f.set_ylim(lo, hi)
    ax_f.set_yticks(ticks)  # at the heights of every function's ticks: the background stays as it is
    for label, y in zip(y_labels, ticks, strict=True):
        label.set_text(tick_text(y))
    return lo, hi


def sideways_histogram(y, lo: float, hi: float, bins: int) -> tuple[np.ndarray, np.ndarray, float]:
    """The samples ``y`` as a histogram on ``bins`` fixed bins over the output axis ``lo`` to ``hi``, drawn
    sideways (density along x, output along y) and divided by its peak, as the demos of chapters 7 and 9 show it.

    Returns
    -------
    (density, output, peak)
        The outline's x and y coordinates, and the sampled peak it was divided by (the demos divide
        their other output densities by it too).
    """
    edges = np.linspace(lo, hi, bins + 1)
    counts, _ = np.histogram(y, bins=edges)
    dens = counts / (y.size * (edges[1] - edges[0]))
    peak = max(float(dens.max()), 1e-12)
    return np.concatenate([[0.0], np.repeat(dens / peak, 2), [0.0]]), np.repeat(edges, 2), peak


def _picture(model: LinearizationModel) -> tuple[FigureRenderer, Callable[[], None]]:
    """The curve f and its tangent at m over the input density, the two output densities beside them,
    and the numbers under those.

    Returns
    -------
    (renderer, draw)
        ``draw()`` shows the model's function, input and outputs.
    """
    fig, ax_f, ax_out, ax_in, ax_txt, y_labels = function_panels(
        8.0, 5.4, X_RANGE, FUNCTIONS[model.function][2], width_ratio=1.3, height_ratio=1.1
    )

    x = np.linspace(*X_RANGE, 400)
    (curve,) = ax_f.plot(x, x, color=palette.INK, lw=1.5, label="f(x)")
    (tangent,) = ax_f.plot(x, x, color=palette.MEASUREMENT, lw=1.8, ls="--", label="tangent at m")
    (point,) = ax_f.plot([0], [0], "o", color=palette.MEASUREMENT, ms=6)
    ax_f.legend(loc="upper left", fontsize=9)
    (inp,) = ax_in.plot(x, x, color=palette.PREDICTION, lw=2)
    (hist,) = ax_out.plot([0, 1], [0, 1], color=palette.TRUTH, lw=1.5, label="sampled")
    (ekf,) = ax_out.plot([0, 1], [0, 1], color=palette.ESTIMATE, lw=2, label="EKF")
    (true_mean,) = ax_out.plot([0, 1], [0, 0], color=palette.TRUTH, lw=1.2, ls=":")
    (ekf_mean,) = ax_out.plot([0, 1], [0, 0], color=palette.ESTIMATE, lw=1.2, ls=":")
    ax_out.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, fontsize=8)  # above: no density reaches it
    info = ax_txt.text(
        -0.1, 0.95, "", transform=ax_txt.transAxes, ha="left", va="top", fontsize=8.5, family="monospace"
    )
    renderer = FigureRenderer(fig, [curve, tangent, point, inp, hist, ekf, true_mean, ekf_mean, info, *y_labels])

    def draw() -> None:
        f, df, ticks = FUNCTIONS[model.function]
        lo, hi = show_output_axis(ax_f, y_labels, ticks)
        curve.set_ydata(f(x))
        m, s = model.m, model.s
        fm, slope = float(f(m)), float(df(m))
        tangent.set_ydata(fm + slope * (x - m))  # f(m) + f'(m) (x - m)
        point.set_data([m], [fm])
        inp.set_ydata(np.exp(-0.5 * (x - m) ** 2 / (s * s)))  # N(m, s^2) divided by its peak
        y = model.samples()
        hist_x, hist_y, top_out = sideways_histogram(y, lo, hi, N_BINS)  # both output densities are divided by top_out
        mean_y, var_y = float(y.mean()), float(y.var())
        mean_e, var_e = model.ekf()
        grid = np.linspace(lo, hi, 600)
        if var_e > 1e-12 * (hi - lo) ** 2:
            ekf.set_data(np.minimum(gaussian_pdf(grid, mean_e, var_e) / top_out, 2.0), grid)
        else:  # f'(m) = 0: the EKF claims no spread at all, a spike at f(m)
            ekf.set_data([0.0, 0.0, 2.0, 0.0, 0.0], [lo, mean_e, mean_e, mean_e, hi])
        hist.set_data(hist_x, hist_y)
        true_mean.set_data([0.0, 2.0], [mean_y, mean_y])
        ekf_mean.set_data([0.0, 2.0], [mean_e, mean_e])
        info.set_text(
            f"input:   m = {m:.2f}, s² = {s * s:.3g}\n"
            f"slope:   f'(m) = {slope:.3f}\n\n"
            f"sampled: mean {mean_y:8.3f}\n"
            f"         var  {var_y:8.3g}\n"
            f"EKF:     mean {mean_e:8.3f}\n"
            f"         var  {var_e:8.3g}"
        )

    return renderer, draw


def linearization(seed: int = 0) -> Demo:
    """Demo "linearization" (chapter 7): a Gaussian through x², sin x or a range,
    the sampled truth against the EKF's tangent-line Gaussian.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = LinearizationModel(seed=seed)
    renderer, draw = _picture(model)
    caption = (
        "<b>Linearization.</b> Purple (bottom): the input Gaussian N(m, s²). Black: the function f; orange "
        "dashed: its tangent at m. Right, on the output axis: grey, a histogram of the true output "
        f"(the same {N_SAMPLES} seeded draws pushed through f); teal, the EKF's Gaussian N(f(m), f'(m)² s²), "
        "what the tangent makes of the input. Dotted lines: the two means. "
        "Each density is drawn relative to a peak (the input's own; on the output side, the samples'), "
        "so shapes and widths compare. Pick a function, drag the mean m "
        "and the width s, and compare the numbers."
    )
    return Demo(
        name="linearization",
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
        },
        layout=["function", ["m", "s"]],
    )
