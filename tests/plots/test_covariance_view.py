"""Chapter 2's view: the contours, their labels, the shadow box and the table show the
model's Σ, and a new Σ never redraws the background (the view is fixed)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.covariance_view import covariance_view, update_covariance
from kfcourse.plots.style import FigureRenderer

WHITE = np.random.default_rng(0).standard_normal((500, 2))


def model(var_x: float, var_y: float, rho: float) -> SimpleNamespace:
    """Everything :func:`update_covariance` reads, and nothing else."""
    c = rho * np.sqrt(var_x * var_y)
    Sig = np.array([[var_x, c], [c, var_y]])
    d2 = np.sum(WHITE**2, axis=1)
    return SimpleNamespace(
        Sig=Sig,
        samples=lambda: WHITE @ np.linalg.cholesky(Sig).T,
        fractions=lambda: np.array([np.mean(d2 <= k * k) for k in (1, 2, 3)]),
    )


@pytest.mark.parametrize(("var_x", "var_y", "rho"), [(2.0, 1.0, 0.6), (0.1, 4.0, -0.95), (1.0, 1.0, 0.0)])
def test_the_update_shows_sigma(var_x, var_y, rho):
    view = covariance_view()
    m = model(var_x, var_y, rho)
    update_covariance(view, m)
    np.testing.assert_allclose(view.dots.get_offsets(), m.samples())
    for ring, label, k in zip(view.rings, view.labels, (1, 2, 3), strict=True):
        width, height, angle = kf.ellipse_axes(m.Sig, k)
        assert (ring.width, ring.height, ring.angle) == pytest.approx((width, height, angle))
        assert ring.center == pytest.approx((0.0, 0.0))
        end = np.array(label.get_position())
        assert np.linalg.norm(end) == pytest.approx(1.03 * k * np.sqrt(np.linalg.eigvalsh(m.Sig)[1]))
        assert end[0] >= 0  # at the right end of the major axis
    box = view.shadow.get_xydata()
    assert box.max(axis=0) == pytest.approx(np.sqrt(np.diag(m.Sig)))  # ±σx, ±σy
    text = view.info.get_text()
    assert f"[{m.Sig[0, 0]:5.2f} {m.Sig[0, 1]:5.2f}]" in text
    for k, share in zip((1, 2, 3), m.fractions(), strict=True):
        theory = kf.mass_inside(np.array([k]), dim=2)[0]
        assert f" {k}σ   {100 * share:5.1f}% {100 * theory:5.1f}%" in text


def test_a_new_sigma_only_moves_the_moving_artists():
    view = covariance_view()
    update_covariance(view, model(2.0, 1.0, 0.6))
    renderer = FigureRenderer(view.fig, view.moving)
    first = renderer.image().tobytes()
    for var_x, var_y, rho in ((4.0, 4.0, 0.95), (0.1, 0.1, -0.95), (2.0, 1.0, 0.0)):
        update_covariance(view, model(var_x, var_y, rho))
        assert renderer.image().tobytes() != first
    assert renderer.full_draws == 1


def test_the_table_follows_the_contours_asked_for():
    view = covariance_view(sigmas=(1, 2))
    assert len(view.rings) == len(view.labels) == 2
    m = model(2.0, 1.0, 0.6)
    m.fractions = lambda: np.array([0.4, 0.86])
    update_covariance(view, m)
    assert "3σ" not in view.info.get_text()


@pytest.mark.parametrize("sigmas", [(), (0,), (1, 4), (True,)])
def test_sigmas_must_be_one_to_three(sigmas):
    with pytest.raises(ValueError, match="sigmas"):
        covariance_view(sigmas)
