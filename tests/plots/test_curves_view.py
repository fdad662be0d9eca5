"""The pictures of chapters 7 and 9 made and moved by hand: the four panels, the density
helpers, and each demo's view driven by a model, without a demo around it."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.curve_panels import (
    ARROW,
    CUT,
    HEADROOM,
    function_panels,
    show_sideways_gaussian,
    sideways_histogram,
)
from kfcourse.plots.ekf_figures import linearization_view, update_linearization_view
from kfcourse.plots.style import FigureRenderer, set_limits
from kfcourse.plots.ukf_figures import sigma_points_view, update_sigma_points_view
from kfcourse.sim.curve_functions import GaussianThroughCurve

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.

LIMITS = {"x²": (-1.0, 9.0), "sin x": (-1.25, 1.25), "range √(x² + 1)": (0.5, 5.5)}


def test_panels_share_the_input_and_the_output_axes():
    p = function_panels(8.0, 4.8, (-4.0, 4.0), width_ratio=1.3, height_ratio=1.1)
    assert p.fig.axes == [p.ax_f, p.ax_out, p.ax_in, p.ax_txt]
    p.ax_f.set_ylim(-2.0, 7.0)
    assert p.ax_out.get_ylim() == (-2.0, 7.0)  # the output densities lie along f's y axis
    assert p.ax_in.get_xlim() == (-4.0, 4.0)  # the input density under f, on its x axis
    assert not p.ax_txt.axison


def test_set_limits_sets_only_what_changed():
    p = function_panels(8.0, 4.8, (-4.0, 4.0), width_ratio=1.3, height_ratio=1.1)
    renderer = FigureRenderer(p.fig)
    renderer.image()
    assert not p.fig.stale
    assert set_limits(p.ax_f, xlim=(-4.0, 4.0)) is False and not p.fig.stale  # the same: nothing to redraw
    assert set_limits(p.ax_f, ylim=(0.0, 2.0)) is True and p.fig.stale
    assert p.ax_f.get_ylim() == (0.0, 2.0)


@pytest.mark.fact
def test_sideways_histogram_is_the_density_of_all_the_samples():
    y = np.random.default_rng(1).normal(0.0, 1.0, 10_000)
    dens, out, peak = sideways_histogram(y, -1.0, 2.0, 30)
    heights, edges = dens[1:-1:2], out[::2]
    assert edges[0] == -1.0 and edges[-1] == 2.0 and heights.size == 30
    assert np.sum(heights * np.diff(edges)) == pytest.approx(np.mean((y >= -1) & (y <= 2)))  # tails count
    assert peak == heights.max() and peak == pytest.approx(1 / np.sqrt(2 * np.pi), rel=0.1)
    assert dens[0] == dens[-1] == 0.0  # the outline starts and ends on the axis


def test_sideways_gaussian_is_cut_off_the_panel_or_an_arrow():
    p = function_panels(8.0, 4.8, (-4.0, 4.0), width_ratio=1.3, height_ratio=1.1)
    (line,) = p.ax_out.plot([], [])
    show_sideways_gaussian(line, 1.0, 0.25, -1.0, 9.0, top=2.0)
    dens, grid = line.get_data()
    assert grid[0] == -1.0 and grid[-1] == 9.0
    np.testing.assert_allclose(dens, kf.gaussian_pdf(grid, 1.0, 0.25))  # peak 0.8 < 2: whole
    show_sideways_gaussian(line, 1.0, 1e-4, -1.0, 9.0, top=2.0)
    dens, _ = line.get_data()
    assert dens.max() == pytest.approx(CUT * 2.0) and CUT > 1.0  # past the edge, where the panel clips it
    show_sideways_gaussian(line, 3.0, 0.0, -1.0, 9.0, top=2.0)
    assert line.get_xydata().tolist() == [[0.0, 3.0], [ARROW * 2.0, 3.0]] and line.get_marker() == ">"


def test_linearization_view_follows_the_model():
    model = GaussianThroughCurve(seed=0, m=1.0, s=0.5)
    view = linearization_view(LIMITS)
    renderer = FigureRenderer(view.fig, view.moving)
    for name, m, s in (("x²", 1.0, 0.5), ("sin x", -0.5, 1.2), ("range √(x² + 1)", 2.0, 0.05)):
        model.set_function(name)
        model.set_m(m)
        model.set_s(s)
        update_linearization_view(view, model)
        renderer.image()
        x = view.curve.get_xdata()
        np.testing.assert_allclose(view.curve.get_ydata(), model.f(x))
        fm, slope = model.f(m), model.df(m)
        np.testing.assert_allclose(view.tangent.get_ydata(), fm + slope * (x - m))
        assert view.point.get_xydata().tolist() == [[m, fm]]
        assert view.panels.ax_f.get_ylim() == LIMITS[name]
        mean_e, _ = model.ekf()
        assert list(view.ekf_mean.get_ydata()) == [mean_e, mean_e]
        assert view.sampled_mean.get_ydata() == pytest.approx([model.samples().mean()] * 2)
        top = view.panels.ax_in.get_ylim()[1]
        assert HEADROOM / (s * np.sqrt(2 * np.pi)) <= top  # the input's peak, with room
        assert f"mean {mean_e:8.3f}" in view.info.get_text()


def test_sigma_points_view_follows_the_model():
    from kfcourse.demos.sigma_points import SigmaPointsModel

    model = SigmaPointsModel(seed=0, m=2.0, s=1.0, lam=2.0)
    view = sigma_points_view({**LIMITS, "x²": (-3.0, 27.0)})
    update_sigma_points_view(view, model)
    chi, _ = model.sigma_points()
    np.testing.assert_allclose(view.on_curve.get_offsets(), np.column_stack([chi, chi**2]))
    np.testing.assert_allclose(view.on_input.get_offsets()[:, 1], kf.gaussian_pdf(chi, 2.0, 1.0))
    np.testing.assert_allclose(view.on_output.get_offsets()[:, 1], chi**2)  # the images, on the output axis
    for (c, y), segment in zip(zip(chi, chi**2, strict=True), view.guides.get_segments(), strict=True):
        np.testing.assert_allclose(segment, [[c, -3.0], [c, y], [5.0, y]])  # up to the curve, across to the right
    rows = {line.split()[0]: line.split()[1:] for line in view.info.get_text().splitlines() if line.strip()}
    assert rows["UKF"] == rows["exact"] == ["5.000", "18.0000"]  # lambda = 2 makes x²'s variance exact


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: function_panels(8.0, 4.8, (4.0, -4.0), 1.3, 1.1), "x_range"),
        (lambda: sideways_histogram([1.0, 2.0], 0.0, 3.0, 0), "bins"),
        (lambda: sideways_histogram([1.0, 2.0], 3.0, 3.0, 10), "lo, hi"),
        (lambda: linearization_view({"x²": (9.0, -1.0)}), "output_limits"),
        (lambda: sigma_points_view(LIMITS, bins=0), "bins"),
        (lambda: sigma_points_view(LIMITS, x_range=(0.0, np.nan)), "x_range"),
    ],
)
def test_bad_input_is_refused_by_name(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_a_gaussian_needs_a_variance_and_a_density_axis():
    (line,) = function_panels(8.0, 4.8, (-4.0, 4.0), 1.3, 1.1).ax_out.plot([], [])
    with pytest.raises(ValueError, match="var"):
        show_sideways_gaussian(line, 0.0, -1.0, -1.0, 1.0, top=1.0)
    with pytest.raises(ValueError, match="top"):
        show_sideways_gaussian(line, 0.0, 1.0, -1.0, 1.0, top=0.0)
