"""Chapter 7's "Try this" prompts for the linearization demo, each driven as the prose says."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.curves import FUNCTIONS

RANGE = "range √(x² + 1)"


def demo_at(function: str, m: float, s: float):
    demo = kf.demos.linearization(seed=0)
    demo.controls["function"].value = function
    demo.controls["m"].value = m
    demo.controls["s"].value = s
    return demo


def test_first_frame_is_x_squared_and_the_ekf_is_the_tangent_gaussian():
    demo = kf.demos.linearization(seed=0)
    m = demo.model
    assert m.function == "x²" and m.m == 1.0 and m.s == 0.5
    assert m.ekf() == pytest.approx((1.0, 4 * 0.25))  # N(f(m), f'(m)^2 s^2) = N(1, (2 * 1)^2 0.5^2)


@pytest.mark.parametrize("name", list(FUNCTIONS))
def test_narrow_input_the_ekf_agrees_with_the_samples(name):
    model = demo_at(name, 1.0, 0.05).model
    (mean_y, var_y), (mean_e, var_e) = model.sampled(), model.ekf()
    assert mean_e == pytest.approx(mean_y, abs=0.01)
    assert var_e == pytest.approx(var_y, rel=0.1)


def test_widen_x_squared_the_ekf_misses_the_sampled_mean():
    """Prompt: x², m = 1, widen s to 1.5: the sampled mean moves to about m² + s² = 3.25, the EKF's stays at 1."""
    demo = demo_at("x²", 1.0, 0.1)
    assert demo.model.sampled()[0] == pytest.approx(1.0, abs=0.02)
    demo.controls["s"].value = 1.5
    (mean_y, var_y), (mean_e, var_e) = demo.model.sampled(), demo.model.ekf()
    assert mean_e == pytest.approx(1.0)
    assert mean_y == pytest.approx(1.0 + 1.5**2, abs=0.15)  # E[x^2] = m^2 + s^2
    assert mean_y - mean_e > 2.0
    assert var_y > 1.5 * var_e  # and the truth is wider than the EKF thinks


def test_x_squared_at_zero_the_ekf_says_variance_zero():
    """Prompt: x², m = 0: f'(0) = 0, so the EKF claims variance 0 while the samples spread (variance 2 s^4)."""
    demo = demo_at("x²", 0.0, 1.0)
    (mean_y, var_y), (mean_e, var_e) = demo.model.sampled(), demo.model.ekf()
    assert var_e == 0.0 and mean_e == 0.0
    assert var_y == pytest.approx(2.0, rel=0.1)
    assert mean_y == pytest.approx(1.0, abs=0.05)
    drawn = np.asarray(demo.view.ekf.get_xydata(), float)  # the EKF's "spike": a short arrow at 0, drawn finite
    assert np.isfinite(drawn).all() and demo.view.ekf.get_marker() == ">"
    assert np.all(drawn[:, 1] == 0.0)


def test_sin_at_its_peak_the_ekf_is_far_too_sure():
    """Prompt: sin x, m = 1.5 (near the top), s = 1.5: the EKF mean stays near 1, the sampled mean drops below 0.4."""
    demo = demo_at("sin x", 1.5, 1.5)
    (mean_y, var_y), (mean_e, var_e) = demo.model.sampled(), demo.model.ekf()
    assert mean_e == pytest.approx(np.sin(1.5))
    assert mean_y < 0.4
    assert var_y > 10 * var_e


def test_range_under_the_landmark_versus_far_from_it():
    """Prompt: range, s = 1: at m = 2 the EKF is close; at m = 0 (right under the landmark) it says variance 0."""
    demo = demo_at(RANGE, 2.0, 1.0)
    (mean_y, var_y), (mean_e, var_e) = demo.model.sampled(), demo.model.ekf()
    assert abs(mean_y - mean_e) < 0.1 and var_e == pytest.approx(var_y, rel=0.25)
    demo.controls["m"].value = 0.0
    (mean_y, var_y), (mean_e, var_e) = demo.model.sampled(), demo.model.ekf()
    assert var_e == 0.0 and var_y > 0.1
    assert mean_y - mean_e > 0.3  # a range never comes out shorter than the offset: the true mean is longer
