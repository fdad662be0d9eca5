"""Static charts: each draws what its docstring promises."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.colors import to_hex

import kfcourse as kf
from kfcourse.plots import palette


def _points_by_colour(ax):
    """Single-point markers of the axes, keyed by their colour."""
    return {to_hex(line.get_color()): line.get_xydata()[0] for line in ax.get_lines() if len(line.get_xdata()) == 1}


@pytest.mark.parametrize(("var1", "var2"), [(0.60, 0.10), (0.10, 0.60), (2.0, 2.0), (1e-3, 5.0)])
def test_blend_variance_chart_marks_the_minimum_at_the_gain(var1, var2):
    fig = kf.plots.charts.blend_variance_chart(var1, var2)
    (ax,) = fig.axes
    K = var1 / (var1 + var2)
    points = _points_by_colour(ax)
    assert np.allclose(points[palette.ESTIMATE], [K, var1 * var2 / (var1 + var2)])
    assert np.allclose(points[palette.PREDICTION], [0.0, var1])
    assert np.allclose(points[palette.MEASUREMENT], [1.0, var2])
    # the parabola's lowest sampled point is where the teal marker sits
    curve = next(line.get_xydata() for line in ax.get_lines() if len(line.get_xdata()) > 1)
    lowest = curve[np.argmin(curve[:, 1])]
    assert lowest[0] == pytest.approx(K, abs=1 / 400)
    assert lowest[1] >= points[palette.ESTIMATE][1] - 1e-12
    assert np.allclose(curve[:, 1], (1 - curve[:, 0]) ** 2 * var1 + curve[:, 0] ** 2 * var2)


def test_blend_variance_chart_worked_numbers_of_chapter_4():
    fig = kf.plots.charts.blend_variance_chart(0.60, 0.10)
    teal = _points_by_colour(fig.axes[0])[palette.ESTIMATE]
    assert teal[0] == pytest.approx(6 / 7)
    assert teal[1] == pytest.approx(0.06 / 0.70)


@pytest.mark.parametrize(("var1", "var2", "name"), [(0.0, 1.0, "var1"), (1.0, -2.0, "var2"), (np.nan, 1.0, "var1")])
def test_blend_variance_chart_rejects_bad_variances(var1, var2, name):
    with pytest.raises(ValueError, match=name):
        kf.plots.charts.blend_variance_chart(var1, var2)


@pytest.mark.parametrize("nsig", [1.0, 2.0])
@pytest.mark.parametrize("Sig", [[[2.0, 0.85], [0.85, 1.0]], [[1.0, -0.9], [-0.9, 3.0]], [[2.5, 0.0], [0.0, 0.5]]])
def test_ellipse_shadow_chart_axes_from_eigenvalues_shadow_from_diagonal(Sig, nsig):
    Sig = np.array(Sig)
    fig = kf.plots.charts.ellipse_shadow_chart(Sig, nsig)
    (ax,) = fig.axes
    lam = np.linalg.eigvalsh(Sig)
    (ellipse,) = ax.patches
    assert sorted([ellipse.width / 2, ellipse.height / 2]) == pytest.approx(nsig * np.sqrt(lam))
    # the ellipse's own extent along x and y, from its semi-axes and tilt
    a, b, t = ellipse.width / 2, ellipse.height / 2, np.radians(ellipse.angle)
    half_x = np.hypot(a * np.cos(t), b * np.sin(t))
    half_y = np.hypot(a * np.sin(t), b * np.cos(t))
    box = next(line.get_xydata() for line in ax.get_lines() if line.get_linestyle() == "--")
    assert np.abs(box[:, 0]).max() == pytest.approx(nsig * np.sqrt(Sig[0, 0]))
    assert np.abs(box[:, 1]).max() == pytest.approx(nsig * np.sqrt(Sig[1, 1]))
    assert [half_x, half_y] == pytest.approx(nsig * np.sqrt(np.diag(Sig)))  # the box fits the ellipse exactly
    teal = [line.get_xydata() for line in ax.get_lines() if to_hex(line.get_color()) == palette.ESTIMATE]
    lengths = sorted(float(np.linalg.norm(seg[1] - seg[0])) for seg in teal)
    assert lengths == pytest.approx(nsig * np.sqrt(lam))
    assert (teal[0][1] - teal[0][0]) @ (teal[1][1] - teal[1][0]) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(
    ("Sig", "nsig", "name"),
    [(np.eye(3), 1.0, "Sig"), ([[1.0, 2.0], [2.0, 1.0]], 1.0, "Sig"), (np.eye(2), 0.0, "nsig")],
)
def test_ellipse_shadow_chart_rejects_bad_input(Sig, nsig, name):
    with pytest.raises(ValueError, match=name):
        kf.plots.charts.ellipse_shadow_chart(Sig, nsig)


def test_samples_chart_draws_samples_in_a_neutral_colour():
    """Samples are neither a prediction nor a measurement: no role colour for the histogram."""
    samples = np.random.default_rng(0).normal(4.0, np.sqrt(2.0), 5000)
    (ax,) = kf.plots.charts.samples_chart(samples, 4.0, 2.0).axes
    colours = {to_hex(bar.get_facecolor()) for bar in ax.patches}
    assert colours == {palette.INK}
    (curve,) = ax.get_lines()
    assert curve.get_color() == palette.ESTIMATE


def test_convergence_chart_draws_the_steady_state_in_a_neutral_colour():
    """The steady-state lines are a limit, not a prediction: ink, dashed, at the given values."""
    fig = kf.plots.charts.convergence_chart([0.9, 0.5, 0.4], [0.2, 0.12, 0.1], 0.328, 0.082)
    for ax, level in zip(fig.axes, (0.328, 0.082), strict=True):
        (steady,) = [line for line in ax.get_lines() if line.get_linestyle() == "--"]
        assert steady.get_color() == palette.INK
        assert steady.get_ydata()[0] == pytest.approx(level)
        assert palette.PREDICTION not in {line.get_color() for line in ax.get_lines()}
