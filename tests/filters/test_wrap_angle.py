"""The unchecked cores behind the models and filters give the public functions' results, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf
from kfcourse import models
from kfcourse.filters import ekf, ukf
from kfcourse.filters.linalg import gain


def _edge_angles() -> np.ndarray:
    """Angles at and next to the ends of (-pi, pi] and its copies, huge ones, and ones whose mod rounds to 2 pi."""
    ends = np.array([k * math.pi for k in range(-9, 10)] + [1e16, -1e16, 1e300, -1e300, 2.0**53, -(2.0**53)])
    near = np.concatenate([np.nextafter(ends, np.inf), np.nextafter(ends, -np.inf)])
    tiny = np.array([0.0, -0.0, 5e-324, -5e-324, 1e-300, -1e-300, np.finfo(float).max, -np.finfo(float).max])
    return np.concatenate([ends, near, tiny, math.pi + 1e-16 * np.arange(-8, 9)])


def test_wrap_angle_of_one_number_equals_the_array_formula_bit_for_bit():
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


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, np.float64("nan"), np.float32("inf")])
def test_wrap_angle_still_refuses_a_number_that_is_not_finite(bad):
    with pytest.raises(ValueError, match=r"^a must be finite \(no NaN or inf\)"):
        kf.wrap_angle(bad)


def test_model_cores_give_the_public_results():
    rng = np.random.default_rng(2)
    poses = rng.uniform(-4, 4, size=(7, 3))
    poses[:, 2] = rng.uniform(-math.pi, math.pi, 7)
    u, dt, m = np.array([0.6, -1.3]), 0.2, np.array([2.0, -1.0])
    for s in (poses, poses[3]):
        assert np.array_equal(models._unicycle(s, u, dt), kf.unicycle(s, u, dt))
        assert np.array_equal(models._range_bearing(s, m), kf.range_bearing(s, m))
    assert np.array_equal(models._unicycle_jacobian(poses[0], u, dt), kf.unicycle_jacobian(poses[0], u, dt))
    assert np.array_equal(
        models._unicycle_control_jacobian(poses[0], u, dt), kf.unicycle_control_jacobian(poses[0], u, dt)
    )
    assert np.array_equal(models._range_bearing_jacobian(poses[0], m), kf.range_bearing_jacobian(poses[0], m))
    assert np.array_equal(models._pose_residual(poses, poses[1]), models.pose_residual(poses, poses[1]))
    assert np.array_equal(models._pose_mean(poses, np.full(7, 1 / 7)), models.pose_mean(poses, np.full(7, 1 / 7)))


def test_a_stack_of_poses_moves_into_a_c_ordered_stack():
    # Sigma points come as a Fortran-ordered stack; the weighted sums over the moved stack round as they did
    # only if it is C-ordered, whatever the order of the points.
    chi = np.asfortranarray(np.random.default_rng(3).normal(size=(7, 3)))
    moved = models._unicycle(chi, np.array([0.5, 0.3]), 0.2)
    assert moved.flags["C_CONTIGUOUS"]
    assert models._range_bearing(chi, np.array([1.0, 1.0])).flags["C_CONTIGUOUS"]


def test_filter_cores_give_the_public_results():
    dt, m = 0.2, np.array([2.0, 1.0])
    mu, Sig, u = np.array([0.1, -0.2, 3.0]), np.diag([0.02, 0.03, 0.01]), np.array([0.5, 0.4])
    R, Q, z = np.diag([1e-3, 2e-3, 5e-4]), np.diag([0.01, 0.0009]), np.array([2.3, -2.9])

    def g(x, c):
        return kf.unicycle(x, c, dt)

    def G(x, c):
        return kf.unicycle_jacobian(x, c, dt)

    def h(x):
        return kf.range_bearing(x, m)

    def H(x):
        return kf.range_bearing_jacobian(x, m)

    public = kf.ekf_predict(mu, Sig, u, g, G, R)
    core = ekf._ekf_predict(mu, Sig, u, g, G, R)
    assert all(np.array_equal(a, b) for a, b in zip(public, core, strict=True))
    public = kf.ekf_update(mu, Sig, z, h, H, Q, residual=models.range_bearing_residual)
    y, Ht, S = ekf._ekf_innovation(mu, Sig, z, h, H, Q, models._range_bearing_residual)
    assert abs(y[1]) < 1.0  # the bearing innovation was wrapped (z is 2 pi away from h's bearing)
    core = ekf._ekf_correct(mu, Sig, y, Ht, S, Q)
    assert all(np.array_equal(a, b) for a, b in zip(public, core, strict=True))

    public = kf.ukf_predict(mu, Sig, u, g, R, 0.0, models.pose_residual, models.pose_mean, vectorized=True)
    core = ukf._ukf_predict(mu, Sig, lambda chi: g(chi, u), R, 0.0, 0.0, models._pose_residual, models._pose_mean)
    assert all(np.array_equal(a, b) for a, b in zip(public, core, strict=True))
    hooks = (models.range_bearing_residual, models.range_bearing_mean, models.pose_residual)
    public = kf.ukf_update(mu, Sig, z, h, Q, 0.0, *hooks, vectorized=True)
    z_hat, S, Sig_xz = ukf._ukf_moments(
        mu, Sig, h, Q, 0.0, 0.0, models._range_bearing_residual, models._range_bearing_mean, models._pose_residual
    )
    K = gain(Sig_xz, S)
    core = ukf._ukf_correct(mu, Sig, models._range_bearing_residual(z, z_hat), S, K)
    assert all(np.array_equal(a, b) for a, b in zip(public, core, strict=True))
