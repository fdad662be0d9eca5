"""The landmark-loop pictures of chapter 10: what the strips plot is the stated definition,
the static chart draws the step asked for, and a step outside the run is refused."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.loop import error_strips, loop_figure, loop_map


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
    _, bound = kf.plots.position_errors(run)
    for ax in (ax_x, ax_y):
        assert ax.get_ylim()[1] >= max(np.abs(run.truth[:, :2] - run.mu[:, :2]).max(), bound.max())
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
