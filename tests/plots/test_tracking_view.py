"""Chapter 6's pictures made and moved by hand: the tracker's map and the NEES panel."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.colors import to_hex

import kfcourse as kf
from kfcourse.filters.gaussian import ellipse_axes
from kfcourse.plots import palette
from kfcourse.plots.style import FigureRenderer
from kfcourse.plots.tracking import (
    ARROW_TIME,
    nees_view,
    tracker_view,
    update_nees_view,
    update_tracker_view,
    velocity_tip,
)

# No test here states a fact of a seeded run: those that run one are listed in tests/facts.py UNMARKED with the
# reason they need no repeat.


@pytest.fixture(scope="module")
def tracked():
    run = kf.sim.simulate_target(0)
    est = kf.sim.filter_target(run, kf.sim.process_noise(run.dt, 10.0), np.eye(2))
    return run, est


def test_tracker_map_holds_the_path_at_one_scale_and_shows_the_step(tracked):
    run, est = tracked
    view = tracker_view(run)
    ax = view.fig.axes[0]
    assert ax.get_aspect() == 1.0  # a metre is as long along x as along y
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x0 < run.truth[:, 0].min() and run.truth[:, 0].max() < x1
    assert y0 < run.truth[:, 1].min() and run.truth[:, 1].max() < y1
    for k in (0, 60, run.t.size - 1):
        update_tracker_view(view, SimpleNamespace(run=run, est=est, frame=k))
        np.testing.assert_array_equal(view.readings.get_offsets(), run.z[: k + 1])
        np.testing.assert_array_equal(view.trail.get_xydata(), est.mu[: k + 1, :2])
        np.testing.assert_array_equal(view.ahead.get_xydata(), est.mu[k:, :2])
        velocity = np.diff(view.truth_velocity.get_xydata(), axis=0)[0]
        np.testing.assert_allclose(velocity, ARROW_TIME * run.truth[k, 2:], atol=1e-9)
        assert view.ring.get_center() == pytest.approx(est.mu[k, :2])
        w, h, _ = ellipse_axes(est.Sig[k, :2, :2], 2.0)
        assert (view.ring.get_width(), view.ring.get_height()) == pytest.approx((w, h))


def test_tracker_steps_redraw_only_the_moving_artists(tracked):
    run, est = tracked
    view = tracker_view(run)
    renderer = FigureRenderer(view.fig, view.moving)
    pictures = []
    for k in (10, 11, 90):
        update_tracker_view(view, SimpleNamespace(run=run, est=est, frame=k))
        pictures.append(np.asarray(renderer.image()))
    assert renderer.full_draws == 1
    assert not np.array_equal(pictures[0], pictures[1])


def test_velocity_tip_is_cut_at_the_edge_of_the_map():
    lo, hi = np.array([0.0, 0.0]), np.array([10.0, 10.0])
    np.testing.assert_allclose(velocity_tip(np.array([5.0, 5.0]), [2.0, 1.0], lo, hi), [7.0, 6.0])  # fits
    np.testing.assert_allclose(velocity_tip(np.array([9.0, 5.0]), [4.0, 0.0], lo, hi), [10.0, 5.0])  # cut at x = 10
    np.testing.assert_allclose(velocity_tip(np.array([5.0, 5.0]), [0.0, 0.0], lo, hi), [5.0, 5.0])
    np.testing.assert_allclose(velocity_tip(np.array([12.0, 5.0]), [3.0, 0.0], lo, hi), [12.0, 5.0])  # off the map


def test_nees_panel_draws_the_band_and_clips_the_curve_to_its_axis():
    t = 0.1 * np.arange(60)
    view = nees_view(t, (3.6, 4.4), dof=4, n_tracks=200)
    ax = view.fig.axes[0]
    assert ax.get_yscale() == "log" and ax.get_ylim() == pytest.approx((0.5, 500.0))
    labels = [h.get_label() for h in ax.get_legend().legend_handles]
    assert labels == ["95 % band for 200 honest runs", "4 = state dimension", "average NEES of the filter"]
    avg = np.geomspace(0.01, 5000.0, 60)
    update_nees_view(view, SimpleNamespace(avg_nees=avg))
    np.testing.assert_array_equal(view.curve.get_xdata(), t)
    np.testing.assert_allclose(view.curve.get_ydata(), np.clip(avg, 0.5, 500.0))  # off-scale: on the edge


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [({"y_range": (0.0, 500.0)}, "y_range"), ({"y_range": (5.0, 1.0)}, "y_range"), ({"band": (4.4, 3.6)}, "band"),
     ({"t": [0.0]}, "t")],
)  # fmt: skip
def test_nees_panel_refuses_bad_input_by_name(kwargs, name):
    args = {"t": 0.1 * np.arange(60), "band": (3.6, 4.4), "dof": 4, "n_tracks": 200} | kwargs
    with pytest.raises(ValueError, match=name):
        nees_view(**args)


def test_tracker_ellipse_is_lightly_filled_so_a_huge_one_still_shows(tracked):
    """An ellipse larger than the map has no edge in the picture; its light teal fill tints the map instead."""
    view = tracker_view(tracked[0])
    assert view.ring.get_fill()
    face, edge = view.ring.get_facecolor(), view.ring.get_edgecolor()
    assert to_hex(face[:3]) == to_hex(edge[:3]) == palette.ESTIMATE
    assert 0.0 < face[3] <= 0.15 and edge[3] == 1.0


def test_nees_panel_labels_the_average_nees_by_name():
    """The course writes NEES by name: eta is chapter 1's normaliser."""
    view = nees_view(0.1 * np.arange(60), (3.6, 4.4), dof=4, n_tracks=200)
    assert view.fig.axes[0].get_ylabel() == "average NEES"
