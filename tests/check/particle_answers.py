"""Answers to chapter 11's exercise, systematic resampling, written the way a student might write
them, independently of the checker's own wrong versions: right answers in other forms than the
package's, one wrong answer (or more) per mistake of the checker's catalogue, and stratified
resampling, a right answer to another question.  ``tests/check/test_particle_check.py`` pairs
each wrong answer with the mistake the checker must name.
"""

from __future__ import annotations

import numpy as np


# ------------------------------------------------------------------ right
def resample_systematic(w, rng):
    """Vectorized: the positions, the cumulative sum made to end at 1, one search."""
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, positions, side="right")


def resample_walk(w, rng):
    """One walk along the cumulative sum of the weights divided by their sum, its last entry set to 1."""
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    cumulative_sum = np.cumsum(w / np.sum(w))
    cumulative_sum[-1] = 1.0
    indexes = np.zeros(N, dtype=int)
    i, j = 0, 0
    while i < N:
        if positions[i] < cumulative_sum[j]:
            indexes[i] = j
            i += 1
        else:
            j += 1
    return indexes


def resample_low_variance(w, rng):
    """The low-variance sampler: r ~ U[0, 1/N), one pointer, a guard at the last particle; a list of ints."""
    N = len(w)
    r = rng.uniform(0, 1 / N)
    c, i, out = w[0] / sum(w), 0, []
    for m in range(N):
        u = r + m / N
        while u >= c and i < N - 1:
            i += 1
            c += w[i] / sum(w)
        out.append(i)
    return out


def resample_digitize(w, rng):
    """np.digitize, an offset drawn as an array of one."""
    N = len(w)
    u = rng.random(size=1)
    c = np.cumsum(w)
    c = c / c[-1]
    return np.digitize(u / N + np.arange(N) / N, c)


# ------------------------------------------------------------------ another question
def resample_stratified(w, rng):
    """Stratified: a new offset for each position."""
    N = len(w)
    c = np.cumsum(w)
    c /= c[-1]
    out = []
    for i in range(N):
        p = (i + rng.random()) / N
        out.append(int(np.searchsorted(c, p, side="right")))
    return np.array(out)


# ------------------------------------------------------------------ wrong
def offset_not_divided(w, rng):
    N = len(w)
    positions = rng.random() + np.arange(N) / N  # wrong: U is not divided by N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, positions, side="right")


def offset_not_divided_walk(w, rng):
    N = len(w)
    positions = rng.uniform() + np.arange(N) / N  # wrong: U is not divided by N
    cumulative_sum = np.cumsum(w)
    cumulative_sum[-1] = 1.0
    indexes = np.zeros(N, dtype=int)
    i, j = 0, 0
    while i < N:
        if positions[i] < cumulative_sum[j]:  # runs past the end once a position is >= 1
            indexes[i] = j
            i += 1
        else:
            j += 1
    return indexes


def no_offset(w, rng):
    N = len(w)
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, np.arange(N) / N, side="right")  # wrong: no U


def offset_divided_twice(w, rng):
    N = len(w)
    u = rng.uniform(0, 1 / N)
    positions = (np.arange(N) + u) / N  # wrong: u is already in [0, 1/N)
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, positions, side="right")


def half_offset(w, rng):
    N = len(w)
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, (np.arange(N) + 0.5) / N, side="right")  # wrong: a fixed offset


def multinomial_choice(w, rng):
    return rng.choice(len(w), size=len(w), p=w)  # wrong: N independent draws


def multinomial_loop(w, rng):
    c = np.cumsum(w)
    c /= c[-1]
    return np.sort([np.searchsorted(c, rng.random(), side="right") for _ in w])  # wrong: N independent draws


def unnormalised_walk(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    cumulative_sum = np.cumsum(w)  # wrong: taken to end at 1
    indexes = np.zeros(N, dtype=int)
    i, j = 0, 0
    while i < N:
        if positions[i] < cumulative_sum[j]:
            indexes[i] = j
            i += 1
        else:
            j += 1
    return indexes


def unnormalised_search(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    return np.searchsorted(np.cumsum(w), positions, side="right")  # wrong: the sum taken to be 1


def cumsum_rounds(w, rng):
    N = len(w)
    w = w / np.sum(w)
    positions = (rng.random() + np.arange(N)) / N
    return np.searchsorted(np.cumsum(w), positions, side="right")  # wrong: the cumsum may end below 1


def cumsum_rounds_walk(w, rng):
    N = len(w)
    w = w / np.sum(w)
    positions = (np.arange(N) + rng.random()) / N
    cumulative_sum = np.cumsum(w)  # wrong: may end below 1
    indexes = []
    j = 0
    for p in positions:
        while p >= cumulative_sum[j]:
            j += 1
        indexes.append(j)
    return np.array(indexes)


def clipped_search(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    idx = np.searchsorted(np.cumsum(w), positions, side="right")
    return np.minimum(idx, N - 1)  # wrong: a position past the sum goes to the last particle, even of weight 0


def guarded_walk(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    c = np.cumsum(w)
    indexes = np.zeros(N, dtype=int)
    j = 0
    for i in range(N):
        while positions[i] >= c[j] and j < N - 1:  # wrong: the guard stops at the last particle, even of weight 0
            j += 1
        indexes[i] = j
    return indexes


def last_set_to_one(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    cumulative_sum = np.cumsum(w)
    cumulative_sum[-1] = 1.0  # wrong: the weights' shortfall goes to the last particle, even of weight 0
    indexes = np.zeros(N, dtype=int)
    i, j = 0, 0
    while i < N:
        if positions[i] < cumulative_sum[j]:
            indexes[i] = j
            i += 1
        else:
            j += 1
    return indexes


def left_side(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, positions)  # wrong: side="left"


def systematic_k_minus_u(w, rng):
    N = len(w)
    positions = (np.arange(1, N + 1) - rng.random()) / N  # (k - U)/N, k = 1 .. N: the offset 1 - U
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, np.minimum(positions, np.nextafter(1.0, 0.0)), side="right")


def systematic_k_minus_u_walk(w, rng):
    N = len(w)
    positions = (np.arange(1, N + 1) - rng.random()) / N  # (k - U)/N: at U = 0 the last one is exactly 1
    c = np.cumsum(w)
    c /= c[-1]
    indexes, j = np.zeros(N, dtype=int), 0
    for i in range(N):
        while c[j] < positions[i]:  # the slices (c_(j-1), c_j]: a position of 1 lands in the last slice
            j += 1
        indexes[i] = j
    return indexes


def systematic_k_minus_u_floats(w, rng):
    return systematic_k_minus_u(w, rng).astype(float)  # wrong: float indices


def left_side_walk(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    c = np.cumsum(w)
    c /= c[-1]
    indexes = np.zeros(N, dtype=int)
    j = 0
    for i in range(N):
        while positions[i] > c[j]:  # wrong: stays on a particle whose c_j equals the position
            j += 1
        indexes[i] = j
    return indexes


def returns_weights(w, rng):
    idx = resample_systematic(w, rng)
    return w[idx]  # wrong: the weights, not the indices


def returns_new_weights(w, rng):
    resample_systematic(w, rng)
    return np.ones(len(w)) / len(w)  # wrong: the new weights, not the indices


def returns_counts(w, rng):
    return np.bincount(resample_systematic(w, rng), minlength=len(w))  # wrong: counts


def keeps_old_weights(w, rng):
    idx = resample_systematic(w, rng)
    return idx, w[idx]  # wrong: the weights are not reset to 1/N


def returns_new_weights_too(w, rng):
    idx = resample_systematic(w, rng)
    return idx, np.full(len(w), 1 / len(w))  # wrong: only the indices are asked for


def float_indices(w, rng):
    N = len(w)
    positions = (rng.random() + np.arange(N)) / N
    c = np.cumsum(w)
    c /= c[-1]
    indexes = np.zeros(N)  # wrong: floats
    j = 0
    for i in range(N):
        while positions[i] >= c[j]:
            j += 1
        indexes[i] = j
    return indexes
