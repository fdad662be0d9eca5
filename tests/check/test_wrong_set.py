"""The checkers against a fixed set of wrong and right solutions, written from the exercise texts apart from
the checkers' catalogue (``tests/check/wrong_set/``): every wrong one is caught, every right one passes, and a
mistake is named only where the name was reviewed as the solution's own (:data:`NAMED`): a wrong name fails.

What each verdict says of the rest (the step, the input, the invariant at fault) is reported by
``python -m tests.check.wrong_set.report``.
"""

from __future__ import annotations

import pytest

import kfcourse as kf
from tests.check.wrong_set import report

SOLUTIONS = report.load()

#: Each wrong solution the checkers name, with the name read against what the solution does and found its own.
NAMED = {
    "drift_linear": "n_not_sqrt_n",
    "drift_variance": "std_not_var",
    "drift_std_as_variance": "root_of_sigma_n",
    "drift_one_step_long": "off_by_one",
    "drift_divided": "divides_by_sqrt_n",
    "predict_always_wall": "ignores_boundary",
    "predict_always_wrap": "ignores_boundary",
    "predict_wall_loses_mass": "leaks_at_wall",
    "predict_wall_renormalised": "leaks_at_wall",
    "predict_wrong_direction": "shift_wrong_way",
    "predict_overwrites": "overwrites_not_adds",
    "predict_in_place": "changes_input",
    "update_not_normalised": "not_normalised",
    "update_eta_from_likelihood": "not_normalised",
    "update_adds": "adds_not_multiplies",
    "update_normalised_by_max": "not_normalised",
    "update_in_place": "changes_input",
    "affine_half_sandwich": "a_not_squared",
    "affine_mean_without_b": "b_forgotten",
    "affine_swapped_pair": "outputs_swapped",
    "affine_in_place": "changes_input",
    "kf1d_gain_without_q": "forgot_Q",
    "kf1d_r_q_swapped": "swapped_R_Q",
    "kf1d_var_times_a": "a_not_squared",
    "kf1d_gain_from_prior": "prior_not_predicted",
    "kf1d_shrinks_prior": "prior_not_predicted",
    "kf1d_shrink_without_c": "c_left_out",
    "kf1d_innovation_from_prior": "prior_not_predicted",
    "kf1d_innovation_sign": "sign_flip",
    "kf1d_swapped_pair": "outputs_swapped",
    "fuse_weights_swapped": "wrong_weights",
    "fuse_plain_average": "wrong_weights",
    "fuse_squares_variances": "std_not_var",
    "fuse_swapped_pair": "outputs_swapped",
    "kf_r_q_swapped": "swapped_R_Q",
    "kf_no_transpose": "missing_transpose",
    "kf_transpose_wrong_side": "missing_transpose",
    "kf_without_r": "forgot_R",
    "kf_without_control": "forgot_control",
    "kf_s_without_q": "forgot_Q",
    "kf_gain_from_prior": "prior_not_predicted",
    "kf_innovation_sign": "sign_flip",
    "kf_shrinks_prior": "prior_not_predicted",
    "kf_covariance_sign": "sign_flip",
    "kf_innovation_in_place": "changes_input",
    "cv_gamma_without_half": "missing_half",
    "cv_gamma_half_dt": "dt_not_dt2",
    "cv_accel_var_squared": "std_not_var",
    "cv_diagonal_R": "R_diagonal",
    "cv_F_transposed": "F_transposed",
    "cv_interleaved_state": "state_order",
    "cv_returns_R_F": "outputs_swapped",
    "rb_heading_added": "heading_sign",
    "rb_atan2_swapped": "atan2_arguments_swapped",
    "rb_arctan_of_quotient": "atan_not_atan2",
    "rb_offset_reversed": "robot_minus_landmark",
    "rb_squared_range": "q_not_sqrt_q",
    "rb_unwrapped": "unwrapped_angle",
    "rb_wrap_zero_to_two_pi": "unwrapped_angle",
    "rb_degrees": "degrees",
    "rb_swapped_outputs": "outputs_swapped",
    "rb_landmark_in_place": "changes_input",
    "rbj_bearing_row_flipped": "bearing_row_sign",
    "rbj_bearing_row_without_chain_rule": "bearing_row_sign",
    "rbj_range_row_without_chain_rule": "range_row_sign",
    "rbj_derivative_wrt_landmark": "position_entries_flipped",
    "rbj_heading_plus_one": "sign_flip",
    "rbj_heading_zero": "missing_theta",
    "rbj_bearing_over_r": "q_not_sqrt_q",
    "rbj_range_over_q": "q_not_sqrt_q",
    "rbj_bearing_dx_dy_swapped": "dx_dy_swapped",
    "rbj_finite_differences": "numeric_not_derived",
    "rbj_landmark_in_place": "changes_input",
    "uni_arc_never_straight": "divides_by_omega",
    "uni_straight_only_at_zero": "exact_zero_test",
    "uni_straight_threshold_too_large": "straight_too_wide",
    "uni_straight_branch_without_dt": "speed_not_distance",
    "uni_heading_without_dt": "heading_without_dt",
    "uni_heading_unwrapped": "unwrapped_angle",
    "uni_y_sign_flipped": "sign_flip",
    "uni_xy_swapped": "sin_cos_swapped",
    "uni_euler_old_heading": "euler_step",
    "uni_in_place": "changes_input",
    "sp_rows_of_L": "missing_transpose",
    "sp_symmetric_square_root": "not_cholesky",
    "sp_elementwise_sqrt": "not_cholesky",
    "sp_without_spread": "missing_scale",
    "sp_spread_not_square_rooted": "missing_scale",
    "sp_outer_weights_without_two": "wrong_weights",
    "sp_beta_two": "wrong_weights",
    "sp_scales_Sig_in_place": "changes_input",
    "ut_image_of_the_mean": "f_of_mean",
    "ut_spread_about_f_of_mu": "deviations_from_f_mu",
    "ut_second_moment": "mean_not_subtracted",
    "ut_points_without_spread": "missing_scale",
    "ut_scales_Sig_in_place": "changes_input",
    "loc_unwrapped_innovation": "bearing_not_wrapped",
    "loc_gate_not_squared": "gate_on_d_not_d2",
    "loc_Q_forgotten": "forgot_Q",
    "loc_stale_prediction": "stale_mean",
    "loc_heading_unwrapped": "heading_not_wrapped",
    "loc_process_noise_forgotten": "forgot_R",
    "loc_predicts_in_place": "changes_input",
    "rs_stratified": "stratified_not_systematic",
    "rs_multinomial": "multinomial",
    "rs_no_offset": "no_offset",
    "rs_fresh_generator": "ignores_rng",
    "rs_offset_not_divided": "offset_not_divided",
    "rs_offset_divided_twice": "no_offset",
    "rs_cumsum_not_normalised": "unnormalised_weights",
    "rs_last_set_to_one": "shortfall_to_last",
    "rs_side_left": "boundary_side",
    "rs_counts_instead_of_indices": "counts_not_indices",
    "rs_cumsum_in_place": "changes_input",
    "ro_offset_to_beacon": "shift_wrong_way",
    "ro_innovation_backwards": "shift_wrong_way",
    "ro_S_without_Q": "forgot_Q",
    "ro_Q_squared": "std_not_var",
    "ro_squared_range": "q_not_sqrt_q",
    "ro_H_unnormalised": "H_not_unit",
    "ro_heading_entry_from_bearing": "heading_in_H",
    "ro_forgets_Sig_bar": "no_Sig_bar",
    "ro_covariance_unchanged": "Sig_not_updated",
    "ro_covariance_product_reversed": "wrong_order",
    "ro_position_only": "heading_held",
    "ro_one_d_arrays": "dot_not_outer",
    "ro_no_guard_at_beacon": "r_zero_not_refused",
    "ro_skips_at_beacon": "r_zero_not_refused",
    "ro_updates_in_place": "changes_input",
}


def _id(solution) -> str:
    return f"{solution.checker}-{solution.fn.__name__}"


@pytest.mark.parametrize("solution", [s for s in SOLUTIONS if not s.right], ids=_id)
def test_a_wrong_solution_is_caught_and_never_named_wrongly(solution):
    result = getattr(kf.check, solution.checker)(solution.fn)
    assert not result.passed, result.message
    assert result.mistake in (None, NAMED.get(solution.fn.__name__)), result.message


@pytest.mark.parametrize("solution", [s for s in SOLUTIONS if s.right], ids=_id)
def test_a_right_solution_in_another_style_passes(solution):
    result = getattr(kf.check, solution.checker)(solution.fn)
    assert result.passed, result.message


def test_the_set_is_as_written_at_least_eight_wrong_and_two_right_per_checker():
    checkers = [name for name in kf.check.__all__ if name not in ("MISTAKES", "CheckResult")]
    for checker in checkers:
        mine = [s for s in SOLUTIONS if s.checker == checker]
        assert sum(not s.right for s in mine) >= 8 and sum(s.right for s in mine) >= 2, checker
    assert sum(not s.right for s in SOLUTIONS) >= 130
