"""The discrete Bayes filter, ``bayes_predict`` and ``bayes_update`` (chapter 1): the
hallway's worked numbers, probability conserved and the update proportional to
likelihood times belief, and the bad input it refuses.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import kfcourse as kf
from tests.filters.strategies import (
    FAST,
    INF,
    NAN,
    assert_raises_naming,
    assert_unique_ids,
    bad_input_cases,
    kernels,
    probability_vectors,
    r3,
    reals,
)

# ================================================================ worked numbers (chapter 1)
HALLWAY_PRIOR = [0.5, 0.3, 0.2]
MOVE_RIGHT = {1: 0.8, 0: 0.2}  # 80 % one cell right, 20 % stall
DOOR_LIKELIHOOD = [0.1, 0.6, 0.3]


def test_ch1_hallway_predict_with_wall():
    bel_bar = kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT, boundary="wall")
    # A: only the stalled 20 % of 0.5; B: 0.8*0.5 + 0.2*0.3; C: 0.8*0.3 + all of 0.2 (wall)
    np.testing.assert_allclose(bel_bar, [0.10, 0.46, 0.44], rtol=0, atol=1e-12)


def test_ch1_hallway_predict_default_boundary_is_wall():
    np.testing.assert_allclose(kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT), [0.10, 0.46, 0.44], atol=1e-12)


def test_ch1_hallway_predict_with_wrap_differs_from_wall():
    # On a ring the 0.8 * 0.2 leaving C re-enters at A.
    np.testing.assert_allclose(
        kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT, boundary="wrap"), [0.26, 0.46, 0.28], atol=1e-12
    )


def test_ch1_hallway_update_eta_and_posterior():
    bel_bar = kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT, boundary="wall")
    bel, eta = kf.bayes_update(bel_bar, DOOR_LIKELIHOOD, return_eta=True)
    assert eta == pytest.approx(1 / 0.418, rel=1e-12)  # 0.1*0.10 + 0.6*0.46 + 0.3*0.44 = 0.418
    assert [r3(p) for p in bel] == [0.024, 0.660, 0.316]
    np.testing.assert_allclose(bel, np.array([0.010, 0.276, 0.132]) / 0.418, rtol=1e-12)
    assert bel.sum() == pytest.approx(1.0, abs=1e-12)


def test_ch1_update_without_eta_returns_the_same_posterior():
    bel = kf.bayes_update([0.10, 0.46, 0.44], DOOR_LIKELIHOOD)
    np.testing.assert_allclose(bel, np.array([0.010, 0.276, 0.132]) / 0.418, rtol=1e-12)


# ================================================================ closed forms
# none beyond the worked numbers: the chapter's hallway is itself computed by hand


# ================================================================ properties
def reference_predict(bel, kernel, boundary):
    """Plain loops, one source cell at a time."""
    n = len(bel)
    out = [0.0] * n
    for i, b in enumerate(bel):
        for off, p in kernel.items():
            j = (i + off) % n if boundary == "wrap" else min(max(i + off, 0), n - 1)
            out[j] += p * b
    return np.array(out)


@settings(max_examples=100, deadline=None)
@given(bel=probability_vectors(), kernel=kernels(), boundary=st.sampled_from(["wall", "wrap"]))
def test_bayes_predict_conserves_probability(bel, kernel, boundary):
    out = kf.bayes_predict(bel, kernel, boundary=boundary)
    assert out.shape == bel.shape
    assert np.all(out >= 0)
    assert out.sum() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(out, reference_predict(bel, kernel, boundary), atol=1e-12)


@FAST
@given(bel=probability_vectors(2, 20), data=st.data())
def test_bayes_update_normalises_and_is_proportional(bel, data):
    lik = np.array(data.draw(st.lists(reals(0.0, 5.0), min_size=bel.size, max_size=bel.size)))
    assume((lik * bel).sum() > 1e-6)
    post, eta = kf.bayes_update(bel, lik, return_eta=True)
    assert post.sum() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(post, eta * lik * bel, rtol=1e-12, atol=1e-15)
    assert eta == pytest.approx(1.0 / (lik * bel).sum(), rel=1e-12)


# ================================================================ bad input
BAD_INPUT = [
    ("bayes_predict/belief 2-D", lambda: kf.bayes_predict([[0.5, 0.5]], {0: 1.0}), "belief"),
    ("bayes_predict/belief NaN", lambda: kf.bayes_predict([NAN, 1.0], {0: 1.0}), "belief"),
    ("bayes_predict/belief inf", lambda: kf.bayes_predict([INF, 0.0], {0: 1.0}), "belief"),
    ("bayes_predict/belief sums to 0.9", lambda: kf.bayes_predict([0.5, 0.4], {0: 1.0}), "belief"),
    ("bayes_predict/belief negative", lambda: kf.bayes_predict([1.5, -0.5], {0: 1.0}), "belief"),
    ("bayes_predict/belief empty", lambda: kf.bayes_predict([], {0: 1.0}), "belief"),
    ("bayes_predict/kernel sums to 0.5", lambda: kf.bayes_predict([0.5, 0.5], {1: 0.5}), "kernel"),
    ("bayes_predict/kernel sums to 1.2", lambda: kf.bayes_predict([0.5, 0.5], {1: 0.8, 0: 0.4}), "kernel"),
    ("bayes_predict/kernel negative", lambda: kf.bayes_predict([0.5, 0.5], {1: 1.2, 0: -0.2}), "kernel"),
    ("bayes_predict/kernel NaN", lambda: kf.bayes_predict([0.5, 0.5], {1: NAN}), "kernel"),
    ("bayes_predict/kernel not a mapping", lambda: kf.bayes_predict([0.5, 0.5], [0.8, 0.2]), "kernel"),
    ("bayes_predict/kernel empty", lambda: kf.bayes_predict([0.5, 0.5], {}), "kernel"),
    ("bayes_predict/kernel half-cell offset", lambda: kf.bayes_predict([0.5, 0.5], {0.5: 1.0}), "kernel"),
    ("bayes_predict/boundary unknown", lambda: kf.bayes_predict([0.5, 0.5], {0: 1.0}, boundary="bounce"), "boundary"),
    ("bayes_predict/boundary wrong case", lambda: kf.bayes_predict([0.5, 0.5], {0: 1.0}, boundary="Wall"), "boundary"),
    ("bayes_update/likelihood negative", lambda: kf.bayes_update([0.5, 0.5], [0.5, -0.1]), "likelihood"),
    ("bayes_update/likelihood wrong length", lambda: kf.bayes_update([0.5, 0.5], [0.5, 0.1, 0.2]), "likelihood"),
    ("bayes_update/likelihood NaN", lambda: kf.bayes_update([0.5, 0.5], [NAN, 0.1]), "likelihood"),
    ("bayes_update/likelihood inf", lambda: kf.bayes_update([0.5, 0.5], [INF, 0.1]), "likelihood"),
    ("bayes_update/likelihood impossible", lambda: kf.bayes_update([1.0, 0.0], [0.0, 1.0]), "likelihood"),
    ("bayes_update/belief sums to 1.1", lambda: kf.bayes_update([0.6, 0.5], [0.5, 0.5]), "belief"),
    ("bayes_update/belief negative", lambda: kf.bayes_update([1.1, -0.1], [0.5, 0.5]), "belief"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.bayes_predict([0.5, 0.5], {0: 1.0})
    kf.bayes_update([0.5, 0.5], [0.5, 0.5])


@pytest.mark.parametrize("kernel", [{"a": 1.0}, {None: 1.0}, {1: 1.5, 0: -0.5}], ids=["text", "none", "negative"])
def test_bad_kernel_is_named(kernel):
    with pytest.raises(ValueError, match=r"^kernel"):
        kf.bayes_predict([0.5, 0.5], kernel)
