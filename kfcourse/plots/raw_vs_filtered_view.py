"""Chapter 0's picture: a robot on a line, its raw readings, dead reckoning and the filter.

The upper panel shows positions over time: the truth (grey, dotted), the sensor's
pings (orange dots) and the trace that trusts each one (orange, dash-dot), dead
reckoning (dashed purple) and the Kalman filter's estimate (solid) with its band of plus
or minus one standard deviation (teal).  The lower panel shows how far each of
the three is from the truth at every step, in the same colours, with their RMS
errors so far written above it.

:func:`raw_vs_filtered_view` builds the figure, empty; :func:`update_raw_vs_filtered`
draws a run up to the step shown.  Introduced in chapter 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PathCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.text import Text

from .. import _validate as v
from . import palette
from .style import fixed_width_ticks, new_figure, nice_limit, set_limits


@dataclass(frozen=True)
class RawVsFilteredView:
    """What :func:`raw_vs_filtered_view` drew; :func:`update_raw_vs_filtered` moves it."""

    fig: Figure
    ax: Axes  #: positions (m) over time
    ax_err: Axes  #: distance from the truth (m) over time
    truth: Line2D
    pings: PathCollection  #: the sensor's readings
    raw: Line2D  #: trusting each reading
    dead_reckoning: Line2D
    band: PolyCollection  #: the filter's mean plus or minus one standard deviation
    estimate: Line2D  #: the filter's mean
    robot: Line2D  #: the estimate at the step shown
    err_raw: Line2D
    err_dead_reckoning: Line2D
    err_estimate: Line2D
    readout: Text  #: the RMS errors so far

    @property
    def moving(self) -> list:
        """Every artist that changes with the step or the run, bottom to top."""
        return [
            self.truth,
            self.pings,
            self.raw,
            self.dead_reckoning,
            self.band,
            self.estimate,
            self.robot,
            self.err_raw,
            self.err_dead_reckoning,
            self.err_estimate,
            self.readout,
        ]


def raw_vs_filtered_view(n_steps: int) -> RawVsFilteredView:
    """The two panels for a run of ``n_steps`` steps, with nothing drawn on them yet.

    Parameters
    ----------
    n_steps : int
        Steps in the run: the time axis spans ``0 .. n_steps - 1``.

    Returns
    -------
    RawVsFilteredView
    """
    n_steps = v.whole(n_steps, "n_steps", 2)
    fig, (ax, ax_err) = new_figure(8.0, 4.6, nrows=2, sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    ax.set_xlim(0, n_steps - 1)
    ax.set_ylabel("position (m)")
    for axis in (ax.yaxis, ax_err.yaxis):
        fixed_width_ticks(axis, 4)  # the layout is found once: wider labels would push "position (m)" out
    (truth,) = ax.plot([], [], color=palette.TRUTH, ls=palette.TRUTH_LINE, lw=4, label="truth (unknown)")
    pings = ax.scatter([], [], s=14, color=palette.MEASUREMENT, alpha=0.75, label="sensor pings", zorder=3)
    (raw,) = ax.plot(
        [], [], color=palette.MEASUREMENT, ls=palette.MEASUREMENT_LINE, lw=1.0, alpha=0.8, label="raw: trust each ping"
    )
    (dead,) = ax.plot([], [], color=palette.PREDICTION, ls=palette.PREDICTION_LINE, lw=1.6, label="dead reckoning")
    band = ax.fill_between([], [], [], color=palette.ESTIMATE, alpha=0.18, lw=0)
    (estimate,) = ax.plot([], [], color=palette.ESTIMATE, ls=palette.ESTIMATE_LINE, lw=2.4, label="filtered (Kalman)")
    (robot,) = ax.plot([], [], "o", color=palette.ESTIMATE, ms=8, zorder=4)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=3, fontsize=9)
    ax_err.set_xlabel("time step")
    ax_err.set_ylabel("distance from truth (m)")
    (err_raw,) = ax_err.plot([], [], color=palette.MEASUREMENT, ls=palette.MEASUREMENT_LINE, lw=0.9, alpha=0.8)
    (err_dead,) = ax_err.plot([], [], color=palette.PREDICTION, ls=palette.PREDICTION_LINE, lw=1.6)
    (err_estimate,) = ax_err.plot([], [], color=palette.ESTIMATE, ls=palette.ESTIMATE_LINE, lw=2.0)
    readout = ax_err.text(0.0, 1.03, "", transform=ax_err.transAxes, ha="left", va="bottom", fontsize=9.5)
    return RawVsFilteredView(
        fig, ax, ax_err, truth, pings, raw, dead, band, estimate, robot, err_raw, err_dead, err_estimate, readout
    )


def raw_vs_filtered_limits(model) -> tuple[tuple[float, float], float]:
    """Axis limits that hold the whole run: the position axis (m) and the top of the error axis (m).

    The margins are powers of two (:func:`~kfcourse.plots.style.nice_limit`), so they change
    only now and then as the sensor noise changes, and every reading and every error stays in view.

    Parameters
    ----------
    model
        As for :func:`update_raw_vs_filtered`.

    Returns
    -------
    ((bottom, top), error_top)
    """
    run = model.run
    lo, hi = float(run.truth.min()), float(run.truth.max())
    seen = np.concatenate([run.z, run.mu, run.dead_reckoning])
    margin = nice_limit(max(0.25 * (hi - lo), lo - seen.min(), seen.max() - hi))  # m beyond the truth's range
    error_top = nice_limit(1.05 * max(e.max() for e in model.errors()))
    return (lo - margin, hi + margin), error_top


def update_raw_vs_filtered(view: RawVsFilteredView, model) -> None:
    """Draw the model's run up to the step shown.

    Parameters
    ----------
    view : RawVsFilteredView
    model
        Anything with ``run`` (a :class:`kfcourse.sim.LineRun`: ``t, truth, z, dead_reckoning,
        mu, var``), ``frame`` (the step shown), ``errors()`` (each estimate's distance from the
        truth at every step: raw, dead reckoning, filtered) and ``rms_errors_all()`` (their RMS
        up to the step shown), such as :class:`kfcourse.demos.raw_vs_filtered.RawVsFiltered`.
    """
    run, k = model.run, model.frame + 1
    t = run.t[:k]
    view.truth.set_data(t, run.truth[:k])
    view.pings.set_offsets(np.column_stack([t, run.z[:k]]))
    view.raw.set_data(t, run.z[:k])
    view.dead_reckoning.set_data(t, run.dead_reckoning[:k])
    sd = np.sqrt(run.var[:k])
    lo, hi = run.mu[:k] - sd, run.mu[:k] + sd  # the band: mu plus or minus one sigma
    view.band.set_verts([np.concatenate([np.column_stack([t, lo]), np.column_stack([t[::-1], hi[::-1]])])])
    view.estimate.set_data(t, run.mu[:k])
    view.robot.set_data([t[-1]], [run.mu[k - 1]])
    e_raw, e_dead, e_estimate = model.errors()
    view.err_raw.set_data(t, e_raw[:k])
    view.err_dead_reckoning.set_data(t, e_dead[:k])
    view.err_estimate.set_data(t, e_estimate[:k])
    positions, error_top = raw_vs_filtered_limits(model)
    set_limits(view.ax, ylim=positions)
    set_limits(view.ax_err, ylim=(0.0, error_top))
    rms_raw, rms_dead, rms_estimate = model.rms_errors_all()
    view.readout.set_text(
        f"RMS error so far: raw {100 * rms_raw:.0f} cm   dead reckoning {100 * rms_dead:.0f} cm   "
        f"filtered {100 * rms_estimate:.0f} cm"
    )
