"""The range-only models of chapter 12 (a radio that ranges to beacons at known positions):
``range_only`` and ``scaled_range`` with their Jacobians.  The 3-4-5 triangle by hand, Jacobians
against finite differences, stacks of states (the particle filter's), the robot standing on the
beacon, an EKF update that moves the estimate along the line to the beacon only, and the bad
input they refuse.

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse.models import range_only, range_only_jacobian, scaled_range, scaled_range_jacobian
from tests.filters.strategies import (
    INF,
    LANDMARK,
    NAN,
    POSE,
    assert_raises_naming,
    assert_unique_ids,
    bad_input_cases,
    poses,
    reals,
    vectors,
)

# ================================================================ worked numbers: the 3-4-5 triangle
ROBOT = np.array([4.0, 6.0, 0.3])  # 3 m east and 4 m north of the beacon, heading anything
BEACON = np.array([1.0, 2.0])
SCALE = 1.07  # the chapter's radio reads about 7 % long


def test_range_only_345():
    z = range_only(ROBOT, BEACON)
    assert z.shape == (1,)
    assert z[0] == pytest.approx(5.0, abs=1e-15)
    assert range_only(ROBOT[:2], BEACON)[0] == pytest.approx(5.0, abs=1e-15)  # a bare position [x, y]
    assert range_only([*ROBOT, SCALE], BEACON)[0] == pytest.approx(5.0, abs=1e-15)  # the scale does not count


def test_range_only_jacobian_345():
    # H = [(x - bx)/r, (y - by)/r, 0] = [3/5, 4/5, 0]: the unit vector from the beacon to the robot
    np.testing.assert_allclose(range_only_jacobian(ROBOT, BEACON), [[0.6, 0.8, 0.0]], atol=1e-15)
    np.testing.assert_allclose(range_only_jacobian(ROBOT[:2], BEACON), [[0.6, 0.8]], atol=1e-15)
    np.testing.assert_allclose(range_only_jacobian([*ROBOT, SCALE], BEACON), [[0.6, 0.8, 0.0, 0.0]], atol=1e-15)


def test_scaled_range_345():
    z = scaled_range([*ROBOT, SCALE], BEACON)
    assert z.shape == (1,)
    assert z[0] == pytest.approx(SCALE * 5.0, abs=1e-14)  # 5.35 m for a true 5 m


def test_scaled_range_jacobian_345():
    # H = [s (x - bx)/r, s (y - by)/r, 0, r] = [1.07 * 0.6, 1.07 * 0.8, 0, 5]
    H = scaled_range_jacobian([*ROBOT, SCALE], BEACON)
    np.testing.assert_allclose(H, [[0.642, 0.856, 0.0, 5.0]], atol=1e-14)


def test_range_only_is_the_range_of_range_bearing():
    # the lesson's worked pose and landmark: range_bearing_jacobian writes the offset m - x, range_only_jacobian
    # x - b; the range row is the same numbers, [-0.6, -0.8, 0]
    assert range_only(POSE, LANDMARK)[0] == pytest.approx(kf.range_bearing(POSE, LANDMARK)[0], rel=1e-15)
    np.testing.assert_allclose(range_only_jacobian(POSE, LANDMARK), [[-0.6, -0.8, 0.0]], atol=1e-15)
    np.testing.assert_allclose(
        range_only_jacobian(POSE, LANDMARK), kf.range_bearing_jacobian(POSE, LANDMARK)[:1], atol=1e-15
    )


# ================================================================ the robot on the beacon
def test_on_the_beacon_the_range_is_zero_but_the_jacobian_is_refused():
    on = np.array([1.0, 2.0, 0.3])
    assert range_only(on, [1.0, 2.0]).tolist() == [0.0]
    assert scaled_range([*on, SCALE], [1.0, 2.0]).tolist() == [0.0]
    # a particle on the beacon is weighed like any other
    np.testing.assert_allclose(range_only(np.vstack([on, ROBOT]), BEACON), [[0.0], [5.0]], atol=1e-15)
    for jacobian, state in [(range_only_jacobian, on), (scaled_range_jacobian, [*on, SCALE])]:
        with pytest.raises(ValueError, match=r"^beacon must not sit exactly at the robot's position") as raised:
            jacobian(state, [1.0, 2.0])
        assert "stands on the beacon" in str(raised.value)
        assert "Jacobian undefined" in str(raised.value)


def test_a_robot_a_hair_from_the_beacon_has_a_unit_jacobian():
    # however close (even where dx^2 underflows to 0), the position part of H is a unit vector
    for gap in (1e-3, 1e-170, 5e-324):
        H = range_only_jacobian([gap, 0.0, 0.0], [0.0, 0.0])
        np.testing.assert_allclose(H, [[1.0, 0.0, 0.0]], atol=1e-15)
        assert range_only([gap, 0.0, 0.0], [0.0, 0.0])[0] == gap


# ================================================================ Jacobians against finite differences
@st.composite
def state_and_beacon(draw, n: int | None = None):
    """A state of n entries (2 to 5 unless given), the position first, and a beacon 0.1 to 60 m from it."""
    n = draw(st.integers(2, 5)) if n is None else n
    state = draw(vectors(n, 50.0))
    r, angle = draw(reals(0.1, 60.0)), draw(reals(-math.pi, math.pi))
    beacon = state[:2] + r * np.array([math.cos(angle), math.sin(angle)])
    assume(math.hypot(*(beacon - state[:2])) >= 0.1)
    return state, beacon


@settings(max_examples=100, deadline=None)
@given(case=state_and_beacon())
@example(case=(np.array([0.0, 0.0]), np.array([0.1, 0.0])))  # a bare position, the beacon close
def test_range_only_jacobian_equals_numeric(case):
    state, beacon = case
    H = range_only_jacobian(state, beacon)
    J = kf.numeric_jacobian(lambda s: range_only(s, beacon), state)
    assert H.shape == J.shape == (1, state.size)
    np.testing.assert_allclose(H, J, rtol=1e-6, atol=1e-6)
    assert np.all(H[0, 2:] == 0.0)  # nothing past the position moves a range
    assert math.hypot(*H[0, :2]) == pytest.approx(1.0, rel=1e-14)  # a unit vector


@settings(max_examples=100, deadline=None)
@given(pose=poses, scale=reals(0.5, 1.5), r=reals(0.1, 60.0), angle=reals(-math.pi, math.pi))
@example(pose=np.array([0.0, 0.0, 0.0]), scale=SCALE, r=0.1, angle=math.pi)
def test_scaled_range_jacobian_equals_numeric(pose, scale, r, angle):
    state = np.append(pose, scale)
    beacon = pose[:2] + r * np.array([math.cos(angle), math.sin(angle)])
    assume(math.hypot(*(beacon - pose[:2])) >= 0.1)
    H = scaled_range_jacobian(state, beacon)
    J = kf.numeric_jacobian(lambda s: scaled_range(s, beacon), state)
    assert H.shape == J.shape == (1, 4)
    np.testing.assert_allclose(H, J, rtol=1e-6, atol=1e-6)
    # the scale times the plain range's Jacobian for the position, the true distance for the scale
    np.testing.assert_allclose(H[0, :3], scale * range_only_jacobian(pose, beacon)[0], rtol=1e-14, atol=1e-15)
    assert H[0, 3] == pytest.approx(range_only(pose, beacon)[0], rel=1e-15)


@settings(max_examples=60, deadline=None)
@given(case=state_and_beacon(3))
def test_range_only_jacobian_is_the_range_row_of_range_bearing(case):
    pose, beacon = case
    np.testing.assert_allclose(
        range_only_jacobian(pose, beacon), kf.range_bearing_jacobian(pose, beacon)[:1], rtol=1e-14, atol=1e-15
    )
    assert range_only(pose, beacon)[0] == pytest.approx(kf.range_bearing(pose, beacon)[0], rel=1e-14)


# ================================================================ stacks of states: the particle filter's
@pytest.mark.parametrize("n", [2, 3, 4])
def test_range_only_of_a_stack_is_one_row_per_state(rng, n):
    states = rng.uniform(-20, 20, size=(50, n))
    beacon = np.array([3.0, -4.0])
    out = range_only(states, beacon)
    assert out.shape == (50, 1)
    np.testing.assert_array_equal(out, np.array([range_only(s, beacon) for s in states]))
    assert range_only(states[:0], beacon).shape == (0, 1)  # no particles, no readings
    np.testing.assert_array_equal(range_only(np.asfortranarray(states), beacon), out)  # any memory order


def test_scaled_range_of_a_stack_is_one_row_per_state(rng):
    states = np.column_stack([rng.uniform(-20, 20, size=(50, 3)), rng.uniform(0.9, 1.2, 50)])
    out = scaled_range(states, BEACON)
    assert out.shape == (50, 1)
    np.testing.assert_array_equal(out, np.array([scaled_range(s, BEACON) for s in states]))
    np.testing.assert_allclose(out[:, 0], states[:, 3] * range_only(states, BEACON)[:, 0], rtol=1e-15)


# ================================================================ in the EKF
def test_ekf_update_moves_the_estimate_along_the_line_to_a_beacon_straight_ahead():
    # the robot at the origin heading 0.7 rad, the beacon 10 m straight ahead; the radio reads 9.5 m (closer).
    # With a round position uncertainty the update moves the position towards the beacon along the line
    # only, leaves the heading alone, and shrinks the spread along the line only.
    heading = 0.7
    ahead = np.array([math.cos(heading), math.sin(heading)])
    mu_bar, Sig_bar = np.array([0.0, 0.0, heading]), np.diag([0.3, 0.3, 0.1])
    beacon = 10.0 * ahead
    Q = np.array([[0.04]])
    mu, Sig = kf.ekf_update(
        mu_bar, Sig_bar, [9.5], lambda x: range_only(x, beacon), lambda x: range_only_jacobian(x, beacon), Q
    )
    step = mu[:2] - mu_bar[:2]
    assert step @ ahead == pytest.approx(0.5 * 0.3 / (0.3 + 0.04), rel=1e-12)  # K (z - h) along the line
    assert abs(step[0] * ahead[1] - step[1] * ahead[0]) < 1e-15  # nothing across it
    assert mu[2] == heading  # a range says nothing of the heading
    across = np.array([-ahead[1], ahead[0], 0.0])
    along = np.array([*ahead, 0.0])
    assert across @ Sig @ across == pytest.approx(0.3, rel=1e-12)  # no wiser across the line
    assert along @ Sig @ along == pytest.approx(0.3 * 0.04 / (0.3 + 0.04), rel=1e-12)  # wiser along it
    assert Sig[2, 2] == pytest.approx(0.1, rel=1e-15)


def test_ekf_update_of_a_well_known_position_learns_the_scale():
    # the position known to a millimetre, the scale to +-0.1: a reading 7 % long is put down to the scale
    mu_bar, Sig_bar = np.array([4.0, 6.0, 0.3, 1.0]), np.diag([1e-6, 1e-6, 0.01, 0.01])
    mu, Sig = kf.ekf_update(
        mu_bar,
        Sig_bar,
        [SCALE * 5.0],
        lambda x: scaled_range(x, BEACON),
        lambda x: scaled_range_jacobian(x, BEACON),
        np.array([[1e-4]]),
    )
    assert mu[3] == pytest.approx(SCALE, abs=2e-3)
    np.testing.assert_allclose(mu[:3], mu_bar[:3], atol=1e-3)
    assert Sig[3, 3] < 1e-4


# ================================================================ bad input
SCALED = np.array([4.0, 6.0, 0.3, SCALE])
BAD_INPUT = [
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, s=s, b=b: fn(s, b)), arg)
        for fn, state in [
            (range_only, ROBOT),
            (range_only_jacobian, ROBOT),
            (scaled_range, SCALED),
            (scaled_range_jacobian, SCALED),
        ]
        for label, s, b, arg in [
            ("state NaN", [NAN, *state[1:]], BEACON, "state"),
            ("state inf", [*state[:-1], INF], BEACON, "state"),
            ("state a string", "x", BEACON, "state"),
            ("state strings", ["4", *state[1:]], BEACON, "state"),
            ("state a number", 4.0, BEACON, "state"),
            ("state 3-D", np.ones((2, 2, state.size)), BEACON, "state"),
            ("beacon wrong length", state, [1.0, 2.0, 0.0], "beacon"),
            ("beacon NaN", state, [1.0, NAN], "beacon"),
            ("beacon a string", state, "x", "beacon"),
            ("beacon a stack", state, [[1.0, 2.0], [3.0, 4.0]], "beacon"),
        ]
    ],
    ("range_only/state of one entry", lambda: range_only([1.0], BEACON), "state"),
    ("range_only/states of one entry", lambda: range_only([[1.0], [2.0]], BEACON), "state"),
    ("range_only/state empty", lambda: range_only([], BEACON), "state"),
    ("range_only_jacobian/state of one entry", lambda: range_only_jacobian([1.0], BEACON), "state"),
    ("range_only_jacobian/a stack of states", lambda: range_only_jacobian(np.ones((2, 3)), BEACON), "state"),
    ("range_only_jacobian/on the beacon", lambda: range_only_jacobian([1.0, 2.0, 0.3], BEACON), "beacon"),
    ("scaled_range/a pose without the scale", lambda: scaled_range(ROBOT, BEACON), "state"),
    ("scaled_range/a state of five", lambda: scaled_range([*SCALED, 0.0], BEACON), "state"),
    ("scaled_range/poses without the scale", lambda: scaled_range(np.ones((2, 3)), BEACON), "state"),
    ("scaled_range_jacobian/a pose without the scale", lambda: scaled_range_jacobian(ROBOT, BEACON), "state"),
    ("scaled_range_jacobian/a state of five", lambda: scaled_range_jacobian([*SCALED, 0.0], BEACON), "state"),
    ("scaled_range_jacobian/a stack of states", lambda: scaled_range_jacobian(np.ones((2, 4)), BEACON), "state"),
    ("scaled_range_jacobian/on the beacon", lambda: scaled_range_jacobian([1.0, 2.0, 0.3, SCALE], BEACON), "beacon"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    range_only(ROBOT, BEACON)
    range_only_jacobian(ROBOT, BEACON)
    scaled_range(SCALED, BEACON)
    scaled_range_jacobian(SCALED, BEACON)


def test_the_shape_messages_say_what_a_state_is():
    with pytest.raises(ValueError, match=r"^state must have shape \(n,\) or \(N, n\) with n >= 2"):
        range_only([1.0], BEACON)
    with pytest.raises(ValueError, match=r"^state must have shape \(4,\) or \(N, 4\), got \(3,\)"):
        scaled_range(ROBOT, BEACON)
    with pytest.raises(ValueError, match=r"^state must have shape \(4,\), got \(2, 4\)"):
        scaled_range_jacobian(np.ones((2, 4)), BEACON)  # a Jacobian is taken at one state
