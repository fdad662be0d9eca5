"""Static figures for the chapters (data in, figure out).

Each function builds a whole figure from arrays it is given and returns it; in a
notebook the figure shows itself when it is a cell's last value.
"""

from __future__ import annotations

import numpy as np
from matplotlib.ticker import MaxNLocator

from .. import _validate as v
from ..filters.gaussian import gaussian_pdf
from . import palette
from .artists import covariance_ellipse
from .style import new_figure


def drift_chart(n, formula_sigma, empirical_sigma, bias_error=None):
    """Chapter 0: spread of dead reckoning against the number of steps.

    Parameters
    ----------
    n : array_like, shape (T,)
        Step counts.
    formula_sigma, empirical_sigma : array_like, shape (T,)
        ``0.02 sqrt(n)`` and the Monte-Carlo spread (m).
    bias_error : array_like, shape (T,), optional
        Error of a constant scale bias (m), drawn for comparison.
    """
    fig, ax = new_figure(7.0, 3.2)
    # Colours by role: the formula is a plain line in ink; the simulated robots are "truth", faint grey
    # dots; prediction purple and measurement orange mean other things in this course.
    ax.plot(n, 100 * np.asarray(formula_sigma), color=palette.INK, lw=1.8, label="formula  0.02·√n", zorder=2)
    ax.plot(
        n,
        100 * np.asarray(empirical_sigma),
        "o",
        color=palette.TRUTH,
        mec=palette.INK,
        mew=0.6,
        ms=6,
        label="simulated robots (Monte Carlo)",
        zorder=3,
    )
    if bias_error is not None:
        ax.plot(n, 100 * np.asarray(bias_error), "--", color=palette.INK, lw=1.2, label="1 % scale bias")
        ax.set_ylim(0, 100 * float(np.max(formula_sigma)) * 2.5)
    ax.set_xlabel("steps n (1 m each)")
    ax.set_ylabel("position error (cm)")
    ax.legend(loc="upper right")  # clear of the data: the bias line leaves the top on the left
    return fig


def samples_chart(samples, mu: float, var: float, title: str = ""):
    """Chapter 2: a histogram of samples over the density ``N(mu, var)`` they should follow."""
    samples = np.asarray(samples, float)
    fig, ax = new_figure(4.0, 2.6)
    ax.hist(samples, bins=60, density=True, color=palette.INK, alpha=0.3, label="samples")  # neutral: not a reading
    x = np.linspace(samples.min(), samples.max(), 400)
    ax.plot(x, gaussian_pdf(x, mu, var), color=palette.ESTIMATE, lw=2.2, label=f"N({mu:g}, {var:g})")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    return fig


def convergence_chart(K, var_post, K_steady: float, var_steady: float):
    """Chapter 4: gain and posterior variance tick by tick, with the steady state."""
    K = np.asarray(K, float)
    ticks = np.arange(1, K.size + 1)
    fig, (ax_k, ax_v) = new_figure(8.0, 3.0, ncols=2)
    ax_k.plot(ticks, K, "o-", color=palette.ESTIMATE, ms=4, label="K per tick")
    ax_k.axhline(K_steady, color=palette.INK, ls="--", label=f"steady state {K_steady:.3f}")
    ax_k.set_xlabel("tick")
    ax_k.set_ylabel("Kalman gain K")
    ax_k.set_ylim(0, 1)
    ax_k.legend()
    ax_v.plot(ticks, var_post, "o-", color=palette.ESTIMATE, ms=4, label="σ² after update")
    ax_v.axhline(var_steady, color=palette.INK, ls="--", label=f"steady state {var_steady:.3f}")
    ax_v.set_xlabel("tick")
    ax_v.set_ylabel("variance (m²)")
    ax_v.set_ylim(0, None)
    for ax in (ax_k, ax_v):
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax_v.legend()
    return fig


def blend_variance_chart(var1: float, var2: float):
    r"""Chapter 4: the variance of every unbiased blend of two independent estimates.

    The blend :math:`(1 - w)\,\mu_1 + w\,\mu_2` has variance
    :math:`(1 - w)^2\sigma_1^2 + w^2\sigma_2^2`, a parabola in :math:`w` whose lowest
    point is at :math:`w = K = \sigma_1^2 / (\sigma_1^2 + \sigma_2^2)`, the Kalman gain.
    Introduced in chapter 4.

    Parameters
    ----------
    var1 : float
        Variance of the first estimate (the prediction), > 0; the blend at ``w = 0``.
    var2 : float
        Variance of the second estimate (the measurement), > 0; the blend at ``w = 1``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    var1, var2 = v.positive(var1, "var1", "a variance"), v.positive(var2, "var2", "a variance")
    w = np.linspace(0.0, 1.0, 401)
    var_blend = (1 - w) ** 2 * var1 + w**2 * var2  # Var(w) = (1 - w)^2 var1 + w^2 var2
    K = var1 / (var1 + var2)  # the weight with the smallest variance
    var_min = var1 * var2 / (var1 + var2)  # Var(K) = var1 var2 / (var1 + var2)
    fig, ax = new_figure(6.0, 3.0)
    ax.plot(w, var_blend, color=palette.INK, lw=1.8, label="variance of the blend")
    ax.plot([0.0], [var1], "o", color=palette.PREDICTION, ms=8, label=f"w = 0: prediction only, {var1:.3g}")
    ax.plot([1.0], [var2], "o", color=palette.MEASUREMENT, ms=8, label=f"w = 1: measurement only, {var2:.3g}")
    ax.axvline(K, color=palette.ESTIMATE, ls=palette.ESTIMATE_LINE, lw=1.0)
    ax.plot([K], [var_min], "o", color=palette.ESTIMATE, ms=9, label=f"minimum at w = K = {K:.3f}: {var_min:.3g}")
    ax.set_xlim(-0.03, 1.03)
    ax.set_ylim(0, 1.08 * max(var1, var2))
    ax.set_xlabel("weight w of the measurement in the blend (1 − w)·μ₁ + w·μ₂")
    ax.set_ylabel("variance of the blend")
    ax.legend(loc="upper center", fontsize=8)
    return fig


def ellipse_shadow_chart(Sig, nsig: float = 1.0):
    r"""Chapter 2: a 2-D covariance ellipse, its semi-axes and its shadow on the x and y axes.

    The ``nsig``-sigma ellipse of ``N(0, Sig)`` (teal) with its two semi-axes
    :math:`k\sqrt{\lambda_i}` along the eigenvectors (teal lines), and the box
    :math:`\pm k\sqrt{\Sigma_{xx}}`, :math:`\pm k\sqrt{\Sigma_{yy}}` that the ellipse
    exactly fits in (dashed): the diagonal of Σ sets the shadow, not the axes.
    Introduced in chapter 2.

    Parameters
    ----------
    Sig : array_like, shape (2, 2)
        Covariance, symmetric positive semi-definite.
    nsig : float
        Number of standard deviations ``k`` (> 0).

    Returns
    -------
    matplotlib.figure.Figure
    """
    Sig = np.asarray(Sig, float)
    if Sig.shape != (2, 2):
        raise ValueError(f"Sig must have shape (2, 2), got {Sig.shape}")
    k = v.positive(nsig, "nsig", "a number of standard deviations")
    fig, ax = new_figure(4.6, 3.4)
    covariance_ellipse(ax, (0.0, 0.0), Sig, k, palette.ESTIMATE)  # checks Sig (finite, symmetric, PSD)
    lam, V = np.linalg.eigh(Sig)  # Σ = V diag(lam) V^T, lam ascending
    lam = np.clip(lam, 0.0, None)
    major = V[:, 1] if V[0, 1] >= 0 else -V[:, 1]  # an axis has no sign: draw it pointing right
    minor = V[:, 0] if V[1, 0] >= 0 else -V[:, 0]  # and this one pointing up
    ends = {"major": (major, np.sqrt(lam[1]), (6, -10), "left"), "minor": (minor, np.sqrt(lam[0]), (-4, 6), "right")}
    for name, (axis, length, offset, ha) in ends.items():
        end = k * length * axis  # semi-axis: k sqrt(lambda_i) along eigenvector i
        ax.plot([0.0, end[0]], [0.0, end[1]], color=palette.ESTIMATE, lw=1.6)
        ax.annotate(
            f"{name} semi-axis\n{k * length:.3g}",
            end,
            xytext=offset,
            textcoords="offset points",
            ha=ha,
            color=palette.ESTIMATE,
            fontsize=8,
        )
    sx, sy = k * np.sqrt(Sig[0, 0]), k * np.sqrt(Sig[1, 1])  # shadow: ±k sigma_x, ±k sigma_y
    ax.plot(
        [-sx, sx, sx, -sx, -sx], [-sy, -sy, sy, sy, -sy], "--", color=palette.INK, lw=1.0, label=f"±{k:g}σx, ±{k:g}σy"
    )
    ax.set_aspect("equal")
    top = 1.25 * max(sx, sy)
    ax.set_xlim(-top, top)
    ax.set_ylim(-top, top)
    ax.set_xlabel(f"x   (shadow ±{sx:.3g})")
    ax.set_ylabel(f"y   (shadow ±{sy:.3g})")
    ax.legend(loc="lower right", fontsize=8)
    return fig
