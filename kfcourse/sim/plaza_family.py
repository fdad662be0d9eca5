"""The family measured on a real robot's log (chapter 12), beside chapter 11's simulated table.

:func:`plaza_family` runs every filter of the course over the same Plaza log, measures each against the
ground truth (mean and 95th-percentile position error, the share of poses inside its 3-sigma ellipse),
whether it finds the robot from a start it is not told, and what a step costs; :meth:`PlazaFamily.table`
prints the table.  The Kalman filters are tuned as chapter 12 tunes them: the radio's scale as a fourth
state, a 3-sigma gate and an odometry noise per metre driven (:data:`TUNED`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .range_particles import FOUND, plaza_box, range_particles
from .range_run import log_steps, range_localize, smoothed
from .records import Record, text_table

if TYPE_CHECKING:
    from ..data import PlazaLog

# Chapter 12's own choice, made on Plaza1 and honest on Plaza2 too: the odometry's noise per metre driven
# (m and rad per square-root metre), the radio's noise (m), its scale estimated, a 3-sigma gate.
TUNED = {"speed_std": 0.05, "turn_std": 0.01, "noise_per": "metre", "range_std": 0.7, "scale": "online", "gate": 3.0}
LOST = (30.0, 30.0, np.pi)  # a Kalman filter not told its start: the plaza's middle, 30 m and pi of doubt


@dataclass(frozen=True)
class PlazaRow(Record):
    """One filter over the log."""

    name: str  #: the row's label
    mean_error: float  #: mean position error (m)
    p95_error: float  #: 95th-percentile position error (m)
    inside: float  #: share of poses with the truth inside the 3-sigma ellipse
    global_start: bool | None  #: found the robot from a start it was not told; None: not asked
    ms_per_step: float  #: wall time per odometry step of the run measured (ms)


@dataclass(frozen=True)
class PlazaFamily(Record):
    """The family over one log: a :class:`PlazaRow` per filter."""

    log: str  #: the log's name
    steps: int  #: odometry steps followed
    rows: tuple  #: the rows, in the order of the table

    def table(self) -> str:
        """The rows as a plain-text table, and how they were measured."""
        header = ["Filter", "error (m)", "95 % under (m)", "in 3σ", "global start", "ms/step"]
        said = {True: "yes", False: "no", None: "—"}
        rows = [
            [r.name, f"{r.mean_error:.2f}", f"{r.p95_error:.2f}", f"{r.inside:.0%}", said[r.global_start],
             f"{r.ms_per_step:.2f}"]
            for r in self.rows
        ]  # fmt: skip
        notes = [
            f"{self.log}, {self.steps} odometry steps; every filter starts at the true pose but in the global start.",
            "error: position error against the ground truth.  in 3σ: share of poses with the truth inside the",
            "filter's own 3σ ellipse.  global start: from the plaza's middle with 30 m and π of doubt (the Kalman",
            f"filters) or a cloud over the whole plaza (the particle filter), yes if within {FOUND:g} m of the robot",
            "at every step of the run's second half.  ms/step: the run's wall time on this machine per step.",
            "dead reckoning: the tuned EKF told no range, its ellipse growing unchecked.",
        ]
        return text_table(header, rows) + "\n\n" + "\n".join(notes)


def _timed(run):
    """``run()`` and its wall time (s)."""
    start = time.perf_counter()
    result = run()
    return result, time.perf_counter() - start


def _found(run) -> bool:
    """Whether the run stays within :data:`FOUND` of the robot over its second half."""
    return bool(np.all(run.error[len(run.error) // 2 :] <= FOUND))


def _row(name: str, run, seconds: float, steps: int, global_start: bool | None) -> PlazaRow:
    s = run.summary()
    return PlazaRow(
        name=name,
        mean_error=s["mean_error"],
        p95_error=s["p95_error"],
        inside=s["inside"],
        global_start=global_start,
        ms_per_step=1000.0 * seconds / steps,
    )


def plaza_family(log: PlazaLog, *, n_particles: int = 1000, seed: int = 0, steps: int | None = None) -> PlazaFamily:
    """Run the course's filters over one log and measure them against its ground truth.  Introduced in chapter 12.

    Rows: dead reckoning (the EKF with no range); the EKF as a data sheet would tune it; the EKF, the UKF
    and the RTS smoother tuned as chapter 12 tunes them (:data:`TUNED`); the particle filter (chapter 11's,
    :func:`~kfcourse.sim.range_particles`).  Each starts at the true pose; each but dead reckoning, the data
    sheet's EKF and the smoother is run again from a start it is not told (the Kalman filters from the plaza's
    middle with :data:`LOST` doubt, the particle filter from a cloud over the whole plaza), to say whether it
    finds the robot.

    Parameters
    ----------
    log : PlazaLog
        :func:`kfcourse.data.load_plaza`.
    n_particles : int
        The particle filter's cloud (1 to 10 000).
    seed : int
        The particle filter's draws (>= 0).
    steps : int, optional
        Follow only the first ``steps`` odometry steps (>= 1); by default the whole log.

    Returns
    -------
    PlazaFamily
    """
    steps = log_steps(log, steps)
    middle = [*plaza_box(log).mean(axis=1), 0.0]
    lost = {"start": middle, "start_std": LOST, "steps": steps}
    rows = [
        _row("dead reckoning", *_timed(lambda: range_localize(log.only([]), steps=steps, **TUNED)), steps, None),
        _row("EKF, data sheet", *_timed(lambda: range_localize(log, steps=steps)), steps, None),
    ]
    for kind in ("ekf", "ukf"):
        run, seconds = _timed(lambda kind=kind: range_localize(log, filter=kind, steps=steps, **TUNED))
        found = _found(range_localize(log, filter=kind, **TUNED, **lost))
        rows.append(_row(f"{kind.upper()}, tuned", run, seconds, steps, found))
        if kind == "ekf":
            after, seconds = _timed(lambda run=run: smoothed(run))
            rows.append(_row("RTS smoother", after, seconds, steps, None))
    pf = {"n_particles": n_particles, "seed": seed, "steps": steps}
    cloud, seconds = _timed(lambda: range_particles(log, start=log.truth[0], **pf))
    found = _found(range_particles(log, **pf))  # from a cloud over the whole plaza
    rows.append(_row(f"PF, N = {cloud.n_particles}", cloud, seconds, steps, found))
    return PlazaFamily(log=log.name, steps=steps, rows=tuple(rows))
