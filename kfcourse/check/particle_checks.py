"""Checker for chapter 11's exercise: your own systematic resampling.

Your ``resample_systematic(w, rng)`` draws one offset ``U`` from ``rng`` and returns the indices
of the particles at the N positions ``(i + U) / N``.  To compare it with the package's function
exactly, both are handed the same prepared generator (:class:`PreparedDraws`): its first uniform
draw is the case's ``U``, whichever way it is asked for.  ``rng.random()``, ``rng.random(1)``,
``rng.uniform()`` all give ``U``, and ``rng.uniform(0, 1 / N)`` gives ``U / N``, so every right way
of drawing the one offset lands on the same positions.  The draws after the first come from a
seeded stream, so a function that draws a new ``U_i`` for each position (stratified resampling)
or N independent positions (multinomial resampling) gets other draws, and is recognised as such.
"""

from __future__ import annotations

import numpy as np

from .. import filters
from ._core import MISTAKES, Case, CheckResult, Invariant, Variant, _block, _quietly, _same_outcome, run_check

WHERE = (
    "chapter 11, equation (6): one U ~ U[0, 1), positions p_i = (i + U)/N; cumulative sum c_i = w_0 + … + w_i "
    "with its last entry exactly 1 (c /= c[-1]); index i where c_(i−1) ≤ p < c_i (np.searchsorted(c, p, side='right'))"
)


class PreparedDraws(np.random.Generator):
    """A numpy Generator whose first uniform draws are given in advance; the rest come from ``seed``.

    ``random`` and ``uniform`` hand out ``first`` before the seeded stream: with ``first = [U]``,
    ``rng.random()`` is U, ``rng.uniform(0, 1/N)`` is U/N and ``rng.random(N)`` is U followed by
    N - 1 seeded draws.  A copy (every case hands each function a fresh copy) starts again from
    the first draw.
    """

    def __init__(self, first, seed: int):
        super().__init__(np.random.PCG64(seed))
        self.first, self.seed = tuple(float(u) for u in first), seed
        self._waiting = list(self.first)  # prepared draws not handed out yet

    def random(self, size=None, dtype=np.float64, out=None):
        size = out.shape if out is not None else size
        draws = np.array(super().random(size, dtype), ndmin=1)  # the seeded stream ...
        k = min(len(self._waiting), draws.size)
        draws.reshape(-1)[:k] = self._waiting[:k]  # ... with the prepared draws first
        del self._waiting[:k]
        if size is None:
            return float(draws[0])
        if out is not None:
            out[...] = draws
            return out
        return draws

    def uniform(self, low=0.0, high=1.0, size=None):
        if size is None:
            size = np.broadcast(np.asarray(low), np.asarray(high)).shape or None
        return low + np.subtract(high, low) * self.random(size)

    def __deepcopy__(self, memo):
        twin = type(self)(self.first, self.seed)
        twin.bit_generator.state = self.bit_generator.state
        twin._waiting = list(self._waiting)
        return twin

    def __repr__(self) -> str:
        many = f"first {len(self.first)} draws" if len(self.first) > 1 else "first draw"
        return f"Generator({many} U = {self.first[0]!r})"


def _resample_with(
    w, rng, *, offset="U", normalise=True, last_one=True, side="right", loop=False, clip=False, returns="indices"
):
    """Chapter 11's systematic resampling written out, with a knob for each mistake."""
    w = np.asarray(w, dtype=float)
    N = len(w)
    i = np.arange(N)
    if offset == "multinomial":
        p = rng.random(N)  # N independent positions
    else:
        U = rng.random()
        p = {"U": (i + U) / N, "none": i / N, "twice": (i + U / N) / N, "half": (i + 0.5) / N, "undivided": U + i / N}
        p = p[offset]
    c = np.cumsum(w / np.sum(w) if normalise else w)
    if last_one:
        c /= c[-1]
    if loop:  # one walk along c, as the textbooks write it: runs past the end if c ends below a position
        idx, j = np.zeros(N, dtype=int), 0
        for k in range(N):
            while p[k] >= c[j]:
                j += 1
            idx[k] = j
    else:
        idx = np.searchsorted(c, p, side=side)
    if clip:  # an index past the end sent back to the last particle, whatever its weight
        idx = np.minimum(idx, N - 1)
    if returns == "indices":
        return idx
    return {  # the right indices, handed back as something else
        "weights": w[idx],
        "new weights": np.full(N, 1.0 / N),
        "counts": np.bincount(idx, minlength=N),
        "indices and weights": (idx, w[idx]),
        "indices and new weights": (idx, np.full(N, 1.0 / N)),
    }[returns]


def _variants() -> list[Variant]:
    def with_(**knobs):
        return lambda w, rng: _resample_with(w, rng, **knobs)

    offset = "The positions are p_i = (i + U)/N with one U ~ U[0, 1) (rng.random()), so p_0 = U/N lies in [0, 1/N)."
    past_end = (
        "The cumulative sum must end at exactly 1: divide it by its last entry, c /= c[-1], "
        "or the last position may fall past it and its index run past the end."
    )
    unnormalised = (
        "Weights are normalised only to rounding (kf.resample_systematic accepts a sum within 1e-6 of 1), while the "
        "positions fill [0, 1): divide the cumulative sum by its last entry, c /= c[-1], so that it ends at exactly 1."
    )
    undivided = "U ~ U[0, 1) is divided by N too: p_i = (i + U)/N = U/N + i/N; added to i/N as it is, it runs past 1."
    indices = (
        "Return the indices of the particles drawn, one per new particle (the new cloud is particles[indices]); "
        "every new weight is 1/N, which the caller sets."
    )
    return [  # the first that reproduces an answer names it: a walk past the end raises the same IndexError
        Variant("cumsum_not_one", with_(last_one=False), "Dividing w by its sum is not enough. " + past_end),
        Variant("cumsum_not_one", with_(last_one=False, loop=True), "Dividing w by its sum is not enough. " + past_end),
        Variant("unnormalised_weights", with_(normalise=False, last_one=False), unnormalised),
        Variant("unnormalised_weights", with_(normalise=False, last_one=False, loop=True), unnormalised),
        Variant(
            "shortfall_to_last",
            with_(normalise=False, last_one=False, clip=True),  # as a guard j < N - 1 in the walk, or c[-1] = 1, does
            "Indices clipped at N − 1 instead of making the cumulative sum end at 1: a particle of weight 0 can be "
            "drawn. np.minimum(idx, N − 1), a guard j < N − 1 in the walk, or c[-1] = 1 on weights that sum to 1 only "
            "to 6 digits, hands every position past their sum to the last particle, whatever its weight. Divide the "
            "cumulative sum by its last entry, c /= c[-1]: it ends at exactly 1 and each particle keeps its share.",
        ),
        Variant("offset_not_divided", with_(offset="undivided"), undivided),
        Variant("offset_not_divided", with_(offset="undivided", loop=True), undivided),
        Variant(
            "no_offset",
            with_(offset="none"),
            offset + " Without it the positions never move: every run draws the same particles.",
        ),
        Variant(
            "no_offset",
            with_(offset="twice"),
            offset + " A u = rng.uniform(0, 1/N) is that offset already: add it to i/N, do not divide it by N again.",
        ),
        Variant(
            "fixed_offset",
            with_(offset="half"),
            offset + " A fixed ½ makes it deterministic, and a particle's count no longer matches N·w on average.",
        ),
        Variant(
            "multinomial",
            with_(offset="multinomial"),
            "Systematic resampling draws one U and spaces the N positions 1/N apart: p_i = (i + U)/N.",
        ),
        Variant(
            "multinomial",
            lambda w, rng: rng.choice(len(w), size=len(w), p=w),
            "rng.choice draws N independent particles; systematic resampling draws one U and spaces the N "
            "positions 1/N apart: p_i = (i + U)/N.",
        ),
        Variant(
            "multinomial",
            lambda w, rng: np.repeat(np.arange(len(w)), rng.multinomial(len(w), w)),
            "rng.multinomial draws N independent particles; systematic resampling draws one U and spaces the N "
            "positions 1/N apart: p_i = (i + U)/N.",
        ),
        Variant(
            "boundary_side",
            with_(side="left"),
            "U ~ U[0, 1) can be 0, and then the positions i/N fall on slice boundaries: with p_i in [i/N, (i+1)/N), "
            "the slices are [c_(i−1), c_i), closed on the left: np.searchsorted(c, p, side='right'), or in a loop "
            "move on while c[j] <= p. Otherwise, at U = 0, a particle of weight 0 is drawn.",
        ),
        Variant("weights_not_indices", with_(returns="weights"), indices),
        Variant("weights_not_indices", with_(returns="new weights"), indices),
        Variant(
            "counts_not_indices",
            with_(returns="counts"),
            indices + " A particle drawn k times appears k times: np.repeat(np.arange(N), counts) turns counts "
            "into indices.",
        ),
        Variant(
            "weights_not_reset",
            with_(returns="indices and weights"),
            "Return the indices alone. After resampling every weight is 1/N: the draws already carry the old "
            "weights (a heavy particle is drawn several times), so keeping w[indices] counts them twice.",
        ),
        Variant(
            "weights_returned_too",
            with_(returns="indices and new weights"),
            "Return the indices alone; the caller sets every new weight to 1/N.",
        ),
    ]


def _k_minus_u(w, rng):
    """Positions (k - U)/N, k = 1 .. N, each in the slice (c_(i-1), c_i]: systematic resampling from the other end,
    whose last position is exactly 1 when U = 0."""
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, (np.arange(1, len(w) + 1) - rng.random()) / len(w), side="left")


def _offset_one_minus_u(w, rng):
    """The package's systematic resampling with each prepared draw U replaced by 1 - U: positions (k - U)/N with
    the slices [c_(i-1), c_i), the last position kept below 1."""
    return filters.resample_systematic(w, PreparedDraws([1.0 - u for u in rng.first], rng.seed))


def _integers(result: CheckResult, student_fn, cases, who: str) -> CheckResult:
    """``result``, a pass, unless the indices come back as floats: ``particles[idx]`` needs integers."""
    got = _quietly(student_fn, cases[0])[1]
    if np.asarray(got).dtype.kind in "iu":
        return result
    headline = (
        f"✘ {who} is not right yet: on case 1 of {len(cases)} ({cases[0].label}), the indices are right "
        f"but they are {np.asarray(got).dtype} numbers, not integers."
    )
    return _verdict(headline, cases[0], got, "float_indices", _FLOATS)


def _cases(rng) -> list[Case]:
    def case(label, w, U, repeat=False):
        w = np.asarray(w, dtype=float)
        first = [U] * len(w) if repeat else [U]  # repeat: every position's draw is U (stratified too)
        return Case(label, w=w, rng=PreparedDraws(first, int(rng.integers(2**32))))

    rounds_low = [0.15, 0.15, 0.15, 0.08, 0.1, 0.11, 0.08, 0.18]  # np.cumsum ends at 0.9999999999999998
    cases = [
        case("chapter 11's example: w = [0.15, 0.2, 0.3, 0.2, 0.15], U = 0.9", [0.15, 0.2, 0.3, 0.2, 0.15], 0.9),
        case("equal weights: each particle once", [0.25, 0.25, 0.25, 0.25], 0.35),
        case("one particle holds all the weight", [0.0, 0.0, 1.0, 0.0, 0.0], 0.5),
        case("U = 0: the positions on slice boundaries, a first weight of 0", [0.0, 0.25, 0.25, 0.5], 0.0),
        case("one particle, N = 1", [1.0], 0.4),
        case(
            "weights that sum to 1 only to 6 digits: to 0.9999992, the last position past that",
            [0.1, 0.2, 0.3, 0.3999992],
            0.999999,
            repeat=True,
        ),
        case(
            "a cumulative sum that rounds below 1: to 0.9999999999999998, the last position at 0.9999999999999999",
            rounds_low,
            1 - 2.0**-50,  # (7 + U)/8 = 1 - 2^-53 exactly, however it is written
            repeat=True,
        ),
        case(
            "a last weight of 0, the sum short of 1: the last position past the sum, yet that particle never drawn",
            [0.5, 0.4999992, 0.0],
            0.999999,
            repeat=True,
        ),
    ]
    for N in [7, 40, 300, 2000]:  # clouds as the filter weighs them: a few heavy particles, some of weight 0
        log_w = -0.5 * (3.0 * rng.normal(size=N)) ** 2
        log_w[rng.random(N) < 0.2] = -np.inf
        log_w[int(rng.integers(N))] = 0.0  # at least one weight above 0
        cases.append(case(f"random: N = {N}", filters.normalise(log_w), float(rng.random())))
    return cases


def _sorted(expected, got):
    """The indices in ascending order: the new cloud is the same whatever order they come in."""
    a = np.asarray(got)
    return np.sort(a) if a.ndim == 1 and a.dtype.kind in "iuf" else got


_FLOATS = "Make them integers: np.zeros(N, dtype=int), or .astype(int) at the end (np.searchsorted gives integers)."
_OWN_RNG = (
    "Draw U from the rng your function is given, rng.random() or rng.uniform(0, 1/N), not from np.random (or a "
    "Generator of its own): the same rng must give the same particles."
)


def _verdict(headline: str, case: Case, got, mistake: str, advice: str) -> CheckResult:
    """A failure the comparison with the package cannot see: the case, what came back, the mistake."""
    details = "inputs:\n" + _block(list(case.inputs.items()), suppress_small=False) + f"\ngot:\n    {got!r}"
    hint = f"Likely mistake: {MISTAKES[mistake]}. {advice} See {WHERE}."
    return CheckResult(False, mistake, "\n".join([headline, details, hint]), headline, details, hint)


# N indices, each a particle's: 0 <= index < N.
INVARIANTS = (
    Invariant(
        lambda i, p: np.size(p["indices"]) == len(i["w"]),
        "your indices are not N in number: resampling draws as many particles as it is given",
    ),
    Invariant(
        lambda i, p: bool(np.all((np.asarray(p["indices"]) >= 0) & (np.asarray(p["indices"]) < len(i["w"])))),
        "your indices reach outside 0 … N − 1, and each must be a particle's",
    ),
)


def resample_systematic(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``resample_systematic(w, rng)`` against :func:`kfcourse.resample_systematic`.

    The cases: chapter 11's example (five weights, U = 0.9), then one case for each classic
    mistake (equal weights, one heavy particle, U = 0 with a weight of 0, N = 1, weights that sum
    to 1 only to 6 digits, a cumulative sum that rounds below 1, a last weight of 0 and a sum
    short of 1) and seeded clouds of 7 to 2 000 particles.  Each case hands your function and the
    package's the same prepared generator (:class:`PreparedDraws`), whose first uniform draw is
    the case's U however it is asked for.
    The indices are compared in ascending order (the new cloud does not depend on their order)
    and must be integers.  Positions (k - U)/N, k = 1 .. N (the offset drawn as 1 - U) pass.
    Stratified resampling (a new U_i for each position) is recognised and named: a right scheme,
    but not the one asked for.  Introduced in chapter 11.

    Parameters
    ----------
    student_fn : callable ``(w (N,), rng) -> indices (N,) of int``
        ``w``: weights >= 0 that sum to 1 (to within 1e-6); ``rng``: a numpy Generator.
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _cases(np.random.default_rng(seed))
    returns = ("indices",)
    result = run_check(
        "resample_systematic",
        student_fn,
        filters.resample_systematic,
        cases,
        _variants(),
        returns,
        WHERE,
        pair=_sorted,
        invariants=INVARIANTS,
    )
    who = getattr(student_fn, "__name__", "your function")
    if result.passed:
        return _integers(result, student_fn, cases, who)
    if not result.details:  # not written yet
        return result
    for number, case in enumerate(cases):  # the same rng twice: the same particles?
        once, again = _quietly(student_fn, case), _quietly(student_fn, case)
        if once[0] == again[0] == "returned" and not _same_outcome(once, again, returns):
            headline = (
                f"✘ {who} is not right yet: on case {number + 1} of {len(cases)} ({case.label}), it gives another "
                "answer each time it is called with the same rng."
            )
            return _verdict(headline, case, once[1], "ignores_rng", _OWN_RNG)
    for mirror in (_k_minus_u, _offset_one_minus_u):  # (k - U)/N, k = 1 .. N: systematic seen from the other end
        if run_check("resample_systematic", student_fn, mirror, cases, [], returns, "", pair=_sorted).passed:
            headline = (
                f"✔ {who} matches systematic resampling on all {len(cases)} cases with the positions (k − U)/N, "
                "k = 1 … N: evenly spaced with one offset for all, 1 − U instead of U, a right form of (6)."
            )
            return _integers(CheckResult(True, None, headline, headline), student_fn, cases, who)
    stratified = run_check("resample_stratified", student_fn, filters.resample_stratified, cases, [], returns, "")
    if stratified.passed:
        headline = (
            f"✘ {who} is not right yet: it is stratified resampling, a right scheme but not the one asked for "
            f"(it matches kf.resample_stratified on all {len(cases)} cases)."
        )
        hint = (
            f"Likely mistake: {MISTAKES['stratified_not_systematic']}. It draws a new U_i for each position, "
            "p_i = (i + U_i)/N. Systematic resampling draws one U for all, p_i = (i + U)/N: one random number, and "
            "each particle's count is ⌊N·w_i⌋ or ⌈N·w_i⌉ (a stratified count differs from N·w_i by less than 2). "
            f"See {WHERE}."
        )
        return CheckResult(False, "stratified_not_systematic", f"{headline}\n{hint}", headline, "", hint)
    return result
