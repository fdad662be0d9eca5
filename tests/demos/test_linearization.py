"""Chapter 7's linearization demo: its first frame and its caption.

The chapter's "Try this" prompts are driven in ``test_prompts_ch07.py``.
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


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


@pytest.mark.fact
@pytest.mark.parametrize("extreme", [(-2.0, 0.05), (-2.0, 1.5), (2.0, 0.05), (2.0, 1.5), (0.0, 1.5)])
def test_every_slider_extreme_draws_finite_numbers(extreme):
    m, s = extreme
    for name in ("x²", "sin x", "range √(x² + 1)"):
        demo = kf.demos.linearization(seed=0)
        demo.controls["function"].value = name
        demo.controls["m"].value, demo.controls["s"].value = m, s
        mean_e, var_e = demo.model.ekf()
        assert np.isfinite([mean_e, var_e, *demo.model.sampled()]).all()


@pytest.mark.fact
@pytest.mark.parametrize("demo_name", ["linearization", "sigma_points"])  # chapter 7's and chapter 9's panels
@pytest.mark.parametrize("name", ["x²", "sin x", "range √(x² + 1)"])
def test_no_tick_label_leaves_the_picture(demo_name, name):
    """The layout is found for the first frame; when the density axis's limit changes (s = 1.5 with x² makes
    it 2), no tick label may be cut off by the figure's edge."""
    demo = getattr(kf.demos, demo_name)(seed=0)
    fig = demo.renderer.fig
    demo.controls["function"].value = name
    for m, s in ((1.0, 1.5), (0.0, 1.0), (1.5, 1.5), (2.0, 0.05), (-2.0, 0.5), (2.0, 0.05)):
        demo.controls["m"].value, demo.controls["s"].value = m, s
        renderer = fig.canvas.get_renderer()
        width, height = fig.bbox.width, fig.bbox.height
        for axis in [a for ax in fig.axes for a in (ax.xaxis, ax.yaxis)]:
            lo, hi = sorted(axis.get_view_interval())
            for tick in axis.get_major_ticks():
                label = tick.label1
                if not (label.get_visible() and label.get_text().strip() and lo <= tick.get_loc() <= hi):
                    continue  # matplotlib keeps ticks just outside the limits, and draws nothing for them
                box = label.get_window_extent(renderer)
                inside = box.x0 >= 0 and box.x1 <= width and box.y0 >= 0 and box.y1 <= height
                assert inside, (demo_name, name, m, s, label.get_text())
