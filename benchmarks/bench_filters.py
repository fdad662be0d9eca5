"""Per-step speed of kfcourse's filters next to filterpy's, and the import time.

Run by hand from the repository root (it is not a pytest test)::

    python benchmarks/bench_filters.py

It needs the ``dev`` extra (filterpy).  Three filters are timed on the same
problems in both libraries -- the linear Kalman filter on a 2-D constant-velocity
tracker, and the EKF and the UKF on a unicycle robot reading range and bearing to
one landmark, set up in ``benchmarks/filterpy_pairs.py`` (which the agreement test
``tests/filters/test_filterpy_agreement.py`` shares) -- after checking that both
libraries compute the same numbers.  Each row reports the median, over several
rounds, of the mean time of one predict + update step, and the range of the
kfcourse / filterpy ratio over the rounds (on a shared machine the spread says how
far to trust the median); a last row reports ``import kfcourse`` in a fresh interpreter.  kfcourse checks every
input on every call (finite, shapes, each covariance symmetric and positive
semi-definite); filterpy checks none.

Noise letters differ between the libraries: kfcourse's ``R`` (process) is
filterpy's ``Q``, and kfcourse's ``Q`` (measurement) is filterpy's ``R``.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from collections.abc import Callable

import numpy as np
from filterpy_pairs import (
    CONTROL,
    CV_MU0,
    CV_SIG0,
    SEED,
    UNI_MU0,
    UNI_SIG0,
    cv_readings,
    filterpy_ekf,
    filterpy_kf,
    filterpy_ukf,
    kfcourse_ekf_predict,
    kfcourse_ekf_update,
    kfcourse_kf_step,
    kfcourse_ukf_predict,
    kfcourse_ukf_update,
    unicycle_readings,
)

STEPS = 2_000  # filter steps per timed round
ROUNDS = 7  # timed rounds per library; the median round is reported
IMPORT_RUNS = 7  # fresh interpreters timed for `import kfcourse`
UKF_LAM = 3 - UNI_MU0.size  # kfcourse spread lam = 3 - n; filterpy's Julier kappa is the same number

UKF_TARGET = 0.5  # kfcourse / filterpy time ratio the UKF step must not exceed
IMPORT_TARGET = 0.3  # s, `import kfcourse` must take less than this


# ---------------------------------------------------------------- the timed runs
# Each factory returns ``run(zs) -> list of (mean, covariance)``, one pair per step,
# starting afresh from the initial belief.  The same functions are timed.
def kfcourse_kf() -> Callable:
    def run(zs):
        mu, Sig, out = CV_MU0, CV_SIG0, []
        for z in zs:
            mu, Sig = kfcourse_kf_step(mu, Sig, z)
            out.append((mu, Sig))
        return out

    return run


def filterpy_kf_run() -> Callable:
    def run(zs):
        f, out = filterpy_kf(), []
        for z in zs:
            f.predict()
            f.update(z)
            out.append((f.x, f.P))
        return out

    return run


def kfcourse_ekf() -> Callable:
    def run(zs):
        mu, Sig, out = UNI_MU0, UNI_SIG0, []
        for z in zs:
            mu, Sig = kfcourse_ekf_predict(mu, Sig)
            mu, Sig = kfcourse_ekf_update(mu, Sig, z)
            out.append((mu, Sig))
        return out

    return run


def filterpy_ekf_run() -> Callable:
    def run(zs):
        f, out = filterpy_ekf(), []
        for z in zs:
            f.predict(CONTROL)
            f.update(z)
            out.append((f.x, f.P))
        return out

    return run


def kfcourse_ukf() -> Callable:
    def run(zs):
        mu, Sig, out = UNI_MU0, UNI_SIG0, []
        for z in zs:
            mu, Sig = kfcourse_ukf_predict(mu, Sig, UKF_LAM)
            mu, Sig = kfcourse_ukf_update(mu, Sig, z, UKF_LAM)
            out.append((mu, Sig))
        return out

    return run


def filterpy_ukf_run() -> Callable:
    def run(zs):
        f, out = filterpy_ukf(UKF_LAM), []
        for z in zs:
            f.predict(u=CONTROL)
            f.update(z)
            out.append((f.x, f.P))
        return out

    return run


# ---------------------------------------------------------------- measuring
def agree(ours: list, theirs: list) -> bool:
    """Whether two runs give the same mean and covariance at every step."""
    return all(
        np.allclose(m1, m2, rtol=1e-7, atol=1e-9) and np.allclose(S1, S2, rtol=1e-7, atol=1e-9)
        for (m1, S1), (m2, S2) in zip(ours, theirs, strict=True)
    )


def per_step_us(runs: dict[str, Callable], zs: list) -> dict[str, list[float]]:
    """The mean µs per step of each of ROUNDS rounds; the libraries' rounds alternate."""
    times: dict[str, list[float]] = {name: [] for name in runs}
    for run in runs.values():
        run(zs[:50])  # warm up
    for _ in range(ROUNDS):
        for name, run in runs.items():
            t0 = time.perf_counter()
            run(zs)
            times[name].append((time.perf_counter() - t0) / len(zs) * 1e6)
    return times


def import_seconds() -> float:
    """Median time of `import kfcourse` measured inside fresh interpreters, s."""
    code = "import time; t = time.perf_counter(); import kfcourse; print(time.perf_counter() - t)"
    runs = [
        float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout)
        for _ in range(IMPORT_RUNS)
    ]
    return statistics.median(runs)


def main() -> None:
    rng = np.random.default_rng(SEED)
    problems = [
        ("kf_step (CV 4-state)", kfcourse_kf(), filterpy_kf_run(), cv_readings(rng, STEPS), None),
        ("EKF step (unicycle)", kfcourse_ekf(), filterpy_ekf_run(), unicycle_readings(rng, STEPS), None),
        ("UKF step (unicycle)", kfcourse_ukf(), filterpy_ukf_run(), unicycle_readings(rng, STEPS), UKF_TARGET),
    ]

    for name, ours, theirs, zs, _ in problems:
        if not agree(ours(zs), theirs(zs)):
            raise AssertionError(f"{name}: kfcourse and filterpy disagree")
    print(f"agree: yes (kfcourse and filterpy give the same mean and covariance at all {STEPS} steps)")
    print(f"numpy {np.__version__}, python {sys.version.split()[0]}; {ROUNDS} rounds of {STEPS} steps\n")

    header = f"{'step':<22} {'kfcourse µs':>12} {'filterpy µs':>12} {'ratio':>7} {'range':>11}  {'target':<9} met"
    print(header)
    print("-" * len(header))
    verdicts = []
    for name, ours, theirs, zs, target in problems:
        times = per_step_us({"kfcourse": ours, "filterpy": theirs}, zs)
        t = {lib: statistics.median(rounds) for lib, rounds in times.items()}
        ratio = t["kfcourse"] / t["filterpy"]
        per_round = [a / b for a, b in zip(times["kfcourse"], times["filterpy"], strict=True)]  # the spread
        spread = f"{min(per_round):.2f}-{max(per_round):.2f}"
        if target is None:
            want, met = "report", "-"
        else:
            ok = ratio <= target
            want, met = f"<= {target:.1f}", "yes" if ok else "NO"
            verdicts.append((name.split()[0], ok))
        print(f"{name:<22} {t['kfcourse']:>12.1f} {t['filterpy']:>12.1f} {ratio:>7.2f} {spread:>11}  {want:<9} {met}")

    secs = import_seconds()
    ok = secs < IMPORT_TARGET
    verdicts.append(("import", ok))
    want = f"< {IMPORT_TARGET} s"
    print(f"{'import kfcourse':<22} {secs:>11.3f}s {'':>12} {'':>7} {'':>11}  {want:<9} {'yes' if ok else 'NO':<4}")

    met = [n for n, ok in verdicts if ok]
    missed = [n for n, ok in verdicts if not ok]
    if missed:
        print(f"\ntargets: met {', '.join(met) or 'none'}; MISSED {', '.join(missed)}")
    else:
        print(f"\ntargets: all met ({', '.join(met)})")


if __name__ == "__main__":
    main()
