"""Time of one particle filter step on chapter 10's map (chapter 11).

Run by hand from the repository root (it is not a pytest test)::

    .venv/bin/python benchmarks/bench_particle.py [N]   (default: 2000 particles)

One step is what a run of the particle filter does at every time step: move the cloud with the
odometry (``pf_predict``), weigh it by two readings (``pf_weight``), normalise the weights, draw
the new cloud by systematic resampling and index the particles with it.  The same step is then
timed with the two readings unlabelled (``pf_weight(..., labelled=False)``): each reading weighed
against every landmark of the 7-landmark map, equation (3').  The cloud sits around
the robot's true pose at a step of the capstone's lap where it reads two landmarks, with the
capstone's noise.  Every run starts from the same cloud; the median and the 95th percentile over
:data:`RUNS` runs are printed, then each part's median.  Target (issue 24): a step of 2000
particles with 2 readings in at most 1 ms.  On a shared machine the p95 says how far to trust
the median.
"""

from __future__ import annotations

import time

import numpy as np

import kfcourse as kf
from kfcourse.sim.capstone_world import BEARING_STD, OMEGA_STD, RANGE_STD, V_STD

RUNS = 200  # timed steps
WARM_UP = 20  # untimed steps first
TARGET = 1.0  # ms, median of a step of 2000 particles and 2 readings
M = np.diag([V_STD, OMEGA_STD]) ** 2  # odometry noise
Q = np.diag([RANGE_STD, BEARING_STD]) ** 2  # reading noise


def setting(N: int, seed: int = 0):
    """A cloud of N particles around the true pose at the lap's first step with two readings."""
    world = kf.sim.loop_world(seed)
    k = int(np.flatnonzero(world.visible.sum(axis=1) == 2)[0])
    seen = world.visible[k]
    rng = np.random.default_rng(seed)
    particles = world.truth[k - 1] + rng.standard_normal((N, 3)) * [0.3, 0.3, 0.1]
    return particles, world.odometry[k], world.dt, world.z[k, seen], world.landmarks[seen], rng


def ms(f) -> float:
    t0 = time.perf_counter()
    f()
    return 1e3 * (time.perf_counter() - t0)


def main(N: int = 2000) -> None:
    particles, u, dt, z, landmarks, rng = setting(N)
    whole_map = np.asarray(kf.sim.DEFAULT_LANDMARKS)
    moved = kf.pf_predict(particles, u, dt, M, rng)
    log_w = kf.pf_weight(moved, z, landmarks, Q)
    w = kf.normalise(log_w)

    def step():
        x = kf.pf_predict(particles, u, dt, M, rng)
        weights = kf.normalise(kf.pf_weight(x, z, landmarks, Q))
        return x[kf.resample_systematic(weights, rng)]

    def unlabelled_step():
        x = kf.pf_predict(particles, u, dt, M, rng)
        weights = kf.normalise(kf.pf_weight(x, z, whole_map, Q, labelled=False))
        return x[kf.resample_systematic(weights, rng)]

    parts = {
        "pf_predict": lambda: kf.pf_predict(particles, u, dt, M, rng),
        "pf_weight (2 readings)": lambda: kf.pf_weight(moved, z, landmarks, Q),
        f"pf_weight unlabelled ({len(whole_map)} marks)": lambda: kf.pf_weight(moved, z, whole_map, Q, labelled=False),
        "normalise": lambda: kf.normalise(log_w),
        "resample_systematic + index": lambda: moved[kf.resample_systematic(w, rng)],
    }
    for _ in range(WARM_UP):
        step()
        unlabelled_step()
    times = np.array([ms(step) for _ in range(RUNS)])
    med, p95 = np.median(times), np.percentile(times, 95)
    times_unlabelled = np.array([ms(unlabelled_step) for _ in range(RUNS)])
    print(f"one particle filter step, N = {N} particles, {len(z)} readings, {RUNS} runs")
    print(f"{'':<34}{'median ms':>10}{'p95 ms':>9}")
    print(f"{'whole step':<34}{med:>10.3f}{p95:>9.3f}")
    unlabelled = np.median(times_unlabelled), np.percentile(times_unlabelled, 95)
    print(f"{'whole step, unlabelled readings':<34}{unlabelled[0]:>10.3f}{unlabelled[1]:>9.3f}")
    for name, f in parts.items():
        t = np.array([ms(f) for _ in range(RUNS)])
        print(f"{name:<34}{np.median(t):>10.3f}{np.percentile(t, 95):>9.3f}")
    if N == 2000:
        print(f"target (median <= {TARGET:.0f} ms for 2000 particles): {'met' if med <= TARGET else 'NOT met'}")


if __name__ == "__main__":
    import sys

    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)
