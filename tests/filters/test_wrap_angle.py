"""wrap_angle of one number and of an array, and the models' stacks of poses."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf


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


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, np.float64("nan"), np.float32("inf")])
def test_wrap_angle_still_refuses_a_number_that_is_not_finite(bad):
    with pytest.raises(ValueError, match=r"^a must be finite \(no NaN or inf\)"):
        kf.wrap_angle(bad)


def test_a_stack_of_poses_moves_into_a_c_ordered_stack():
    # Sigma points come as a Fortran-ordered stack; the weighted sums over the moved stack round as they did
    # only if it is C-ordered, whatever the order of the points.
    chi = np.asfortranarray(np.random.default_rng(3).normal(size=(7, 3)))
    assert kf.unicycle(chi, np.array([0.5, 0.3]), 0.2).flags["C_CONTIGUOUS"]
    assert kf.range_bearing(chi, np.array([1.0, 1.0])).flags["C_CONTIGUOUS"]
