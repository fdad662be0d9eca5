"""Chapter 12's blind tuning round: noises chosen on one log, scored on the other.

A student picks the noise the filter assumes (R through the odometry's speed and turn-rate noise, Q through
the range noise), the radio's scale and the gate, looking only at Plaza1.  :func:`tuning_score` runs the
same choice on Plaza2, which the student never tuned on, and says how far off the filter is, how often its
NEES lies where an honest filter's would, and whether it is honest, timid or over-confident.
"""

from __future__ import annotations

from dataclasses import dataclass

from .range_run import DATA_SHEET, range_localize
from .records import Record
from .scores import NEES_BAND


@dataclass(frozen=True)
class TuningScore(Record):
    """A choice of noises, run on the log it was not tuned on."""

    log: str  #: the log scored on
    speed_std: float  #: the speed noise assumed (m/s; per metre driven: m per square-root metre)
    turn_std: float  #: the turn-rate noise assumed (rad/s; per metre driven: rad per square-root metre)
    noise_per: str  #: what the odometry noise grows with: "second" or "metre"
    range_std: float  #: the range noise assumed (m)
    scale: float | str  #: the radio's scale assumed, or "online"
    gate: float | None  #: the gate (standard deviations), or None
    mean_error: float  #: mean position error (m)
    p95_error: float  #: 95th-percentile position error (m)
    in_band: float  #: share of steps whose position NEES lies in :data:`NEES_BAND` (0.95 when honest)
    mean_nees: float  #: mean position NEES (2 when honest)
    verdict: str  #: "honest", "timid" or "over-confident"

    def __str__(self) -> str:
        return (
            f"On {self.log}: mean error {self.mean_error:.2f} m (95 % under {self.p95_error:.2f} m); "
            f"NEES in its band at {self.in_band:.0%} of steps (95 % if honest), mean {self.mean_nees:.3g} "
            f"(2 if honest): {self.verdict}."
        )


def tuning_score(
    speed_std: float = DATA_SHEET["speed_std"],
    turn_std: float = DATA_SHEET["turn_std"],
    noise_per: str = "second",
    range_std: float = DATA_SHEET["range_std"],
    scale=1.0,
    gate: float | None = None,
    log: str = "Plaza2",
) -> TuningScore:
    """Run the course's EKF with these noises on a log (by default Plaza2, the one not tuned on) and score it.

    Introduced in chapter 12.

    Parameters
    ----------
    speed_std, turn_std, noise_per, range_std, scale, gate
        As in :func:`~kfcourse.sim.range_localize`.
    log : {"Plaza1", "Plaza2"}
        The log to score on.

    Returns
    -------
    TuningScore
        ``print`` it for one line: the errors, the NEES and the verdict.
    """
    from ..data import PLAZA_RUNS, load_plaza  # here: kfcourse.data builds its record from kfcourse.sim's

    if not isinstance(log, str) or log not in PLAZA_RUNS:
        raise ValueError(f"log must be one of {PLAZA_RUNS}, got {log!r}")
    settings = {"speed_std": speed_std, "turn_std": turn_std, "noise_per": noise_per, "range_std": range_std}
    settings.update(scale=scale, gate=gate)
    run = range_localize(load_plaza(log), **settings)
    low, high = NEES_BAND
    summary = run.summary()
    return TuningScore(
        log=log,
        **{**settings, "speed_std": run.speed_std, "turn_std": run.turn_std, "range_std": run.range_std},
        mean_error=summary["mean_error"],
        p95_error=summary["p95_error"],
        in_band=float(((run.nees >= low) & (run.nees <= high)).mean()),
        mean_nees=summary["mean_nees"],
        verdict=summary["verdict"],
    )
