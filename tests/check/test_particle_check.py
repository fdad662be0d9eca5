"""Chapter 11's checker, systematic resampling: the package's answer passes, every mistake of the
catalogue is named, stratified resampling is recognised and not called wrong, and a function that
is not written yet, raises, returns NaN or the wrong shape gets a clear verdict.

The answers judged here are written the way a student might write them, in
``tests/check/particle_answers.py``.
"""

from __future__ import annotations

import ast
import copy

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.check import particle_checks as particle
from kfcourse.check._core import show
from tests.check import particle_answers as a

RIGHT = [a.resample_systematic, a.resample_walk, a.resample_low_variance, a.resample_digitize]

#: A student's wrong answer and the mistake the checker must name.
WRONG = [
    (a.offset_not_divided, "offset_not_divided"),
    (a.offset_not_divided_walk, "offset_not_divided"),
    (a.no_offset, "no_offset"),
    (a.offset_divided_twice, "no_offset"),
    (a.half_offset, "fixed_offset"),
    (a.multinomial_choice, "multinomial"),
    (a.multinomial_loop, "multinomial"),
    (kf.resample_multinomial, "multinomial"),
    (a.unnormalised_search, "unnormalised_weights"),
    (a.unnormalised_walk, "unnormalised_weights"),
    (a.clipped_search, "shortfall_to_last"),
    (a.guarded_walk, "shortfall_to_last"),
    (a.last_set_to_one, "shortfall_to_last"),
    (a.cumsum_rounds, "cumsum_not_one"),
    (a.cumsum_rounds_walk, "cumsum_not_one"),
    (a.left_side, "boundary_side"),
    (a.left_side_walk, "boundary_side"),
    (a.returns_weights, "weights_not_indices"),
    (a.returns_new_weights, "weights_not_indices"),
    (a.returns_counts, "counts_not_indices"),
    (a.keeps_old_weights, "weights_not_reset"),
    (a.returns_new_weights_too, "weights_returned_too"),
    (a.float_indices, "float_indices"),
]

#: The keys the MISTAKES block "chapter 11" adds.
NEW_KEYS = {
    "offset_not_divided",
    "no_offset",
    "fixed_offset",
    "multinomial",
    "unnormalised_weights",
    "shortfall_to_last",
    "cumsum_not_one",
    "boundary_side",
    "weights_not_indices",
    "counts_not_indices",
    "weights_not_reset",
    "weights_returned_too",
    "float_indices",
    "ignores_rng",
    "stratified_not_systematic",
}


def _ignores_rng(w, rng):
    N = len(w)
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, (np.arange(N) + np.random.default_rng().random()) / N, side="right")  # its own


def _not_yet(w, rng):
    raise NotImplementedError("your turn")


def test_the_checker_is_exported():
    assert "resample_systematic" in kf.check.__all__
    assert kf.check.resample_systematic is particle.resample_systematic


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_package_function_passes(seed):
    result = kf.check.resample_systematic(kf.resample_systematic, seed=seed)
    assert result.passed, result.message
    assert result.mistake is None and result.message.startswith("✔")


@pytest.mark.parametrize("fn", RIGHT, ids=[fn.__name__ for fn in RIGHT])
def test_a_right_answer_written_differently_passes(fn):
    result = kf.check.resample_systematic(fn)
    assert result.passed, result.message
    assert "stratified" not in result.message


@pytest.mark.parametrize(
    "draw",
    [
        lambda rng, N: rng.random(),
        lambda rng, N: rng.random(1),
        lambda rng, N: rng.random(size=(1,))[0],
        lambda rng, N: rng.uniform(),
        lambda rng, N: rng.uniform(0.0, 1.0, size=1),
        lambda rng, N: rng.uniform(0, 1 / N) * N,
        lambda rng, N: N * rng.uniform(high=1 / N),
    ],
)
def test_every_way_of_drawing_the_one_offset_passes(draw):
    def resample(w, rng):
        N = len(w)
        c = np.cumsum(w)
        c /= c[-1]
        return np.searchsorted(c, (np.arange(N) + draw(rng, N)) / N, side="right")

    result = kf.check.resample_systematic(resample)
    assert result.passed, result.message


def test_the_checker_opens_with_the_chapters_example():
    result = kf.check.resample_systematic(kf.resample_systematic)
    assert result.message.split(": ", 1)[1].startswith("chapter 11's example"), result.message
    first = particle._cases(np.random.default_rng(0))[0]
    np.testing.assert_array_equal(first.inputs["w"], [0.15, 0.2, 0.3, 0.2, 0.15])
    idx = first.call(kf.resample_systematic)
    np.testing.assert_array_equal(idx, [1, 2, 2, 3, 4])
    counts = np.bincount(idx, minlength=5)  # 0, 1, 2, 1, 1: each floor or ceil of N w = .75, 1, 1.5, 1, .75
    np.testing.assert_array_equal(counts, [0, 1, 2, 1, 1])
    assert (np.abs(counts - 5 * first.inputs["w"]) < 1).all()


@pytest.mark.parametrize(("fn", "mistake"), WRONG, ids=[f"{fn.__name__}-{m}" for fn, m in WRONG])
def test_a_known_mistake_is_named(fn, mistake):
    result = kf.check.resample_systematic(fn)
    assert not result.passed
    assert result.mistake == mistake, result.message
    assert result.message.startswith("✘")
    assert f"Likely mistake: {kf.check.MISTAKES[mistake]}" in result.message
    assert "inputs:" in result.message and "hapter 11" in result.hint


def test_every_new_catalogue_key_is_in_the_catalogue_and_exercised():
    assert NEW_KEYS <= set(kf.check.MISTAKES)
    assert NEW_KEYS - {"ignores_rng", "stratified_not_systematic"} == {mistake for _, mistake in WRONG}
    assert {v.mistake for v in particle._variants()} <= NEW_KEYS


def test_a_function_that_ignores_the_rng_is_told_to_use_it():
    result = kf.check.resample_systematic(_ignores_rng)
    assert not result.passed and result.mistake == "ignores_rng", result.message
    assert "np.random" in result.hint


# ------------------------------------------------------------ stratified: right, but not what is asked
@pytest.mark.parametrize("fn", [kf.resample_stratified, a.resample_stratified], ids=["package", "student"])
def test_stratified_resampling_is_named_and_does_not_pass(fn):
    result = kf.check.resample_systematic(fn)
    assert not result.passed and result.mistake == "stratified_not_systematic", result.message
    assert result.headline.startswith("✘") and "stratified resampling" in result.headline
    assert "one offset for all" in result.hint and "one U for all" in result.hint


@pytest.mark.parametrize("fn", [a.systematic_k_minus_u, a.systematic_k_minus_u_walk])
def test_positions_k_minus_u_over_n_are_systematic_resampling_and_pass(fn):
    """(k − U)/N for k = 1 … N is (i + U')/N with U' = 1 − U: one offset for all, as right as (i + U)/N, whether the
    last position is kept below 1 or lands in the last slice (c_(N−1), c_N]."""
    result = kf.check.resample_systematic(fn)
    assert result.passed and result.mistake is None, result.message
    assert "1 − U" in result.headline


def test_positions_k_minus_u_over_n_as_floats_are_named():
    result = kf.check.resample_systematic(a.systematic_k_minus_u_floats)
    assert not result.passed and result.mistake == "float_indices", result.message


# ------------------------------------------------------------ functions that misbehave
def test_not_yet_is_no_failure():
    result = kf.check.resample_systematic(_not_yet)
    assert result.passed is False and result.mistake is None and "Not yet" in result.message


@pytest.mark.parametrize(
    ("fn", "says"),
    [
        (lambda w, rng: np.full(len(w), np.nan), "indices contains NaN"),
        (lambda w, rng: kf.resample_systematic(w, rng)[1:], "indices has shape (4,); expected (5,)"),
        (lambda w, rng: None, "it returned None: is its return statement missing?"),
        (lambda w, rng: 1 / 0, "it raised ZeroDivisionError"),
    ],
)
def test_a_misbehaving_function_gets_a_clear_verdict(fn, says):
    result = kf.check.resample_systematic(fn)
    assert not result.passed and says in result.message, result.message
    assert "Traceback" not in result.message


def test_the_verdict_points_at_the_entries_that_differ():
    headline = kf.check.resample_systematic(a.left_side).headline
    assert "case 4 of" in headline and "indices has the wrong value at [0], [1] and [2]" in headline


def test_anything_but_a_function_is_refused_by_its_own_name():
    with pytest.raises(ValueError, match=r"kf.check.resample_systematic\(my_resample_systematic\)"):
        kf.check.resample_systematic(42)


def test_indices_in_another_order_pass():
    result = kf.check.resample_systematic(lambda w, rng: kf.resample_systematic(w, rng)[::-1])
    assert result.passed, result.message


# ------------------------------------------------------------ the prepared generator
def test_the_prepared_generator_gives_the_offset_however_it_is_asked_for():
    rng = particle.PreparedDraws([0.9], seed=3)
    assert isinstance(rng, np.random.Generator)
    assert copy.deepcopy(rng).random() == 0.9
    assert copy.deepcopy(rng).uniform() == 0.9
    assert copy.deepcopy(rng).uniform(0, 1 / 8) == 0.9 / 8
    np.testing.assert_array_equal(copy.deepcopy(rng).random(1), [0.9])
    many = copy.deepcopy(rng).random(4)  # U, then the seeded stream: a new draw for each position
    assert many[0] == 0.9 and len(set(many)) == 4
    stepwise = copy.deepcopy(rng)
    np.testing.assert_array_equal([stepwise.random() for _ in range(4)], many)
    used = copy.deepcopy(rng)
    used.random()
    assert copy.deepcopy(used).random() != 0.9 and copy.deepcopy(rng).random() == 0.9  # a copy restarts where it is


def test_each_case_does_what_its_label_says():
    cases = {c.label.split(":")[0]: c for c in particle._cases(np.random.default_rng(0))}
    # a first weight of 0 and U = 0: side="left" draws it, the package never does
    tie = cases["U = 0"]
    assert 0 not in tie.call(kf.resample_systematic)
    assert 0 in tie.call(lambda w, rng: np.searchsorted(np.cumsum(w), (np.arange(len(w)) + rng.random()) / len(w)))
    # weights that sum to 1 only to 6 digits: accepted by the package, the last position past their sum
    six = cases["weights that sum to 1 only to 6 digits"]
    w = six.inputs["w"]
    assert 0 < 1 - w.sum() <= 1e-6
    last = (len(w) - 1 + copy.deepcopy(six.inputs["rng"]).random()) / len(w)
    assert w.sum() < last < 1
    # a cumulative sum that rounds below 1, the last position between it and 1, however it is written
    low = cases["a cumulative sum that rounds below 1"]
    w, U = low.inputs["w"], copy.deepcopy(low.inputs["rng"]).random()
    N = len(w)
    assert abs(w.sum() - 1) < 1e-15
    for c in [np.cumsum(w), np.cumsum(w / np.sum(w))]:
        assert c[-1] == 0.9999999999999998
    for position in [(N - 1 + U) / N, U / N + (N - 1) / N, (N - 1) / N + U * (1 / N)]:
        assert position == 0.9999999999999999 == 1 - 2.0**-53
    assert low.call(kf.resample_systematic)[-1] == N - 1
    # a last weight of 0 and a sum short of 1: the last position past the sum, the particle of weight 0 never drawn
    zero = cases["a last weight of 0, the sum short of 1"]
    w = zero.inputs["w"]
    assert w[-1] == 0 and 0 < 1 - w.sum() <= 1e-6
    last = (len(w) - 1 + copy.deepcopy(zero.inputs["rng"]).random()) / len(w)
    assert w.sum() < last < 1
    assert len(w) - 1 not in zero.call(kf.resample_systematic)
    assert zero.call(a.clipped_search)[-1] == len(w) - 1


@pytest.mark.parametrize("label", ["weights that sum to 1 only to 6 digits", "a last weight of 0, the sum short of 1"])
def test_weights_short_of_1_look_short_of_1_as_printed(label):
    w = {c.label.split(":")[0]: c for c in particle._cases(np.random.default_rng(0))}[label].inputs["w"]
    printed = np.array(ast.literal_eval(show(w)))  # the inputs as the verdict prints them
    assert printed.sum() < 1 - 5e-7, show(w)


def test_a_clipped_index_is_named_as_such():
    hint = kf.check.resample_systematic(a.clipped_search).hint
    assert (
        "Indices clipped at N − 1 instead of making the cumulative sum end at 1: a particle of weight 0 can be drawn"
        in hint
    )
