"""The chapter 3 run chart draws what it says, and nothing drawn is NaN."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import PolyCollection
from matplotlib.lines import Line2D

import kfcourse as kf
from kfcourse.plots import palette

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


def lines_by_colour(ax, colour):
    return [a for a in ax.get_lines() if a.get_color() == colour]


@pytest.mark.parametrize("kwargs", [{}, {"velocity": 0.1}, {"Q": 0.0025}, {"mu0": 10.0, "var0": 100.0}])
def test_chart_draws_two_finite_panels(kwargs):
    run = kf.sim.simulate_walk(seed=0, **kwargs)
    fig = kf.plots.kf_run_chart(run, title="a run")
    assert len(fig.axes) == 2
    for ax in fig.axes:
        for line in ax.get_lines():
            assert np.isfinite(np.asarray(line.get_xydata(), float)).all()
        for coll in ax.collections:
            for path in coll.get_paths():
                assert np.isfinite(path.vertices).all()
    png = fig._repr_png_()
    assert png[:4] == b"\x89PNG" and len(png) > 10_000


def test_top_panel_is_estimate_band_truth_and_readings_relative_to_the_commanded_path():
    run = kf.sim.simulate_walk(30, seed=1)
    top, _ = kf.plots.kf_run_chart(run).axes
    path = run.x0 + np.cumsum(run.u)
    (truth,) = lines_by_colour(top, palette.TRUTH)
    readings, estimate = lines_by_colour(top, palette.MEASUREMENT) + lines_by_colour(top, palette.ESTIMATE)
    np.testing.assert_allclose(truth.get_ydata(), run.truth - path)
    np.testing.assert_allclose(readings.get_ydata(), run.z - path)
    np.testing.assert_allclose(estimate.get_ydata(), run.mu - path)
    (band,) = [c for c in top.collections if isinstance(c, PolyCollection)]
    ys = band.get_paths()[0].vertices[:, 1]
    sigma = np.sqrt(run.var)
    assert ys.max() == pytest.approx(np.max(run.mu - path + sigma))
    assert ys.min() == pytest.approx(np.min(run.mu - path - sigma))


def test_without_detrend_positions_are_plotted_as_they_are():
    run = kf.sim.simulate_walk(30, seed=1)
    top, _ = kf.plots.kf_run_chart(run, detrend=False).axes
    (truth,) = lines_by_colour(top, palette.TRUTH)
    np.testing.assert_allclose(truth.get_ydata(), run.truth)


def test_bottom_panel_is_innovations_in_their_sqrt_S_band():
    run = kf.sim.simulate_walk(30, seed=1, velocity=0.1)
    _, bottom = kf.plots.kf_run_chart(run).axes
    innovation, mean = lines_by_colour(bottom, palette.MEASUREMENT)
    np.testing.assert_allclose(innovation.get_ydata(), run.innovation)
    assert mean.get_ydata()[0] == pytest.approx(run.innovation.mean())
    (band,) = [c for c in bottom.collections if isinstance(c, PolyCollection)]
    ys = band.get_paths()[0].vertices[:, 1]
    assert ys.max() == pytest.approx(np.sqrt(run.S).max())
    assert isinstance(innovation, Line2D)


@pytest.mark.fact
@pytest.mark.parametrize("start", [0, 20])
def test_mean_innovation_line_covers_its_window_and_the_legend_names_it(start):
    """The dashed mean is over the steps from index ``start`` on, drawn only there, and its legend
    entry says which steps and matches the run's own mean_innovation(start)."""
    run = kf.sim.simulate_walk(seed=0, velocity=0.1)
    _, bottom = kf.plots.kf_run_chart(run, start=start).axes
    _, mean = lines_by_colour(bottom, palette.MEASUREMENT)
    assert mean.get_ydata()[0] == pytest.approx(run.mean_innovation(start))
    assert list(mean.get_xdata()) == [start + 1, 100]
    label = mean.get_label()
    assert f"{run.mean_innovation(start):+.2f} m" in label
    assert ("all steps" in label) == (start == 0)
    assert start == 0 or "steps 21–100" in label
    assert run.mean_innovation(20) != pytest.approx(run.mean_innovation(0), abs=0.01)  # the window shows


@pytest.mark.parametrize("start", [-1, 100, 2.5, True])
def test_bad_start_is_refused(start):
    run = kf.sim.simulate_walk(seed=0)
    with pytest.raises(ValueError, match="start"):
        kf.plots.kf_run_chart(run, start=start)
