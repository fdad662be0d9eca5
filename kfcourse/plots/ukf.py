"""Static figures of chapter 9: the unscented transform against the samples, and the UKF beside the EKF."""

from __future__ import annotations

import numpy as np

from .. import _validate as v
from . import palette
from .artists import landmarks
from .style import new_figure


def _gaussian(grid, mean: float, var: float) -> np.ndarray:
    var = max(var, 1e-12)
    return np.exp(-0.5 * (grid - mean) ** 2 / var) / np.sqrt(2 * np.pi * var)  # N(grid; mean, var)


def transform_moments_chart(y, ukf, ekf, bins: int = 80, y_range=None):
    """Chapter 9: the samples of a transformed Gaussian against the UKF's and the EKF's Gaussians.

    A grey histogram of the true output samples ``y``; the UKF's Gaussian (teal)
    and the EKF's (orange, dashed); a dotted line at each filter's mean, and a wide
    pale grey band at the samples' mean, so that it still shows when a filter's
    mean lies on it.

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
        color=palette.MEASUREMENT,
        lw=1.8,
        ls="--",
        label=f"EKF N({mean_e:.3g}, {var_e:.3g})",
    )
    # The samples' mean: a wide band under the filters' dotted means, visible even where one of them lies on it.
    ax.axvline(float(y.mean()), color=palette.TRUTH, lw=5.0, alpha=0.5, zorder=1.5, label="samples' mean")
    for mean, colour in ((mean_u, palette.ESTIMATE), (mean_e, palette.MEASUREMENT)):
        ax.axvline(mean, color=colour, lw=1.2, ls=":")
    ax.set_xlim(lo, hi)
    ax.set_xlabel("output y = f(x)")
    ax.set_ylabel("density")
    ax.set_title(f"samples: mean {y.mean():.3g}, variance {y.var():.3g}", fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    return fig


def _rms(error) -> float:
    return float(np.sqrt(np.mean(np.square(error))))


def filter_comparison_chart(ekf, ukf):
    """Chapter 9: the same drive followed by an EKF and by a UKF.

    Left: the map, the true path (grey), the EKF's estimate (orange, dashed), the
    UKF's (teal) and the landmarks (purple squares), with the legend above the map
    so that it hides no landmark.  Right: the position error of each over time,
    with its RMS in the legend.

    Introduced in chapter 9.

    Parameters
    ----------
    ekf, ukf : object with ``t, truth, landmarks, mu, error``
        Run records such as :class:`kfcourse.sim.localization.LoopRun`, for the
        same drive (the same ``t`` and ``truth``).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if ekf.t.shape != ukf.t.shape or not np.allclose(ekf.truth, ukf.truth):
        raise ValueError("ekf and ukf must be runs of the same drive (the same t and truth)")
    fig, (ax_map, ax_e) = new_figure(10.0, 3.8, ncols=2, gridspec_kw={"width_ratios": [1, 1.2]})
    ax_map.plot(ekf.truth[:, 0], ekf.truth[:, 1], color=palette.TRUTH, lw=3, label="truth")
    ax_map.plot(ekf.mu[:, 0], ekf.mu[:, 1], color=palette.MEASUREMENT, lw=1.6, ls="--", label="EKF")
    ax_map.plot(ukf.mu[:, 0], ukf.mu[:, 1], color=palette.ESTIMATE, lw=1.6, label="UKF")
    landmarks(ax_map, ekf.landmarks, label="landmarks")
    ax_map.set_aspect("equal", adjustable="datalim")
    ax_map.set_xlabel("x (m)")
    ax_map.set_ylabel("y (m)")
    ax_map.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=4, fontsize=8, frameon=False)
    ax_e.plot(ekf.t, ekf.error, color=palette.MEASUREMENT, lw=1.8, ls="--", label=f"EKF, RMS {_rms(ekf.error):.3f} m")
    ax_e.plot(ukf.t, ukf.error, color=palette.ESTIMATE, lw=1.8, label=f"UKF, RMS {_rms(ukf.error):.3f} m")
    ax_e.set_xlabel("time (s)")
    ax_e.set_ylabel("position error (m)")
    ax_e.set_ylim(bottom=0.0)
    ax_e.legend(loc="upper left", fontsize=8)
    return fig
