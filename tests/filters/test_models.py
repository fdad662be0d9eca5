"""The robot models of ``kfcourse.models`` (chapters 5, 7 and 8): ``constant_velocity``,
``unicycle`` and its Jacobians, ``range_bearing`` and its Jacobian, ``numeric_jacobian``,
and stacks of poses.  The lesson's numbers, the models by hand, Jacobians against finite
differences, bearings that do not care about whole turns, and the bad input they refuse.
(``wrap_angle``, the residuals and the circular means: ``test_angles.py``.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse import models
from kfcourse.models import constant_velocity, pose_residual, range_bearing_residual
from tests.filters.strategies import (
    FAST,
    INF,
    LANDMARK,
    NAN,
    POSE,
    TWO_PI,
    angle_gap,
    assert_raises_naming,
    assert_raises_saying,
    assert_unique_ids,
    bad_input_cases,
    h_rb,
    lin,
    omegas,
    poses,
    r3,
    reals,
)

# ================================================================ worked numbers (chapters 7 and 8)
H_WORKED = np.array([[-0.6, -0.8, 0.0], [0.16, -0.12, -1.0]])


def test_ch7_range_bearing():
    r, phi = kf.range_bearing(POSE, LANDMARK)
    assert r == pytest.approx(5.0, abs=1e-12)
    assert r3(phi) == 0.927
    assert phi == pytest.approx(math.atan2(4.0, 3.0), abs=1e-15)


def test_ch7_range_bearing_jacobian():
    np.testing.assert_allclose(kf.range_bearing_jacobian(POSE, LANDMARK), H_WORKED, atol=1e-12)


def test_ch7_numeric_jacobian_agrees():
    J = kf.numeric_jacobian(lambda s: kf.range_bearing(s, LANDMARK), POSE)
    np.testing.assert_allclose(J, H_WORKED, atol=1e-7)
    assert np.allclose(kf.range_bearing_jacobian(POSE, LANDMARK), J)


def test_ch7_numeric_jacobian_catches_a_wrong_jacobian():
    # The #1 cause of a diverging EKF: the bearing row with its signs flipped.  The check the lesson
    # teaches must pass for range_bearing_jacobian and fail for the flipped one.
    J = kf.numeric_jacobian(lambda s: kf.range_bearing(s, LANDMARK), POSE)
    H = kf.range_bearing_jacobian(POSE, LANDMARK)
    np.testing.assert_allclose(H, J, atol=1e-7)
    wrong = H.copy()
    wrong[1, :2] *= -1
    assert np.abs(wrong - J).max() > 0.2  # 2 * 0.16 off in the bearing row


def test_ch8_unicycle_jacobian_worked():
    G = kf.unicycle_jacobian([0.0, 0.0, 0.0], [0.5, 0.0], 1.0)
    np.testing.assert_allclose(G, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]], atol=1e-15)
    assert G[1, 2] == pytest.approx(0.5)  # heading error leaks into y


def test_ch8_unicycle_straight_line_worked():
    np.testing.assert_allclose(kf.unicycle([0.0, 0.0, 0.0], [0.5, 0.0], 1.0), [0.5, 0.0, 0.0], atol=1e-15)


# ================================================================ closed forms
def test_constant_velocity_closed_form_2d():
    F, H = constant_velocity(0.5, dim=2)
    np.testing.assert_array_equal(F, [[1, 0, 0.5, 0], [0, 1, 0, 0.5], [0, 0, 1, 0], [0, 0, 0, 1]])
    np.testing.assert_array_equal(H, [[1, 0, 0, 0], [0, 1, 0, 0]])


def test_numeric_jacobian_closed_form():
    # f(x, y) = (x y, sin x) at (2, 0): J = [[y, x], [cos x, 0]] = [[0, 2], [cos 2, 0]]
    J = kf.numeric_jacobian(lambda s: np.array([s[0] * s[1], math.sin(s[0])]), [2.0, 0.0])
    np.testing.assert_allclose(J, [[0.0, 2.0], [math.cos(2.0), 0.0]], atol=1e-9)


def test_unicycle_closed_form_quarter_circle():
    # V = 1, omega = pi/2, dt = 1 from the origin facing +x: a quarter of a circle of radius 2/pi
    # ends at (2/pi, 2/pi) facing +y; G[0:2, 2] = (-(y'-y), x'-x) = (-2/pi, 2/pi)
    out = kf.unicycle([0.0, 0.0, 0.0], [1.0, math.pi / 2], 1.0)
    np.testing.assert_allclose(out, [2 / math.pi, 2 / math.pi, math.pi / 2], atol=1e-15)
    G = kf.unicycle_jacobian([0.0, 0.0, 0.0], [1.0, math.pi / 2], 1.0)
    np.testing.assert_allclose(G, [[1, 0, -2 / math.pi], [0, 1, 2 / math.pi], [0, 0, 1]], atol=1e-15)


def test_unicycle_control_jacobian_closed_forms():
    # straight ahead, theta = 0, V = 0.5, dt = 1: speed moves x by dt; the turn rate swings the chord,
    # dy/domega = (dt/2) V dt = 0.25, and turns the heading by dt
    V = kf.unicycle_control_jacobian([0.0, 0.0, 0.0], [0.5, 0.0], 1.0)
    np.testing.assert_allclose(V, [[1.0, 0.0], [0.0, 0.25], [0.0, 1.0]], atol=1e-15)
    # the quarter circle: x' = y' = (V/omega)(1 - 0) with omega = pi/2, so dx'/dV = dy'/dV = 2/pi;
    # dx'/domega = d/domega [V sin(omega)/omega] = V (omega cos omega - sin omega)/omega^2 = -4/pi^2,
    # dy'/domega = d/domega [V (1 - cos omega)/omega] = V (omega sin omega - 1 + cos omega)/omega^2 = 2/pi - 4/pi^2
    V = kf.unicycle_control_jacobian([0.0, 0.0, 0.0], [1.0, math.pi / 2], 1.0)
    c = 4 / math.pi**2
    np.testing.assert_allclose(V, [[2 / math.pi, -c], [2 / math.pi, 2 / math.pi - c], [0.0, 1.0]], atol=1e-15)


def test_range_bearing_closed_form_wraps_the_bearing():
    # heading -3 rad, landmark straight along -x: atan2(0, -1) - (-3) = pi + 3 -> wrapped 3 - pi
    r, phi = kf.range_bearing([0.0, 0.0, -3.0], [-2.0, 0.0])
    assert r == pytest.approx(2.0, rel=1e-15)
    assert phi == pytest.approx(3.0 - math.pi, abs=1e-15)
    # heading +3, landmark along +x: 0 - 3 = -3 stays
    assert kf.range_bearing([0.0, 0.0, 3.0], [1.0, 0.0])[1] == pytest.approx(-3.0, abs=1e-15)
    # heading 2 pi + 0.5 (one whole turn more) reads as if the heading were 0.5
    assert kf.range_bearing([0.0, 0.0, TWO_PI + 0.5], [1.0, 1.0])[1] == pytest.approx(math.pi / 4 - 0.5, abs=1e-14)


def test_range_bearing_to_many_landmarks_is_one_row_per_landmark():
    # chapter 11 takes every particle to every landmark at once: row j is landmark j's reading, to the last bit
    poses = np.array([[0.0, 0.0, 0.3], [1.0, -2.0, -3.0], [4.0, 1.0, 2.0]])
    marks = np.array([[3.0, 4.0], [-1.0, 0.5], [0.0, -6.0], [5.0, 5.0]])
    each = np.stack([kf.range_bearing(poses, m) for m in marks])
    assert np.array_equal(kf.range_bearing(poses, marks), each) and each.shape == (4, 3, 2)
    assert np.array_equal(kf.range_bearing(poses[1], marks), each[:, 1])
    with pytest.raises(ValueError, match="landmark"):
        kf.range_bearing(poses, np.ones((2, 2, 2)))
    with pytest.raises(ValueError, match="landmark must not sit"):
        kf.range_bearing(poses, [[3.0, 4.0], [1.0, -2.0]])  # the second sits on the second pose


# ================================================================ properties
@FAST
@given(dt=reals(1e-3, 5.0), dim=st.integers(1, 3), k=st.integers(1, 6))
def test_constant_velocity_k_steps_advance_position_by_k_dt_v(dt, dim, k):
    F, H = constant_velocity(dt, dim)
    eye = np.eye(dim)
    expected = np.block([[eye, k * dt * eye], [np.zeros((dim, dim)), eye]])
    np.testing.assert_allclose(np.linalg.matrix_power(F, k), expected, rtol=1e-12)
    np.testing.assert_array_equal(H @ F @ np.concatenate([np.zeros(dim), np.ones(dim)]), dt * np.ones(dim))


@FAST
@given(
    A=st.lists(reals(-3, 3), min_size=6, max_size=6).map(lambda a: np.array(a).reshape(2, 3)),
    x=st.tuples(reals(-5, 5), reals(-5, 5), reals(-5, 5)).map(np.array),
)
def test_numeric_jacobian_of_a_linear_map_is_the_matrix(A, x):
    np.testing.assert_allclose(kf.numeric_jacobian(lambda s: A @ s + 1.0, x), A, atol=1e-8)


@settings(max_examples=100, deadline=None)
@given(pose=poses, r=reals(0.1, 60.0), angle=reals(-math.pi, math.pi))
@example(pose=np.array([0.0, 0.0, 0.0]), r=1.0, angle=math.pi)  # landmark straight behind: bearing = pi
@example(pose=np.array([0.0, 0.0, -math.pi / 2]), r=0.1, angle=math.pi / 2 + 1e-9)  # closest allowed
def test_range_bearing_jacobian_equals_numeric(pose, r, angle):
    landmark = pose[:2] + r * np.array([math.cos(angle), math.sin(angle)])
    assume(np.hypot(*(landmark - pose[:2])) >= 0.1)
    H = kf.range_bearing_jacobian(pose, landmark)
    J = kf.numeric_jacobian(lambda s: kf.range_bearing(s, landmark), pose, residual=range_bearing_residual)
    assert H.shape == J.shape == (2, 3)
    np.testing.assert_allclose(H, J, rtol=1e-6, atol=1e-6)


@settings(max_examples=150, deadline=None)
@given(pose=poses, V=reals(-5, 5), omega=omegas, dt=reals(1e-3, 2.0))
@example(pose=np.array([0.0, 0.0, math.pi]), V=1.0, omega=0.0, dt=1.0)  # heading right at the wrap
@example(pose=np.array([1.0, 2.0, 0.3]), V=2.0, omega=5e-324, dt=1.0)  # smallest subnormal
def test_unicycle_jacobian_equals_numeric(pose, V, omega, dt):
    u = np.array([V, omega])
    G = kf.unicycle_jacobian(pose, u, dt)
    J = kf.numeric_jacobian(lambda s: kf.unicycle(s, u, dt), pose, residual=pose_residual)
    assert G.shape == J.shape == (3, 3)
    np.testing.assert_allclose(G, J, rtol=1e-6, atol=1e-6)


@settings(max_examples=150, deadline=None)
@given(pose=poses, V=reals(-5, 5), omega=omegas, dt=reals(1e-3, 2.0))
@example(pose=np.array([1.0, 2.0, 0.3]), V=2.0, omega=5e-324, dt=1.0)  # smallest subnormal
@example(pose=np.array([1.0, 2.0, 0.3]), V=2.0, omega=2e-3, dt=1.0)  # just past the series' switch
def test_unicycle_control_jacobian_equals_numeric(pose, V, omega, dt):
    u = np.array([V, omega])
    Vu = kf.unicycle_control_jacobian(pose, u, dt)
    J = kf.numeric_jacobian(lambda c: kf.unicycle(pose, c, dt), u, residual=pose_residual)
    assert Vu.shape == J.shape == (3, 2)
    np.testing.assert_allclose(Vu, J, rtol=1e-6, atol=1e-6)


@FAST
@given(pose=poses, V=reals(-5, 5), dt=reals(1e-3, 2.0))
def test_unicycle_at_zero_omega_is_the_straight_line(pose, V, dt):
    x, y, th = pose
    out = kf.unicycle(pose, [V, 0.0], dt)
    np.testing.assert_allclose(
        out[:2], [x + V * dt * math.cos(th), y + V * dt * math.sin(th)], rtol=0, atol=1e-12 * (1 + abs(x) + abs(y))
    )
    assert out[2] == pytest.approx(kf.wrap_angle(th), abs=1e-15)
    G = kf.unicycle_jacobian(pose, [V, 0.0], dt)
    np.testing.assert_allclose(G[:2, 2], [-V * dt * math.sin(th), V * dt * math.cos(th)], atol=1e-12)


@FAST
@given(pose=poses, V=reals(-5, 5), dt=reals(1e-3, 2.0), sign=st.sampled_from([-1.0, 1.0]))
def test_unicycle_is_continuous_as_omega_goes_to_zero(pose, V, dt, sign):
    g0 = kf.unicycle(pose, [V, 0.0], dt)
    G0 = kf.unicycle_jacobian(pose, [V, 0.0], dt)
    tol0 = 1e-12 * (1.0 + np.abs(pose[:2]).max() + abs(V) * dt)
    for w in sign * np.logspace(-1, -12, 12):
        gap = np.abs(pose_residual(kf.unicycle(pose, [V, w], dt), g0))
        # |chord drift| <= |V| dt^2 |w| (turning by w dt/2 and shortening by the sinc)
        assert np.all(gap[:2] <= abs(V) * dt * dt * abs(w) + tol0), (w, gap)
        assert gap[2] <= abs(w) * dt * (1 + 1e-12) + 1e-14  # a few ulps from the two wraps
        Ggap = np.abs(kf.unicycle_jacobian(pose, [V, w], dt) - G0)
        assert np.all(Ggap <= abs(V) * dt * dt * abs(w) + tol0), (w, Ggap)


@FAST
@given(pose=poses, V=reals(-5, 5), omega=st.one_of(reals(0.01, 20), reals(-20, -0.01)), dt=reals(0.05, 2.0))
def test_unicycle_matches_the_lessons_arc_formula(pose, V, omega, dt):
    x, y, th = pose
    expected = [
        x + V / omega * (math.sin(th + omega * dt) - math.sin(th)),
        y + V / omega * (math.cos(th) - math.cos(th + omega * dt)),
    ]
    out = kf.unicycle(pose, [V, omega], dt)
    np.testing.assert_allclose(out[:2], expected, rtol=0, atol=1e-9 * (1 + abs(x) + abs(y) + abs(V / omega)))
    assert pose_residual(out, [*expected, th + omega * dt])[2] == pytest.approx(0.0, abs=1e-12)


@FAST
@given(
    pose=st.tuples(reals(-20, 20), reals(-20, 20), reals(-20, 20)).map(np.array),
    lm=st.tuples(reals(-20, 20), reals(-20, 20)).map(np.array),
)
def test_range_bearing_is_distance_and_bearing_in_range(pose, lm):
    dx, dy = lm - pose[:2]
    assume(math.hypot(dx, dy) > 1e-3)
    r, phi = kf.range_bearing(pose, lm)
    assert r == pytest.approx(math.hypot(dx, dy), rel=1e-14)
    assert -math.pi < phi <= math.pi
    assert angle_gap(phi, math.atan2(dy, dx) - pose[2]) < 1e-12
    stacked = kf.range_bearing(np.vstack([pose, pose + np.array([0.0, 0.0, TWO_PI])]), lm)  # (N, 3) in, (N, 2) out
    assert stacked.shape == (2, 2)
    assert np.all((stacked[:, 1] > -math.pi) & (stacked[:, 1] <= math.pi))
    assert stacked[0, 1] == pytest.approx(phi, abs=1e-12)


DT = 0.1  # s


def test_models_take_stacks_of_poses():
    rng = np.random.default_rng(1)
    poses = rng.uniform(-3, 3, size=(7, 3))
    u = np.array([0.7, -0.4])
    assert kf.unicycle(poses, u, DT) == pytest.approx(np.array([kf.unicycle(p, u, DT) for p in poses]))
    assert kf.range_bearing(poses, LANDMARK) == pytest.approx(np.array([kf.range_bearing(p, LANDMARK) for p in poses]))
    a, b = rng.uniform(-4, 4, size=(7, 3)), rng.uniform(-4, 4, size=3)
    assert pose_residual(a, b) == pytest.approx(np.array([pose_residual(r, b) for r in a]))
    with pytest.raises(ValueError, match="state"):
        kf.unicycle(np.zeros((2, 4)), u, DT)
    with pytest.raises(ValueError, match="state"):
        kf.range_bearing_jacobian(poses, LANDMARK)  # a Jacobian is for one pose


def test_a_stack_of_poses_moves_into_a_c_ordered_stack():
    # Sigma points come as a Fortran-ordered stack; the weighted sums over the moved stack round as they did
    # only if it is C-ordered, whatever the order of the points.
    chi = np.asfortranarray(np.random.default_rng(3).normal(size=(7, 3)))
    assert kf.unicycle(chi, np.array([0.5, 0.3]), 0.2).flags["C_CONTIGUOUS"]
    assert kf.range_bearing(chi, np.array([1.0, 1.0])).flags["C_CONTIGUOUS"]


# ================================================================ bad input
BAD_INPUT = [
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, s=s, m=m: fn(s, m)), arg)
        for fn in (kf.range_bearing, kf.range_bearing_jacobian)
        for label, s, m, arg in [
            ("state wrong length", [1.0, 2.0], LANDMARK, "state"),
            ("state NaN", [1.0, NAN, 0.0], LANDMARK, "state"),
            ("landmark wrong length", POSE, [4.0, 6.0, 0.0], "landmark"),
            ("landmark inf", POSE, [INF, 6.0], "landmark"),
            ("landmark at robot position", POSE, [1.0, 2.0], "landmark"),
        ]
    ],
    *[
        (f"{fn.__name__}/{label}", (lambda fn=fn, s=s, u=u, dt=dt: fn(s, u, dt)), arg)
        for fn in (kf.unicycle, kf.unicycle_jacobian, kf.unicycle_control_jacobian)
        for label, s, u, dt, arg in [
            ("state wrong length", [0.0, 0.0], [0.5, 0.0], 1.0, "state"),
            ("u wrong length", POSE, [0.5], 1.0, "u"),
            ("u NaN", POSE, [0.5, NAN], 1.0, "u"),
            ("dt zero", POSE, [0.5, 0.0], 0.0, "dt"),
            ("dt negative", POSE, [0.5, 0.0], -0.1, "dt"),
        ]
    ],
    ("numeric_jacobian/f not callable", lambda: kf.numeric_jacobian(3.0, [1.0]), "f"),
    ("numeric_jacobian/eps zero", lambda: kf.numeric_jacobian(lin, [1.0], eps=0.0), "eps"),
    ("numeric_jacobian/eps negative", lambda: kf.numeric_jacobian(lin, [1.0], eps=-1e-6), "eps"),
    ("numeric_jacobian/x NaN", lambda: kf.numeric_jacobian(lin, [NAN]), "x"),
    ("numeric_jacobian/x 2-D", lambda: kf.numeric_jacobian(lin, [[1.0, 2.0]]), "x"),
    ("numeric_jacobian/f returns a matrix", lambda: kf.numeric_jacobian(lambda x: np.eye(2), [1.0]), "f"),
    ("constant_velocity/dt zero", lambda: models.constant_velocity(0.0, 2), "dt"),
    ("constant_velocity/dim zero", lambda: models.constant_velocity(0.1, 0), "dim"),
    ("constant_velocity/dim fractional", lambda: models.constant_velocity(0.1, 1.5), "dim"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.range_bearing(POSE, LANDMARK)
    kf.unicycle(POSE, [0.5, 0.0], 1.0)
    kf.numeric_jacobian(lin, [1.0])


@pytest.mark.parametrize(
    "call", [lambda: kf.numeric_jacobian(h_rb, np.zeros(3), residual=[1])], ids=["numeric_jacobian"]
)
def test_hook_that_is_not_callable(call):
    with pytest.raises(ValueError, match=r"\b(residual|mean) must be callable"):
        call()


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: models.constant_velocity(0.0, 2), "dt must be a time step > 0 s"),
        (lambda: kf.unicycle(POSE, [0.5, 0.0], -0.1), "dt must be a time step > 0 s"),
        (lambda: kf.numeric_jacobian(lin, [1.0], eps=0.0), "eps must be a finite-difference step > 0"),
    ],
)
def test_message_says_what_the_argument_is(call, message):
    """A step, a distance or a standard deviation is not called a variance."""
    assert_raises_saying(call, message)


@pytest.mark.parametrize("jacobian", [kf.unicycle_jacobian, kf.unicycle_control_jacobian])
def test_a_jacobian_of_a_stack_of_poses_is_refused(jacobian):
    with pytest.raises(ValueError, match=r"^state must have shape \(3,\)"):
        jacobian(np.zeros((4, 3)), [0.5, 0.1], 0.2)  # a Jacobian is taken at one pose


def test_a_three_dimensional_state_is_refused():
    with pytest.raises(ValueError, match=r"^state must have shape \(3,\) or \(N, 3\)"):
        kf.unicycle(np.zeros((2, 2, 3)), [0.5, 0.1], 0.2)


def test_unicycle_moves_each_pose_by_its_own_control():
    """N poses with N controls (chapter 11's particles) move as each pose alone would."""
    rng = np.random.default_rng(3)
    poses = rng.normal(size=(5, 3))
    controls = np.column_stack([rng.uniform(0, 2, 5), rng.normal(0, 1, 5)])
    moved = kf.unicycle(poses, controls, 0.2)
    for pose, u, out in zip(poses, controls, moved, strict=True):
        np.testing.assert_array_equal(out, kf.unicycle(pose, u, 0.2))


def test_unicycle_refuses_controls_that_do_not_pair_with_the_poses():
    with pytest.raises(ValueError, match="u of shape"):
        kf.unicycle(np.zeros((4, 3)), np.zeros((3, 2)), 0.2)
    with pytest.raises(ValueError, match="u of shape"):
        kf.unicycle(np.zeros(3), np.zeros((1, 2)), 0.2)
    with pytest.raises(ValueError, match="u must be a 1-D vector"):
        kf.unicycle_jacobian(np.zeros(3), np.zeros((1, 2)), 0.2)
