r"""The error strips of the landmark localization loop (chapter 10), drawn under its map.

Two strips show the position error along x and along y over the
whole run, in metres, each with the band of plus or minus two standard deviations of that
coordinate, read from the filter's own covariance.  An honest filter keeps its
error inside the band about 95 % of the time: the x error is Gaussian with
variance :math:`\Sigma_{xx}` if the filter is right about itself.

Every function takes a run record with the fields of
:class:`kfcourse.sim.LoopRun` (``t, dt, start, truth, landmarks, used,
rejected, mu_bar, Sig_bar, mu, Sig, dropout, kidnap``); :func:`update_error_strips` moves what was drawn to
another step (or another run) in place.  :mod:`kfcourse.plots.loop` draws the map and the whole
picture, and offers these functions too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from matplotlib.ticker import MaxNLocator

from . import palette
from .style import fixed_width_ticks, set_limits

NSIG = 2.0  # the map's ellipses and the strips' bands are 2-sigma
AXES = ("x", "y")
HEADROOM = 1.15  # the strips' limit is at least this many times the largest error or bound of the run
TICK_WIDTH = 5  # characters a strip's tick label may take, as in "-0.05" (limits from 0.01 m up)


def run_step(run, k) -> int:
    """``k`` as a step of ``run``; ``None`` means the last step (shared with the map, :mod:`kfcourse.plots.loop`)."""
    T = len(run.t)
    k = T - 1 if k is None else int(k)
    if not 0 <= k < T:
        raise ValueError(f"k must be a step of the run, 0 to {T - 1}, got {k}")
    return k


def kidnap_step(run) -> int | None:
    """The step at which the truth jumps, or ``None``."""
    return None if run.kidnap is None else int(run.kidnap)


def position_errors(run) -> tuple[np.ndarray, np.ndarray]:
    r"""The position error per axis and its 2-sigma bound, at every step.

    The error is truth minus estimate, :math:`e_k = p_k - \hat p_k` (x and y
    separately), and the bound is :math:`2\sqrt{\Sigma_{xx}}` for x and
    :math:`2\sqrt{\Sigma_{yy}}` for y, with Σ the filter's covariance after
    the step's readings.  If the filter is honest, each error is Gaussian with
    that variance and stays within its bound at about 95 % of the steps.
    Introduced in chapter 10.

    Parameters
    ----------
    run : LoopRun

    Returns
    -------
    (error, bound) : ndarray, shape (T, 2) each
        Columns x and y (m).
    """
    error = np.asarray(run.truth)[:, :2] - np.asarray(run.mu)[:, :2]  # e = p - p_hat
    bound = NSIG * np.sqrt(np.diagonal(np.asarray(run.Sig), axis1=1, axis2=2)[:, :2])  # 2 sqrt(Sig_xx), 2 sqrt(Sig_yy)
    return error, bound


def strip_limit(run) -> float:
    """The strips' y limit (m): they run from minus to plus this value.

    The first of 1, 2, 5, 10, 20, ... times a power of ten (0.01, 0.02, 0.05,
    0.1, ...) at or above 1.15 times the largest error or bound of ``run``, so the
    strips hold the whole run.  Such a limit changes in coarse steps as the run
    changes (most changes of a setting keep it) and reads as a round number.
    Introduced in chapter 10.

    Parameters
    ----------
    run : LoopRun

    Returns
    -------
    float
    """
    error, bound = position_errors(run)
    value = HEADROOM * max(float(np.abs(error).max()), float(bound.max()), 1e-12)
    decade = 10.0 ** np.floor(np.log10(value))
    return next(float(step * decade) for step in (1.0, 2.0, 5.0, 10.0) if step * decade >= value)


@dataclass(frozen=True)
class ErrorStrips:
    """What :func:`error_strips` drew, one entry per axis (x, then y).

    The strips plot the errors and bands in metres on real axes from
    ``-strip_limit(run)`` to ``strip_limit(run)``; their ticks are matplotlib's,
    at the limits and at zero.
    """

    axes: tuple
    past: tuple[Line2D, ...]  #: the error up to the step shown
    future: tuple[Line2D, ...]  #: the rest of the run, faint
    bands: tuple[PolyCollection, ...]  #: plus or minus 2 sigma
    cursors: tuple[Line2D, ...]  #: the step shown
    blind: tuple[Rectangle, ...]  #: the steps without readings (hidden without dropout)
    kidnap: tuple[Line2D, ...]  #: the kidnap step (hidden without one)

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the run, bottom to top."""
        per_axis = zip(self.blind, self.bands, self.kidnap, self.future, self.past, self.cursors, strict=True)
        return [artist for group in per_axis for artist in group]


def _band_verts(t, bound) -> np.ndarray:
    """The outline of the band -bound..+bound over t, as one closed polygon."""
    return np.concatenate([np.column_stack([t, bound]), np.column_stack([t[::-1], -bound[::-1]])])


def error_strips(axes, run, k: int | None = None) -> ErrorStrips:
    """Draw the x and y position errors of ``run`` with their 2-sigma bands.

    See :func:`position_errors` for the definitions and :func:`strip_limit`
    for the shared y limit.  Introduced in chapter 10.

    Parameters
    ----------
    axes : pair of matplotlib Axes
        For the x error and the y error (sharing their time axis).
    run : LoopRun
    k : int, optional
        The step marked by the cursor; by default the last.

    Returns
    -------
    ErrorStrips
    """
    k = run_step(run, k)
    t = np.asarray(run.t, float)
    parts: dict[str, list] = {name: [] for name in ("past", "future", "bands", "cursors", "blind", "kidnap")}
    for ax, name in zip(axes, AXES, strict=True):
        ax.set_xlim(t[0], t[-1])
        ax.axhline(0.0, color=palette.INK, lw=0.8, alpha=0.5)
        ax.set_ylabel(f"{name} error (m)")
        ax.yaxis.set_major_locator(MaxNLocator(nbins=2, steps=[1, 2, 5, 10]))  # at -limit, 0 and +limit
        fixed_width_ticks(ax.yaxis, TICK_WIDTH)  # the layout is found once: labels keep their width
        # The blind stretch and the vertical lines span the strip's height whatever its limits (x in s, y in axes).
        blind = Rectangle((t[0], 0.0), 0.0, 1.0, color=palette.TRUTH, alpha=0.25, lw=0, visible=False)
        blind.set_transform(ax.get_xaxis_transform())
        ax.add_patch(blind)
        band = PolyCollection([], facecolors=palette.ESTIMATE, alpha=0.18, lw=0)
        ax.add_collection(band, autolim=False)
        kidnap = ax.axvline(t[0], color=palette.INK, lw=1.2, ls=":", visible=False)
        (future,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.2, alpha=0.35)
        (past,) = ax.plot([], [], color=palette.ESTIMATE, lw=1.8)
        cursor = ax.axvline(t[0], color=palette.INK, lw=1.0, alpha=0.6)
        for key, artist in zip(parts, (past, future, band, cursor, blind, kidnap), strict=True):
            parts[key].append(artist)
    axes[-1].set_xlabel("time (s)")
    strips = ErrorStrips(tuple(axes), **{key: tuple(value) for key, value in parts.items()})
    update_error_strips(strips, run, k)
    return strips


def update_error_strips(strips: ErrorStrips, run, k: int) -> None:
    """Show ``run`` with the cursor at step ``k`` on strips made by :func:`error_strips`.

    The y limits are set only when :func:`strip_limit` changes, that is only for some
    new runs, never for a new step: a renderer then redraws the background (the axes
    and their ticks) only when it did change.
    """
    k = run_step(run, k)
    t = np.asarray(run.t, float)
    error, bound = position_errors(run)
    top = strip_limit(run)
    k0 = kidnap_step(run)
    for i, ax in enumerate(strips.axes):
        set_limits(ax, ylim=(-top, top))
        strips.past[i].set_data(t[: k + 1], error[: k + 1, i])
        strips.future[i].set_data(t[k:], error[k:, i])
        strips.bands[i].set_verts([_band_verts(t, bound[:, i])])
        strips.cursors[i].set_xdata([t[k], t[k]])
        blind = strips.blind[i]
        blind.set_visible(run.dropout is not None)
        if run.dropout is not None:
            t0, t1 = run.dropout
            first, last = t[min(t0, len(t) - 1)], t[min(max(t1 - 1, t0), len(t) - 1)]
            blind.set_x(first - 0.5 * run.dt)
            blind.set_width(last - first + run.dt)
        strips.kidnap[i].set_visible(k0 is not None)
        if k0 is not None:
            strips.kidnap[i].set_xdata([t[k0], t[k0]])
