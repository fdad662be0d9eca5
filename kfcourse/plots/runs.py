"""Static figures of whole filter runs (data in, figure out)."""

from __future__ import annotations

import numpy as np

from . import palette
from .style import new_figure


def kf_run_chart(run, title: str = "", detrend: bool = True, start: int = 0):
    """Chapter 3: a 1-D Kalman filter run over time, in two panels.

    Top: the estimate ``mu`` with its ``±sigma`` band (teal) against the truth
    (grey) and the readings (orange).  A robot that drives 1 m a step covers
    100 m in 100 steps, which would hide centimetre errors, so by default the top
    panel subtracts the commanded path ``x0 + u_1 + ... + u_k`` from every
    curve: it shows where things are *relative to where the commands alone
    would have put the robot*.  Bottom: the innovations ``z - mu_bar``
    (orange) with the ``±sqrt(S)`` band the filter expects them in (purple,
    ``S = var_bar + Q``) and their mean (dashed) over the steps from index
    ``start`` on, the same window as the run's health numbers
    (:meth:`kfcourse.sim.walk.WalkRun.health`); the legend names the window.

    Introduced in chapter 3.

    Parameters
    ----------
    run : object with arrays ``t, truth, z, mu, var, innovation, S`` of shape (T,)
        A run record such as :class:`kfcourse.sim.walk.WalkRun`.
    title : str
        Drawn above the top panel.
    detrend : bool
        Subtract the commanded path (needs ``run.x0`` and ``run.u``); if False,
        plot positions as they are.
    start : int
        Index of the first step in the mean innovation (0: all steps; 20: from time step 21 on,
        after the start-up).

    Returns
    -------
    matplotlib.figure.Figure
    """
    t = np.asarray(run.t, float)
    path = run.x0 + np.cumsum(run.u) if detrend else np.zeros_like(t)  # the commanded path (m)
    truth = np.asarray(run.truth, float) - path
    z = np.asarray(run.z, float) - path
    mu = np.asarray(run.mu, float) - path
    sigma = np.sqrt(np.asarray(run.var, float))
    innovation = np.asarray(run.innovation, float)
    band = np.sqrt(np.asarray(run.S, float))
    fig, (ax_x, ax_nu) = new_figure(8.0, 4.6, nrows=2, sharex=True, height_ratios=(3, 2))

    ax_x.plot(t, truth, color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=2.5, label="truth")
    ax_x.plot(t, z, "o", color=palette.MEASUREMENT, ms=3, alpha=0.8, label="readings z")
    ax_x.fill_between(t, mu - sigma, mu + sigma, color=palette.ESTIMATE, alpha=0.25, lw=0, label="μ ± σ")
    ax_x.plot(t, mu, color=palette.ESTIMATE, lw=1.8, label="estimate μ")
    ax_x.set_ylabel("position − commanded path (m)" if detrend else "position (m)")
    ax_x.legend(loc="upper left", fontsize=8, ncols=2)
    if title:
        ax_x.set_title(title, fontsize=10)

    ax_nu.fill_between(t, -band, band, color=palette.PREDICTION, alpha=0.15, lw=0, label="± √S")
    ax_nu.axhline(0.0, color=palette.INK, lw=0.8)
    ax_nu.plot(t, innovation, "o-", color=palette.MEASUREMENT, ms=2.5, lw=0.8, label="innovation z − μ̄")
    if isinstance(start, bool) or not isinstance(start, (int, np.integer)) or not 0 <= start < t.size:
        raise ValueError(f"start must be a whole number from 0 to {t.size - 1}, got {start!r}")
    mean = float(np.mean(innovation[start:]))  # over the window only
    window = "all steps" if start == 0 else f"steps {t[start]:.0f}–{t[-1]:.0f}"
    ax_nu.plot(
        t[start:][[0, -1]],
        [mean, mean],
        color=palette.MEASUREMENT,
        ls=palette.MEASUREMENT_LINE,
        lw=1.2,
        label=f"mean ({window}) {mean:+.2f} m",
    )
    ax_nu.set_xlabel("time step k")
    ax_nu.set_ylabel("innovation (m)")
    ax_nu.legend(loc="upper left", fontsize=8, ncols=3)
    return fig
