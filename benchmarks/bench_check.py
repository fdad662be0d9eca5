"""Time every exercise checker: a verdict must be on screen in well under a second.

Run by hand (not part of the test suite):

    .venv/bin/python benchmarks/bench_check.py

Each checker is timed on three functions: the package's own (it passes, so every
case runs), a stub that raises NotImplementedError (the "not yet" verdict) and a
function that is right on every case but the last, where it returns something no
known mistake explains (so every case runs and then every wrong variant is tried
as well: the slowest verdict there is).  The first call of each checker is
reported apart (it pays for the first use of its code), then the slowest of
several more rounds.  Target: every check under 1 s.
"""

from __future__ import annotations

import time

import kfcourse as kf
from kfcourse.check.exercises import _cv_reference

CHECKERS = [name for name in kf.check.__all__ if name not in ("MISTAKES", "CheckResult")]
REFERENCES = {  # the package's function each checker compares with, where it is not kf.<checker>
    "cv_model": _cv_reference,
    "drift_sigma": kf.sim.drift_sigma,
    "localization_step": kf.ekf_localization_step,
}


def reference_of(name: str):
    return REFERENCES.get(name) or getattr(kf, name)


ROUNDS = 5  # timed rounds after the first call
TARGET = 1000.0  # ms


def stub(*args):
    raise NotImplementedError("your turn")


def right_until_the_last_case(name: str):
    """The package's function, except that on the checker's last case it returns the wrong thing.

    The last case is told by its inputs (their repr), so the function answers every call on it alike: the
    checker's first pass over its cases is the calls of a passing run up to the first inputs seen twice."""
    reference = reference_of(name)
    seen = []

    def record(*args):
        seen.append(repr(args))
        return reference(*args)

    getattr(kf.check, name)(record)
    first_pass = seen[: next((i for i, r in enumerate(seen) if r in seen[:i]), len(seen))]
    last = first_pass[-1]

    def late(*args):
        return "wrong" if repr(args) == last else reference(*args)

    return lambda: late


def timed(check, make_fn) -> float:
    fn = make_fn()
    t0 = time.perf_counter()
    check(fn)
    return 1e3 * (time.perf_counter() - t0)


def main() -> None:
    print(f"{'checker':<24}{'first ms':>9}{'pass ms':>9}{'stub ms':>9}{'late fail ms':>14}")
    worst = 0.0
    for name in CHECKERS:
        check = getattr(kf.check, name)
        first = timed(check, lambda n=name: reference_of(n))
        late = right_until_the_last_case(name)
        row = [
            max(timed(check, make) for _ in range(ROUNDS))
            for make in (lambda n=name: reference_of(n), lambda: stub, late)
        ]
        result = check(late())
        assert not result.passed and result.mistake is None, result.message  # the slow path really ran
        worst = max(worst, first, *row)
        print(f"{name:<24}{first:>9.1f}{row[0]:>9.1f}{row[1]:>9.1f}{row[2]:>14.1f}")
    verdict = "met" if worst < TARGET else "NOT met"
    print(f"slowest check {worst:.1f} ms; target (every check < {TARGET:.0f} ms): {verdict}")


if __name__ == "__main__":
    main()
