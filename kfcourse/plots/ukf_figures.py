"""The figures of chapter 9: the unscented transform against the samples, the UKF beside
the EKF (data in, figure out), and the sigma-points demo's picture (:func:`sigma_points_view`,
moved by :func:`update_sigma_points_view`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection, PathCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from matplotlib.text import Text

from .. import _validate as v
from ..filters.gaussian import gaussian_pdf
from . import palette
from .artists import landmarks
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


def _gaussian(grid, mean: float, var: float) -> np.ndarray:
    var = max(var, 1e-12)
    return np.exp(-0.5 * (grid - mean) ** 2 / var) / np.sqrt(2 * np.pi * var)  # N(grid; mean, var)


def transform_moments_chart(y, ukf, ekf, bins: int = 80, y_range=None):
    """Chapter 9: the samples of a transformed Gaussian against the UKF's and the EKF's Gaussians.

    A grey histogram of the true output samples ``y``; the UKF's Gaussian (teal,
    solid) and the EKF's (teal, dashed: in the course the EKF beside another filter
    is teal dashed); a thin line at each filter's mean in its curve's style, and a
    wide grey dotted line (the truth's style) at the samples' mean, so that it still
    shows when a filter's mean lies on it.

    Introduced in chapter 9.

    Parameters
    ----------
    y : array_like, shape (N,)
        Output samples ``f(x)`` of input samples ``x``.
    ukf, ekf : (float, float)
        (mean, variance) of each filter's output Gaussian; variances >= 0.
    bins : int
        Histogram bins (>= 2).
    y_range : (float, float), optional
        The output range shown; by default the 0.1 % to 99.5 % quantiles of ``y``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    y = v.vector(y, "y")
    if y.size < 2:
        raise ValueError(f"y must hold at least 2 samples, got {y.size}")
    (mean_u, var_u), (mean_e, var_e) = (
        (v.scalar(pair[0], f"{name}[0]"), v.variance(pair[1], f"{name}[1]"))
        for pair, name in ((ukf, "ukf"), (ekf, "ekf"))
    )
    bins = int(bins)
    if bins < 2:
        raise ValueError(f"bins must be a whole number >= 2, got {bins}")
    lo, hi = np.quantile(y, [0.001, 0.995]) if y_range is None else v.vector(y_range, "y_range", 2)
    if not hi > lo:
        raise ValueError(f"y_range must be (low, high) with low < high, got {(lo, hi)}")
    fig, ax = new_figure(7.0, 3.2)
    edges = np.linspace(lo, hi, bins + 1)
    weight = np.full(y.size, 1.0 / (y.size * (edges[1] - edges[0])))  # a density of all the samples, tails included
    ax.hist(y, bins=edges, weights=weight, color=palette.TRUTH, alpha=0.6, label="samples")
    grid = np.linspace(lo, hi, 600)
    ax.plot(
        grid, _gaussian(grid, mean_u, var_u), color=palette.ESTIMATE, lw=2.2, label=f"UKF N({mean_u:.3g}, {var_u:.3g})"
    )
    ax.plot(
        grid,
        _gaussian(grid, mean_e, var_e),
        color=palette.ESTIMATE,
        lw=1.8,
        ls="--",
        label=f"EKF N({mean_e:.3g}, {var_e:.3g})",
    )
    # The samples' mean: wide dots under the filters' thin mean lines, visible even where one of them lies on it.
    ax.axvline(float(y.mean()), color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=3.0, zorder=1.5, label="samples' mean")
    for mean, style in ((mean_u, "-"), (mean_e, "--")):
        ax.axvline(mean, color=palette.ESTIMATE, lw=1.0, ls=style)
    ax.set_xlim(lo, hi)
    ax.set_xlabel("output y = f(x)")
    ax.set_ylabel("density")
    ax.set_title(f"samples: mean {y.mean():.3g}, variance {y.var():.3g}", fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    return fig


# The UKF and the EKF on one picture: both teal (estimates), the UKF solid and wide and pale, the EKF dashed over it.
UKF_STYLE = {"color": palette.ESTIMATE, "lw": 3.2, "alpha": 0.5, "solid_capstyle": "butt"}
EKF_STYLE = {"color": palette.ESTIMATE, "lw": 1.4, "ls": "--"}
HANDLE = 2.5  # legend handle length (font sizes) that holds three whole dashes of EKF_STYLE, not a dash-dot look


def _rms(error) -> float:
    return float(np.sqrt(np.mean(np.square(error))))


def filter_comparison_chart(ekf, ukf):
    """Chapter 9: the same drive followed by an EKF and by a UKF.

    Left: the map, the true path (grey, dotted), the UKF's estimate (teal, solid: a wide pale
    line), the EKF's (teal, dashed, drawn over it, so that both show where they
    agree) and the landmarks (purple squares), with the legend above the map so
    that it hides no landmark.  Right: the position error of each over time, in the
    same styles, with its RMS in the legend.

    Introduced in chapter 9.

    Parameters
    ----------
    ekf, ukf : object with ``t, truth, landmarks, mu, error``
        Run records such as :class:`kfcourse.sim.LoopRun`, for the
        same drive (the same ``t`` and ``truth``).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if ekf.t.shape != ukf.t.shape or not np.allclose(ekf.truth, ukf.truth):
        raise ValueError("ekf and ukf must be runs of the same drive (the same t and truth)")
    fig, (ax_map, ax_e) = new_figure(10.0, 3.8, ncols=2, gridspec_kw={"width_ratios": [1, 1.2]})
    ax_map.plot(ekf.truth[:, 0], ekf.truth[:, 1], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=3, label="truth")
    ax_map.plot(ukf.mu[:, 0], ukf.mu[:, 1], label="UKF", **UKF_STYLE)
    ax_map.plot(ekf.mu[:, 0], ekf.mu[:, 1], label="EKF", **EKF_STYLE)
    landmarks(ax_map, ekf.landmarks, label="landmarks")
    ax_map.set_aspect("equal", adjustable="datalim")
    ax_map.set_xlabel("x (m)")
    ax_map.set_ylabel("y (m)")
    ax_map.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=4, fontsize=8, frameon=False, handlelength=HANDLE)
    ax_e.plot(ukf.t, ukf.error, label=f"UKF, RMS {_rms(ukf.error):.3f} m", **UKF_STYLE)
    ax_e.plot(ekf.t, ekf.error, label=f"EKF, RMS {_rms(ekf.error):.3f} m", **EKF_STYLE)
    ax_e.set_xlabel("time (s)")
    ax_e.set_ylabel("position error (m)")
    ax_e.set_ylim(bottom=0.0)
    ax_e.legend(loc="upper left", fontsize=8, handlelength=HANDLE)
    return fig


# --------------------------------------------------------------------------- the sigma-points demo

ON_OUTPUT = 0.03  # where the sigma points' images sit across the output panel (a fraction of its width)


@dataclass(frozen=True)
class SigmaPointsView:
    """What :func:`sigma_points_view` drew; :func:`update_sigma_points_view` moves it."""

    panels: FunctionPanels
    output_limits: dict  #: function name -> (low, high) of the output axis
    bins: int  #: bins of the sampled output's histogram
    curve: Line2D  #: f
    tangent: Line2D  #: the EKF's tangent at m, teal dashed
    guides: LineCollection  #: dashed paths of the sigma points: up to the curve, across to the output axis
    on_curve: PathCollection  #: the sigma points on the curve
    input_density: Line2D  #: N(m, s²), purple
    on_input: PathCollection  #: the sigma points on the input density
    sampled: Polygon  #: histogram of the true output, grey
    ukf: Line2D  #: the UKF's output Gaussian, teal
    ekf: Line2D  #: the EKF's output Gaussian, teal dashed
    on_output: PathCollection  #: the sigma points' images on the output axis
    info: Text  #: the numbers

    @property
    def fig(self):
        return self.panels.fig

    @property
    def moving(self) -> list:
        """Every artist that changes with the model, bottom to top."""
        return [
            self.curve,
            self.tangent,
            self.guides,
            self.on_curve,
            self.input_density,
            self.on_input,
            self.sampled,
            self.ukf,
            self.ekf,
            self.on_output,
            self.info,
        ]


def _sigma_dots(ax, colour: str, **kwargs) -> PathCollection:
    """Three dots, one per sigma point (placed, sized and filled by the update)."""
    return ax.scatter([0, 0, 0], [0, 0, 0], s=40, color=colour, edgecolor=colour, lw=1.5, zorder=3, **kwargs)


def sigma_points_readout(chi, w, moments) -> str:
    """The numbers panel: the sigma points and their weights, left to right, then each answer's mean and variance.

    Parameters
    ----------
    chi, w : array_like, shape (3,)
        The sigma points in the order :func:`kfcourse.sigma_points` makes them (m, m + spread,
        m - spread) and their weights.
    moments : list of (name, mean, variance)
    """
    order = [2, 0, 1]  # shown left to right
    return (
        f"{'sigma points':12}"
        + "".join(f"{chi[i]:6.2f}" for i in order)
        + f"\n{'weights':12}"
        + "".join(f"{w[i]:6.2f}" for i in order)
        + f"\n\n{'':12}mean{'':7}var\n"
        + "\n".join(f"{name:7}{mean:9.3f} {var:9.4f}" for name, mean, var in moments)
    )


def sigma_points_view(
    output_limits: dict, x_range=(-5.0, 5.0), bins: int = 60, width: float = 8.4, height: float = 4.9
) -> SigmaPointsView:
    """Chapter 9's demo picture: the curve f with three sigma points climbing it from the input
    density, the output densities (sampled, UKF, EKF) beside it, and the numbers under those.

    Nothing is shown until :func:`update_sigma_points_view`.  Introduced in chapter 9.

    Parameters
    ----------
    output_limits : dict
        For each function's name, the (low, high) of its output axis.
    x_range : (float, float)
        The input axis; the sigma points must stay on it.
    bins : int
        Bins of the output histogram over the output axis.
    width, height : float
        Figure size (inches).

    Returns
    -------
    SigmaPointsView
    """
    output_limits = {name: axis_range(pair, f"output_limits[{name!r}]") for name, pair in output_limits.items()}
    bins = v.whole(bins, "bins", 1)
    panels = function_panels(width, height, x_range, width_ratio=1.4, height_ratio=1.3)
    ax_f, ax_out, ax_in = panels.ax_f, panels.ax_out, panels.ax_in
    x = np.linspace(*x_range, 500)
    (curve,) = ax_f.plot(x, x, color=palette.INK, lw=1.5, label="f(x)")
    (tangent,) = ax_f.plot(x, x, color=palette.ESTIMATE, lw=1.6, ls="--", label="EKF: tangent at m")
    guides = LineCollection([], colors=palette.PREDICTION, lw=0.9, linestyles=palette.PREDICTION_LINE)
    ax_f.add_collection(guides)
    on_curve = _sigma_dots(ax_f, palette.PREDICTION)
    # Above the panel: inside it, sin x near its peak would run under the legend.
    ax_f.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, fontsize=9, frameon=False)
    (density,) = ax_in.plot(x, x, color=palette.PREDICTION, ls=palette.PREDICTION_LINE, lw=2)
    on_input = _sigma_dots(ax_in, palette.PREDICTION)
    sampled = Polygon([[0, 0], [1, 1], [0, 1]], closed=True, facecolor=palette.TRUTH, alpha=0.45, lw=0, label="sampled")
    ax_out.add_patch(sampled)
    (ukf,) = ax_out.plot([0, 1], [0, 1], color=palette.ESTIMATE, lw=2.2, label="UKF")
    (ekf,) = ax_out.plot([0, 1], [0, 1], color=palette.ESTIMATE, lw=1.8, ls="--", label="EKF")
    on_output = _sigma_dots(ax_out, palette.ESTIMATE, transform=ax_out.get_yaxis_transform())  # x: panel fraction
    # Above the panel, where no output density can reach it.
    ax_out.legend(
        loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, fontsize=8, frameon=False, handlelength=2.0,
        columnspacing=0.8, handletextpad=0.4,
    )  # fmt: skip
    # The readout: row names and numbers in one monospace grid (only x² has the row "exact").
    text_style = {"ha": "left", "va": "top", "fontsize": 8.5, "family": "monospace"}
    info = panels.ax_txt.text(-0.12, 1.0, "", transform=panels.ax_txt.transAxes, **text_style)
    return SigmaPointsView(
        panels,
        output_limits,
        bins,
        curve,
        tangent,
        guides,
        on_curve,
        density,
        on_input,
        sampled,
        ukf,
        ekf,
        on_output,
        info,
    )


def update_sigma_points_view(view: SigmaPointsView, model) -> None:
    """Show ``model`` on a picture made by :func:`sigma_points_view`.

    ``model`` needs what :func:`kfcourse.plots.ekf_figures.update_linearization_view` reads (``m``,
    ``s``, ``function``, ``f``, ``df``, ``samples()``, ``ekf()``), and ``sigma_points()``
    (the three points and their weights), ``ukf()`` (the UKF's mean and variance) and
    ``exact()`` (the exact mean and variance, or None where unknown).
    """
    panels = view.panels
    lo, hi = view.output_limits[model.function]
    show_function(panels, view.curve, view.tangent, model, (lo, hi))
    m, s, f = model.m, model.s, model.f
    show_input_density(panels, view.input_density, m, s)
    chi, w = model.sigma_points()
    Y = f(chi)  # the sigma points through the true f
    view.on_input.set_offsets(np.column_stack([chi, gaussian_pdf(chi, m, s * s)]))
    view.on_curve.set_offsets(np.column_stack([chi, Y]))
    view.on_output.set_offsets(np.column_stack([np.full(3, ON_OUTPUT), Y]))
    sizes = 30.0 + 90.0 * np.abs(w)  # dot area grows with the weight
    for dots, colour in (
        (view.on_input, palette.PREDICTION),
        (view.on_curve, palette.PREDICTION),
        (view.on_output, palette.ESTIMATE),
    ):
        dots.set_sizes(sizes)
        dots.set_facecolors([colour if wi > 0 else "white" for wi in w])  # a weight-0 point: an empty ring
    x_end = panels.ax_f.get_xlim()[1]
    view.guides.set_segments([[(c, lo), (c, y), (x_end, y)] for c, y in zip(chi, Y, strict=True)])
    y = model.samples()
    dens, out, top = show_sampled_output(panels, y, view.bins)
    view.sampled.set_xy(np.column_stack([dens, out]))
    mean_u, var_u = model.ukf()
    mean_e, var_e = model.ekf()
    show_sideways_gaussian(view.ukf, mean_u, var_u, lo, hi, top)
    show_sideways_gaussian(view.ekf, mean_e, var_e, lo, hi, top)
    moments = [("sampled", float(y.mean()), float(y.var())), ("UKF", mean_u, var_u), ("EKF", mean_e, var_e)]
    if model.exact() is not None:
        moments.append(("exact", *model.exact()))
    view.info.set_text(sigma_points_readout(chi, w, moments))
