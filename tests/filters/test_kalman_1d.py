"""The scalar Kalman filter (chapters 3 and 4): ``kf_1d_predict``, ``kf_1d_gain``,
``kf_1d_update``, ``kf_1d_cycle``, ``kf_1d_step`` and ``steady_state_1d``.  The
lesson's cycles, gain limits and steady state, hand-built fixed points with a, c != 1,
the lesson's equations for any input, and the bad input they refuse.

Where the lesson prints a rounded number, the test rounds the package's output the
same way (3 decimal places) and compares with the printed value; the exact value is
checked too wherever the lesson's rounding hides something.
"""

from __future__ import annotations

import itertools
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kfcourse as kf
from tests.filters.strategies import (
    FAST,
    INF,
    NAN,
    assert_raises_naming,
    assert_raises_saying,
    assert_unique_ids,
    bad_input_cases,
    r3,
    reals,
)


# ================================================================ worked numbers (chapters 3 and 4)
def test_ch3_cycle_one():
    c = kf.kf_1d_cycle(2.0, 0.40, u=1.0, z=3.6, R=0.20, Q=0.10)
    assert c.mu_bar == pytest.approx(3.0, abs=1e-12)
    assert c.var_bar == pytest.approx(0.60, abs=1e-12)
    assert c.innovation == pytest.approx(0.6, abs=1e-12)
    assert (r3(c.K), r3(c.mu), r3(c.var)) == (0.857, 3.514, 0.086)
    assert c.K == pytest.approx(6 / 7, rel=1e-12)  # 0.60 / 0.70


def test_ch3_kf_1d_step_reproduces_the_lesson_print():
    mu, var = kf.kf_1d_step(2.0, 0.4, u=1.0, z=3.6, R=0.2, Q=0.1)
    assert (r3(mu), r3(var)) == (3.514, 0.086)


def test_ch3_kf_1d_step_defaults_are_the_lessons():
    # a = b = c = 1, R = 0.2, Q = 0.1 by default, written out by hand:
    # var_bar = 0.4 + 0.2 = 0.6, K = 0.6 / 0.7 = 6/7, mu = 3 + 6/7 * 0.6, var = (1 - 6/7) 0.6 = 0.6/7
    mu, var = kf.kf_1d_step(2.0, 0.4, 1.0, 3.6)
    assert mu == pytest.approx(3.0 + 6.0 / 7.0 * 0.6, rel=1e-14)
    assert var == pytest.approx(0.6 / 7.0, rel=1e-14)
    # a default that is not 1 would show: with a = 2 the prediction is 2 * 2 + 1 = 5, not 3
    assert kf.kf_1d_cycle(2.0, 0.4, 1.0, None, a=2.0).mu_bar == pytest.approx(5.0, abs=1e-14)
    assert r3(mu) == 3.514


def test_ch3_cycle_two_continues_from_cycle_one():
    mu, var = kf.kf_1d_step(2.0, 0.40, u=1.0, z=3.6, R=0.20, Q=0.10)
    c = kf.kf_1d_cycle(mu, var, u=1.0, z=4.7, R=0.20, Q=0.10)
    assert r3(c.mu_bar) == 4.514
    assert (r3(c.var_bar), r3(c.K), r3(c.mu), r3(c.var)) == (0.286, 0.741, 4.652, 0.074)
    assert kf.kf_1d_step(mu, var, 1.0, 4.7, R=0.20, Q=0.10) == pytest.approx((c.mu, c.var), rel=1e-14)


def test_ch3_predict_only_tick_skips_the_update():
    c = kf.kf_1d_cycle(2.0, 0.40, u=1.0, z=None, R=0.20, Q=0.10)
    assert (c.mu, c.var, c.K) == pytest.approx((3.0, 0.60, 0.0), abs=1e-12)


def test_ch4_gain_limit_trust_the_measurement():
    # var_bar = 10, Q = 0.01 -> K = 10 / 10.01
    c = kf.kf_1d_cycle(0.0, 10.0, u=0.0, z=1.0, R=0.0, Q=0.01)
    assert r3(c.K) == 0.999
    assert c.mu == pytest.approx(c.K * 1.0) and c.mu > 0.998  # essentially the raw reading
    _, K = kf.kf_gain([[10.0]], [[1.0]], [[0.01]])
    assert K[0, 0] == pytest.approx(10 / 10.01, rel=1e-12)


def test_ch4_gain_limit_trust_the_prediction():
    # var_bar = 0.01, Q = 10 -> K = 0.01 / 10.01
    c = kf.kf_1d_cycle(0.0, 0.01, u=0.0, z=1.0, R=0.0, Q=10.0)
    assert r3(c.K) == 0.001
    assert c.mu < 0.002  # the noisy reading barely moves the estimate
    _, K = kf.kf_gain([[0.01]], [[1.0]], [[10.0]])
    assert K[0, 0] == pytest.approx(0.01 / 10.01, rel=1e-12)


STATIC = {"a": 1.0, "b": 0.0, "R": 0.04, "Q": 0.25}  # a robot at rest


def test_ch4_steady_state_ticks():
    var, gains, post = 4.0, [], []
    for _ in range(4):
        c = kf.kf_1d_cycle(0.0, var, u=0.0, z=0.0, **STATIC)
        gains.append(r3(c.K))
        post.append(r3(c.var))
        var = c.var
    assert gains == [0.942, 0.524, 0.406, 0.362]
    # The lesson's table shows 0.091 at tick 4 because it carried rounded values forward.
    assert post == [0.235, 0.131, 0.102, 0.090]


def test_ch4_steady_state_values():
    K, P_prior, P_post = kf.steady_state_1d(0.04, 0.25)
    assert (r3(K), r3(P_prior), r3(P_post)) == (0.328, 0.122, 0.082)
    # closed form for a = c = 1: P = (R + sqrt(R^2 + 4 R Q)) / 2
    assert P_prior == pytest.approx((0.04 + math.sqrt(0.04**2 + 4 * 0.04 * 0.25)) / 2, rel=1e-12)
    assert K == pytest.approx(P_prior / (P_prior + 0.25), rel=1e-12)
    assert P_post == pytest.approx((1 - K) * P_prior, rel=1e-12)


def test_ch4_steady_state_is_a_fixed_point_of_one_cycle():
    K, P_prior, P_post = kf.steady_state_1d(0.04, 0.25)
    c = kf.kf_1d_cycle(0.0, P_post, u=0.0, z=0.0, **STATIC)
    assert c.var_bar == pytest.approx(P_prior, rel=1e-12)
    assert c.K == pytest.approx(K, rel=1e-12)
    assert c.var == pytest.approx(P_post, rel=1e-12)


def test_ch4_iterating_converges_to_the_steady_state():
    K, _, P_post = kf.steady_state_1d(0.04, 0.25)
    var, errors = 4.0, []
    for _ in range(60):
        c = kf.kf_1d_cycle(0.0, var, u=0.0, z=0.0, **STATIC)
        var = c.var
        errors.append(abs(c.K - K))
    assert var == pytest.approx(P_post, rel=1e-10)
    assert errors[-1] < 1e-12
    assert all(b <= a for a, b in itertools.pairwise(errors))  # monotone from a vague prior


# ================================================================ closed forms
# Hand-built fixed points of P = a^2 P Q / (c^2 P + Q) + R (the prior variance):
#  a = 0.5, c = 1, Q = 4, P = 4: a^2 * 16 / 8 = 0.5, so R = 3.5; K = 4 / 8 = 0.5; post (1 - 0.5) 4 = 2
#  a = 1,   c = 2, Q = 4, P = 1: 1 * 4 / 8 = 0.5, so R = 0.5; K = 2 / 8 = 0.25; post (1 - 0.5) 1 = 0.5
#  a = -0.5, c = 2, Q = 8, P = 2: 0.25 * 16 / 16 = 0.25, so R = 1.75; K = 4 / 16 = 0.25; post 0.5 * 2 = 1
@pytest.mark.parametrize(
    ("R", "Q", "a", "c", "expected"),
    [
        (3.5, 4.0, 0.5, 1.0, (0.5, 4.0, 2.0)),
        (0.5, 4.0, 1.0, 2.0, (0.25, 1.0, 0.5)),
        (1.75, 8.0, -0.5, 2.0, (0.25, 2.0, 1.0)),
    ],
)
def test_steady_state_1d_closed_form_with_a_and_c(R, Q, a, c, expected):
    assert kf.steady_state_1d(R, Q, a=a, c=c) == pytest.approx(expected, rel=1e-12)


def test_steady_state_1d_without_a_measurement():
    # c = 0, |a| < 1: P = a^2 P + R, so P = R / (1 - a^2) = 0.75 / 0.75 = 1, and K = 0
    assert kf.steady_state_1d(0.75, 1.0, a=0.5, c=0.0) == pytest.approx((0.0, 1.0, 1.0), abs=1e-14)


# ================================================================ properties
@settings(max_examples=100, deadline=None)
@given(R=reals(1e-3, 10), Q=reals(1e-3, 10), a=reals(-1.5, 1.5), c=st.one_of(reals(-3, -0.1), reals(0.1, 3)))
def test_steady_state_1d_is_the_fixed_point_of_the_riccati_map(R, Q, a, c):
    K, P, P_post = kf.steady_state_1d(R, Q, a=a, c=c)
    # written out here, not through kfcourse: one predict and one update from P_post
    P_bar = a * a * P_post + R
    K_next = c * P_bar / (c * c * P_bar + Q)
    assert P_bar == pytest.approx(P, rel=1e-9)
    assert K_next == pytest.approx(K, rel=1e-9)
    assert (1 - K * c) * P == pytest.approx(P_post, rel=1e-9)
    # ... and kf_1d_cycle agrees with that fixed point
    cyc = kf.kf_1d_cycle(0.0, P_post, 0.0, 0.0, a=a, b=1.0, c=c, R=R, Q=Q)
    assert (cyc.var_bar, cyc.K, cyc.var) == pytest.approx((P, K, P_post), rel=1e-9)


@FAST
@given(
    mu=reals(-10, 10),
    var=reals(0, 5),
    u=reals(-2, 2),
    z=reals(-10, 10),
    a=reals(-2, 2),
    b=reals(-2, 2),
    c=reals(-2, 2),
    R=reals(0, 2),
    Q=reals(0.01, 2),
)
def test_kf_1d_cycle_fields_follow_the_lesson_equations(mu, var, u, z, a, b, c, R, Q):
    cyc = kf.kf_1d_cycle(mu, var, u, z, a=a, b=b, c=c, R=R, Q=Q)
    assert cyc.mu_bar == pytest.approx(a * mu + b * u, abs=1e-12)
    assert cyc.var_bar == pytest.approx(a * a * var + R, rel=1e-12, abs=1e-15)
    assert cyc.innovation == pytest.approx(z - c * cyc.mu_bar, abs=1e-11)
    assert cyc.K == pytest.approx(c * cyc.var_bar / (c * c * cyc.var_bar + Q), rel=1e-12, abs=1e-15)
    assert cyc.mu == pytest.approx(cyc.mu_bar + cyc.K * cyc.innovation, abs=1e-11)
    assert cyc.var == pytest.approx(cyc.var_bar * Q / (c * c * cyc.var_bar + Q), rel=1e-9, abs=1e-15)
    assert kf.kf_1d_step(mu, var, u, z, a=a, b=b, c=c, R=R, Q=Q) == (cyc.mu, cyc.var)


def test_one_dimensional_steps_agree_with_the_cycle():
    """kf_1d_cycle is kf_1d_predict, kf_1d_gain and kf_1d_update in a row (valid inputs)."""
    cyc = kf.kf_1d_cycle(2.0, 0.4, 1.0, 3.6, a=0.9, b=1.1, c=1.2, R=0.3, Q=0.2)
    mu_bar, var_bar = kf.kf_1d_predict(2.0, 0.4, 1.0, a=0.9, b=1.1, R=0.3)
    assert (mu_bar, var_bar) == (cyc.mu_bar, cyc.var_bar)
    assert kf.kf_1d_gain(var_bar, c=1.2, Q=0.2) == cyc.K
    assert kf.kf_1d_update(mu_bar, var_bar, 3.6, c=1.2, Q=0.2) == (cyc.mu, cyc.var)
    assert cyc.mu != cyc.mu_bar and cyc.var < cyc.var_bar  # the update did something


# ================================================================ bad input
BAD_INPUT = [
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, kw=kw: fn(**{**dict(mu=2.0, var=0.4, u=1.0, z=3.6), **kw})), arg)
        for fn in (kf.kf_1d_step, kf.kf_1d_cycle)
        for label, kw, arg in [
            ("var negative", {"var": -0.4}, "var"),
            ("var NaN", {"var": NAN}, "var"),
            ("R negative", {"R": -0.2}, "R"),
            ("Q negative", {"Q": -0.1}, "Q"),
            ("Q inf", {"Q": INF}, "Q"),
            ("Q zero with exact prediction", {"var": 0.0, "R": 0.0, "Q": 0.0}, "Q"),
            ("mu NaN", {"mu": NAN}, "mu"),
            ("z inf", {"z": INF}, "z"),
            ("u vector", {"u": [1.0, 2.0]}, "u"),
            ("a NaN", {"a": NAN}, "a"),
            ("c not a number", {"c": "one"}, "c"),
        ]
    ],
    ("kf_1d_predict/var negative", lambda: kf.kf_1d_predict(2.0, -0.4, 1.0), "var"),
    ("kf_1d_step/z a string of digits", lambda: kf.kf_1d_step(2.0, 0.4, 1.0, "3.6"), "z"),
    ("kf_1d_step/mu a list with a string", lambda: kf.kf_1d_step(["2.0"], 0.4, 1.0, 3.6), "mu"),
    ("kf_1d_predict/mu NaN", lambda: kf.kf_1d_predict(NAN, 0.4, 1.0), "mu"),
    ("kf_1d_predict/u vector", lambda: kf.kf_1d_predict(2.0, 0.4, [1.0, 2.0]), "u"),
    ("kf_1d_predict/a inf", lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, a=INF), "a"),
    ("kf_1d_predict/b not a number", lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, b="one"), "b"),
    ("kf_1d_predict/R negative", lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, R=-0.2), "R"),
    ("kf_1d_gain/var_bar negative", lambda: kf.kf_1d_gain(-0.6), "var_bar"),
    ("kf_1d_gain/var_bar NaN", lambda: kf.kf_1d_gain(NAN), "var_bar"),
    ("kf_1d_gain/c inf", lambda: kf.kf_1d_gain(0.6, c=INF), "c"),
    ("kf_1d_gain/Q negative", lambda: kf.kf_1d_gain(0.6, Q=-0.1), "Q"),
    ("kf_1d_gain/Q zero with exact prediction", lambda: kf.kf_1d_gain(0.0, Q=0.0), "Q"),
    ("kf_1d_update/mu_bar inf", lambda: kf.kf_1d_update(INF, 0.6, 3.6), "mu_bar"),
    ("kf_1d_update/var_bar negative", lambda: kf.kf_1d_update(3.0, -0.6, 3.6), "var_bar"),
    ("kf_1d_update/z NaN", lambda: kf.kf_1d_update(3.0, 0.6, NAN), "z"),
    ("kf_1d_update/z None", lambda: kf.kf_1d_update(3.0, 0.6, None), "z"),
    ("kf_1d_update/c vector", lambda: kf.kf_1d_update(3.0, 0.6, 3.6, c=[1.0, 1.0]), "c"),
    ("kf_1d_update/Q NaN", lambda: kf.kf_1d_update(3.0, 0.6, 3.6, Q=NAN), "Q"),
    ("steady_state_1d/R negative", lambda: kf.steady_state_1d(-0.04, 0.25), "R"),
    ("steady_state_1d/Q NaN", lambda: kf.steady_state_1d(0.04, NAN), "Q"),
    ("steady_state_1d/R and Q zero", lambda: kf.steady_state_1d(0.0, 0.0), "R"),
    ("steady_state_1d/c zero, a unstable", lambda: kf.steady_state_1d(0.04, 0.25, a=1.0, c=0.0), "c"),
    ("steady_state_1d/a inf", lambda: kf.steady_state_1d(0.04, 0.25, a=INF), "a"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.kf_1d_step(mu=2.0, var=0.4, u=1.0, z=3.6)
    kf.steady_state_1d(0.04, 0.25)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: kf.kf_1d_predict(2.0, 0.4, 1.0, R=-0.2), "R must be a variance >= 0"),
        (lambda: kf.kf_1d_gain(-0.6), "var_bar must be a variance >= 0"),
    ],
)
def test_message_says_what_the_argument_is(call, message):
    """A step, a distance or a standard deviation is not called a variance."""
    assert_raises_saying(call, message)
