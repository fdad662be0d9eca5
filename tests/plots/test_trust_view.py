"""Chapter 4's view: the three curves, the gauge and the readout show the model, the density
axis's top is a power of two above the fused peak, and moving a mean redraws only what moves."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.style import FigureRenderer
from kfcourse.plots.trust_view import trust_view, update_trust


def model(mu_pred=-1.0, var_pred=1.0, z=1.5, var_meas=0.3, fused=None) -> SimpleNamespace:
    """Everything :func:`update_trust` reads, and nothing else."""
    K = var_pred / (var_pred + var_meas)
    fused = fused or (mu_pred + K * (z - mu_pred), (1 - K) * var_pred)
    return SimpleNamespace(mu_pred=mu_pred, var_pred=var_pred, z=z, var_meas=var_meas, K=K, fused=lambda: fused)


@pytest.mark.parametrize(("var_pred", "var_meas"), [(1.0, 0.3), (0.01, 10.0), (10.0, 0.01)])
def test_the_update_shows_the_model(var_pred, var_meas):
    view = trust_view()
    m = model(var_pred=var_pred, var_meas=var_meas)
    update_trust(view, m)
    mu_f, var_f = m.fused()
    for (line, shade), mu, var in (
        (view.prediction, m.mu_pred, m.var_pred),
        (view.measurement, m.z, m.var_meas),
        (view.fused, mu_f, var_f),
    ):
        np.testing.assert_allclose(line.get_ydata(), kf.gaussian_pdf(line.get_xdata(), mu, var))
        assert shade.get_paths()[0].vertices[:, 1].max() == pytest.approx(line.get_ydata().max())
    bar, label = view.gauge
    assert bar.get_width() == pytest.approx(m.K) and label.get_text() == f"K = {m.K:.3f}"
    assert f"= {m.K:.3f}" in view.readout.get_text() and f"μ = {mu_f:.3f}" in view.readout.get_text()
    assert "σ² = " in view.readout.get_text() and "not narrower" not in view.readout.get_text()
    top = view.ax.get_ylim()[1]
    peak = view.fused[0].get_ydata().max()
    assert 1.1 * peak <= top < 2.2 * peak and np.log2(top) == round(np.log2(top))


def test_the_verdict_is_computed():
    view = trust_view()
    update_trust(view, model(fused=(0.0, 2.0)))  # wider than both inputs: not what fusion gives
    assert "not narrower than both inputs" in view.readout.get_text()


def test_moving_a_mean_redraws_only_what_moves():
    view = trust_view()
    update_trust(view, model())
    renderer = FigureRenderer(view.fig, view.moving)
    pictures = {renderer.image().tobytes()}
    for mu_pred, z in ((-4.0, 4.0), (3.0, -2.5), (0.0, 0.5)):
        update_trust(view, model(mu_pred=mu_pred, z=z))
        pictures.add(renderer.image().tobytes())
    assert len(pictures) == 4 and renderer.full_draws == 1  # the variances, and so the density axis, stayed
    update_trust(view, model(var_pred=0.01, var_meas=0.01))  # a much taller fused curve: a new top
    renderer.image()
    assert renderer.full_draws == 2
