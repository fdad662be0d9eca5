"""Chapter 9's charts: the unscented transform against the samples, and the UKF beside the EKF."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots import palette

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


@pytest.fixture(scope="module")
def runs():
    return kf.sim.landmark_loop(0, filter="ekf"), kf.sim.landmark_loop(0, filter="ukf")


def lines_of(ax, colour):
    return [line for line in ax.get_lines() if line.get_color() == colour]


@pytest.mark.pixels
@pytest.mark.fact
def test_moments_chart_draws_the_samples_and_both_gaussians():
    y = np.random.default_rng(0).normal(2.0, 1.0, 50_000) ** 2
    fig = kf.plots.transform_moments_chart(y, (5.0, 16.0), (4.0, 16.0), bins=50, y_range=(-1.0, 25.0))
    (ax,) = fig.axes
    assert len(ax.patches) == 50
    heights = np.array([p.get_height() for p in ax.patches])
    widths = np.array([p.get_width() for p in ax.patches])
    assert np.sum(heights * widths) == pytest.approx(np.mean((y >= -1) & (y <= 25)), rel=1e-6)  # density of all y
    assert not lines_of(ax, palette.MEASUREMENT)  # no orange: the EKF is an estimate, teal dashed
    for style, mean in (("-", 5.0), ("--", 4.0)):  # the UKF solid, the EKF dashed
        curve, mean_line = [line for line in lines_of(ax, palette.ESTIMATE) if line.get_linestyle() == style]
        grid, dens = curve.get_data()
        assert grid[np.argmax(dens)] == pytest.approx(mean, abs=0.05)
        mass = 0.5 * (math.erf((25 - mean) / (4 * math.sqrt(2))) - math.erf((-1 - mean) / (4 * math.sqrt(2))))
        assert np.trapezoid(dens, grid) == pytest.approx(mass, abs=1e-3)  # N(mean, 16) over (-1, 25)
        assert np.allclose(mean_line.get_xdata(), mean)
    assert "UKF N(5, 16)" in [t.get_text() for t in ax.get_legend().get_texts()]
    # The samples' mean (here on the UKF's) is wide dots (the truth's style) under the filters' thin lines: all show.
    (band,) = [line for line in ax.get_lines() if line.get_label() == "samples' mean"]
    assert np.allclose(band.get_xdata(), y.mean()) and abs(y.mean() - 5.0) < 0.05
    (_, ukf_mean) = [line for line in lines_of(ax, palette.ESTIMATE) if line.get_linestyle() == "-"]
    assert band.get_linewidth() >= 3 * ukf_mean.get_linewidth() and band.get_zorder() < ukf_mean.get_zorder()
    assert band.get_linestyle() == palette.TRUTH_LINE
    png = fig._repr_png_()
    assert png[:4] == b"\x89PNG" and len(png) > 5_000


def test_moments_chart_refuses_bad_input():
    y = np.arange(10.0)
    with pytest.raises(ValueError, match="ukf"):
        kf.plots.transform_moments_chart(y, (5.0, -1.0), (4.0, 16.0))
    with pytest.raises(ValueError, match="bins"):
        kf.plots.transform_moments_chart(y, (5.0, 1.0), (4.0, 16.0), bins=1)
    with pytest.raises(ValueError, match="y_range"):
        kf.plots.transform_moments_chart(y, (5.0, 1.0), (4.0, 16.0), y_range=(3.0, 3.0))


def test_comparison_chart_draws_both_estimates_and_errors(runs):
    """Both teal: the UKF solid (wide, pale), the EKF dashed over it; no orange."""
    ekf, ukf = runs
    fig = kf.plots.filter_comparison_chart(ekf, ukf)
    ax_map, ax_e = fig.axes
    for ax, ekf_data, ukf_data in ((ax_map, ekf.mu[:, :2], ukf.mu[:, :2]), (ax_e, ekf.error, ukf.error)):
        assert not lines_of(ax, palette.MEASUREMENT)
        (u_line, e_line) = lines_of(ax, palette.ESTIMATE)  # the UKF first, the EKF drawn over it
        assert u_line.get_linestyle() == "-" and e_line.get_linestyle() == "--"
        assert u_line.get_linewidth() > e_line.get_linewidth()
        got = [line.get_xydata() if ax is ax_map else line.get_ydata() for line in (e_line, u_line)]
        assert np.allclose(got[0], ekf_data) and np.allclose(got[1], ukf_data)
    labels = [t.get_text() for t in ax_e.get_legend().get_texts()]
    assert labels == [
        f"UKF, RMS {np.sqrt(np.mean(ukf.error**2)):.3f} m",
        f"EKF, RMS {np.sqrt(np.mean(ekf.error**2)):.3f} m",
    ]
    png = fig._repr_png_()
    assert png[:4] == b"\x89PNG" and len(png) > 10_000


@pytest.mark.fact
@pytest.mark.parametrize("motion_noise", [1.0, 50.0])
def test_comparison_chart_shows_every_landmark_clear_of_the_legend(motion_noise):
    ekf = kf.sim.landmark_loop(0, filter="ekf", motion_noise=motion_noise)
    ukf = kf.sim.landmark_loop(0, filter="ukf", motion_noise=motion_noise)
    fig = kf.plots.filter_comparison_chart(ekf, ukf)
    fig.canvas.draw()
    ax_map = fig.axes[0]
    renderer = fig.canvas.get_renderer()
    assert len(ekf.landmarks) == 7
    points = ax_map.transData.transform(ekf.landmarks)  # pixels
    axes_box = ax_map.get_window_extent(renderer)
    legend_box = ax_map.get_legend().get_window_extent(renderer).padded(6.0)  # a square's half-width in pixels
    for (px, py), landmark in zip(points, ekf.landmarks, strict=True):
        assert axes_box.x0 < px < axes_box.x1 and axes_box.y0 < py < axes_box.y1, landmark
        assert not legend_box.contains(px, py), landmark


def test_comparison_chart_refuses_two_different_drives(runs):
    other = kf.sim.landmark_loop(0, filter="ukf", laps=2)
    with pytest.raises(ValueError, match="same drive"):
        kf.plots.filter_comparison_chart(runs[0], other)
