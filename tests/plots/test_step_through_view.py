"""Chapter 3's view: each half-step shows its curves (and fades the others in the legend),
the axes follow the belief in whole metres and powers of two, and a change that moves
no limit and no legend entry redraws only the curves."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.step_through_view import HALF_WIDTH, step_through_view, update_step_through
from kfcourse.plots.style import FigureRenderer


def model(phase: str, R: float = 0.2, Q: float = 0.1) -> SimpleNamespace:
    """Everything :func:`update_step_through` reads, and nothing else: chapter 3's first cycle
    after the prior, the Predict or the Update."""
    mu_bar, var_bar = 3.0, 0.4 + R
    K = var_bar / (var_bar + Q)
    m = SimpleNamespace(phase=phase, R=R, Q=Q, note="", k=1, before=(2.0, 0.4))
    if phase == "prior":
        m.predicted, m.z, m.K, m.mu, m.var, m.k = None, None, None, 2.0, 0.4, 0
    elif phase == "predicted":
        m.predicted, m.z, m.K, m.mu, m.var = (mu_bar, var_bar), None, None, mu_bar, var_bar
    else:
        m.before = (mu_bar, var_bar)
        m.predicted, m.z, m.K = (mu_bar, var_bar), 3.6, K
        m.mu, m.var = mu_bar + K * (3.6 - mu_bar), (1 - K) * var_bar
    return m


SHOWN = {  # phase -> visible curves (before, prediction, measurement, belief)
    "prior": (False, False, False, True),
    "predicted": (True, True, False, False),
    "updated": (False, True, True, True),
}


@pytest.mark.parametrize("phase", list(SHOWN))
def test_each_half_step_shows_its_curves(phase):
    view = step_through_view()
    m = model(phase)
    update_step_through(view, m)
    visible = tuple(curve[0].get_visible() for curve in view.curves)
    assert visible == SHOWN[phase]
    params = (m.before, m.predicted or m.before, (m.z, m.Q), (m.mu, m.var))
    for curve, shown, (mu, var) in zip(view.curves, visible, params, strict=True):
        if shown:
            line = curve[0]
            np.testing.assert_allclose(line.get_ydata(), kf.gaussian_pdf(line.get_xdata(), mu, var))
    faded = tuple(handle.get_alpha() == 1.0 for handle in view.legend.legend_handles)
    assert faded == visible  # the legend fades what is not shown
    assert view.reading.get_visible() == (phase == "updated")
    if phase == "updated":
        assert view.reading.get_xdata()[0] == 3.6
        assert "K = 0.857" in view.status.get_text()


@pytest.mark.parametrize("phase", list(SHOWN))
def test_the_axes_follow_the_belief_in_coarse_steps(phase):
    view = step_through_view()
    m = model(phase)
    update_step_through(view, m)
    lo, hi = view.ax.get_xlim()
    assert (lo + hi) / 2 == round(m.mu) and hi - lo == 2 * HALF_WIDTH
    bottom, top = view.ax.get_ylim()
    peak = max(curve[0].get_ydata().max() for curve in view.curves if curve[0].get_visible())
    assert bottom == 0 and 1.1 * peak <= top < 2.2 * peak
    assert np.log2(top) == round(np.log2(top))  # a power of two


def test_a_new_noise_with_the_same_limits_redraws_only_the_curves():
    view = step_through_view()
    update_step_through(view, model("updated"))
    renderer = FigureRenderer(view.fig, view.moving)
    first = renderer.image().tobytes()
    update_step_through(view, model("updated", Q=0.12))  # the same phase, centre and density top
    assert renderer.image().tobytes() != first
    assert renderer.full_draws == 1
    update_step_through(view, model("predicted"))  # the legend changes: drawn again
    renderer.image()
    assert renderer.full_draws == 2
