"""The checker of chapter 12's exercise (a), ``kf.check.range_update``, and its reference ``kf.range_update``.

The package's answer passes; right answers written otherwise pass (the simple and the Joseph covariance, a
heading wrapped or left past π); every mistake of the catalogue is named, and only where every failing case
supports it; a robot exactly at the beacon must be refused with ValueError; a function that is not written
yet, raises, or returns NaN or the wrong shape gets a clear verdict.  Noise letters: R = process noise,
Q = measurement noise.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.check import range_checks as rc

WORKED = rc.WORKED


# ------------------------------------------------------------ students' answers
def _offset(mu_bar, beacon):
    dx, dy = mu_bar[0] - beacon[0], mu_bar[1] - beacon[1]
    r = math.hypot(dx, dy)
    if r == 0.0:
        raise ValueError("beacon: the robot stands on the beacon, r = 0")
    return dx, dy, r


def simple_form(mu_bar, Sig_bar, z, beacon, Q):
    """(I − KH)Σ̄, K with np.linalg.inv."""
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


def joseph_form(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = np.linalg.solve(H @ Sig_bar @ H.T + Q, H @ Sig_bar).T
    A = np.eye(3) - K @ H
    return mu_bar + K @ (z - r), A @ Sig_bar @ A.T + K @ Q @ K.T


def wrapped(mu_bar, Sig_bar, z, beacon, Q):
    """The heading wrapped into (−π, π] after the update."""
    mu, Sig = simple_form(mu_bar, Sig_bar, z, beacon, Q)
    return np.array([mu[0], mu[1], kf.wrap_angle(mu[2])]), Sig


def with_the_package(mu_bar, Sig_bar, z, beacon, Q):
    h, H = partial(kf.models.range_only, beacon=beacon), partial(kf.models.range_only_jacobian, beacon=beacon)
    return kf.ekf_update(mu_bar, Sig_bar, z, h, H, Q)


def _knobs(**mistake):
    return lambda *args: rc._update_with(*args, **mistake)


def _refusing(fn):
    """``fn`` with the exercise's refusal of r = 0 in front (the catalogue's wrong versions divide 0 by 0 there)."""

    def refusing(mu_bar, Sig_bar, z, beacon, Q):
        _offset(mu_bar, beacon)
        return fn(mu_bar, Sig_bar, z, beacon, Q)

    return refusing


def no_guard(mu_bar, Sig_bar, z, beacon, Q):
    """Right everywhere but at the beacon, where numpy's 0/0 gives NaN."""
    d = np.asarray(mu_bar[:2]) - np.asarray(beacon)
    r = np.sqrt(d @ d)
    H = np.array([[d[0] / r, d[1] / r, 0.0]])
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


def skips_at_beacon(mu_bar, Sig_bar, z, beacon, Q):
    if np.array_equal(np.asarray(mu_bar[:2]), np.asarray(beacon)):
        return mu_bar, Sig_bar
    return simple_form(mu_bar, Sig_bar, z, beacon, Q)


def zero_division_at_beacon(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy = float(mu_bar[0] - beacon[0]), float(mu_bar[1] - beacon[1])
    r = math.hypot(dx, dy)
    H = np.array([[dx / r, dy / r, 0.0]])  # Python floats: ZeroDivisionError at r = 0
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


RIGHT = [simple_form, joseph_form, wrapped, with_the_package, kf.range_update]

#: (a student's wrong answer, the mistake it must be named as): every key the checker knows.
WRONG = [
    (_refusing(_knobs(H_sign=True)), "shift_wrong_way"),
    (_refusing(_knobs(innovation_sign=True)), "shift_wrong_way"),
    (_refusing(_knobs(noise="none")), "forgot_Q"),
    (_refusing(_knobs(noise="squared")), "std_not_var"),
    (_refusing(_knobs(noise="root")), "std_not_var"),
    (_refusing(_knobs(z_hat_q=True)), "q_not_sqrt_q"),
    (_refusing(_knobs(H_over="q")), "q_not_sqrt_q"),
    (_refusing(_knobs(z_hat_q=True, H_over="q/2")), "q_not_sqrt_q"),
    (_refusing(_knobs(H_over="1")), "H_not_unit"),
    (_refusing(_knobs(H_swapped=True)), "dx_dy_swapped"),
    (_refusing(_knobs(H_theta=-1.0)), "heading_in_H"),
    (_refusing(_knobs(H_theta=1.0)), "heading_in_H"),
    (_refusing(_knobs(no_inverse=True)), "no_inverse"),
    (_refusing(_knobs(covariance_sign=True)), "sign_flip"),
    (_refusing(_knobs(Sig="right_side")), "wrong_order"),
    (_refusing(_knobs(Sig="no_Sig_bar")), "no_Sig_bar"),
    (_refusing(_knobs(Sig="unchanged")), "Sig_not_updated"),
    (_refusing(_knobs(heading_held=True)), "heading_held"),
    (_refusing(_knobs(K_heading_zero=True)), "heading_held"),
    (_refusing(rc._dot_not_outer), "dot_not_outer"),
    (lambda *args: tuple(reversed(kf.range_update(*args))), "outputs_swapped"),
    (no_guard, "r_zero_not_refused"),
    (skips_at_beacon, "r_zero_not_refused"),
]

#: The keys the MISTAKES block "chapter 12" adds.
NEW_KEYS = {
    "H_not_unit",
    "heading_in_H",
    "no_Sig_bar",
    "Sig_not_updated",
    "heading_held",
    "dot_not_outer",
    "r_zero_not_refused",
}


# ------------------------------------------------------------ the reference
def test_the_checker_and_its_reference_are_exported():
    assert "range_update" in kf.check.__all__ and "range_update" in kf.__all__


def test_the_reference_is_the_ekf_update_with_the_range_only_model():
    mu, Sig = kf.range_update(*WORKED.values())
    # r = 5, H = [-0.8, -0.6, 0], S = 0.5 + 0.25 = 0.75, K = [-0.4, -0.3, 0] / 0.75, nu = 0.35
    np.testing.assert_allclose(mu, [2.0 - 0.4 * 0.35 / 0.75, 1.0 - 0.3 * 0.35 / 0.75, 0.3], rtol=1e-12)
    np.testing.assert_allclose(
        Sig, [[0.5 - 0.16 / 0.75, -0.12 / 0.75, 0], [-0.12 / 0.75, 0.5 - 0.09 / 0.75, 0], [0, 0, 0.1]]
    )
    for case in rc._cases(np.random.default_rng(1)):
        for got, want in zip(case.call(kf.range_update), case.call(with_the_package), strict=True):
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15)


def test_the_reference_refuses_a_robot_at_the_beacon_by_name():
    with pytest.raises(ValueError, match=r"^beacon must not sit exactly at the robot's position"):
        rc.AT_BEACON.call(kf.range_update)


# ------------------------------------------------------------ right answers pass
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_package_function_passes(seed):
    result = kf.check.range_update(kf.range_update, seed=seed)
    assert result.passed and result.mistake is None, result.message
    assert result.message.startswith("✔ range_update matches kf.range_update on all 16 cases")
    assert "refuses a robot exactly at the beacon (r = 0) with ValueError" in result.message


@pytest.mark.parametrize("fn", RIGHT, ids=lambda fn: fn.__name__)
def test_a_right_answer_written_differently_passes(fn):
    result = kf.check.range_update(fn)
    assert result.passed, result.message


def test_it_opens_with_the_chapter_worked_example():
    result = kf.check.range_update(kf.range_update)
    assert result.message.split(": ", 1)[1].startswith("chapter 12's worked example"), result.message
    first = rc._cases(np.random.default_rng(0))[0]
    assert first.label.startswith("chapter 12's worked example: r = 5")
    assert kf.models.range_only(first.inputs["mu_bar"], first.inputs["beacon"])[0] == 5.0


# ------------------------------------------------------------ the heading: by whole turns, never held
def test_a_heading_whole_turns_away_passes_and_half_a_turn_fails():
    def turned(by):
        def fn(*args):
            mu, Sig = kf.range_update(*args)
            return mu + np.array([0.0, 0.0, by]), Sig

        return fn

    assert kf.check.range_update(turned(2 * np.pi)).passed
    assert kf.check.range_update(turned(-4 * np.pi)).passed
    result = kf.check.range_update(turned(np.pi))
    assert not result.passed and "mu has the wrong value at [2]" in result.headline


def test_the_cases_do_what_their_labels_say():
    cases = {c.label.split(":")[0].split(" (")[0]: c for c in rc._cases(np.random.default_rng(0))}
    worked = cases["chapter 12's worked example"]
    assert worked.call(kf.range_update)[0][2] == worked.inputs["mu_bar"][2]  # no correlation: θ unchanged
    correlated = cases["the worked example with θ correlated with x"]
    assert abs(correlated.call(kf.range_update)[0][2] - 0.3) > 0.01  # the range moves the heading
    as_predicted = cases["a reading exactly as predicted, z = r"]
    mu, Sig = as_predicted.call(kf.range_update)
    np.testing.assert_array_equal(mu, as_predicted.inputs["mu_bar"])
    assert np.trace(Sig) < np.trace(as_predicted.inputs["Sig_bar"])
    ahead = cases["a beacon straight ahead along the heading"]
    offset = ahead.inputs["beacon"] - ahead.inputs["mu_bar"][:2]
    assert math.isclose(math.atan2(offset[1], offset[0]), ahead.inputs["mu_bar"][2])
    north = cases["a beacon due north"]
    np.testing.assert_allclose(
        kf.models.range_only_jacobian(north.inputs["mu_bar"], north.inputs["beacon"]), [[0, -1, 0]]
    )
    past_pi = cases["the update turns the heading past π"]
    assert past_pi.inputs["mu_bar"][2] < np.pi < past_pi.call(kf.range_update)[0][2]
    tiny = cases["a tiny range, r = 1e-6"]
    r = kf.models.range_only(tiny.inputs["mu_bar"], tiny.inputs["beacon"])[0]
    H = kf.models.range_only_jacobian(tiny.inputs["mu_bar"], tiny.inputs["beacon"])
    assert 0.9e-6 < r < 1.1e-6 and math.isclose(np.linalg.norm(H), 1.0)
    assert cases["a large Q"].inputs["Q"][0, 0] == 400.0


def test_a_heading_held_is_named_only_where_theta_is_correlated():
    """Held fixed, the heading is right on every case whose Σ̄ has no θ correlation: the name rests on the others."""
    result = kf.check.range_update(_refusing(_knobs(heading_held=True)))
    assert result.mistake == "heading_held" and "θ correlated with x" in result.headline, result.message


# ------------------------------------------------------------ the catalogue
@pytest.mark.parametrize(("fn", "mistake"), WRONG, ids=[f"{m}-{i}" for i, (_, m) in enumerate(WRONG)])
def test_a_known_mistake_is_named(fn, mistake):
    result = kf.check.range_update(fn)
    assert not result.passed
    assert result.mistake == mistake, result.message
    assert result.message.startswith("✘")
    assert f"Likely mistake: {kf.check.MISTAKES[mistake]}" in result.message
    assert "inputs:" in result.message and "expected:" in result.message
    assert "chapter 12" in result.hint


def test_every_mistake_the_checker_knows_is_exercised(monkeypatch):
    seen = {}

    def record(name, student_fn, reference, cases, variants, *args, **kwargs):
        seen.update(cases=cases, variants=variants)
        return kf.check.CheckResult(False, None, "recorded")

    monkeypatch.setattr(rc, "run_check", record)
    kf.check.range_update(kf.range_update)
    known = {variant.mistake for variant in seen["variants"]} | {"outputs_swapped", "r_zero_not_refused"}
    assert known == {mistake for _, mistake in WRONG}
    assert known <= set(kf.check.MISTAKES)
    assert NEW_KEYS <= known


def test_the_two_wrong_ways_cannot_be_told_apart_and_are_one_name():
    """H with the sign of b − p and the innovation ẑ − z give one answer everywhere (K's sign flips, Σ does not)."""
    cases = rc._cases(np.random.default_rng(0))
    for case in cases:
        a, b = case.call(_knobs(H_sign=True)), case.call(_knobs(innovation_sign=True))
        for x, y in zip(a, b, strict=True):
            np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-14)
    result = kf.check.range_update(_refusing(_knobs(H_sign=True)))
    assert "ν is ẑ − z, or H has the sign of b − p" in result.hint
    assert "mu has the wrong value" in result.headline and "(Sig is right)" in result.headline


def test_a_wrong_answer_no_mistake_explains_is_not_named_and_says_what_it_breaks():
    def grows(mu_bar, Sig_bar, z, beacon, Q):  # the Joseph form with (I + KH): Σ grows
        mu, _ = kf.range_update(mu_bar, Sig_bar, z, beacon, Q)
        H = kf.models.range_only_jacobian(mu_bar, beacon)
        K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
        A = np.eye(3) + K @ H
        return mu, A @ Sig_bar @ A.T + K @ Q @ K.T

    result = kf.check.range_update(grows)
    assert not result.passed and result.mistake is None, result.message
    assert "No known mistake gives this answer" in result.hint
    assert "your Sig is larger than Sig_bar in some direction" in result.hint
    assert "With z = ẑ = ‖p − b‖ (the reading exactly as predicted)" in result.hint


def test_an_epsilon_in_r_fails_on_the_tiny_range():
    def epsilon(mu_bar, Sig_bar, z, beacon, Q):
        dx, dy = mu_bar[0] - beacon[0], mu_bar[1] - beacon[1]
        r = math.hypot(dx, dy) + 1e-6
        H = np.array([[dx / r, dy / r, 0.0]])
        K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
        return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar

    assert not kf.check.range_update(epsilon).passed


# ------------------------------------------------------------ a robot exactly at the beacon
def test_nan_at_the_beacon_fails_with_a_clear_verdict():
    result = kf.check.range_update(no_guard)
    assert not result.passed and result.mistake == "r_zero_not_refused", result.message
    assert "matches kf.range_update on all 16 cases, but on one more, a robot exactly at the beacon" in result.headline
    assert "it returned an answer with NaN in it" in result.headline
    assert "raise ValueError" in result.hint and "Traceback" not in result.message


def test_an_answer_at_the_beacon_fails():
    result = kf.check.range_update(skips_at_beacon)
    assert not result.passed and result.mistake == "r_zero_not_refused", result.message
    assert result.headline.endswith("it returned an answer.")


def test_something_else_at_the_beacon_fails_unnamed():
    def says_so(*args):
        return "the robot is on the beacon" if np.array_equal(args[0][:2], args[3]) else kf.range_update(*args)

    result = kf.check.range_update(says_so)
    assert not result.passed and result.mistake is None, result.message
    assert result.headline.endswith("it returned one str.") and "raise ValueError" in result.hint


def test_another_error_at_the_beacon_fails_unnamed():
    result = kf.check.range_update(zero_division_at_beacon)
    assert not result.passed and result.mistake is None, result.message
    assert "it raised ZeroDivisionError" in result.headline and "Refuse it with a ValueError" in result.hint
    assert "raised in zero_division_at_beacon" in result.details


# ------------------------------------------------------------ functions that misbehave
def test_not_yet_is_no_failure():
    def range_update(mu_bar, Sig_bar, z, beacon, Q):
        raise NotImplementedError("your turn")

    result = kf.check.range_update(range_update)
    assert result.passed is False and result.mistake is None and "Not yet" in result.message


@pytest.mark.parametrize(
    ("fn", "says"),
    [
        (lambda mu_bar, Sig_bar, z, beacon, Q: mu_bar, "expected 2 values (mu, Sig)"),
        (lambda mu_bar, Sig_bar, z, beacon, Q: (mu_bar[:2], Sig_bar), "mu has shape (2,); expected (3,)"),
        (lambda mu_bar, Sig_bar, z, beacon, Q: (mu_bar, np.full((3, 3), np.nan)), "Sig contains NaN"),
        (lambda mu_bar, Sig_bar, z, beacon, Q: (mu_bar + Sig_bar @ beacon, Sig_bar), "it raised ValueError"),
    ],
)
def test_a_misbehaving_function_gets_a_clear_verdict(fn, says):
    result = kf.check.range_update(fn)
    assert not result.passed and says in result.message, result.message
    assert "Traceback" not in result.message


def test_a_function_that_changes_its_input_is_named():
    def in_place(mu_bar, Sig_bar, z, beacon, Q):
        mu, Sig = kf.range_update(mu_bar, Sig_bar, z, beacon, Q)
        mu_bar[:] = mu
        return mu_bar, Sig

    result = kf.check.range_update(in_place)
    assert result.mistake == "changes_input" and "mu_bar" in result.headline, result.message


def test_anything_but_a_function_is_refused_by_its_own_name():
    with pytest.raises(ValueError, match=r"kf.check.range_update\(my_range_update\)"):
        kf.check.range_update(42)
