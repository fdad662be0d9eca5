"""The exercise checkers of chapters 1, 3, 4, 5, 7, 8 and 9: the package's own functions pass,
each checker opens with its chapter's worked example, every mistake of its catalogue is named,
the verdict points at the output that is wrong, and a function that raises, returns NaN or the
wrong shape gets a clear verdict.

The right and wrong answers the checkers judge are written the way a student might write
them, in ``tests/check/answers.py``; :data:`CATALOGUE` below pairs each wrong one with the
mistake its checker must name.  Noise letters: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest

import kfcourse as kf
from tests.check import answers, new_answers

CHECKERS = {  # checker -> the module that holds it
    "bayes_predict": "bayes_checks",
    "bayes_update": "bayes_checks",
    "fuse": "kalman_checks",
    "kf_1d_step": "kalman_checks",
    "kf_step": "kalman_checks",
    "range_bearing": "nonlinear",
    "range_bearing_jacobian": "nonlinear",
    "sigma_points": "ukf_checks",
    "unicycle": "nonlinear",
    "unscented_transform": "ukf_checks",
}

#: Each checker's catalogue: the mistakes students make, each as a student would write it.
CATALOGUE = {
    "bayes_predict": [
        (answers.predict_backwards, "shift_wrong_way"),
        (answers.predict_always_ring, "ignores_boundary"),
        (answers.predict_leaky, "leaks_at_wall"),
        (answers.predict_leaky_renormalised, "leaks_at_wall"),
        (answers.predict_stays_put_at_wall, "wall_sends_back"),
        (answers.predict_overwrites, "overwrites_not_adds"),
    ],
    "bayes_update": [
        (answers.update_unnormalised, "not_normalised"),
        (answers.update_by_largest, "not_normalised"),
        (answers.update_adds, "adds_not_multiplies"),
    ],
    "kf_1d_step": [
        (answers.kf_1d_swapped, "swapped_R_Q"),
        (answers.kf_1d_squares_noise, "std_not_var"),
        (answers.kf_1d_sqrt_noise, "std_not_var"),
        (answers.kf_1d_a_once, "a_not_squared"),
        (answers.kf_1d_innovation_backwards, "sign_flip"),
        (answers.kf_1d_forgets_R, "forgot_R"),
        (answers.kf_1d_forgets_Q, "forgot_Q"),
        (answers.kf_1d_forgets_bu, "forgot_control"),
        (answers.kf_1d_gain_from_var, "prior_not_predicted"),
        (answers.kf_1d_innovation_from_mu, "prior_not_predicted"),
        (answers.kf_1d_update_from_var, "prior_not_predicted"),
        (answers.kf_1d_gain_for_c_one, "c_left_out"),
    ],
    "fuse": [
        (answers.fuse_own_weights, "wrong_weights"),
        (answers.fuse_plain_average, "wrong_weights"),
        (answers.fuse_squares, "std_not_var"),
        (answers.fuse_adds, "adds_variances"),
    ],
    "kf_step": [
        (answers.kf_step_swapped, "swapped_R_Q"),
        (answers.kf_step_swapped_with_solve, "swapped_R_Q"),
        (answers.kf_step_no_transpose, "missing_transpose"),
        (answers.kf_step_transpose_on_the_left, "missing_transpose"),
        (answers.kf_step_gain_without_HT, "missing_transpose"),
        (answers.kf_step_innovation_backwards, "sign_flip"),
        (answers.kf_step_plus_KH, "sign_flip"),
        (answers.kf_step_forgets_R, "forgot_R"),
        (answers.kf_step_S_without_Q, "forgot_Q"),
        (answers.kf_step_forgets_Bu, "forgot_control"),
        (answers.kf_step_gain_from_Sig, "prior_not_predicted"),
        (answers.kf_step_gain_and_S_from_Sig, "prior_not_predicted"),
        (answers.kf_step_innovation_from_mu, "prior_not_predicted"),
        (answers.kf_step_update_from_Sig, "prior_not_predicted"),
        (answers.kf_step_no_inverse, "no_inverse"),
        (answers.kf_step_one_over_S, "elementwise_inverse"),
        (answers.kf_step_update_on_the_right, "wrong_order"),
        (answers.kf_step_row_vector, "wrong_order"),
    ],
    "range_bearing": [
        (answers.range_bearing_unwrapped, "unwrapped_angle"),
        (answers.range_bearing_mod_2pi, "unwrapped_angle"),
        (answers.range_bearing_atan, "atan_not_atan2"),
        (answers.range_bearing_atan2_swapped, "atan2_arguments_swapped"),
        (answers.range_bearing_robot_minus_landmark, "robot_minus_landmark"),
        (answers.range_bearing_plus_theta, "heading_sign"),
        (answers.range_bearing_heading_minus_direction, "sign_flip"),
        (answers.range_bearing_degrees, "degrees"),
        (answers.range_bearing_squared_range, "q_not_sqrt_q"),
        (answers.range_bearing_bearing_first, "outputs_swapped"),
    ],
    "range_bearing_jacobian": [
        (answers.jacobian_numeric, "numeric_not_derived"),
        (answers.jacobian_lesson_finite_differences, "numeric_not_derived"),
        (answers.jacobian_bearing_row_flipped, "bearing_row_sign"),
        (answers.jacobian_range_row_flipped, "range_row_sign"),
        (answers.jacobian_robot_minus_landmark, "position_entries_flipped"),
        (answers.jacobian_q_and_r_mixed, "q_not_sqrt_q"),
        (answers.jacobian_r_in_bearing_row, "q_not_sqrt_q"),
        (answers.jacobian_q_in_range_row, "q_not_sqrt_q"),
        (answers.jacobian_dx_dy_swapped, "dx_dy_swapped"),
        (answers.jacobian_no_theta, "missing_theta"),
        (answers.jacobian_plus_one_theta, "sign_flip"),
    ],
    "unicycle": [
        (answers.unicycle_no_limit, "divides_by_omega"),
        (answers.unicycle_no_limit_floats, "divides_by_omega"),
        (answers.unicycle_exact_zero_test, "exact_zero_test"),
        (answers.unicycle_exact_zero_test_math, "exact_zero_test"),
        (answers.unicycle_straight_too_wide, "straight_too_wide"),
        (answers.unicycle_unwrapped, "unwrapped_angle"),
        (answers.unicycle_y_backwards, "sign_flip"),
        (answers.unicycle_euler, "euler_step"),
        (answers.unicycle_sin_cos_swapped, "sin_cos_swapped"),
        (answers.unicycle_heading_without_dt, "heading_without_dt"),
        (answers.unicycle_speed_not_distance, "speed_not_distance"),
    ],
    "sigma_points": [
        (answers.sigma_points_rows_of_L, "missing_transpose"),
        (answers.sigma_points_no_root, "std_not_var"),
        (answers.sigma_points_weights_without_half, "wrong_weights"),
        (answers.sigma_points_outer_weights_half_n, "wrong_weights"),
        (answers.sigma_points_with_beta, "wrong_weights"),
        (answers.sigma_points_unscaled, "missing_scale"),
        (answers.sigma_points_columns, "points_as_columns"),
        (answers.sigma_points_symmetric_root, "not_cholesky"),
        (answers.sigma_points_entrywise_sqrt, "not_cholesky"),
    ],
    "unscented_transform": [
        (answers.unscented_points_not_through_f, "f_not_applied"),
        (answers.unscented_mean_at_mu, "f_of_mean"),
        (answers.unscented_mean_not_subtracted, "mean_not_subtracted"),
        (answers.unscented_deviations_from_centre, "deviations_from_f_mu"),
        (answers.unscented_plain_average, "wrong_weights"),
        (answers.unscented_np_cov, "wrong_weights"),
        (answers.unscented_inner_product, "outer_product_order"),
        (answers.unscented_unscaled_points, "missing_scale"),
    ],
}
WRONG = [(name, fn, mistake) for name, entries in CATALOGUE.items() for fn, mistake in entries]


def what_the_checker_runs(name, monkeypatch) -> dict:
    """The cases and variants the checker ``name`` hands to run_check."""
    module = importlib.import_module(f"kfcourse.check.{CHECKERS[name]}")
    seen = {}

    def record(name, student_fn, reference, cases, variants, *args, **kwargs):
        seen.update(cases=cases, variants=variants)

    monkeypatch.setattr(module, "run_check", record)
    getattr(kf.check, name)(getattr(kf, name))
    return seen


def test_every_checker_exists_and_has_a_catalogue():
    assert set(CHECKERS) <= set(kf.check.__all__)
    assert set(CATALOGUE) == set(CHECKERS)


@pytest.mark.parametrize("name", CHECKERS)
def test_the_package_function_passes_and_the_verdict_names_the_worked_example(name):
    result = getattr(kf.check, name)(getattr(kf, name))
    assert result.passed, result.message
    assert result.mistake is None
    assert result.message.startswith("✔") and f"kf.{name}" in result.message
    assert "worked example" in result.message


@pytest.mark.parametrize("name", CHECKERS)
def test_the_first_case_is_the_chapters_worked_example(name, monkeypatch):
    first = what_the_checker_runs(name, monkeypatch)["cases"][0]
    assert first.label.startswith("chapter ") and "worked example" in first.label


def test_the_worked_examples_are_the_lessons_numbers(monkeypatch):
    first = {name: what_the_checker_runs(name, monkeypatch)["cases"][0].inputs for name in CHECKERS}
    mu, _ = kf.kf_step(*first["kf_step"].values())
    assert np.round(mu, 3).tolist() == [1.16, 1.08]  # chapter 5's worked numbers
    assert kf.range_bearing(*first["range_bearing"].values()) == pytest.approx([5.0, math.atan2(4, 3)])
    H = kf.range_bearing_jacobian(*first["range_bearing_jacobian"].values())
    assert np.round(H, 3).tolist() == [[-0.6, -0.8, 0.0], [0.16, -0.12, -1.0]]  # chapter 7
    assert kf.unicycle(*first["unicycle"].values()) == pytest.approx([0.5, 0.0, 0.0])  # chapter 8
    _, w, _ = kf.sigma_points(*first["sigma_points"].values())
    assert w.tolist() == [0.0, 0.5, 0.5]  # chapter 9
    mu_y, Sig_y = kf.unscented_transform(*first["unscented_transform"].values())
    assert (float(mu_y[0]), float(Sig_y[0, 0])) == pytest.approx((5.0, 16.0))  # chapter 9: x ~ N(2, 1), y = x²


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
        ("range_bearing_jacobian", answers.lesson_H_analytic),
        ("range_bearing_jacobian", answers.jacobian_by_angles),
        ("unicycle", answers.hand_unicycle),
        ("unicycle", answers.unicycle_straight_below_1e_6),
        ("sigma_points", answers.hand_sigma_points),
        ("sigma_points", answers.sigma_points_interleaved),
        ("sigma_points", answers.sigma_points_centre_last),
        ("unscented_transform", answers.hand_unscented_transform),
    ],
)
def test_a_right_answer_written_differently_passes(name, fn):
    """The checker compares with a tolerance, not bit for bit, and sigma points in any order:
    textbook code in another form passes."""
    result = getattr(kf.check, name)(fn)
    assert result.passed, result.message


@pytest.mark.parametrize(("name", "fn", "mistake"), WRONG, ids=[f"{n}-{f.__name__}" for n, f, _ in WRONG])
def test_a_known_mistake_is_named(name, fn, mistake):
    result = getattr(kf.check, name)(fn)
    assert not result.passed
    assert result.mistake == mistake, result.message
    assert result.message.startswith("✘")
    assert f"Likely mistake: {kf.check.MISTAKES[mistake]}" in result.message
    assert "expected:" in result.message and "inputs:" in result.message
    assert "hapter" in result.hint  # the hint points at the chapter's equation


@pytest.mark.parametrize("name", CHECKERS)
def test_at_least_nine_in_ten_of_the_catalogue_are_named(name):
    named = [getattr(kf.check, name)(fn).mistake == mistake for fn, mistake in CATALOGUE[name]]
    assert sum(named) / len(named) >= 0.9
    assert all(named)


#: Mistakes that give the same answer as another on every input, so that no answer can be named for them alone:
#: the checker knows them only to say that either may be the one.
TWINS = {"range_bearing": {"wrap_shifted_by_pi"}}


@pytest.mark.parametrize("name", CHECKERS)
def test_every_mistake_a_checker_knows_is_in_its_catalogue(name, monkeypatch):
    known = {variant.mistake for variant in what_the_checker_runs(name, monkeypatch)["variants"]}
    assert known == {mistake for _, mistake in CATALOGUE[name]} | TWINS.get(name, set())
    assert known <= set(kf.check.MISTAKES)


# --------------------------------------------------- a name only when every case supports it
@pytest.mark.parametrize(
    ("name", "fn", "not_this"),
    [
        # z - mu_bar: on the first failing case c mu = mu_bar, where it gives what z - c mu gives
        ("kf_1d_step", answers.kf_1d_forgets_c_in_innovation, "prior_not_predicted"),
        # mu_bar = mu + B u: on the worked example mu F (the product the wrong way round) is mu too
        ("kf_step", answers.kf_step_forgets_F_in_mean, "wrong_order"),
    ],
)
def test_a_mistake_that_matches_on_one_case_only_is_not_named(name, fn, not_this):
    result = getattr(kf.check, name)(fn)
    assert not result.passed and result.mistake is None, result.message
    assert kf.check.MISTAKES[not_this] not in result.message
    assert "No known mistake gives this answer" in result.hint


# ------------------------------------------- with no name: which step, and which input, is at fault
@pytest.mark.parametrize(
    ("name", "fn", "prediction", "update"),
    [
        ("kf_1d_step", answers.kf_1d_forgets_c_in_innovation, "right", "wrong"),
        ("kf_1d_step", answers.kf_1d_R_scaled_by_a, "wrong", "right"),
        ("kf_step", answers.kf_step_forgets_F_in_mean, "wrong", "right"),
    ],
)
def test_each_step_is_run_on_its_own_and_the_verdict_says_which_is_wrong(name, fn, prediction, update):
    result = getattr(kf.check, name)(fn)
    assert not result.passed and result.mistake is None, result.message
    assert f"the answer is the prediction (1)-(2) alone, and yours is {prediction} there" in result.hint
    assert f"the answer is the update (3)-(5) alone, and yours is {update} there" in result.hint


def test_steps_right_on_their_own_are_said_so_and_nothing_is_guessed_from_it():
    """Both steps right alone says where the mistake is not; where it is (how they join) is not a fact, so unsaid."""
    hint = kf.check.kf_1d_step(answers.kf_1d_R_in_gain_too).hint
    assert hint.count("and yours is right there") == 2 and "both act at once" not in hint


def test_steps_that_are_all_wrong_tell_nothing_apart_and_are_not_said():
    """F * Σ * Fᵀ entry by entry: wrong with H = 0, and wrong with F = I too (I * Σ * I keeps Σ's diagonal), although
    the update is right: every isolation fails, none points anywhere, so no step sentence is said."""

    def elementwise_predict(mu, Sig, u, z, F, B, H, R, Q):
        mu_bar, Sig_bar = F @ mu + B @ u, F * Sig * F.T + R
        K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
        return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar

    hint = kf.check.kf_step(elementwise_predict).hint
    assert "No known mistake" in hint and "alone, and yours is" not in hint


def test_an_output_that_ignores_an_input_it_needs_is_named_with_its_equation():
    hint = kf.check.kf_1d_step(answers.kf_1d_var_with_fixed_Q).hint
    assert "Your var does not change when Q changes, and the right one does: Q enters (3)" in hint
    assert "Your mu does not change" not in hint  # its mean takes Q as it should


def test_chapter_4s_fused_variance_follows_the_variances_only():
    def var_from_the_means(mu1, var1, mu2, var2):
        mu = (mu1 / var1 + mu2 / var2) / (1 / var1 + 1 / var2)
        return mu, 1 / (1 / var1 + 1 / var2) + 0.01 * abs(mu1 - mu2)  # wrong: the spread of the means added

    def var2_fixed(mu1, var1, mu2, var2):
        mu = (mu1 / var1 + mu2 / var2) / (1 / var1 + 1 / var2)
        return mu, 1 / (1 / var1 + 1 / 0.1)  # wrong: the worked example's var2 typed in

    hint = kf.check.fuse(var_from_the_means).hint
    assert "Your var changes when mu1 changes, and the right one does not" in hint and "mu2 changes" in hint
    assert "Your var does not change when var2 changes, and the right one does: var2 enters the fused variance" in (
        kf.check.fuse(var2_fixed).hint
    )


def test_chapter_2s_covariance_does_not_follow_b():
    def plus_b_b(mu, Sig, A, b):
        return A @ mu + b, A @ Sig @ A.T + np.outer(b, b)  # wrong: b moves the mean, not the spread

    assert "Your Sig changes when b changes, and the right one does not" in kf.check.affine_gaussian(plus_b_b).hint


def test_an_output_that_follows_an_input_it_should_not_is_named():
    def var_follows_z(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
        right_mu, right_var = kf.kf_1d_step(mu, var, u, z, a, b, c, R, Q)
        return right_mu, right_var + 1e-3 * abs(z)  # wrong: the variance moves with the reading

    assert "Your var changes when z changes, and the right one does not" in kf.check.kf_1d_step(var_follows_z).hint


def test_chapter_10s_noises_exchanged_are_found_by_exchanging_them():
    """M and Q swapped shows in every isolation; the right step with the two exchanged gives the student's answer."""
    result = kf.check.localization_step(new_answers.localization_M_and_Q_swapped)
    assert not result.passed and result.mistake is None, result.message
    assert "Your answers are the right ones with M and Q exchanged" in result.hint
    assert "alone, and yours is wrong there" not in result.hint  # every step wrong: not said


@pytest.mark.parametrize(
    ("fn", "prediction", "updates"),
    [
        (new_answers.localization_innovation_backwards, "right", "wrong"),
        (new_answers.localization_jacobians_at_mu_bar, "wrong", "right"),
    ],
)
def test_chapter_10s_step_says_whether_its_prediction_or_its_updates_are_wrong(fn, prediction, updates):
    """The innovation backwards, G and W taken at μ̄: no name, but the step at fault."""
    result = kf.check.localization_step(fn)
    assert not result.passed and result.mistake is None, result.message
    assert f"Wᵀ, alone, and yours is {prediction} there" in result.hint
    assert f"the answer is the updates (2)-(5) alone, and yours is {updates} there" in result.hint


def test_two_mistakes_no_case_tells_apart_are_both_said_and_neither_named():
    """(φ mod 2π) − π turns φ by π, as robot-minus-landmark offsets wrapped into [−π, π) do, on every input."""
    result = kf.check.range_bearing(answers.range_bearing_shifted_wrap)
    assert not result.passed and result.mistake is None, result.message
    assert "no case tells them apart" in result.hint
    for mistake in ("robot_minus_landmark", "wrap_shifted_by_pi"):
        assert kf.check.MISTAKES[mistake] in result.hint
    # wrapped into (−π, π], the reversed offsets differ from it straight ahead (π against −π), and are named
    assert kf.check.range_bearing(answers.range_bearing_robot_minus_landmark).mistake == "robot_minus_landmark"


# -------------------------------------------------------- the verdict points at the output
def test_a_covariance_mistake_points_at_sig_and_says_mu_is_right():
    result = kf.check.kf_step(answers.kf_step_update_from_Sig)
    assert "case 1 of" in result.headline and "worked example" in result.headline
    assert "Sig has the wrong value (mu is right)" in result.headline


def test_a_mean_mistake_points_at_mu_and_says_sig_is_right():
    result = kf.check.kf_step(answers.kf_step_innovation_from_mu)
    assert "mu has the wrong value" in result.headline and "(Sig is right)" in result.headline


def test_every_multi_output_checker_points_at_the_wrong_output():
    assert "var has the wrong value (mu is right)" in kf.check.kf_1d_step(answers.kf_1d_update_from_var).headline
    assert (
        "wc has the wrong value at [0] (chi and wm are right)"
        in kf.check.sigma_points(answers.sigma_points_with_beta).headline
    )
    assert "(mu_y is right)" in kf.check.unscented_transform(answers.unscented_mean_not_subtracted).headline
    assert "mu has the wrong value (var is right)" in kf.check.fuse(answers.fuse_plain_average).headline


def test_a_jacobian_mistake_points_at_the_entries_that_differ():
    result = kf.check.range_bearing_jacobian(answers.jacobian_bearing_row_flipped)
    assert "worked example" in result.headline
    assert "H has the wrong value at [1, 0] and [1, 1]" in result.headline


def test_a_swap_that_raises_on_the_worked_example_is_named():
    """R and Q have different shapes in chapter 5's example: the swap raises there."""
    result = kf.check.kf_step(answers.kf_step_swapped_with_solve)
    assert "case 1 of" in result.headline and "it raised" in result.headline
    assert result.mistake == "swapped_R_Q"


# ------------------------------------------------------------- what the exercises ask
def test_a_numerically_differentiated_jacobian_is_told_to_derive_it():
    result = kf.check.range_bearing_jacobian(answers.jacobian_numeric)
    assert not result.passed and result.mistake == "numeric_not_derived"
    assert "only to" in result.headline and "derive" in result.hint
    # it is within the tolerance everywhere: only the rounding-level agreement tells it apart
    assert "case" in result.headline and "got:" in result.details


def test_an_exact_zero_test_fails_where_chapter_8_shows_the_arc_formula_off():
    result = kf.check.unicycle(answers.unicycle_exact_zero_test)
    assert "ω = 1e-15" in result.headline and result.mistake == "exact_zero_test"
    x_arc = answers.unicycle_exact_zero_test([0.0, 0.0, 0.3], [0.5, 1e-15], 1.0)[0]
    assert 0.02 <= abs(x_arc - kf.unicycle([0.0, 0.0, 0.3], [0.5, 1e-15], 1.0)[0]) <= 0.15  # 2-15 cm off


def test_sigma_points_in_another_order_pass_but_not_with_their_weights_mixed_up():
    assert kf.check.sigma_points(answers.sigma_points_interleaved).passed

    def weights_not_moved(mu, Sig, lam):
        chi, w, _ = answers.sigma_points_interleaved(mu, Sig, lam)
        return chi, w[::-1], w[::-1]  # the points in one order, the weights in another

    assert not kf.check.sigma_points(weights_not_moved).passed


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


def test_a_function_that_changes_its_inputs_is_told_so_and_does_not_change_the_expected_answer():
    def sloppy(mu, Sig, u, z, F, B, H, R, Q):
        Sig += R  # changes the caller's array
        return answers.hand_kf_step(mu, Sig - R, u, z, F, B, H, R, Q)

    result = kf.check.kf_step(sloppy)  # its answers are right: each call had its own copy of the inputs
    assert not result.passed and result.mistake == "changes_input", result.message
    assert "its answers are right, but on case 1 of" in result.headline and "argument Sig in place" in result.headline
    assert kf.check.kf_step(answers.hand_kf_step).passed  # a function that builds new arrays passes


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


def test_integers_and_booleans_show_as_they_are_not_as_floats():
    from kfcourse.check._core import show

    assert show(np.array([1, 2, 2, 3])) == "[1, 2, 2, 3]"  # indices, not [1., 2., 2., 3.]
    assert show(np.array([True, False])) == "[ True, False]"  # flags, not [1., 0.]
    assert show(np.int64(7)) == "7" and show(np.True_) == "True" and show(1234567) == "1234567"
    assert show(np.array([1.0, 2.0])) == "[1., 2.]" and show(0.1234567) == "0.123457"  # floats stay floats
    assert show([1, 2.5]) == "[1. , 2.5]"  # an integer among floats is a float


def test_a_verdict_shows_indices_as_integers():
    details = kf.check.resample_systematic(lambda w, rng: kf.resample_systematic(w, rng) - 1).details
    assert "indices = [1, 2, 2, 3, 4]" in details and "indices = [0, 1, 1, 2, 3]" in details, details


def test_the_functions_of_the_unscented_transform_show_their_formula():
    result = kf.check.unscented_transform(answers.unscented_points_not_through_f)
    assert "f   = f(x) = x²" in result.details and " at 0x" not in result.message


def test_the_same_seed_gives_the_same_verdict_and_another_seed_other_cases():
    first = kf.check.unicycle(answers.unicycle_y_backwards, seed=5)
    assert first.message == kf.check.unicycle(answers.unicycle_y_backwards, seed=5).message
    odd = kf.check.kf_step(answers.kf_step_forgets_Bu, seed=0).details
    assert odd != kf.check.kf_step(answers.kf_step_forgets_Bu, seed=1).details


def test_a_hint_starting_with_a_symbol_keeps_it():
    from kfcourse.check._core import _sentence

    assert _sentence("divide by the sum") == "Divide by the sum"
    assert _sentence("x moves with cos θ") == "x moves with cos θ"  # x, not X
    assert _sentence("n σ² is the variance") == "n σ² is the variance"
    assert _sentence("θ + ωΔt can leave (−π, π]") == "θ + ωΔt can leave (−π, π]"
    assert _sentence("accel_var is already the variance") == "accel_var is already the variance"  # a name in code
    assert _sentence("np.sqrt takes the root of each") == "np.sqrt takes the root of each"
