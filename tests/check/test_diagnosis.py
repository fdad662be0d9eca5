"""The diagnosis under the catalogue (``run_check``'s steps and probes), checker by checker: for a wrong
function no known mistake explains, the verdict says which step is right on its own and which input the
wrong output follows or ignores.  Each wrong function here has one mistake, chosen so that no catalogue
entry names it; each test fails when its checker's declaration (or the rule that reads it) is removed.
"""

from __future__ import annotations

import math

import numpy as np

import kfcourse as kf


def _unnamed(result):
    assert not result.passed and result.mistake is None, result.message
    return result.hint


# ------------------------------------------------------------ the rule: what is wrong depends on few inputs
def test_an_error_that_depends_on_one_input_alone_is_traced_to_it():
    def mu_off_by_a_tenth_of_Q(mu, var, u, z, a, b, c, R, Q):
        right_mu, right_var = kf.kf_1d_step(mu, var, u, z, a, b, c, R, Q)
        return right_mu + 0.1 * Q, right_var

    hint = _unnamed(kf.check.kf_1d_step(mu_off_by_a_tenth_of_Q))
    assert "What is wrong in your answer depends on Q alone" in hint
    assert "Q enters (3)" in hint


# ------------------------------------------------------------------ chapter 0, 1: steps of one formula
def test_drift_sigma_one_step_alone():
    hint = _unnamed(kf.check.drift_sigma(lambda step_std, n: step_std * np.sqrt(n) * 1.01))
    assert "With n = 1 the answer is one step's spread, σ₁ = σ, step_std itself, and yours is wrong there" in hint


def test_bayes_predict_no_move_and_a_pure_shift():
    def mixes_twice(belief, kernel, boundary="wall"):
        once = kf.bayes_predict(belief, kernel, boundary)
        return kf.bayes_predict(once, kernel, boundary) if len(kernel) > 1 else once

    hint = _unnamed(kf.check.bayes_predict(mixes_twice))
    assert "the answer is the belief unchanged, and yours is right there" in hint
    assert "the answer is the belief moved one cell right, nothing mixed, and yours is right there" in hint


def test_bayes_update_a_flat_likelihood():
    hint = _unnamed(kf.check.bayes_update(lambda belief, likelihood: np.asarray(likelihood) * belief * 3.0))
    assert "a likelihood of 0.5 in every cell the answer is the belief unchanged" in hint
    assert "and yours is wrong there" in hint


# ------------------------------------------------------------------ chapter 6: F alone, and R's inputs
def test_cv_model_F_alone_and_R_following_accel_var():
    def R_without_accel_var(dt, accel_var):
        F, R = kf.models.constant_velocity(dt, 2)[0], kf.sim.process_noise(dt, 1.0)
        return F, R * (accel_var > 0)

    hint = _unnamed(kf.check.cv_model(R_without_accel_var))
    assert "With σa² = 0 the answer is F = [[I, Δt I], [0, I]] with R = 0, and yours is right there" in hint
    assert "Your R does not change when accel_var changes, and the right one does" in hint


# ---------------------------------------------------------- chapter 7: each part of the pose and landmark
def test_range_bearing_without_the_heading():
    def no_heading(state, landmark):
        dx, dy = landmark[0] - state[0], landmark[1] - state[1]
        return np.array([math.hypot(dx, dy), math.atan2(dy, dx)])

    hint = _unnamed(kf.check.range_bearing(no_heading))
    assert "With the heading θ = 0 the answer is r = √q and the landmark's direction atan2(Δy, Δx) alone" in hint
    assert "Your z does not change when the heading θ changes, and the right one does" in hint


def test_a_jacobian_that_follows_the_heading():
    def H_with_heading(state, landmark):
        return kf.range_bearing_jacobian(state, landmark) * (1.0 + 0.1 * math.cos(state[2]) ** 2)

    hint = _unnamed(kf.check.range_bearing_jacobian(H_with_heading))
    assert "Your H changes when the heading θ changes, and the right one does not" in hint


# ---------------------------------------------------------------- chapter 8: the line and the turn alone
def test_unicycle_a_mistake_only_in_the_turn():
    def turns_a_little_too_far(state, u, dt):
        return kf.unicycle(state, np.array([u[0], 1.01 * u[1]]), dt)

    hint = _unnamed(kf.check.unicycle(turns_a_little_too_far))
    assert "With ω = 0 the answer is the straight line" in hint and "θ' = θ, and yours is right there" in hint
    assert "With V = 0 the answer is the turn on the spot" in hint and "wrapped, and yours is wrong there" in hint


# ------------------------------------------------------------- chapter 9: the points, the weights, the sums
def test_sigma_points_whose_weights_follow_mu():
    def weights_follow_mu(mu, Sig, lam):
        chi, wm, wc = kf.sigma_points(mu, Sig, lam)
        shift = 0.01 * float(np.sum(mu))
        return chi, wm + shift * (np.arange(len(wm)) == 0) - shift * (np.arange(len(wm)) == 1), wc

    hint = _unnamed(kf.check.sigma_points(weights_follow_mu))
    assert "Your wm changes when mu changes, and the right one does not" in hint


def test_unscented_transform_right_through_the_identity():
    def bends_the_mean(mu, Sig, f, lam):
        mu_y, Sig_y = kf.unscented_transform(mu, Sig, f, lam)
        straight = np.allclose(f(np.asarray(mu, dtype=float)), mu)
        return (mu_y if straight else 1.01 * mu_y), Sig_y

    hint = _unnamed(kf.check.unscented_transform(bends_the_mean))
    assert "With f(x) = x the answer is μ and Σ themselves" in hint and "and yours is right there" in hint


# ------------------------------------------------------------------ answers that are not numbers
def test_the_same_non_number_twice_is_the_same_answer_not_a_changing_one():
    """Called twice with the same rng, a function that returns the same text both times answers alike: its
    verdict says the answer is not a number, and does not blame the rng."""

    def text_for_large_clouds(w, rng):
        return "wrong" if len(w) > 1000 else kf.resample_systematic(w, rng)

    result = kf.check.resample_systematic(text_for_large_clouds)
    assert not result.passed and result.mistake is None, result.message
    assert "indices is not a number or an array of numbers" in result.headline
