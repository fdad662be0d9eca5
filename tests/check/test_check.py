"""The exercise checkers: the package's own functions pass, each known mistake is named,
and a function that raises, returns NaN or the wrong shape gets a clear verdict.

The right and wrong answers the checkers judge are written the way a student might write
them, in ``tests/check/answers.py``; the tables below pair each with its expected verdict.
Noise letters: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf
from tests.check import answers

CHECKERS = [
    "bayes_predict",
    "bayes_update",
    "fuse",
    "kf_1d_step",
    "kf_step",
    "range_bearing",
    "range_bearing_jacobian",
    "sigma_points",
    "unicycle",
]


def test_every_checker_named_in_the_task_exists():
    required = {"bayes_predict", "bayes_update", "kf_1d_step", "kf_step", "range_bearing_jacobian"}
    assert required | {"unicycle", "sigma_points"} <= set(kf.check.__all__)
    assert set(CHECKERS) <= set(kf.check.__all__)


def test_the_catalogue_has_the_required_mistakes():
    required = {
        "not_normalised",
        "shift_wrong_way",
        "swapped_R_Q",
        "std_not_var",
        "missing_transpose",
        "sign_flip",
        "divides_by_omega",
        "unwrapped_angle",
        "wrong_weights",
    }
    assert required <= set(kf.check.MISTAKES)


@pytest.mark.parametrize("name", CHECKERS)
def test_the_package_function_passes(name):
    result = getattr(kf.check, name)(getattr(kf, name))
    assert result.passed, result.message
    assert result.mistake is None
    assert result.message.startswith("✔") and f"kf.{name}" in result.message


@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("name", CHECKERS)
def test_the_package_function_passes_with_other_seeds(name, seed):
    assert getattr(kf.check, name)(getattr(kf, name), seed=seed).passed


# ------------------------------------------------------------ right and wrong answers
@pytest.mark.parametrize(
    ("name", "fn"),
    [
        ("bayes_predict", answers.hand_bayes_predict),
        ("kf_step", answers.hand_kf_step),
        ("unicycle", answers.hand_unicycle),
        ("sigma_points", answers.hand_sigma_points),
    ],
)
def test_a_right_answer_written_differently_passes(name, fn):
    """The checker compares with a tolerance, not bit for bit: textbook code in another form passes."""
    result = getattr(kf.check, name)(fn)
    assert result.passed, result.message


WRONG = [
    ("bayes_predict", answers.predict_backwards, "shift_wrong_way"),
    ("bayes_predict", answers.predict_always_ring, "ignores_boundary"),
    ("bayes_predict", answers.predict_leaky, "leaks_at_wall"),
    ("bayes_update", answers.update_unnormalised, "not_normalised"),
    ("kf_1d_step", answers.kf_1d_swapped, "swapped_R_Q"),
    ("kf_1d_step", answers.kf_1d_squares_noise, "std_not_var"),
    ("kf_1d_step", answers.kf_1d_a_once, "a_not_squared"),
    ("fuse", answers.fuse_own_weights, "wrong_weights"),
    ("fuse", answers.fuse_squares, "std_not_var"),
    ("fuse", answers.fuse_adds, "adds_variances"),
    ("kf_step", answers.kf_step_swapped, "swapped_R_Q"),
    ("kf_step", answers.kf_step_no_transpose, "missing_transpose"),
    ("kf_step", answers.kf_step_innovation_backwards, "sign_flip"),
    ("range_bearing", answers.range_bearing_unwrapped, "unwrapped_angle"),
    ("range_bearing", answers.range_bearing_atan, "atan_not_atan2"),
    ("range_bearing_jacobian", answers.jacobian_robot_minus_landmark, "sign_flip"),
    ("range_bearing_jacobian", answers.jacobian_q_and_r_mixed, "q_not_sqrt_q"),
    ("unicycle", answers.unicycle_no_limit, "divides_by_omega"),
    ("unicycle", answers.unicycle_no_limit_floats, "divides_by_omega"),
    ("unicycle", answers.unicycle_unwrapped, "unwrapped_angle"),
    ("unicycle", answers.unicycle_y_backwards, "sign_flip"),
    ("unicycle", answers.unicycle_euler, "euler_step"),
    ("sigma_points", answers.sigma_points_rows_of_L, "missing_transpose"),
    ("sigma_points", answers.sigma_points_no_root, "std_not_var"),
    ("sigma_points", answers.sigma_points_weights_without_half, "wrong_weights"),
    ("sigma_points", answers.sigma_points_columns, "points_as_columns"),
    ("sigma_points", answers.sigma_points_symmetric_root, "not_cholesky"),
]


@pytest.mark.parametrize(("name", "fn", "mistake"), WRONG, ids=[f"{n}-{m}" for n, _, m in WRONG])
def test_a_known_mistake_is_named(name, fn, mistake):
    result = getattr(kf.check, name)(fn)
    assert not result.passed
    assert result.mistake == mistake, result.message
    assert result.message.startswith("✘")
    assert f"Likely mistake: {kf.check.MISTAKES[mistake]}" in result.message
    assert "expected:" in result.message and "inputs:" in result.message
    assert "hapter" in result.hint  # the hint points at the chapter's equation


def test_every_catalogue_key_is_exercised_by_a_wrong_function():
    assert {mistake for _, _, mistake in WRONG} == set(kf.check.MISTAKES)


# ------------------------------------------------------------- functions that misbehave
def test_an_unknown_mistake_gets_the_generic_verdict():
    def off_by_a_bit(belief, likelihood):
        bel = np.multiply(likelihood, belief)
        return bel / bel.sum() + 0.01

    result = kf.check.bayes_update(off_by_a_bit)
    assert not result.passed and result.mistake is None
    assert "No known mistake gives this answer" in result.message
    assert "case 1 of" in result.message and "got:" in result.message


def test_not_yet_is_no_failure():
    def my_kf_step(mu, Sig, u, z, F, B, H, R, Q):
        raise NotImplementedError("your turn")

    result = kf.check.kf_step(my_kf_step)
    assert result.passed is False and result.mistake is None
    assert "Not yet" in result.message and "my_kf_step" in result.message


def test_a_function_written_only_in_part_is_not_yet_done():
    def walls_only(belief, kernel, boundary="wall"):
        if boundary == "wrap":
            raise NotImplementedError("rings come later")
        return answers.hand_bayes_predict(belief, kernel, boundary)

    result = kf.check.bayes_predict(walls_only)
    assert result.passed is False and result.mistake is None and "Not yet" in result.message


def test_a_function_that_raises_gets_a_clear_verdict():
    def broken(state, landmark):
        return np.array([1.0, 2.0]) @ np.ones(3)

    result = kf.check.range_bearing(broken)
    assert not result.passed and result.mistake is None
    assert "it raised ValueError" in result.message
    assert "raised in broken" in result.message  # the line of the student's code that raised
    assert "Traceback" not in result.message


def test_a_function_that_returns_nan_gets_a_clear_verdict():
    result = kf.check.fuse(lambda mu1, var1, mu2, var2: (math.nan, 0.1))
    assert not result.passed and "mu contains NaN" in result.message


def test_a_function_that_returns_the_wrong_shape_gets_a_clear_verdict():
    result = kf.check.range_bearing_jacobian(lambda state, landmark: np.zeros((3, 2)))
    assert not result.passed and "H has shape (3, 2); expected (2, 3)" in result.message


def test_a_function_that_returns_too_few_values_gets_a_clear_verdict():
    result = kf.check.kf_1d_step(lambda mu, var, u, z, a, b, c, R, Q: mu)
    assert not result.passed and "expected 2 values (mu, var)" in result.message


def test_a_function_that_returns_no_numbers_gets_a_clear_verdict():
    result = kf.check.bayes_predict(lambda belief, kernel, boundary: "moved right")
    assert not result.passed and "bel_bar is not a number" in result.message


def test_a_function_that_changes_its_inputs_does_not_change_the_expected_answer():
    def sloppy(mu, Sig, u, z, F, B, H, R, Q):
        Sig += R  # changes the caller's array
        return answers.hand_kf_step(mu, Sig - R, u, z, F, B, H, R, Q)

    assert kf.check.kf_step(sloppy).passed


def test_prints_and_warnings_of_the_function_stay_quiet(capsys, recwarn):
    def chatty(belief, likelihood):
        print("debugging")
        np.log(np.zeros(1))  # a RuntimeWarning
        bel = np.multiply(likelihood, belief)
        return bel / bel.sum()

    assert kf.check.bayes_update(chatty).passed
    assert capsys.readouterr().out == ""
    assert len(recwarn) == 0


def test_anything_but_a_function_is_refused():
    with pytest.raises(ValueError, match="student_fn"):
        kf.check.kf_step(np.eye(2))


# ------------------------------------------------------------------------ the display
def test_the_verdict_displays_in_a_notebook():
    result = kf.check.kf_step(answers.kf_step_no_transpose)
    assert repr(result) == result.message
    page = result._repr_html_()
    assert "<pre>" in page and "Likely mistake" in page and "&lt;" not in result.headline
    ok = kf.check.kf_step(kf.kf_step)
    assert "✔" in ok._repr_html_() and repr(ok) == ok.message


def test_the_same_seed_gives_the_same_verdict_and_another_seed_other_cases():
    first = kf.check.unicycle(answers.unicycle_y_backwards, seed=5)
    assert first.message == kf.check.unicycle(answers.unicycle_y_backwards, seed=5).message
    odd = kf.check.kf_step(answers.kf_step_no_transpose, seed=0).details
    assert odd != kf.check.kf_step(answers.kf_step_no_transpose, seed=1).details
