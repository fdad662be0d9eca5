"""Static figures for the chapters (data in, figure out).

Each function builds a whole figure from arrays it is given and returns it; in a
notebook the figure shows itself when it is a cell's last value.
"""

from __future__ import annotations

import numpy as np
from matplotlib.ticker import MaxNLocator

from ..filters.gaussian import gaussian_pdf
from . import palette
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
    ax.plot(n, 100 * np.asarray(formula_sigma), color=palette.PREDICTION, lw=2.2, label="formula  0.02·√n")
    ax.plot(n, 100 * np.asarray(empirical_sigma), "o", color=palette.MEASUREMENT, ms=5, label="Monte Carlo")
    if bias_error is not None:
        ax.plot(n, 100 * np.asarray(bias_error), "--", color=palette.INK, lw=1.2, label="1 % scale bias")
        ax.set_ylim(0, 100 * float(np.max(formula_sigma)) * 2.5)
    ax.set_xlabel("steps n (1 m each)")
    ax.set_ylabel("position error (cm)")
    ax.legend(loc="upper left")
    return fig


def samples_chart(samples, mu: float, var: float, title: str = ""):
    """Chapter 2: a histogram of samples over the density ``N(mu, var)`` they should follow."""
    samples = np.asarray(samples, float)
    fig, ax = new_figure(4.0, 2.6)
    ax.hist(samples, bins=60, density=True, color=palette.MEASUREMENT, alpha=0.45, label="samples")
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
    ax_k.axhline(K_steady, color=palette.PREDICTION, ls="--", label=f"steady state {K_steady:.3f}")
    ax_k.set_xlabel("tick")
    ax_k.set_ylabel("Kalman gain K")
    ax_k.set_ylim(0, 1)
    ax_k.legend()
    ax_v.plot(ticks, var_post, "o-", color=palette.ESTIMATE, ms=4, label="σ² after update")
    ax_v.axhline(var_steady, color=palette.PREDICTION, ls="--", label=f"steady state {var_steady:.3f}")
    ax_v.set_xlabel("tick")
    ax_v.set_ylabel("variance (m²)")
    ax_v.set_ylim(0, None)
    for ax in (ax_k, ax_v):
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax_v.legend()
    return fig
