"""The diagnosis under the catalogue (``run_check``'s steps and probes), checker by checker: for a wrong
function no known mistake explains, the verdict says which step is right on its own and which input the
wrong output follows or ignores.  Each wrong function here has one mistake, chosen so that no catalogue
entry names it; each test fails when its checker's declaration (or the rule that reads it) is removed.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf
from tests.check import new_answers


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


# ------------------------------------------------------------------ invariants every right answer holds
def test_a_belief_that_does_not_sum_to_one_is_told_so():
    def unit_length(belief, likelihood):
        p = np.asarray(likelihood) * belief
        return p / np.linalg.norm(p)

    assert "your bel does not sum to 1: η = 1 / Σ p(z | x) bel̄(x) makes it" in _unnamed(
        kf.check.bayes_update(unit_length)
    )


def test_a_fused_variance_larger_than_the_surer_one_is_told_so():
    hint = _unnamed(kf.check.fuse(lambda mu1, var1, mu2, var2: (kf.fuse(mu1, var1, mu2, var2)[0], (var1 + var2) / 2)))
    assert "your var is not between 0 and the smaller of var1 and var2" in hint


def test_a_covariance_that_is_not_symmetric_is_told_so():
    def lopsided(mu, Sig, u, z, F, B, H, R, Q):
        mu, Sig = kf.kf_step(mu, Sig, u, z, F, B, H, R, Q)
        return mu, Sig + 0.01 * np.triu(np.ones_like(Sig), 1)

    assert "your Sig is not a covariance: it is not symmetric" in _unnamed(kf.check.kf_step(lopsided))


def test_an_angle_outside_the_range_is_told_so():
    def wraps_only_above(state, landmark):
        dx, dy = landmark[0] - state[0], landmark[1] - state[1]
        phi = math.atan2(dy, dx) - state[2]
        return np.array([math.hypot(dx, dy), phi - 2 * math.pi if phi > math.pi else phi])

    assert "your bearing φ lies outside (−π, π]" in _unnamed(kf.check.range_bearing(wraps_only_above))


def test_indices_past_the_last_particle_are_told_so():
    def positions_from_one(w, rng):
        c = np.cumsum(w)
        return np.searchsorted(c / c[-1], (np.arange(1, len(w) + 1) + rng.random()) / len(w), side="right")

    assert "your indices reach outside 0 … N − 1" in _unnamed(kf.check.resample_systematic(positions_from_one))


def test_the_right_numbers_in_the_wrong_places_are_told_so():
    def rows_swapped(state, landmark):
        return kf.range_bearing_jacobian(state, landmark)[::-1]

    assert "Your H holds the right numbers, some in the wrong places" in _unnamed(
        kf.check.range_bearing_jacobian(rows_swapped)
    )


def test_an_invariant_the_right_answers_break_is_a_checker_bug_not_a_verdict():
    from kfcourse.check._core import Case, Invariant, run_check

    never = Invariant(lambda inputs, parts: False, "never holds")
    with pytest.raises(AssertionError, match="the right answer breaks 'never holds'"):
        run_check(
            "fuse",
            kf.fuse,
            kf.fuse,
            [Case("one", mu1=0.0, var1=1.0, mu2=1.0, var2=1.0)],
            [],
            ("mu", "var"),
            "",
            invariants=(never,),
        )


# ------------------------------------------------------------- chapter 9's points and chapter 10's gate apart
def test_sigma_points_right_on_one_axis_and_a_diagonal_but_not_with_correlation():
    def diagonal_only(mu, Sig, lam):
        chi, wm, wc = kf.sigma_points(mu, np.diag(np.diag(Sig)), lam)
        return chi, wm, wc

    hint = _unnamed(kf.check.sigma_points(diagonal_only))
    assert "With Σ diagonal (its off-diagonal entries 0) the answer is" in hint and "yours is right there" in hint


def test_chapter_10s_step_right_without_its_gate():
    hint = _unnamed(kf.check.localization_step(new_answers.localization_gate_with_S))
    assert "With gate = ∞ (no reading refused) the answer is (1), (2), (4) and (5), without the gate (3)" in hint
    assert "without the gate (3), and yours is right there" in hint
