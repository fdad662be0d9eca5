"""The landmark-loop pictures of chapter 10: what the strips plot is the stated definition,
the static chart draws the step asked for, and a step outside the run is refused."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.loop import error_strips, loop_figure, loop_map, strip_limit


@pytest.fixture(scope="module")
def run():
    return kf.sim.landmark_loop(0, dropout=(40, 70), kidnap=90, gate=4.0)


def test_position_errors_are_truth_minus_estimate_and_two_sigma_per_axis(run):
    error, bound = kf.plots.position_errors(run)
    np.testing.assert_allclose(error, run.truth[:, :2] - run.mu[:, :2])
    np.testing.assert_allclose(bound[:, 0], 2 * np.sqrt(run.Sig[:, 0, 0]))
    np.testing.assert_allclose(bound[:, 1], 2 * np.sqrt(run.Sig[:, 1, 1]))
    np.testing.assert_allclose(np.hypot(*error.T), run.error)  # the record's distance, split into x and y


def test_chart_draws_the_step_asked_for(run):
    fig = kf.plots.loop_chart(run, k=55)
    ax_map, ax_x, ax_y = fig.axes
    trail = next(line for line in ax_map.get_lines() if len(line.get_xydata()) == 56)
    np.testing.assert_allclose(trail.get_xydata()[-1], run.mu[55, :2])  # the estimate's trail ends at step 55
    assert "sensor blind" in [t.get_text() for t in ax_map.texts]
    for ax in (ax_x, ax_y):  # the strips hold the whole run: every error and bound within their limit
        assert ax.get_ylim() == (-1.0, 1.0) and ax.texts[-1].get_text() == f"{strip_limit(run):g}"
        errors = [line.get_ydata() for line in ax.get_lines() if len(line.get_ydata()) > 2]  # past and future
        assert sum(map(len, errors)) == run.t.size + 1 and np.abs(np.concatenate(errors)).max() <= 1.0
        (band,) = (c for c in ax.collections if len(c.get_paths()))
        assert np.abs(band.get_paths()[0].vertices[:, 1]).max() <= 1.0
    assert fig._repr_png_()[:4] == b"\x89PNG"


def test_kidnap_splits_the_true_path(run):
    _, ax_map, strip_axes = loop_figure(run)
    view = loop_map(ax_map, run, 100)
    strips = error_strips(strip_axes, run, 100)
    assert len(view.truth_before.get_xydata()) == 90 and len(view.truth_after.get_xydata()) == run.t.size - 90
    assert "kidnapped" in view.note.get_text()
    assert all(line.get_visible() for line in strips.kidnap)
    assert strips.kidnap[0].get_xdata()[0] == pytest.approx(run.t[90])


@pytest.mark.parametrize("k", [-1, 122, 1000])
def test_a_step_outside_the_run_is_refused(run, k):
    with pytest.raises(ValueError, match="k must be a step of the run"):
        kf.plots.loop_chart(run, k=k)


def test_the_ellipses_are_drawn_over_the_estimated_robot(run):
    """A 2-sigma ellipse of a few centimetres must not hide under the robot's triangle."""
    _, ax_map, _ = loop_figure(run)
    view = loop_map(ax_map, run, 60)
    for ring in (view.ring, view.prior_ring):
        assert ring.get_zorder() > view.robot.get_zorder()  # the static chart draws by zorder
        assert view.moving.index(ring) > view.moving.index(view.robot)  # the demo's renderer draws in this order
    assert view.robot.get_facecolor()[3] < 1.0  # a see-through fill


def test_strips_plot_in_units_of_their_limit_and_label_it(run):
    _, _, strip_axes = loop_figure(run)
    strips = error_strips(strip_axes, run, 100)
    error, bound = kf.plots.position_errors(run)
    top = strip_limit(run)
    assert top >= 1.15 * max(np.abs(error).max(), bound.max())
    decade = 10.0 ** np.floor(np.log10(top))
    assert round(top / decade, 9) in (1.0, 2.0, 5.0) and top / 2.5 < 1.15 * max(np.abs(error).max(), bound.max())
    for i, ax in enumerate(strip_axes):
        assert ax.get_ylim() == (-1.0, 1.0)
        np.testing.assert_allclose(strips.past[i].get_xydata()[-1], [run.t[100], error[100, i] / top])
        assert strips.bands[i].get_paths()[0].vertices[:, 1].max() == pytest.approx(bound[:, i].max() / top)
        assert [label.get_text() for label in strips.labels[i]] == [f"\u2212{top:g}", "0", f"{top:g}"]
        assert all(not label.get_text().strip("\u2007") for label in ax.get_yticklabels())  # the axis's own: blank


def test_a_new_run_changes_the_tick_labels_never_the_axes():
    """The strips' limit follows the run through their labels only, so the demo's blitted picture,
    which never redraws its background after a change of run, is still right."""
    demo = kf.demos.landmark_loop(seed=0)
    strips_axes = demo.renderer.fig.axes[1:]
    changes = [
        lambda: demo.controls["kidnap"].click(),
        lambda: demo.controls["kidnap"].click(),
        lambda: setattr(demo.controls["dropout"], "value", True),
        lambda: setattr(demo.controls["sensor"], "value", 10.0),
        lambda: setattr(demo.controls["motion"], "value", 0.1),
        lambda: setattr(demo.controls["dropout"], "value", False),
    ]
    tops = set()
    for change in changes:
        change()
        tops.add(strip_limit(demo.model.run))
        label = strips_axes[0].texts[0]  # the x strip's label at -1
        assert label.get_text() == f"\u2212{strip_limit(demo.model.run):g}"
        assert all(ax.get_ylim() == (-1.0, 1.0) for ax in strips_axes)
        shown = np.asarray(demo.renderer.image(), dtype=float)
        demo.renderer.fig.stale = True
        full = np.asarray(demo.renderer.image(), dtype=float)
        assert (np.abs(shown - full).max(axis=2) > 40).sum() == 0
    assert len(tops) >= 4  # the limit did change on the way
