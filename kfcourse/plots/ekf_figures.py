"""The figures of chapter 7: EKF runs and samples (data in, figure out), and the
linearization demo's picture (:func:`linearization_view`, moved by
:func:`update_linearization_view`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.text import Text

from .. import _validate as v
from . import palette
from .artists import covariance_ellipse, landmarks
from .curve_panels import (
    FunctionPanels,
    axis_range,
    function_panels,
    show_function,
    show_input_density,
    show_sampled_output,
    show_sideways_gaussian,
)
from .style import new_figure


def share_outside(run) -> str:
    """How often the truth is outside the run's 3-sigma ellipse, in words, in whole tenths of the steps.

    "never", "at fewer than 1 step in 10", or "at least N steps in 10": rounded down to whole
    tenths, so that a step more or less (another machine's rounding) does not change the words.
    Introduced in chapter 7.

    Parameters
    ----------
    run : object with ``inside``, a (T,) bool array (the truth inside the ellipse at each step)
    """
    inside = np.asarray(run.inside, bool)
    if inside.all():
        return "never"
    tenths = int(np.floor(10 * (1 - inside.mean())))
    return "at fewer than 1 step in 10" if tenths == 0 else f"at least {tenths} steps in 10"


def jacobian_runs_chart(right, wrong, every: int = 12):
    """Chapter 7: the same drive filtered with the right Jacobian and with a wrong one.

    Left and middle: the map, the true path (grey), the estimate (teal) and its
    3-sigma position ellipse every ``every`` steps, the landmarks (purple squares);
    one panel per run, titled with its largest error and how often the truth is
    outside the ellipse (:func:`share_outside`; not the final error, which after a
    divergence depends on the machine's rounding).  Right: the position error over
    time of both runs (solid: right Jacobian, dashed: wrong).

    Introduced in chapter 7.

    Parameters
    ----------
    right, wrong : object with ``t, truth, landmarks, mu, Sig, error, inside``
        Run records such as :class:`kfcourse.sim.ekf_runs.EkfRun`.
    every : int
        Steps between two drawn ellipses (>= 1).

    Returns
    -------
    matplotlib.figure.Figure
    """
    every = int(every)
    if every < 1:
        raise ValueError(f"every must be a whole number >= 1, got {every}")
    fig, (ax_a, ax_b, ax_e) = new_figure(11.0, 3.8, ncols=3, gridspec_kw={"width_ratios": [1, 1, 1.1]})
    for ax, run, name in ((ax_a, right, "right H"), (ax_b, wrong, "flipped bearing row")):
        ax.plot(run.truth[:, 0], run.truth[:, 1], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=2.5, label="truth")
        ax.plot(run.mu[:, 0], run.mu[:, 1], color=palette.ESTIMATE, lw=1.5, label="EKF estimate")
        for k in range(0, run.t.size, every):
            covariance_ellipse(ax, run.mu[k, :2], run.Sig[k, :2, :2], nsig=3.0, lw=1.0)
        landmarks(ax, run.landmarks)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x (m)")
        largest = run.error.max()  # not the final error: a diverged run's depends on the last bit of a sine
        ax.set_title(f"{name}: largest error {largest:.1f} m\ntruth outside 3σ {share_outside(run)}", fontsize=10)
    ax_a.set_ylabel("y (m)")
    ax_a.legend(loc="upper left", fontsize=8)
    ax_e.plot(right.t, right.error, color=palette.ESTIMATE, lw=2, label="right H")
    ax_e.plot(wrong.t, wrong.error, color=palette.ESTIMATE, lw=2, ls="--", label="flipped bearing row")
    ax_e.set_xlabel("time (s)")
    ax_e.set_ylabel("position error (m)")
    ax_e.legend(loc="upper right", fontsize=8)
    return fig


def nonlinear_samples_chart(x, y, bins: int = 60):
    """Chapter 7: samples of a Gaussian input and of their images under a nonlinear function.

    Left: a histogram of the input samples ``x`` (purple); right: of the outputs
    ``y`` (grey) with the Gaussian of the same mean and variance (dashed) — the
    outputs are not Gaussian, whatever their mean and variance.

    Introduced in chapter 7.

    Parameters
    ----------
    x, y : array_like, shape (N,)
        Input samples and their images ``y = f(x)``.
    bins : int
        Histogram bins (>= 2).

    Returns
    -------
    matplotlib.figure.Figure
    """
    x, y = np.asarray(x, float).ravel(), np.asarray(y, float).ravel()
    if x.size < 2 or y.size != x.size or not (np.isfinite(x).all() and np.isfinite(y).all()):
        raise ValueError(f"x and y must be finite arrays of the same length >= 2, got {x.size} and {y.size}")
    bins = int(bins)
    if bins < 2:
        raise ValueError(f"bins must be a whole number >= 2, got {bins}")
    fig, (ax_x, ax_y) = new_figure(8.0, 3.0, ncols=2)
    ax_x.hist(x, bins=bins, density=True, color=palette.PREDICTION, alpha=0.6)
    ax_x.set_xlabel("input x")
    ax_x.set_ylabel("density")
    ax_y.hist(y, bins=bins, density=True, color=palette.TRUTH, alpha=0.8, label="samples of f(x)")
    grid = np.linspace(y.min(), y.max(), 400)
    var = max(float(y.var()), 1e-12)
    ax_y.plot(
        grid,
        np.exp(-0.5 * (grid - y.mean()) ** 2 / var) / np.sqrt(2 * np.pi * var),
        color=palette.INK,
        ls="--",
        label="Gaussian, same mean and variance",
    )
    ax_y.set_xlabel("output y = f(x)")
    ax_y.legend(loc="upper right", fontsize=8)
    return fig


# --------------------------------------------------------------------------- the linearization demo


@dataclass(frozen=True)
class LinearizationView:
    """What :func:`linearization_view` drew; :func:`update_linearization_view` moves it."""

    panels: FunctionPanels
    output_limits: dict  #: function name -> (low, high) of the output axis
    bins: int  #: bins of the sampled output's histogram
    curve: Line2D  #: f
    tangent: Line2D  #: f(m) + f'(m) (x - m), teal dashed (the EKF's linearization)
    point: Line2D  #: (m, f(m))
    input_density: Line2D  #: N(m, s²), purple
    sampled: Line2D  #: histogram of the true output, grey
    ekf: Line2D  #: the EKF's output Gaussian, teal
    sampled_mean: Line2D  #: dotted grey (the truth's style)
    ekf_mean: Line2D  #: thin solid teal
    info: Text  #: the numbers

    @property
    def fig(self):
        return self.panels.fig

    @property
    def moving(self) -> list:
        """Every artist that changes with the model."""
        return [
            self.curve,
            self.tangent,
            self.point,
            self.input_density,
            self.sampled,
            self.ekf,
            self.sampled_mean,
            self.ekf_mean,
            self.info,
        ]


def linearization_view(
    output_limits: dict, x_range=(-4.0, 4.0), bins: int = 60, width: float = 8.0, height: float = 4.8
) -> LinearizationView:
    """Chapter 7's demo picture: the curve f and its tangent at m over the input density,
    the sampled output and the EKF's Gaussian beside them on the output axis, the numbers under those.

    Nothing is shown until :func:`update_linearization_view`.  Introduced in chapter 7.

    Parameters
    ----------
    output_limits : dict
        For each function's name, the (low, high) of its output axis.
    x_range : (float, float)
        The input axis.
    bins : int
        Bins of the output histogram over the output axis.
    width, height : float
        Figure size (inches).

    Returns
    -------
    LinearizationView
    """
    output_limits = {name: axis_range(pair, f"output_limits[{name!r}]") for name, pair in output_limits.items()}
    bins = v.whole(bins, "bins", 1)
    panels = function_panels(width, height, x_range, width_ratio=1.3, height_ratio=1.1)
    ax_f, ax_out, ax_in = panels.ax_f, panels.ax_out, panels.ax_in
    x = np.linspace(*x_range, 400)
    (curve,) = ax_f.plot(x, x, color=palette.INK, lw=1.5, label="f(x)")
    (tangent,) = ax_f.plot(x, x, color=palette.ESTIMATE, lw=1.8, ls="--", label="EKF: tangent at m")
    (point,) = ax_f.plot([0], [0], "o", color=palette.ESTIMATE, ms=6)
    ax_f.legend(loc="upper center", fontsize=9)  # the middle top: clear of every curve's arms
    (density,) = ax_in.plot(x, x, color=palette.PREDICTION, ls=palette.PREDICTION_LINE, lw=2)
    (sampled,) = ax_out.plot(
        [0, 1], [0, 1], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=palette.TRUTH_WIDTH, label="sampled"
    )
    (ekf,) = ax_out.plot([0, 1], [0, 1], color=palette.ESTIMATE, ls=palette.ESTIMATE_LINE, lw=2, label="EKF")
    across = {"transform": ax_out.get_yaxis_transform()}  # x from edge to edge of the panel
    (sampled_mean,) = ax_out.plot(
        [0, 1], [0, 0], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=palette.TRUTH_WIDTH, **across
    )
    (ekf_mean,) = ax_out.plot([0, 1], [0, 0], color=palette.ESTIMATE, ls=palette.ESTIMATE_LINE, lw=1.0, **across)
    ax_out.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, fontsize=8)  # above: no density reaches it
    info = panels.ax_txt.text(
        -0.1, 0.95, "", transform=panels.ax_txt.transAxes, ha="left", va="top", fontsize=8.5, family="monospace"
    )
    return LinearizationView(
        panels, output_limits, bins, curve, tangent, point, density, sampled, ekf, sampled_mean, ekf_mean, info
    )


def update_linearization_view(view: LinearizationView, model) -> None:
    """Show ``model`` (an input N(m, s²) through f, such as
    :class:`kfcourse.sim.curve_functions.GaussianThroughCurve`) on a picture made by :func:`linearization_view`.

    ``model`` needs ``m``, ``s``, ``function`` (a key of the view's ``output_limits``),
    ``f`` and ``df`` (f and f'), ``samples()`` (the true output) and ``ekf()`` (the
    EKF's mean and variance).
    """
    panels = view.panels
    lo, hi = view.output_limits[model.function]
    fm, slope = show_function(panels, view.curve, view.tangent, model, (lo, hi))
    m, s = model.m, model.s
    view.point.set_data([m], [fm])
    show_input_density(panels, view.input_density, m, s)
    y = model.samples()
    dens, out, top = show_sampled_output(panels, y, view.bins)
    view.sampled.set_data(dens, out)
    mean_y, var_y = float(y.mean()), float(y.var())
    mean_e, var_e = model.ekf()
    show_sideways_gaussian(view.ekf, mean_e, var_e, lo, hi, top)
    view.sampled_mean.set_ydata([mean_y, mean_y])
    view.ekf_mean.set_ydata([mean_e, mean_e])
    view.info.set_text(
        f"input:   m = {m:.2f}, s² = {s * s:.3g}\n"
        f"slope:   f'(m) = {slope:.3f}\n\n"
        f"sampled: mean {mean_y:8.3f}\n"
        f"         var  {var_y:8.3g}\n"
        f"EKF:     mean {mean_e:8.3f}\n"
        f"         var  {var_e:8.3g}"
    )
