"""Angles on the circle, in ``kfcourse.models``: ``wrap_angle`` (any angle into (-pi, pi],
of one number and of an array by one formula, bit for bit, the same whole number of
turns away, and NaN or inf refused), the residuals ``pose_residual`` and
``range_bearing_residual`` (differences the short way round) and the circular means
``pose_mean`` and ``range_bearing_mean`` (the filters' angle hooks), and the bad input
they refuse.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse import models
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual
from tests.filters.strategies import (
    FAST,
    INF,
    NAN,
    POSE,
    TWO_PI,
    angle_gap,
    assert_raises_naming,
    assert_unique_ids,
    bad_input_cases,
    reals,
)

# ================================================================ worked numbers
# none of their own: the lesson wraps bearings and headings through the models (test_models.py)


# ================================================================ closed forms
def test_wrap_angle_closed_form():
    assert kf.wrap_angle(1.5 * math.pi) == pytest.approx(-0.5 * math.pi, abs=1e-15)
    assert kf.wrap_angle(-math.pi) == math.pi  # the interval is (-pi, pi]
    np.testing.assert_allclose(kf.wrap_angle(np.array([7.0, -7.0])), [7.0 - TWO_PI, TWO_PI - 7.0], atol=1e-15)


def test_residual_closed_forms_wrap_the_angle():
    # (pi - 0.1) - (-pi + 0.1) = 2 pi - 0.2 -> -0.2
    np.testing.assert_allclose(
        pose_residual([1.0, 2.0, math.pi - 0.1], [0.5, 3.0, -math.pi + 0.1]), [0.5, -1.0, -0.2], atol=1e-14
    )
    np.testing.assert_allclose(range_bearing_residual([5.0, -3.0], [4.0, 3.0]), [1.0, TWO_PI - 6.0], atol=1e-14)


def test_circular_means_closed_form_across_pi():
    # two headings 0.1 either side of pi: the mean heading is pi, not 0 (the linear average)
    pts = np.array([[0.0, 0.0, math.pi - 0.1], [2.0, 4.0, -math.pi + 0.1]])
    m = pose_mean(pts, [0.5, 0.5])
    np.testing.assert_allclose(m[:2], [1.0, 2.0], atol=1e-15)
    assert angle_gap(m[2], math.pi) < 1e-12
    # weights 1/4, 3/4 of headings pi/2 and 0: atan2(1/4, 3/4)
    m = pose_mean(np.array([[0.0, 0.0, math.pi / 2], [4.0, 0.0, 0.0]]), [0.25, 0.75])
    assert m[2] == pytest.approx(math.atan2(0.25, 0.75), abs=1e-15)
    rb = range_bearing_mean(np.array([[4.0, math.pi - 0.2], [6.0, -math.pi + 0.2]]), [0.5, 0.5])
    assert rb[0] == pytest.approx(5.0, abs=1e-15) and angle_gap(rb[1], math.pi) < 1e-12


# ================================================================ properties
@settings(max_examples=300, deadline=None)
@given(a=reals(-1e6, 1e6))
@example(a=math.pi)
@example(a=-math.pi)
@example(a=float(np.nextafter(-math.pi, 0.0)))
@example(a=float(np.nextafter(math.pi, 4.0)))
@example(a=3 * math.pi)
@example(a=-3 * math.pi)
@example(a=0.0)
def test_wrap_angle_range_and_congruence(a):
    w = kf.wrap_angle(a)
    assert isinstance(w, float)
    assert -math.pi < w <= math.pi
    k = (a - w) / (2 * math.pi)  # a whole number of turns
    assert abs(k - round(k)) <= 1e-15 * (1.0 + abs(a)) / (2 * math.pi) * 8
    if -math.pi < a <= math.pi:
        assert w == a  # an angle already in range is left alone


@settings(max_examples=100, deadline=None)
@given(a=st.floats(allow_nan=False, allow_infinity=False))
def test_wrap_angle_range_for_any_finite_float(a):
    assert -math.pi < kf.wrap_angle(a) <= math.pi


@FAST
@given(angles=st.lists(reals(-1e4, 1e4), min_size=1, max_size=30))
def test_wrap_angle_array_elementwise(angles):
    a = np.array(angles)
    w = kf.wrap_angle(a)
    assert isinstance(w, np.ndarray) and w.shape == a.shape
    assert np.all((w > -np.pi) & (w <= np.pi))
    np.testing.assert_array_equal(w, [kf.wrap_angle(x) for x in angles])


@FAST
@given(a=reals(-3 * math.pi, 3 * math.pi))
@example(a=-6.113747517288847)  # the modulo's pi - ((pi - a) mod 2 pi) rounds this one in its last bit
def test_an_angle_within_a_turn_of_the_range_takes_exactly_one_turn(a):
    """(pi, 3 pi] and (-3 pi, -pi] come back by one 2 pi, with no rounding: a and 2 pi are within a factor 2."""
    turns = 0.0 if -math.pi < a <= math.pi else math.copysign(TWO_PI, a)
    if -math.pi < a - turns <= math.pi:
        assert kf.wrap_angle(a) == a - turns
        assert kf.wrap_angle(np.array([a]))[0] == a - turns


def _edge_angles() -> np.ndarray:
    """Angles at and next to the ends of (-pi, pi] and its copies, huge ones, and ones whose mod rounds to 2 pi."""
    ends = np.array([k * math.pi for k in range(-9, 10)] + [1e16, -1e16, 1e300, -1e300, 2.0**53, -(2.0**53)])
    near = np.concatenate([np.nextafter(ends, np.inf), np.nextafter(ends, -np.inf)])
    tiny = np.array([0.0, -0.0, 5e-324, -5e-324, 1e-300, -1e-300, np.finfo(float).max, -np.finfo(float).max])
    return np.concatenate([ends, near, tiny, math.pi + 1e-16 * np.arange(-8, 9)])


def test_wrap_angle_of_one_number_equals_the_array_formula_bit_for_bit():  # as before: one formula
    rng = np.random.default_rng(0)
    angles = np.concatenate(
        [
            _edge_angles(),
            rng.normal(0.0, 4.0, 20_000),
            rng.normal(0.0, 1e6, 5_000),
            rng.choice([-1.0, 1.0], 5_000) * 10.0 ** rng.uniform(-300, 300, 5_000),
        ]
    )
    expected = kf.wrap_angle(angles)  # the array formula, element by element
    one_by_one = np.array([kf.wrap_angle(float(a)) for a in angles])
    assert one_by_one.tobytes() == expected.tobytes()  # every bit, the sign of zero too
    as_numpy = np.array([kf.wrap_angle(a) for a in angles])  # np.float64 scalars
    assert as_numpy.tobytes() == expected.tobytes()
    zero_d = np.array([kf.wrap_angle(np.array(a)) for a in angles[:2000]])  # 0-d arrays take the array formula
    assert zero_d.tobytes() == expected[:2000].tobytes()
    assert (np.abs(expected) <= math.pi).all() and (expected > -math.pi).all()


@pytest.mark.parametrize("a", [7, -7, True, np.int64(-9), np.float32(3.5), np.float32(-3.25), 10**17])
def test_wrap_angle_of_other_numbers_is_a_float_as_before(a):
    got = kf.wrap_angle(a)
    assert type(got) is float
    assert got == kf.wrap_angle(np.array([a], dtype=float))[0]


@FAST
@given(
    a=st.tuples(reals(-10, 10), reals(-10, 10), reals(-10, 10)).map(np.array),
    b=st.tuples(reals(-10, 10), reals(-10, 10), reals(-10, 10)).map(np.array),
)
def test_pose_and_range_bearing_residuals_are_differences_mod_two_pi(a, b):
    d = pose_residual(a, b)
    np.testing.assert_allclose(d[:2], a[:2] - b[:2], atol=1e-14)
    assert -math.pi < d[2] <= math.pi and angle_gap(d[2], a[2] - b[2]) < 1e-12
    e = range_bearing_residual(a[:2], b[:2])
    assert e[0] == pytest.approx(a[0] - b[0], abs=1e-14)
    assert -math.pi < e[1] <= math.pi and angle_gap(e[1], a[1] - b[1]) < 1e-12


@FAST
@given(
    centre=reals(-math.pi, math.pi),
    cloud=st.lists(st.tuples(reals(-0.3, 0.3), reals(0.05, 1.0)), min_size=3, max_size=7),
    turn=st.integers(-3, 3),
)
@example(centre=math.pi, cloud=[(-0.3, 1.0), (0.0, 1.0), (0.3, 1.0)], turn=0)
@example(centre=math.pi, cloud=[(-0.3, 0.1), (0.0, 0.1), (0.3, 1.0)], turn=1)
def test_circular_means_follow_a_weighted_cloud_around_the_circle(centre, cloud, turn):
    # a tight cloud of angles around `centre` (written with any number of whole turns) has its weighted
    # mean at centre + the weighted mean offset, to within the cubic term (< 0.01 rad for offsets <= 0.3)
    spread = np.array([c[0] for c in cloud])
    w = np.array([c[1] for c in cloud])
    w = w / w.sum()
    k = len(cloud)
    ang = centre + spread + TWO_PI * turn
    expected = centre + float(w @ spread)
    poses = np.column_stack([np.arange(k, dtype=float), -(np.arange(k, dtype=float) ** 2), ang])
    m = pose_mean(poses, w)
    np.testing.assert_allclose(m[:2], w @ poses[:, :2], atol=1e-12)  # x, y: the plain weighted mean
    assert angle_gap(m[2], expected) < 0.01
    # exact: it is the direction of the weighted sum of unit vectors, however the angles are written
    assert angle_gap(m[2], math.atan2(w @ np.sin(ang), w @ np.cos(ang))) < 1e-12
    rb = range_bearing_mean(np.column_stack([np.ones(k), ang]), w)
    assert rb[0] == pytest.approx(1.0, abs=1e-14) and angle_gap(rb[1], m[2]) < 1e-12


# ================================================================ bad input
BAD_INPUT = [
    ("wrap_angle/a NaN", lambda: kf.wrap_angle(NAN), "a"),
    ("wrap_angle/a inf", lambda: kf.wrap_angle([0.0, -INF]), "a"),
    ("wrap_angle/a not a number", lambda: kf.wrap_angle("north"), "a"),
    ("pose_residual/a wrong length", lambda: models.pose_residual([0.0, 0.0], POSE), "a"),
    ("range_bearing_residual/b NaN", lambda: models.range_bearing_residual([1.0, 0.0], [NAN, 0.0]), "b"),
    ("pose_mean/weights wrong length", lambda: models.pose_mean(np.zeros((3, 3)), [0.5, 0.5]), "weights"),
    ("range_bearing_mean/points NaN", lambda: models.range_bearing_mean([[NAN, 0.0]], [1.0]), "points"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, np.float64("nan"), np.float32("inf")])
def test_wrap_angle_still_refuses_a_number_that_is_not_finite(bad):
    with pytest.raises(ValueError, match=r"^a must be finite \(no NaN or inf\)"):
        kf.wrap_angle(bad)


def test_pose_residual_checks_both_poses():
    with pytest.raises(ValueError, match=r"^pose_residual b must be finite"):
        kf.models.pose_residual(np.zeros(3), [0.0, np.nan, 0.0])
    with pytest.raises(ValueError, match=r"^pose_residual b must have shape"):
        kf.models.pose_residual(np.zeros(3), np.zeros(2))
