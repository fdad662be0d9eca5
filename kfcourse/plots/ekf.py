"""Static figures of EKF runs (chapter 7): data in, figure out."""

from __future__ import annotations

import numpy as np

from . import palette
from .artists import covariance_ellipse, landmarks
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
        ax.plot(run.truth[:, 0], run.truth[:, 1], color=palette.TRUTH, lw=2.5, label="truth")
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
