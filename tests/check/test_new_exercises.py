"""The checkers of chapters 0, 2, 6 and 10: the package's answer passes, every mistake of each
checker's catalogue is named, and a function that is not written yet, raises, returns NaN or the
wrong shape gets a clear verdict that points at the wrong output.

The answers judged here are written the way a student might write them, in
``tests/check/new_answers.py``.  Noise letters: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.check import localization_checks as localization
from tests.check import new_answers as a

#: checker name -> the package's own answer
PACKAGE = {
    "drift_sigma": kf.sim.drift_sigma,
    "affine_gaussian": kf.affine_gaussian,
    "cv_model": lambda dt, accel_var: (kf.models.constant_velocity(dt, 2)[0], kf.sim.process_noise(dt, accel_var)),
    "localization_step": kf.ekf_localization_step,
}

RIGHT = [
    ("drift_sigma", a.drift_sigma),
    ("affine_gaussian", a.affine_gaussian),
    ("cv_model", a.cv_model),
    ("localization_step", a.localization_step),
    ("localization_step", a.localization_with_package_steps),
]

#: Each checker's catalogue: (checker, a student's wrong answer, the mistake it must be named as).
WRONG = [
    # chapter 0: n not sqrt(n), the variance, sigma / sqrt(n), off by one, one number only
    ("drift_sigma", a.drift_linear, "n_not_sqrt_n"),
    ("drift_sigma", a.drift_variance, "std_not_var"),
    ("drift_sigma", a.drift_divides, "divides_by_sqrt_n"),
    ("drift_sigma", a.drift_counts_start, "off_by_one"),
    ("drift_sigma", a.drift_loop, "off_by_one"),
    ("drift_sigma", a.drift_math_sqrt, "scalar_only"),
    ("drift_sigma", a.drift_root_of_wrong_thing, "root_of_sigma_n"),
    # chapter 2: A Sig, A Sig A, A^T Sig A, variance times A, b in the covariance, b forgotten
    ("affine_gaussian", a.affine_half, "a_not_squared"),
    ("affine_gaussian", a.affine_no_transpose, "missing_transpose"),
    ("affine_gaussian", a.affine_transpose_first, "transpose_on_left"),
    ("affine_gaussian", a.affine_scalar_thinking, "a_not_squared"),
    ("affine_gaussian", a.affine_star, "elementwise_not_matmul"),
    ("affine_gaussian", a.affine_b_everywhere, "b_in_covariance"),
    ("affine_gaussian", a.affine_no_b, "b_forgotten"),
    # chapter 6: dt^2 for dt^2/2, dt for dt^2, R diagonal, [px, vx, py, vy], F transposed, sigma_a for sigma_a^2
    ("cv_model", a.cv_no_half, "missing_half"),
    ("cv_model", a.cv_dt_for_position, "dt_not_dt2"),
    ("cv_model", a.cv_diagonal, "R_diagonal"),
    ("cv_model", a.cv_interleaved, "state_order"),
    ("cv_model", a.cv_F_transposed, "F_transposed"),
    ("cv_model", a.cv_sigma_a, "std_not_var"),
    # chapter 10
    ("localization_step", a.localization_no_wrap, "bearing_not_wrapped"),
    ("localization_step", a.localization_update_without_residual, "bearing_not_wrapped"),
    ("localization_step", a.localization_d2_vs_gate, "gate_on_d_not_d2"),
    ("localization_step", a.localization_d_vs_gate2, "gate_on_d_not_d2"),
    ("localization_step", a.localization_no_Q, "forgot_Q"),
    ("localization_step", a.localization_no_Q_in_gate, "forgot_Q"),
    ("localization_step", a.localization_no_Q_in_update, "forgot_Q"),
    ("localization_step", a.localization_stale, "stale_mean"),
    ("localization_step", a.localization_restarts_from_prediction, "stale_mean"),
    ("localization_step", a.localization_gain_from_prediction, "stale_mean"),
    ("localization_step", a.localization_R_is_M, "R_not_mapped"),
    ("localization_step", a.localization_ekf_predict_with_M, "R_not_mapped"),
    ("localization_step", a.localization_no_R, "forgot_R"),
    ("localization_step", a.localization_heading_unwrapped, "heading_not_wrapped"),
    ("localization_step", a.localization_all_used, "used_wrong"),
    ("localization_step", a.localization_forgets_used, "used_wrong"),
    ("localization_step", a.localization_no_gate, "no_gate"),
    ("localization_step", a.localization_blind_skips, "no_predict_when_blind"),
]

#: The keys the MISTAKES block "chapters 0, 2, 6 and 10" adds; the rest are shared with other checkers.
NEW_KEYS = {
    "n_not_sqrt_n",
    "divides_by_sqrt_n",
    "off_by_one",
    "scalar_only",
    "transpose_on_left",
    "b_in_covariance",
    "b_forgotten",
    "missing_half",
    "dt_not_dt2",
    "R_diagonal",
    "state_order",
    "F_transposed",
    "R_not_mapped",
    "stale_mean",
    "bearing_not_wrapped",
    "heading_not_wrapped",
    "gate_on_d_not_d2",
    "no_gate",
    "used_wrong",
    "no_predict_when_blind",
}


def test_the_checkers_are_exported():
    assert set(PACKAGE) <= set(kf.check.__all__)
    assert "ekf_localization_step" in kf.__all__


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
@pytest.mark.parametrize("name", PACKAGE)
def test_the_package_function_passes(name, seed):
    result = getattr(kf.check, name)(PACKAGE[name], seed=seed)
    assert result.passed, result.message
    assert result.mistake is None and result.message.startswith("✔")


@pytest.mark.parametrize(("name", "fn"), RIGHT, ids=[fn.__name__ for _, fn in RIGHT])
def test_a_right_answer_written_differently_passes(name, fn):
    result = getattr(kf.check, name)(fn)
    assert result.passed, result.message


def test_each_checker_opens_with_the_chapter():
    labels = {
        "drift_sigma": "chapter 0's drift table",
        "affine_gaussian": "the lesson's Z = 2X",
        "cv_model": "chapter 6's tracker: Δt = 0.1 s, σa² = 10",
        "localization_step": "chapter 10's step 60: two landmarks in view",
    }
    for name, label in labels.items():
        result = getattr(kf.check, name)(PACKAGE[name])
        assert result.message.split(": ", 1)[1].startswith(label.split(":")[0]), result.message


@pytest.mark.parametrize(("name", "fn", "mistake"), WRONG, ids=[fn.__name__ for _, fn, _ in WRONG])
def test_a_known_mistake_is_named(name, fn, mistake):
    result = getattr(kf.check, name)(fn)
    assert not result.passed
    assert result.mistake == mistake, result.message
    assert result.message.startswith("✘")
    assert f"Likely mistake: {kf.check.MISTAKES[mistake]}" in result.message
    assert "expected:" in result.message and "inputs:" in result.message
    assert "hapter" in result.hint


def test_every_new_catalogue_key_is_in_the_catalogue_and_exercised():
    assert NEW_KEYS <= set(kf.check.MISTAKES)
    assert NEW_KEYS <= {mistake for _, _, mistake in WRONG}


def test_at_least_90_percent_of_each_catalogue_is_named():
    for name in PACKAGE:
        tried = [(fn, m) for n, fn, m in WRONG if n == name]
        named = sum(getattr(kf.check, name)(fn).mistake == m for fn, m in tried)
        assert tried and named >= 0.9 * len(tried), name


# ------------------------------------------------------------ the verdict points at the wrong output
@pytest.mark.parametrize(
    ("name", "fn", "wrong", "right"),
    [
        ("cv_model", a.cv_diagonal, "R", "F is right"),
        ("cv_model", a.cv_F_transposed, "F", "R is right"),
        ("affine_gaussian", a.affine_no_b, "mu", "Sig is right"),
        ("affine_gaussian", a.affine_half, "Sig", "mu is right"),
        ("localization_step", a.localization_forgets_used, "used", "mu and Sig are right"),
        ("localization_step", a.localization_heading_unwrapped, "mu", "Sig and used are right"),
    ],
)
def test_the_verdict_points_at_the_wrong_output(name, fn, wrong, right):
    headline = getattr(kf.check, name)(fn).headline
    assert f", {wrong} " in headline and right in headline, headline


# ------------------------------------------------------------ functions that misbehave
SKELETONS = {
    "drift_sigma": lambda step_std, n: _not_yet(),
    "affine_gaussian": lambda mu, Sig, A, b: _not_yet(),
    "cv_model": lambda dt, accel_var: _not_yet(),
    "localization_step": lambda mu, Sig, u, z, landmarks, dt, M, Q, gate: _not_yet(),
}


def _not_yet():
    raise NotImplementedError("your turn")


@pytest.mark.parametrize("name", PACKAGE)
def test_not_yet_is_no_failure(name):
    result = getattr(kf.check, name)(SKELETONS[name])
    assert result.passed is False and result.mistake is None and "Not yet" in result.message


@pytest.mark.parametrize(
    ("name", "fn", "says"),
    [
        ("drift_sigma", lambda step_std, n: np.sqrt(n) * math.nan, "sigma contains NaN"),
        ("affine_gaussian", lambda mu, Sig, A, b: (A @ mu + b, np.full_like(Sig, np.nan)), "Sig contains NaN"),
        ("cv_model", lambda dt, accel_var: (np.eye(4), np.eye(2)), "R has shape (2, 2); expected (4, 4)"),
        ("localization_step", lambda mu, Sig, *rest: (mu, Sig), "expected 3 values (mu, Sig, used)"),
        ("localization_step", lambda mu, Sig, *rest: (mu[:2], Sig, []), "mu has shape (2,); expected (3,)"),
        ("drift_sigma", lambda step_std, n: step_std * math.sqrt(n), "it raised TypeError"),
        ("cv_model", lambda dt, accel_var: 1 / 0, "it raised ZeroDivisionError"),
    ],
)
def test_a_misbehaving_function_gets_a_clear_verdict(name, fn, says):
    result = getattr(kf.check, name)(fn)
    assert not result.passed and says in result.message, result.message
    assert "Traceback" not in result.message


@pytest.mark.parametrize("name", PACKAGE)
def test_anything_but_a_function_is_refused_by_its_own_name(name):
    with pytest.raises(ValueError, match=f"kf.check.{name}\\(my_{name}\\)"):
        getattr(kf.check, name)(42)


# ------------------------------------------------------------ the chapter's case is the chapter's
def test_the_opening_case_is_step_60_of_the_chapter():
    """The checker's rounded copy of chapter 10's step 60 (seed 0, gate 4) is that step, to its rounding."""
    run = kf.sim.landmark_loop(0, gate=4.0)
    seen = run.used[60] | run.rejected[60]
    step = localization.CHAPTER_STEP
    np.testing.assert_allclose(step["mu"], run.mu[59], atol=1e-5)
    np.testing.assert_allclose(step["Sig"], run.Sig[59], atol=1e-8)
    np.testing.assert_allclose(step["u"], run.odometry[60], atol=1e-5)
    np.testing.assert_allclose(step["z"], run.z[60, seen], atol=1e-5)
    np.testing.assert_array_equal(step["landmarks"], run.landmarks[seen])
    assert seen.sum() == 2 and run.used[60, seen].all()
    mu, _, used = kf.ekf_localization_step(*step.values(), localization.DT, localization.M, localization.Q, 4.0)
    np.testing.assert_allclose(mu, run.mu[60], atol=1e-4)
    assert used.all()


def test_each_mistake_case_does_what_its_label_says():
    cases = {c.label: c for c in localization._cases(np.random.default_rng(0))}
    step = kf.ekf_localization_step
    _, _, used = cases["a reading far outside the gate, a stray one (20 standard deviations)"].call(step)
    assert not used.any()
    _, _, used = cases["a reading just outside the gate (4.2 standard deviations)"].call(step)
    assert not used.any()
    _, _, used = cases["a reading just inside the gate (3.8 standard deviations)"].call(step)
    assert used.all()
    mu, _, used = cases["the update turns the heading across ±π"].call(step)
    assert used.all() and -np.pi < mu[2] < -np.pi + 0.1  # turned past pi, wrapped
    across = cases["a landmark straight behind, bearing read across ±π"]
    assert np.pi - abs(across.inputs["z"][0, 1]) < 0.02
    assert cases["a landmark straight behind, bearing read across ±π"].call(step)[2].all()
