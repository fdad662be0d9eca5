"""Speed of kf_step_batch against a loop of kf_step.

Run by hand (not part of the test suite):

    .venv/bin/python benchmarks/bench_batch.py

Targets: 300 tracks x 100 steps in one pass of kf_step_batch < 1 s, and the cost
per filter-step <= 0.15 x the cost of calling kf_step once per track and step.
"""

from __future__ import annotations

import time

import numpy as np

import kfcourse as kf
from kfcourse.sim.target import filter_tracks, simulate_tracks

N_TRACKS = 300
N_STEPS = 100
LOOP_TRACKS = 30  # the loop of kf_step is timed on fewer tracks, then scaled per filter-step
REPEATS = 5
PASS_TARGET = 1.0  # s
RATIO_TARGET = 0.15


def batch_pass(batch) -> float:
    t0 = time.perf_counter()
    filter_tracks(batch, batch.R, batch.Q)  # kf_step_batch once per step, all tracks at once
    return time.perf_counter() - t0


def loop_pass(batch, n_tracks: int) -> float:
    F, H = kf.models.constant_velocity(batch.dt, dim=2)
    R, Q = batch.R, batch.Q
    Sig0 = np.diag([Q[0, 0], Q[1, 1], 4.0, 4.0])
    t0 = time.perf_counter()
    for i in range(n_tracks):
        mu, Sig = np.array([*batch.z[i, 0], 0.0, 0.0]), Sig0
        for k in range(1, batch.z.shape[1]):
            mu, Sig = kf.kf_step(mu, Sig, None, batch.z[i, k], F, None, H, R, Q)
    return time.perf_counter() - t0


def main() -> None:
    batch = simulate_tracks(N_TRACKS, N_STEPS, seed=0)
    steps = N_STEPS - 1
    t_batch = float(np.median([batch_pass(batch) for _ in range(REPEATS)]))
    t_loop = float(np.median([loop_pass(batch, LOOP_TRACKS) for _ in range(REPEATS)]))
    per_batch = t_batch / (N_TRACKS * steps)
    per_loop = t_loop / (LOOP_TRACKS * steps)
    ratio = per_batch / per_loop
    print(
        f"kf_step_batch: {N_TRACKS} tracks x {N_STEPS} steps in {1e3 * t_batch:.0f} ms (target < {PASS_TARGET:.0f} s)"
    )
    print(f"per filter-step: batch {1e6 * per_batch:.2f} us, loop of kf_step {1e6 * per_loop:.2f} us")
    print(f"ratio {ratio:.3f} (target <= {RATIO_TARGET})")
    verdict = "met" if t_batch < PASS_TARGET and ratio <= RATIO_TARGET else "NOT met"
    print(f"targets: {verdict}")


if __name__ == "__main__":
    main()
