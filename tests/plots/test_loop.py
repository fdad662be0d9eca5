"""The landmark-loop pictures of chapter 10: what the strips plot is the stated definition, in
metres on real axes, the static chart draws the step asked for, a step outside the run is
refused, and the demo's picture redraws its background only when the strips' limits change."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots.loop import error_strips, loop_figure, loop_map, strip_limit

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


def tick_values(ax) -> list[float]:
    """The y tick labels of an axis, read as numbers."""
    return [float(label.get_text().strip("\u2007").replace("\u2212", "-")) for label in ax.get_yticklabels()]


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
    top = strip_limit(run)
    for ax in (ax_x, ax_y):  # the strips hold the whole run: every error and bound within their limits
        assert ax.get_ylim() == (-top, top) and tick_values(ax) == [-top, 0.0, top]
        errors = [line.get_ydata() for line in ax.get_lines() if len(line.get_ydata()) > 2]  # past and future
        assert sum(map(len, errors)) == run.t.size + 1 and np.abs(np.concatenate(errors)).max() <= top
        (band,) = (c for c in ax.collections if len(c.get_paths()))
        assert np.abs(band.get_paths()[0].vertices[:, 1]).max() <= top
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


def test_strips_plot_metres_on_real_axes_with_a_round_limit(run):
    _, _, strip_axes = loop_figure(run)
    strips = error_strips(strip_axes, run, 100)
    error, bound = kf.plots.position_errors(run)
    top = strip_limit(run)
    assert top >= 1.15 * max(np.abs(error).max(), bound.max())
    decade = 10.0 ** np.floor(np.log10(top))
    assert round(top / decade, 9) in (1.0, 2.0, 5.0) and top / 2.5 < 1.15 * max(np.abs(error).max(), bound.max())
    for i, ax in enumerate(strip_axes):
        assert ax.get_ylim() == (-top, top)
        assert tick_values(ax) == [-top, 0.0, top]  # matplotlib's own ticks, at the limits and at zero
        np.testing.assert_allclose(strips.past[i].get_xydata()[-1], [run.t[100], error[100, i]])  # metres
        assert strips.bands[i].get_paths()[0].vertices[:, 1].max() == pytest.approx(bound[:, i].max())
        y = ax.transData.transform([[run.t[100], error[100, i]]])[0, 1]  # where the error is drawn, in pixels
        y0, y1 = ax.transData.transform([[0.0, -top], [0.0, top]])[:, 1]
        assert y == pytest.approx(y0 + (y1 - y0) * (error[100, i] + top) / (2 * top))  # at its height on the axis


def strip_state(demo):
    """The strips' limits and the number of full draws so far."""
    return [ax.get_ylim() for ax in demo.renderer.fig.axes[1:]], demo.renderer.full_draws


def test_run_never_redraws_the_background():
    """Moving in time changes no limit: every frame of Run is blitted over the background drawn once."""
    demo = kf.demos.landmark_loop(seed=0)
    demo.controls["dropout"].value = True  # a run whose strips are not the first ones
    limits, draws = strip_state(demo)
    demo.controls["frame"].value = 0
    while demo.step():
        assert strip_state(demo) == (limits, draws)


@pytest.mark.pixels
@pytest.mark.fact
def test_a_new_run_redraws_the_background_only_when_the_limits_change():
    """A change of setting reruns the lap: the strips take the new run's limits, drawn in full once,
    and a change that keeps the limits only blits; either way the picture is right."""
    demo = kf.demos.landmark_loop(seed=0)
    changes = [
        lambda: demo.controls["kidnap"].click(),
        lambda: demo.controls["kidnap"].click(),
        lambda: setattr(demo.controls["dropout"], "value", True),
        lambda: setattr(demo.controls["sensor"], "value", 10.0),
        lambda: setattr(demo.controls["sensor"], "value", 9.0),
        lambda: setattr(demo.controls["motion"], "value", 0.1),
        lambda: setattr(demo.controls["dropout"], "value", False),
        lambda: setattr(demo.controls["filter"], "value", "UKF"),
    ]
    tops, kept = set(), 0
    for change in changes:
        before, draws = strip_state(demo)
        change()
        top = strip_limit(demo.model.run)
        tops.add(top)
        after, now = strip_state(demo)
        assert after == [(-top, top)] * 2
        assert now - draws == (after != before)  # one full draw if the limits changed, none if not
        kept += after == before
        shown = np.asarray(demo.renderer.image(), dtype=float)
        demo.renderer.fig.stale = True
        full = np.asarray(demo.renderer.image(), dtype=float)
        assert (np.abs(shown - full).max(axis=2) > 40).sum() == 0
    assert len(tops) >= 4 and kept >= 1  # the limits did change on the way, and some changes kept them


def sorted_rows(points) -> np.ndarray:
    points = np.asarray(points, float).reshape(-1, 2)
    return points[np.lexsort(points.T[::-1])]


def beam_ends(lines) -> np.ndarray:
    """The far end of every beam drawn, sorted by row."""
    return sorted_rows([seg[-1] for seg in lines.get_segments()])


@pytest.mark.fact
def test_the_teal_beams_go_to_the_landmarks_the_filter_matched():
    """An EKF started at the mirror of the start, its readings unlabelled, matches each reading to the
    mirror landmark: its teal beams run from its estimate to those; the orange ones, to the landmarks
    whose readings it refused, as with labels."""
    labelled = kf.sim.landmark_loop(0, gate=4.0, kidnap=60)
    mirror = kf.sim.landmark_loop(0, gate=4.0, labelled=False, start=[0.0, 5.0, np.pi])
    k = int(np.flatnonzero(mirror.used.sum(axis=1) >= 2)[0])  # the first step with two readings
    used = np.flatnonzero(mirror.used[k])
    for run in (labelled, mirror):
        _, ax_map, _ = loop_figure(run)
        view = loop_map(ax_map, run, k)
        shown = np.flatnonzero(run.used[k])
        np.testing.assert_allclose(beam_ends(view.beams), sorted_rows(run.landmarks[run.matched[k, shown]]))
        assert all(np.allclose(seg[0], run.mu[k, :2]) for seg in view.beams.get_segments())
    mirrored = [-1, -1] * mirror.landmarks[used] + [0, 5]  # (x, y) -> (-x, 5 - y): the mirror landmarks
    np.testing.assert_allclose(mirror.landmarks[mirror.matched[k, used]], mirrored)
    assert not np.allclose(mirrored, mirror.landmarks[used])  # not the readings' own
    _, ax_map, _ = loop_figure(labelled)
    view = loop_map(ax_map, labelled, 90)  # after the kidnap: refused readings, drawn to their own landmarks
    refused = labelled.landmarks[labelled.rejected[90]]
    assert len(refused) and np.allclose(beam_ends(view.rejected), sorted_rows(refused))
