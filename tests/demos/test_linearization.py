"""Chapter 7's linearization demo: its first frame and its caption.

The chapter's "Try this" prompts are driven in ``test_prompts_ch07.py``.
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf


def test_first_frame_is_x_squared_and_the_ekf_is_the_tangent_gaussian():
    demo = kf.demos.linearization(seed=0)
    m = demo.model
    assert m.function == "x²" and m.m == 1.0 and m.s == 0.5
    assert m.ekf() == pytest.approx((1.0, 4 * 0.25))  # N(f(m), f'(m)^2 s^2) = N(1, (2 * 1)^2 0.5^2)


def test_the_ekf_is_drawn_teal_and_the_caption_says_so():
    demo = kf.demos.linearization(seed=0)
    teal = kf.plots.palette.ESTIMATE
    assert demo.view.ekf.get_color() == teal and demo.view.ekf_mean.get_color() == teal
    assert "teal, the EKF's" in caption(demo)


def caption(widget) -> str:
    """The text of the demo's caption widget (class kf-caption)."""
    if "kf-caption" in getattr(widget, "_dom_classes", ()):
        return widget.value
    return "".join(caption(child) for child in getattr(widget, "children", ()))


@pytest.mark.parametrize("extreme", [(-2.0, 0.05), (-2.0, 1.5), (2.0, 0.05), (2.0, 1.5), (0.0, 1.5)])
def test_every_slider_extreme_draws_finite_numbers(extreme):
    m, s = extreme
    for name in ("x²", "sin x", "range √(x² + 1)"):
        demo = kf.demos.linearization(seed=0)
        demo.controls["function"].value = name
        demo.controls["m"].value, demo.controls["s"].value = m, s
        mean_e, var_e = demo.model.ekf()
        assert np.isfinite([mean_e, var_e, *demo.model.sampled()]).all()
