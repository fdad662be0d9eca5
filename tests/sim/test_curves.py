"""The shared maths of chapters 7 and 9: the test functions' derivatives, and the input
Gaussian, its seeded samples through f and the EKF's tangent Gaussian."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.curve_functions import FUNCTIONS, OFFSET, GaussianThroughCurve

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


@pytest.mark.parametrize("name", list(FUNCTIONS))
def test_each_derivative_is_the_slope_of_its_function(name):
    f, df = FUNCTIONS[name]
    x = np.linspace(-4.0, 4.0, 33)
    numeric = np.array([kf.numeric_jacobian(lambda u: np.atleast_1d(f(u[0])), [xi])[0, 0] for xi in x])
    np.testing.assert_allclose(df(x), numeric, atol=1e-6)


def test_the_range_is_the_distance_to_a_landmark_off_the_line():
    f = FUNCTIONS["range √(x² + 1)"][0]
    assert OFFSET == 1.0
    assert f(0.0) == pytest.approx(OFFSET)  # right under the landmark
    assert f(3.0) == pytest.approx(np.hypot(3.0, OFFSET))


def test_samples_are_the_seeded_draws_moved_and_pushed_through_f():
    a, b, c = GaussianThroughCurve(seed=3), GaussianThroughCurve(seed=3), GaussianThroughCurve(seed=4)
    np.testing.assert_array_equal(a.draws, b.draws)
    assert not np.array_equal(a.draws, c.draws)
    a.set_function("sin x")
    a.set_m(0.7)
    a.set_s(1.3)
    np.testing.assert_array_equal(a.samples(), np.sin(0.7 + 1.3 * a.draws))
    mean, var = a.sampled()
    assert mean == pytest.approx(a.samples().mean()) and var == pytest.approx(a.samples().var())


def test_sampled_moments_of_x_squared_are_near_the_closed_form():
    model = GaussianThroughCurve(seed=0, m=2.0, s=1.0, n_samples=200_000)
    mean, var = model.sampled()
    assert mean == pytest.approx(5.0, rel=0.01)  # m² + s²
    assert var == pytest.approx(18.0, rel=0.03)  # 4 m² s² + 2 s⁴


@pytest.mark.parametrize(("name", "m", "s"), [("x²", 1.0, 0.5), ("sin x", 1.5, 1.5), ("range √(x² + 1)", 0.0, 1.0)])
def test_ekf_is_the_tangent_gaussian(name, m, s):
    model = GaussianThroughCurve(m=m, s=s, function=name)
    f, df = FUNCTIONS[name]
    assert model.ekf() == pytest.approx((f(m), df(m) ** 2 * s**2))
    assert (model.f, model.df) == (f, df)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [({"s": 0.0}, "s"), ({"s": -1.0}, "s"), ({"m": np.nan}, "m"), ({"function": "tan x"}, "function"),
     ({"n_samples": 1}, "n_samples")],
)  # fmt: skip
def test_bad_input_is_refused_by_name(kwargs, name):
    with pytest.raises(ValueError, match=name):
        GaussianThroughCurve(**kwargs)


def test_setters_refuse_bad_values_and_keep_the_old_ones():
    model = GaussianThroughCurve()
    for setter, bad, name in (
        (model.set_s, 0.0, "s"),
        (model.set_m, np.inf, "m"),
        (model.set_function, "x³", "function"),
    ):
        with pytest.raises(ValueError, match=name):
            setter(bad)
    assert (model.m, model.s, model.function) == (1.0, 0.5, "x²")
