r"""Chapter 12's static charts: a real robot's log, its ranges, and filters run over it.

- :func:`plaza_chart`: the plaza at the scale of the data (metres the same across and up): the four beacons
  (purple squares), the true path (grey, dotted), dead reckoning (purple, dashed: the odometry alone, a
  prediction never corrected) and each run's estimated path (teal: the first thin and solid, the next ones in
  other line styles, :data:`RUN_STYLES`).
- :func:`ranges_chart`: every range against the true distance to its beacon (orange points), the line an honest
  radio would read along (range = distance, grey and dotted like the truth) and the least-squares line through
  the readings (a darker orange, dash-dot): the radio's scale error.
- :func:`nees_chart`: each run's position NEES over time on a log scale, against the band an honest filter's
  NEES lies in at 95 % of its steps (:data:`~kfcourse.sim.NEES_BAND`, chi-square with 2 degrees of freedom)
  and its average, 2 (grey: guides, not a role).

Each takes records and returns a figure; in a notebook the figure shows itself when it is a cell's last value.
A run is anything with ``t``, ``mu`` (rows ``[x, y, ...]``), ``error`` and ``nees``, one row per pose of the log:
:class:`~kfcourse.sim.RangeRun` (:func:`~kfcourse.sim.range_localize`, :func:`~kfcourse.sim.smoothed`),
:class:`~kfcourse.sim.RangeParticleRun` or :class:`~kfcourse.sim.FactorGraphRun`.
"""

from __future__ import annotations

import numpy as np

from ..sim.scores import NEES_BAND
from . import palette
from .artists import landmarks
from .style import new_figure

__all__ = ["RUN_STYLES", "nees_chart", "plaza_chart", "ranges_chart", "run_label"]

MAP_MARGIN = 6.0  # m of room around the beacons and the paths
WANDER = 0.25  # a path that leaves the plaza stretches the map by at most this share of the plaza's span each way
MAP_WIDTH = 6.4  # inches
LEGEND_HEIGHT = 0.5  # inches above the map for its legend (two rows)
NEES_LIMITS = (1e-2, 1e4)  # the NEES chart's log scale, as the real-run demo's strip; widened for a larger NEES

# The runs' styles, in order: the first is the estimate as every chapter draws it (teal, thin, solid); the next
# ones stay teal (they are estimates too) and differ by line style, never by colour alone: a wide pale band
# under the others (chapter 9's UKF, the demo's smoother), then dashed (chapter 9's EKF), then dash-dot.
RUN_STYLES = (
    {"color": palette.ESTIMATE, "lw": 1.3, "ls": "-", "zorder": 5},
    {"color": palette.ESTIMATE, "lw": 4.5, "ls": "-", "alpha": 0.35, "solid_capstyle": "round", "zorder": 3},
    {"color": palette.ESTIMATE, "lw": 1.2, "ls": "--", "zorder": 4},
    {"color": palette.ESTIMATE, "lw": 1.2, "ls": "-.", "zorder": 4},
)
TRUTH_STYLE = {"color": palette.TRUTH, "ls": palette.TRUTH_LINE, "lw": 2.5}
DEAD_RECKONING_STYLE = {"color": palette.PREDICTION, "ls": palette.PREDICTION_LINE, "lw": 1.1, "zorder": 2}


def run_label(run) -> str:
    """What a run is called when no label is given: its filter ("EKF", "UKF"), "particle filter" or "factor graph".

    A smoothed EKF run is an EKF's record too (:func:`~kfcourse.sim.smoothed`): give it its own label.
    """
    name = type(run).__name__
    if name == "RangeParticleRun":
        return "particle filter"
    if name == "FactorGraphRun":
        return "factor graph"
    return str(run.filter).upper() if hasattr(run, "filter") else "estimate"


def _labels(runs, labels) -> list[str]:
    """One label per run: those given, or :func:`run_label`'s, a repeated one numbered."""
    if labels is None:
        names = [run_label(run) for run in runs]
        return [
            f"{name} ({names[:i].count(name) + 1})" if names.count(name) > 1 else name for i, name in enumerate(names)
        ]
    if isinstance(labels, str):
        labels = [labels]
    labels = [str(label) for label in labels]
    if len(labels) != len(runs):
        raise ValueError(f"labels must name each of the {len(runs)} runs, got {len(labels)} labels")
    return labels


def _style(i: int) -> dict:
    return RUN_STYLES[i % len(RUN_STYLES)]


def _check_run(run, name: str, rows: int | None = None) -> None:
    for field in ("t", "mu", "error", "nees"):
        if not hasattr(run, field):
            raise ValueError(f"{name} must be a run record with t, mu, error and nees, got {type(run).__name__}")
    if rows is not None and len(run.mu) > rows:
        raise ValueError(f"{name} has {len(run.mu)} poses, more than the log's {rows}: is it a run of this log?")


def _map_limits(log, paths) -> tuple[np.ndarray, np.ndarray]:
    """The map's corners: the beacons and the true path with a margin, stretched to hold the other paths up to
    :data:`WANDER` of the plaza's span each way (a filter lost far off does not shrink the plaza to a dot)."""
    plaza = np.vstack([log.beacons, log.truth[:, :2]])
    lo, hi = plaza.min(axis=0) - MAP_MARGIN, plaza.max(axis=0) + MAP_MARGIN
    reach = WANDER * (hi - lo)
    for path in paths:
        finite = path[np.isfinite(path).all(axis=1)]
        if len(finite):
            lo = np.minimum(lo, np.maximum(finite.min(axis=0) - MAP_MARGIN, lo - reach))
            hi = np.maximum(hi, np.minimum(finite.max(axis=0) + MAP_MARGIN, hi + reach))
    return lo, hi


def plaza_chart(log, *runs, labels=None, dead_reckoning: bool = True):
    """Chapter 12: a Plaza log on its plaza, and the paths of filters run over it.

    The beacons (purple squares, numbered by their rows of ``log.beacons``), the true path (grey, dotted), the
    dead reckoning from the true start (``log.dead_reckoning()``, purple, dashed) and each run's estimated path
    in the styles of :data:`RUN_STYLES`: the first teal and solid, the second a wide pale teal band under it,
    the third teal and dashed.  The legend above the map gives each run's mean position error.  The map spans
    the beacons and the true path, metres the same across and up.  Introduced in chapter 12.

    Parameters
    ----------
    log : PlazaLog
        :func:`kfcourse.data.load_plaza`'s record.
    *runs : run records of this log
        Each with ``mu`` (its rows ``[x, y, ...]``) and ``error``: :func:`~kfcourse.sim.range_localize`,
        :func:`~kfcourse.sim.smoothed`, :func:`~kfcourse.sim.range_particles`, :func:`~kfcourse.sim.factor_graph`.
        None: the log alone.
    labels : sequence of str, optional
        A name per run; by default :func:`run_label`'s ("EKF", "factor graph", ...).
    dead_reckoning : bool
        Draw the dead reckoning.

    Returns
    -------
    matplotlib.figure.Figure
    """
    rows = len(log.truth)
    for i, run in enumerate(runs):
        _check_run(run, f"run {i + 1}", rows)
    names = _labels(runs, labels)
    drift = log.dead_reckoning() if dead_reckoning else np.empty((0, 3))
    lo, hi = _map_limits(log, [drift[:, :2], *(np.asarray(run.mu, float)[:, :2] for run in runs)])
    map_height = (MAP_WIDTH - 0.9) * (hi[1] - lo[1]) / (hi[0] - lo[0]) + 0.6  # metres square, room for the x label
    fig, ax = new_figure(MAP_WIDTH, map_height + LEGEND_HEIGHT)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    fig.suptitle(f"{log.name}: {log.duration:.0f} s, {log.path_length / 1000:.2f} km", fontsize=10)
    ax.plot(log.truth[:, 0], log.truth[:, 1], label="truth", zorder=1, **TRUTH_STYLE)
    if dead_reckoning:
        off = np.hypot(*(drift[:, :2] - log.truth[:, :2]).T).mean()
        ax.plot(drift[:, 0], drift[:, 1], label=f"dead reckoning: mean error {off:.1f} m", **DEAD_RECKONING_STYLE)
    for i, (run, name) in enumerate(zip(runs, names, strict=True)):
        mu = np.asarray(run.mu, float)
        ax.plot(mu[:, 0], mu[:, 1], label=f"{name}: mean error {np.mean(run.error):.2f} m", **_style(i))
    landmarks(ax, log.beacons, labels=True, label="beacons", zorder=6)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=2, fontsize=8, columnspacing=1.2, handlelength=2.5)
    return fig


def ranges_chart(log):
    """Chapter 12: every range of a Plaza log against the true distance to its beacon.

    The readings (orange points, one per range), the line an honest radio's readings would scatter about (range
    = true distance: grey and dotted, the truth's style) and the least-squares line through the readings (darker
    orange, dash-dot), its slope and offset in the legend: about 1.07, a radio that reads 7 % long.  The true
    distance is ``log.true_distance()``: the ground truth interpolated to each range's time.  Introduced in
    chapter 12.

    Parameters
    ----------
    log : PlazaLog

    Returns
    -------
    matplotlib.figure.Figure
    """
    d, z = log.true_distance(), np.asarray(log.range, float)
    slope, intercept = np.polyfit(d, z, 1)  # range = slope * distance + intercept
    spread = float(np.std(z - slope * d - intercept))
    fig, ax = new_figure(4.8, 4.6)
    top = 1.05 * max(d.max(), z.max())
    ax.plot(d, z, "o", color=palette.MEASUREMENT, ms=2.5, alpha=0.4, mew=0, label=f"{z.size} ranges", zorder=2)
    line = np.array([0.0, top])
    ax.plot(line, line, label="honest radio: range = distance", zorder=3, **TRUTH_STYLE)
    ax.plot(
        line,
        slope * line + intercept,
        color=palette.MEASUREMENT_TEXT,  # the orange's darker shade: a thin line over the orange points still shows
        ls=palette.MEASUREMENT_LINE,
        lw=1.6,
        label=f"fit: range = {slope:.3f} × distance {'+' if intercept >= 0 else '−'} {abs(intercept):.2f} m "
        f"(spread {spread:.2f} m)",
        zorder=4,
    )
    ax.set_xlim(0.0, top)
    ax.set_ylim(0.0, top)
    ax.set_aspect("equal")
    ax.set_xlabel("true distance to the beacon (m)")
    ax.set_ylabel("range read (m)")
    ax.set_title(f"{log.name}: {z.size} ranges to {len(log.beacons)} beacons", fontsize=10)
    ax.legend(loc="upper left", fontsize=8, markerscale=2.5)
    return fig


def _nees_limits(runs) -> tuple[float, float]:
    """:data:`NEES_LIMITS`, the top raised to the decade above the largest finite NEES."""
    finite = [np.asarray(run.nees, float)[np.isfinite(run.nees)] for run in runs]
    largest = max((values.max() for values in finite if values.size), default=0.0)
    top = max(NEES_LIMITS[1], 10.0 ** np.ceil(np.log10(max(largest, 1.0) * 1.5)))
    return NEES_LIMITS[0], float(top)


def nees_chart(*runs, labels=None):
    """Chapter 12: each run's position NEES over time, on a log scale, against an honest filter's band.

    The shaded band (grey: a guide; the runs are teal) is :data:`~kfcourse.sim.NEES_BAND`, where one position NEES
    of an honest filter lies at 95 % of its steps (chi-square with 2 degrees of freedom: 0.05 to 7.4); the dotted
    line is its average, 2.  One line per run, in the styles of :func:`plaza_chart`, its mean NEES in the legend.
    A NEES of 0 or below the axis is drawn at its bottom, an infinite one (a flat ellipse the truth left) at its
    top.  Introduced in chapter 12.

    Parameters
    ----------
    *runs : run records
        At least one, each with ``t`` (s) and ``nees``.
    labels : sequence of str, optional
        A name per run; by default :func:`run_label`'s.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not runs:
        raise ValueError("nees_chart needs at least one run")
    for i, run in enumerate(runs):
        _check_run(run, f"run {i + 1}")
    names = _labels(runs, labels)
    low, high = _nees_limits(runs)
    fig, ax = new_figure(8.0, 3.2)
    ax.set_yscale("log")
    band = f"honest: 95 % of steps in {NEES_BAND[0]:.2f} to {NEES_BAND[1]:.1f}"
    ax.axhspan(*NEES_BAND, color=palette.INK, alpha=0.08, lw=0, zorder=0, label=band)  # a guide: no role's colour
    ax.axhline(2.0, color=palette.INK, lw=0.9, ls=":", label="honest average, 2", zorder=1)
    for i, (run, name) in enumerate(zip(runs, names, strict=True)):
        values = np.asarray(run.nees, float)
        shown = np.clip(np.nan_to_num(values, nan=high, posinf=high), low, high)
        ax.plot(run.t, shown, label=f"{name}: mean NEES {np.mean(values):.3g}", **(_style(i) | {"lw": _nees_width(i)}))
    ax.set_ylim(low, high)
    ax.set_xlim(0.0, max(float(run.t[-1]) for run in runs))
    ax.set_xlabel("t (s)")
    ax.set_ylabel("position NEES (log scale)")
    logs = sorted({str(getattr(run, "log", "")) for run in runs} - {""})
    fig.suptitle(f"{', '.join(logs)}: position NEES" if logs else "position NEES", fontsize=10)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=2, fontsize=8, columnspacing=1.2, handlelength=2.5)
    return fig


def _nees_width(i: int) -> float:
    """The NEES lines are thinner than the map's paths: thousands of steps side by side."""
    return 2.5 if _style(i)["lw"] > 2 else 0.8
