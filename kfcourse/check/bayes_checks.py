"""Checkers for chapter 1: the two steps of the Bayes filter."""

from __future__ import annotations

import numpy as np

from .. import filters
from ._core import Case, CheckResult, Probe, Step, Variant, run_check, sums_to_one

HALLWAY = np.array([0.5, 0.3, 0.2])  # the chapter's prior over cells A, B, C
MOVE_RIGHT = {1: 0.8, 0: 0.2}  # one cell right, or stall
DOOR = np.array([0.1, 0.6, 0.3])  # p(z = "door" | x) for A, B, C


def _random_belief(rng, n: int) -> np.ndarray:
    return rng.dirichlet(np.ones(n))


def _random_kernel(rng) -> dict[int, float]:
    offsets = rng.choice([-2, -1, 0, 1, 2], size=rng.integers(1, 4), replace=False)
    return {int(k): float(p) for k, p in zip(offsets, rng.dirichlet(np.ones(offsets.size)), strict=True)}


def _normalised(p) -> np.ndarray:
    return np.asarray(p) / np.sum(p)


# ------------------------------------------------------------------ bayes_predict
def _predict_with(belief, kernel, boundary, *, sign=1, ends=None, keep_at_wall=True, at_wall="end", overwrite=False):
    """The predict sum with a knob for each mistake: sign of the move, which ends, what a wall does,
    whether a contribution adds to its cell or overwrites it."""
    belief = np.asarray(belief, dtype=float)
    n = belief.size
    bel_bar = np.zeros(n)
    for start in range(n):
        for offset, p in kernel.items():
            end = start + sign * offset
            if (ends or boundary) == "wrap":
                end = end % n
            elif not 0 <= end < n and not keep_at_wall:
                continue  # the mass that hits the wall is lost
            elif not 0 <= end < n and at_wall == "start":
                end = start  # the move fails and the robot stays where it was
            else:
                end = min(max(end, 0), n - 1)
            bel_bar[end] = p * belief[start] + (0.0 if overwrite else bel_bar[end])
    return bel_bar


# A kernel that never moves leaves the belief as it is; one that always moves one cell is the shift alone,
# without the mixing of several offsets.
PREDICT_STEPS = (
    Step("the kernel {0: 1} (the robot never moves)", "the belief unchanged", lambda i: {**i, "kernel": {0: 1.0}}),
    *(
        Step(
            f"the kernel {{{k}: 1}} (always one cell {way})",
            f"the belief moved one cell {way}, nothing mixed",
            lambda i, k=k: {**i, "kernel": {k: 1.0}},
        )
        for k, way in ((1, "right"), (-1, "left"))
    ),
)
# The boundary switched alone (run_check's diagnosis): it changes only what happens at the ends.
PREDICT_PROBES = (
    Probe(
        "boundary",
        lambda b: "wrap" if b == "wall" else "wall",
        'the ends alone: at a wall ("wall") a move past the end stops in the end cell; on a ring ("wrap") cell n − 1 '
        "leads to cell 0",
    ),
)
# A likelihood equal in every cell multiplies every cell alike, and η undoes it.
UPDATE_STEPS = (
    Step(
        "a likelihood of 0.5 in every cell",
        "the belief unchanged (η undoes the common factor)",
        lambda i: {**i, "likelihood": np.full(np.shape(i["likelihood"]), 0.5)},
    ),
)

PREDICT_WHERE = (
    "chapter 1, the predict step: bel̄(x_t) = Σ p(x_t | u_t, x_{t−1}) bel(x_{t−1}), a sum over every start cell"
)


def bayes_predict(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``bayes_predict(belief, kernel, boundary)`` against :func:`kfcourse.bayes_predict`.

    Introduced in chapter 1.

    Parameters
    ----------
    student_fn : callable ``(belief (n,), kernel dict offset -> probability, boundary "wall" or "wrap") -> (n,)``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    cases = [
        Case("chapter 1's worked example: the hallway, wall", belief=HALLWAY, kernel=MOVE_RIGHT, boundary="wall"),
        Case("chapter 1's worked example: the hallway, ring", belief=HALLWAY, kernel=MOVE_RIGHT, boundary="wrap"),
        Case("moving left: wall", belief=HALLWAY, kernel={-1: 0.7, 0: 0.3}, boundary="wall"),
        Case("n = 1: wall", belief=np.array([1.0]), kernel=MOVE_RIGHT, boundary="wall"),
        Case("n = 1: ring", belief=np.array([1.0]), kernel=MOVE_RIGHT, boundary="wrap"),
    ]
    for boundary in ("wall", "wrap") * 6:
        n = int(rng.integers(2, 10))
        belief, kernel = _random_belief(rng, n), _random_kernel(rng)
        cases.append(Case(f"random: n = {n}, {boundary}", belief=belief, kernel=kernel, boundary=boundary))
    SHIFT = "An offset k moves probability from cell i to cell i + k: the kernel {1: 0.8, 0: 0.2} moves it right."
    BOUNDARY = 'With boundary "wall" the robot stops in the end cell; with "wrap" cell n − 1 leads to cell 0.'
    WALL = "At a wall the robot stays in the end cell, so no probability leaves the hallway (the sum stays 1)."
    RENORMALISED = (
        "Normalising afterwards spreads the lost probability over every cell; at a wall it belongs in the end cell."
    )
    STOPS = "A move that would pass a wall stops in the end cell (as far as the robot gets), not where it started."
    ADDS = "Several start cells can lead to the same end cell: add each contribution (+=), do not overwrite it."
    variants = [
        Variant("shift_wrong_way", lambda b, k, e: _predict_with(b, k, e, sign=-1), SHIFT),
        Variant("ignores_boundary", lambda b, k, e: _predict_with(b, k, e, ends="wall"), BOUNDARY),
        Variant("ignores_boundary", lambda b, k, e: _predict_with(b, k, e, ends="wrap"), BOUNDARY),
        Variant("leaks_at_wall", lambda b, k, e: _predict_with(b, k, e, keep_at_wall=False), WALL),
        Variant("leaks_at_wall", lambda b, k, e: _normalised(_predict_with(b, k, e, keep_at_wall=False)), RENORMALISED),
        Variant("wall_sends_back", lambda b, k, e: _predict_with(b, k, e, at_wall="start"), STOPS),
        Variant("overwrites_not_adds", lambda b, k, e: _predict_with(b, k, e, overwrite=True), ADDS),
    ]
    return run_check(
        "bayes_predict",
        student_fn,
        filters.bayes_predict,
        cases,
        variants,
        ("bel_bar",),
        PREDICT_WHERE,
        steps=PREDICT_STEPS,
        probes=PREDICT_PROBES,
        invariants=(sums_to_one("bel_bar", "a move carries probability from cell to cell, and makes or loses none"),),
    )


# ------------------------------------------------------------------- bayes_update
UPDATE_WHERE = "chapter 1, the update step: bel(x_t) = η p(z_t | x_t) bel̄(x_t), η = 1 / Σ_x p(z_t | x) bel̄(x)"


def bayes_update(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``bayes_update(belief, likelihood)`` against :func:`kfcourse.bayes_update`.

    Introduced in chapter 1.

    Parameters
    ----------
    student_fn : callable ``(belief (n,), likelihood (n,)) -> (n,)``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    bel_bar = filters.bayes_predict(HALLWAY, MOVE_RIGHT)
    cases = [
        Case("chapter 1's worked example: the door reading", belief=bel_bar, likelihood=DOOR),
        Case("n = 1", belief=np.array([1.0]), likelihood=np.array([0.3])),
        Case("a likelihood that is zero in some cells", belief=np.full(4, 0.25), likelihood=np.array([0, 0.5, 0, 0.1])),
        Case("a likelihood that sums to more than 1", belief=HALLWAY, likelihood=np.array([0.9, 0.8, 0.7])),
    ]
    for _ in range(10):
        n = int(rng.integers(2, 12))
        cases.append(Case(f"random: n = {n}", belief=_random_belief(rng, n), likelihood=rng.uniform(0.01, 1.0, n)))
    variants = [
        Variant("not_normalised", lambda b, lik: np.asarray(lik) * b, "Divide the products by their sum (that is η)."),
        Variant(
            "not_normalised",
            lambda b, lik: np.asarray(lik) / np.sum(lik) * b,
            "Normalise the product p(z | x) bel̄(x), not the likelihood alone: the result must sum to 1.",
        ),
        Variant(
            "not_normalised",
            lambda b, lik: np.asarray(lik) * b / np.max(np.asarray(lik) * b),
            "η makes the cells sum to 1: divide by the sum of the products, not by the largest.",
        ),
        Variant(
            "adds_not_multiplies",
            lambda b, lik: _normalised(np.asarray(lik) + b),
            "Bayes' rule multiplies: bel(x) = η p(z | x) bel̄(x), cell by cell.",
        ),
    ]
    return run_check(
        "bayes_update",
        student_fn,
        filters.bayes_update,
        cases,
        variants,
        ("bel",),
        UPDATE_WHERE,
        steps=UPDATE_STEPS,
        invariants=(sums_to_one("bel", "η = 1 / Σ p(z | x) bel̄(x) makes it"),),
    )
