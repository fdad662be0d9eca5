"""Chapter 12's static charts: the plaza map, the ranges against the true distances and the NEES over time draw
what their docstrings say (what is drawn, in which style, on which axes), not pixels."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from matplotlib.colors import to_hex

import kfcourse as kf
from kfcourse.plots import palette
from kfcourse.plots.describe import figure_alt
from kfcourse.plots.plaza_charts import NEES_LIMITS, RUN_STYLES, WANDER

STEPS = 600  # the first minute of Plaza2: enough of the plaza, quick to run


@pytest.fixture(scope="module")
def plaza2():
    return kf.data.load_plaza("Plaza2")


@pytest.fixture(scope="module")
def runs(plaza2):
    ekf = kf.sim.range_localize(plaza2, scale=1.07, steps=STEPS)
    ukf = kf.sim.range_localize(plaza2, scale=1.07, steps=STEPS, filter="ukf")
    return ekf, kf.sim.smoothed(ekf), ukf


def paths(ax) -> list:
    """The lines of more than two points (the paths and NEES curves, not the guides), in the order drawn."""
    return [line for line in ax.get_lines() if len(line.get_xdata()) > 2]


def legend_texts(ax) -> list[str]:
    return [text.get_text() for text in ax.get_legend().get_texts()]


def test_the_map_alone_is_the_plaza_at_one_scale(plaza2):
    fig = kf.plots.plaza_chart(plaza2)
    (ax,) = fig.axes
    assert ax.get_aspect() == 1.0  # metres the same across and up
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x (m)", "y (m)")
    assert fig.get_suptitle() == "Plaza2: 410 s, 1.35 km"
    truth, drift = paths(ax)
    np.testing.assert_allclose(truth.get_xydata(), plaza2.truth[:, :2])
    np.testing.assert_allclose(drift.get_xydata(), plaza2.dead_reckoning()[:, :2])
    assert (to_hex(truth.get_color()), truth.get_linestyle()) == (palette.TRUTH, palette.TRUTH_LINE)
    assert (to_hex(drift.get_color()), drift.get_linestyle()) == (palette.PREDICTION, palette.PREDICTION_LINE)
    (beacons,) = ax.collections  # purple squares, numbered
    np.testing.assert_allclose(beacons.get_offsets(), plaza2.beacons)
    assert to_hex(beacons.get_facecolor()[0]) == palette.LANDMARK
    assert [text.get_text() for text in ax.texts] == ["0", "1", "2", "3"]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for x, y in np.vstack([plaza2.beacons, plaza2.truth[:, :2], plaza2.dead_reckoning()[:, :2]]):
        assert x0 < x < x1 and y0 < y < y1
    off = np.hypot(*(plaza2.dead_reckoning()[:, :2] - plaza2.truth[:, :2]).T).mean()
    assert legend_texts(ax) == ["truth", f"dead reckoning: mean error {off:.1f} m", "beacons"]
    assert kf.plots.plaza_chart(plaza2, dead_reckoning=False).axes[0].get_legend() is not None
    assert len(paths(kf.plots.plaza_chart(plaza2, dead_reckoning=False).axes[0])) == 1


def test_each_run_is_a_path_in_its_own_style_named_in_the_legend(plaza2, runs):
    fig = kf.plots.plaza_chart(plaza2, *runs, labels=["EKF", "RTS smoother", "UKF"])
    (ax,) = fig.axes
    _, _, *estimates = paths(ax)
    assert len(estimates) == 3
    for line, run, style in zip(estimates, runs, RUN_STYLES, strict=False):
        np.testing.assert_allclose(line.get_xydata(), run.mu[:, :2])
        assert to_hex(line.get_color()) == palette.ESTIMATE  # every estimate teal, told apart by its style
        assert (line.get_linestyle(), line.get_linewidth()) == (style["ls"], style["lw"])
    first, band, dashed = estimates
    assert first.get_linestyle() == "-" and band.get_linewidth() > 3 * first.get_linewidth()
    assert band.get_zorder() < first.get_zorder()  # the wide pale band under the thin line
    assert dashed.get_linestyle() == "--"
    labels = legend_texts(ax)
    for name, run in zip(["EKF", "RTS smoother", "UKF"], runs, strict=True):
        assert f"{name}: mean error {run.error.mean():.2f} m" in labels


def test_runs_without_labels_are_named_by_their_filter(plaza2, runs):
    ekf, smooth, ukf = runs
    labels = legend_texts(kf.plots.plaza_chart(plaza2, ekf, smooth, ukf).axes[0])
    assert [label.split(":")[0] for label in labels[2:5]] == ["EKF (1)", "EKF (2)", "UKF"]
    assert kf.plots.plaza_charts.run_label(ukf) == "UKF"


def test_a_path_that_wanders_off_stretches_the_map_only_so_far(plaza2, runs):
    ekf = runs[0]
    lost = dataclasses.replace(ekf, mu=ekf.mu + np.array([1000.0, 0.0, 0.0]))
    ax = kf.plots.plaza_chart(plaza2, lost).axes[0]
    plaza = np.vstack([plaza2.beacons, plaza2.truth[:, :2], plaza2.dead_reckoning()[:, :2]])
    span = np.ptp(plaza, axis=0)
    assert ax.get_xlim()[1] < plaza[:, 0].max() + 2 * WANDER * span[0] + 20  # not 1000 m off
    assert ax.get_aspect() == 1.0


@pytest.mark.parametrize("labels", [["one"], ["one", "two", "three"]])
def test_a_label_per_run_or_a_clear_refusal(plaza2, runs, labels):
    with pytest.raises(ValueError, match="labels must name each of the 2 runs"):
        kf.plots.plaza_chart(plaza2, *runs[:2], labels=labels)
    with pytest.raises(ValueError, match="labels must name each of the 2 runs"):
        kf.plots.nees_chart(*runs[:2], labels=labels)


def test_a_run_of_another_log_or_not_a_run_is_refused(plaza2):
    plaza1 = kf.data.load_plaza("Plaza1")
    longer = kf.sim.range_localize(plaza1, steps=plaza2.distance.size + 10)
    with pytest.raises(ValueError, match="more than the log's"):
        kf.plots.plaza_chart(plaza2, longer)
    with pytest.raises(ValueError, match="run 1 must be a run record"):
        kf.plots.plaza_chart(plaza2, plaza2.truth)
    with pytest.raises(ValueError, match="at least one run"):
        kf.plots.nees_chart()


@pytest.mark.parametrize("name", kf.data.PLAZA_RUNS)
def test_ranges_chart_draws_each_range_against_its_true_distance_and_the_scale(name):
    log = kf.data.load_plaza(name)
    fig = kf.plots.ranges_chart(log)
    (ax,) = fig.axes
    assert ax.get_aspect() == 1.0 and ax.get_xlim() == ax.get_ylim()
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("true distance to the beacon (m)", "range read (m)")
    assert ax.get_title() == f"{name}: {log.range.size} ranges to 4 beacons"
    readings, honest, fit = ax.get_lines()
    np.testing.assert_allclose(readings.get_xydata(), np.column_stack([log.true_distance(), log.range]))
    assert readings.get_linestyle() == "None" and to_hex(readings.get_color()) == palette.MEASUREMENT
    assert readings.get_xydata().max() < ax.get_xlim()[1]  # every range shows
    x, y = honest.get_data()
    np.testing.assert_allclose(x, y)  # range = distance
    assert (to_hex(honest.get_color()), honest.get_linestyle()) == (palette.TRUTH, palette.TRUTH_LINE)
    slope, intercept = np.polyfit(log.true_distance(), log.range, 1)
    x, y = fit.get_data()
    np.testing.assert_allclose(y, slope * x + intercept)
    assert fit.get_linestyle() == palette.MEASUREMENT_LINE
    assert 1.06 < slope < 1.08  # the radio reads 7 % long, in both logs
    assert f"fit: range = {slope:.3f} × distance" in legend_texts(ax)[2]


def test_nees_chart_draws_each_runs_nees_on_a_log_scale_against_the_95_band(runs):
    fig = kf.plots.nees_chart(*runs[:2], labels=["EKF", "RTS smoother"])
    (ax,) = fig.axes
    assert ax.get_yscale() == "log" and ax.get_ylim() == NEES_LIMITS
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("t (s)", "position NEES (log scale)")
    assert fig.get_suptitle() == "Plaza2: position NEES"
    lines = paths(ax)
    assert len(lines) == 2
    for line, run in zip(lines, runs, strict=False):
        np.testing.assert_allclose(line.get_xdata(), run.t)
        np.testing.assert_allclose(line.get_ydata(), np.clip(run.nees, *NEES_LIMITS))
        assert to_hex(line.get_color()) == palette.ESTIMATE
    assert lines[1].get_linewidth() > 2 * lines[0].get_linewidth()  # the second a wide pale band, as on the map
    (band,) = ax.patches
    ys = band.get_path().transformed(band.get_patch_transform()).vertices[:, 1]
    assert (ys.min(), ys.max()) == pytest.approx(kf.sim.NEES_BAND)  # one NEES's 95 % band, chi-square 2 dof
    (average,) = [line for line in ax.get_lines() if len(line.get_ydata()) == 2]
    assert np.allclose(average.get_ydata(), 2.0)
    labels = legend_texts(ax)
    assert labels[0] == "honest: 95 % of steps in 0.05 to 7.4" and labels[1] == "honest average, 2"
    assert labels[2:] == [
        f"EKF: mean NEES {runs[0].nees.mean():.3g}",
        f"RTS smoother: mean NEES {runs[1].nees.mean():.3g}",
    ]


def test_nees_chart_draws_a_zero_at_the_bottom_and_an_infinite_nees_at_the_top(runs):
    run = dataclasses.replace(runs[0], nees=np.where(np.arange(runs[0].t.size) % 2, np.inf, 0.0))
    (line,) = paths(kf.plots.nees_chart(run).axes[0])
    assert set(line.get_ydata()) == set(NEES_LIMITS)
    huge = dataclasses.replace(runs[0], nees=np.full(runs[0].t.size, 3e5))
    ax = kf.plots.nees_chart(huge).axes[0]
    assert ax.get_ylim() == (NEES_LIMITS[0], 1e6)  # the axis reaches the largest NEES
    assert paths(ax)[0].get_ydata().max() == 3e5


def test_the_alt_text_names_the_title_the_axes_and_the_runs(plaza2, runs):
    alt = figure_alt(kf.plots.plaza_chart(plaza2, runs[0], labels=["EKF"]))
    assert alt.startswith("Figure: Plaza2: 410 s, 1.35 km. Panel: y (m) against x (m); shows truth, dead reckoning")
    assert "EKF" in alt and "beacons" in alt
    alt = figure_alt(kf.plots.nees_chart(runs[0], labels=["EKF"]))
    assert "position NEES (log scale) against t (s)" in alt and "honest" in alt
    assert "range read (m) against true distance to the beacon (m)" in figure_alt(kf.plots.ranges_chart(plaza2))


def test_the_charts_are_figures_that_show_themselves(plaza2, runs):
    for fig in (kf.plots.plaza_chart(plaza2, *runs), kf.plots.ranges_chart(plaza2), kf.plots.nees_chart(*runs)):
        png = fig._repr_png_()
        assert png[:4] == b"\x89PNG" and len(png) > 10_000
