"""The Kalman family measured side by side on chapter 10's loop (chapter 11).

The lesson closes on a table of the whole family: what each filter handles, how, and when
to use it.  :func:`family_table` runs the EKF, the UKF and the particle filter over the
same seeds of the same world (:func:`~kfcourse.sim.landmark_loop`,
:func:`~kfcourse.sim.particle_loop`: the same draws for the same seed) and measures, for
each filter, its error, its honesty, whether it survives a kidnap, whether it finds the
robot from an unknown start, and what a step costs.  :meth:`FamilyTable.table` prints the
lesson's table with these numbers beside its words.
"""

from __future__ import annotations

import inspect
import time
from dataclasses import dataclass
from functools import partial

import numpy as np

from .. import _validate as v
from .capstone_world import BEARING_STD, OMEGA_STD, RANGE_STD, SIG0, V_STD, loop_world
from .landmark_lap import landmark_loop
from .loop_filters import localize, loop_filter
from .particle_lap import LOCALIZED, MAX_PARTICLES, ParticleRun, localized, particle_loop
from .records import Record, text_table

KIDNAP = 60  # the step of chapter 10's kidnap, about half a lap
GATE = 4.0  # the EKF's and UKF's validation gate on the kidnapped lap, as in chapter 10's capstone
INJECTION = 0.05  # the share of particles injected after each resampling on the kidnapped lap

# The lesson's closing table: filter, what it handles, when to use it.
LESSON_ROWS = (
    ("Bayes filter", "any belief", "the theory all others specialize"),
    ("Kalman (KF)", "linear + Gaussian", "linear models (constant-velocity tracking)"),
    ("EKF", "nonlinear, unimodal", "mildly nonlinear, good init (position tracking)"),
    ("UKF", "nonlinear, unimodal", "strong nonlinearity / nasty Jacobian"),
    ("Particle", "nonlinear, multi-modal", "global localization / kidnapped robot"),
)


@dataclass(frozen=True)
class FilterScore(Record):
    """What one filter did over the seeds of a :class:`FamilyTable`; one entry per seed."""

    name: str  #: "EKF", "UKF", or "PF 2000" (a particle filter and its particle count)
    error: np.ndarray  #: (S,) mean position error over the normal lap (m)
    inside: np.ndarray  #: (S,) share of the normal lap's steps with the truth inside the filter's 3-sigma ellipse
    found: np.ndarray  #: (S,) bool: localized at the lap's end after the kidnap
    localized: np.ndarray | None  #: (S,) bool: localized at the lap's end from a global start; None: not run
    ms_per_step: float  #: wall time of one step of the filter alone, over the first seed's normal lap (ms)


@dataclass(frozen=True)
class FamilyTable(Record):
    """The family measured on one map: a :class:`FilterScore` per filter, over the same seeds.

    ``scores`` is keyed by filter name: ``"EKF"``, ``"UKF"``, ``"PF 200"``, ``"PF 2000"``.
    """

    seeds: np.ndarray  #: (S,) the seeds, the same for every filter
    scores: dict[str, FilterScore]  #: what each filter did, by name
    kidnap: int  #: the step at which the robot is kidnapped
    gate: float  #: the EKF's and UKF's validation gate on the kidnapped lap (standard deviations)
    injection: float  #: the share of particles injected after each resampling on the kidnapped lap

    def table(self) -> str:
        """The lesson's closing table (what each filter handles and when to use it), the measured
        numbers beside its words, and notes on how they were measured."""
        S, dash = len(self.seeds), ["—"] * 5
        words = [list(row) for row in LESSON_ROWS]
        rows = [[*words[0], *dash], [*words[1], *dash]]
        rows += [[*words[i], *_cells(self.scores[name], S)] for i, name in ((2, "EKF"), (3, "UKF"))]
        pfs = [score for name, score in self.scores.items() if name.startswith("PF")]
        for i, score in enumerate(pfs):
            n = score.name.removeprefix("PF ")
            row = [f"Particle, N = {n}", *words[4][1:]] if i == 0 else [f"  N = {n}", "", ""]
            rows.append([*row, *_cells(score, S)])
        for col in (1, 2):  # words read left-aligned: pad them to their column's width
            width = max(len(row[col]) for row in rows)
            for row in rows:
                row[col] = row[col].ljust(width)
        header = ["Filter", "Handles".ljust(len(rows[0][1])), "Use when".ljust(len(rows[0][2]))]
        header += ["error (m)", "in 3σ", "kidnap", "global start", "ms/step"]
        notes = [
            f"Seeds {_seed_span(self.seeds)} of chapter 10's loop, the same for every filter, honest noise.",
            "error: mean position error over a normal lap.  in 3σ: share of its steps with the truth",
            "inside the filter's own 3σ ellipse.  kidnap, global start: seeds localized at the lap's end",
            f"(error under {LOCALIZED} m over its last quarter) after a kidnap at step {self.kidnap}, or from a",
            "start spread over the whole map.  After the kidnap the EKF and UKF gate their readings at",
            f"{self.gate:g}σ, and the particle filter replaces a share {self.injection:g} of its particles by random",
            "poses after each resampling.  The EKF and UKF start at the true pose: no global start (—).",
            "ms/step: one step of the filter alone on this machine, world and record left out (one timed lap: seed",
            f"{self.seeds[0]}'s normal lap).",
            "The Bayes filter is the theory the others approximate; the KF needs linear models, and this loop is not.",
        ]
        return text_table(header, rows) + "\n\n" + "\n".join(notes)


def _cells(score: FilterScore, S: int) -> list[str]:
    """The measured cells of one filter's row."""
    glob = "—" if score.localized is None else f"{int(score.localized.sum())}/{S}"
    return [
        f"{score.error.mean():.3f}",
        f"{100 * score.inside.mean():.0f}%",
        f"{int(score.found.sum())}/{S}",
        glob,
        f"{score.ms_per_step:.2f}",
    ]


def _seed_span(seeds: np.ndarray) -> str:
    """``0-19`` for a run of consecutive seeds, else the seeds themselves."""
    if len(seeds) > 1 and (np.diff(seeds) == 1).all():
        return f"{seeds[0]}-{seeds[-1]}"
    return ", ".join(str(s) for s in seeds)


def _score(name: str, drive, seeds, kidnapped: dict, global_start: dict | None, ms_per_step: float) -> FilterScore:
    """Run one filter over the seeds: a normal lap, a kidnapped lap and (unless None) a global start each.

    ``drive(seed, **settings)`` runs one lap.  The runs are measured one by one and not kept
    (a particle filter's lap keeps its whole cloud)."""
    error, inside, found, from_anywhere = [], [], [], []
    for seed in seeds:
        for settings, measure in (({}, None), (kidnapped, found), (global_start, from_anywhere)):
            if settings is None:
                continue
            run = drive(seed, **settings)
            if measure is None:
                error.append(run.error.mean())
                inside.append(run.share_inside)
            else:
                measure.append(localized(run))
    return FilterScore(
        name=name,
        error=np.array(error),
        inside=np.array(inside),
        found=np.array(found),
        localized=None if global_start is None else np.array(from_anywhere),
        ms_per_step=ms_per_step,
    )


def _seconds(run) -> float:
    """The wall time of one call of ``run()`` (s)."""
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def _kalman_ms(kind: str, seed: int) -> float:
    """A step of the EKF or UKF alone (ms): chapter 10's loop over this seed's world, nothing else."""
    world = loop_world(seed)
    M = np.diag([V_STD, OMEGA_STD]) ** 2  # honest noise, as landmark_loop's
    Q = np.diag([RANGE_STD, BEARING_STD]) ** 2
    predict, update = loop_filter(kind, world.dt, M, Q)
    return 1000.0 * _seconds(lambda: localize(world, predict, update, SIG0)) / len(world.t)


def _particle_ms(N: int, seed: int) -> float:
    """A step of the particle filter alone (ms): its lap on this seed less the simulation of the lap's world.

    What is left besides the filter's steps is the record (the cloud kept at every step, the NEES
    at the end), under 1 % of the lap."""
    lap = _seconds(lambda: particle_loop(seed, n_particles=N))
    world = _seconds(lambda: loop_world(seed))
    return 1000.0 * (lap - world) / len(loop_world(seed).t)


# particle_loop's settings that its run records as they were given (the map, the range and the start are the world's)
_PARTICLE_DEFAULTS = {
    name: p.default
    for name, p in inspect.signature(particle_loop).parameters.items()
    if name in ParticleRun.__dataclass_fields__ and name not in ("starts", "landmarks")
}


def _particle_lap(N: int, made: list):
    """``drive(seed, **settings)`` for :func:`_score`: the particle filter's lap with N particles, taken from
    ``made`` where one of those runs is that very lap, else run."""

    def drive(seed: int, **settings):
        lap = _PARTICLE_DEFAULTS | {"seed": seed, "n_particles": N} | settings
        for run in made:
            if all(getattr(run, name) == value for name, value in lap.items()) and _same_world(run, lap):
                return run
        return particle_loop(seed, n_particles=N, **settings)

    return drive


def _same_world(run, lap: dict) -> bool:
    """Whether ``run`` drove the world :func:`particle_loop` builds for ``lap``: the map, the readings, the start."""
    world = loop_world(lap["seed"], kidnap=lap["kidnap"])
    if lap["global_start"]:
        same_starts = run.starts is None
    else:  # the cloud started round the true start
        same_starts = run.starts is not None and np.array_equal(run.starts, world.start[None])
    arrays = ("landmarks", "z", "visible", "truth", "odometry")
    return same_starts and all(np.array_equal(getattr(run, name), getattr(world, name)) for name in arrays)


def family_table(seeds=range(20), particle_counts=(200, 2000), runs=()) -> FamilyTable:
    """Measure the EKF, the UKF and the particle filter side by side on chapter 10's loop.

    Over the same seeds and with honest noise, each filter drives per seed a normal lap
    (its mean error, and the share of steps with the truth inside its own 3σ ellipse); a
    lap with a kidnap at step :data:`KIDNAP` (the EKF and UKF gated at :data:`GATE`σ as in
    chapter 10, the particle filter injecting a share :data:`INJECTION` of random
    particles); and, the particle filter only, a lap from a start spread over the whole
    map (the EKF and UKF start at the true pose).  A lap that ends localized keeps its
    error under 0.5 m over its last quarter (:func:`~kfcourse.sim.localized`).
    The cost per step is the wall time of one step of the filter alone (the world's simulation
    and the record left out), timed over one more run of the first seed's normal lap; it is a figure of
    this machine, not a property of the filter.

    Laps of the particle filter already run, with the very settings a row needs (say earlier in a
    chapter), may be passed in ``runs``: each is used instead of running that lap again.

    Introduced in chapter 11.  Twenty seeds and two particle counts take about 25 s on a 2-core machine,
    less for each lap passed in ``runs``.

    Parameters
    ----------
    seeds : iterable of int
        The seeds (whole numbers >= 0, at least one), the same for every filter.
    particle_counts : iterable of int
        The particle filter's counts N (from 1 to :data:`~kfcourse.sim.particle_lap.MAX_PARTICLES`, at least one).
    runs : iterable of ParticleRun, optional
        Particle-filter laps already run (:func:`~kfcourse.sim.particle_loop`); a lap the table needs (the
        same seed, N, world and settings) is taken from them instead of being run again.

    Returns
    -------
    FamilyTable
    """
    seeds = [v.whole(seed, "seeds", 0) for seed in _listed(seeds, "seeds", "seeds")]
    counts = [v.whole(n, "particle_counts", 1) for n in _listed(particle_counts, "particle_counts", "counts")]
    if max(counts) > MAX_PARTICLES:
        raise ValueError(f"particle_counts must be whole numbers from 1 to {MAX_PARTICLES}, got {max(counts)}")
    if len(set(counts)) < len(counts):
        raise ValueError(f"particle_counts must be different counts, got {counts}")
    try:
        made = list(runs)
    except TypeError:
        made = [runs]
    for run in made:
        if not isinstance(run, ParticleRun):
            got = type(run).__name__
            raise ValueError(f"runs must be a list of kf.sim.particle_loop's runs (ParticleRun), got a {got}")
    scores = {}
    for kind in ("ekf", "ukf"):
        drive, ms = partial(landmark_loop, filter=kind), _kalman_ms(kind, seeds[0])
        scores[kind.upper()] = _score(kind.upper(), drive, seeds, {"kidnap": KIDNAP, "gate": GATE}, None, ms)
    for N in counts:
        drive, ms = _particle_lap(N, made), _particle_ms(N, seeds[0])
        kidnapped = {"kidnap": KIDNAP, "injection": INJECTION}
        scores[f"PF {N}"] = _score(f"PF {N}", drive, seeds, kidnapped, {"global_start": True}, ms)
    return FamilyTable(seeds=np.array(seeds), scores=scores, kidnap=KIDNAP, gate=GATE, injection=INJECTION)


def _listed(x, name: str, what: str) -> list:
    """``x`` as a non-empty list, or a ValueError naming ``name``."""
    try:
        items = list(x)
    except TypeError:
        raise ValueError(f"{name} must be a non-empty list of {what}, got {x!r}") from None
    if not items:
        raise ValueError(f"{name} must be a non-empty list of {what}, got {x!r}")
    return items
