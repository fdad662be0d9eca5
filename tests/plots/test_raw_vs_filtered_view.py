"""Chapter 0's view: the run drawn up to the step shown, every reading and error in view,
and the background drawn again only when a limit moves."""

from __future__ import annotations

import numpy as np
import pytest

from kfcourse.demos.raw_vs_filtered import N_STEPS, RawVsFiltered
from kfcourse.plots.raw_vs_filtered_view import raw_vs_filtered_limits, raw_vs_filtered_view, update_raw_vs_filtered
from kfcourse.plots.style import FigureRenderer

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


@pytest.fixture
def shown():
    """A model, its view, and a renderer that has drawn the first picture."""
    model = RawVsFiltered(seed=0)
    view = raw_vs_filtered_view(N_STEPS)
    update_raw_vs_filtered(view, model)
    renderer = FigureRenderer(view.fig, view.moving)
    renderer.image()
    return model, view, renderer


def test_the_update_draws_the_run_up_to_the_step_shown(shown):
    model, view, _ = shown
    run = model.run
    for frame in (0, 40, N_STEPS - 1):
        model.frame = frame
        update_raw_vs_filtered(view, model)
        k = frame + 1
        np.testing.assert_array_equal(view.truth.get_xydata(), np.column_stack([run.t[:k], run.truth[:k]]))
        np.testing.assert_array_equal(view.pings.get_offsets(), np.column_stack([run.t[:k], run.z[:k]]))
        np.testing.assert_array_equal(view.estimate.get_ydata(), run.mu[:k])
        np.testing.assert_array_equal(view.dead_reckoning.get_ydata(), run.dead_reckoning[:k])
        assert tuple(view.robot.get_xydata()[0]) == (run.t[frame], run.mu[frame])
        band = view.band.get_paths()[0].vertices
        assert band[:, 1].min() == pytest.approx((run.mu[:k] - np.sqrt(run.var[:k])).min())
        for line, error in zip((view.err_raw, view.err_dead_reckoning, view.err_estimate), model.errors(), strict=True):
            np.testing.assert_array_equal(line.get_ydata(), error[:k])
        rms = [f"{100 * e:.0f} cm" for e in model.rms_errors_all()]
        assert all(text in view.readout.get_text() for text in rms)


@pytest.mark.parametrize("sensor_std", [0.05, 0.4, 3.0])
def test_every_reading_estimate_and_error_is_in_view(sensor_std):
    model = RawVsFiltered(seed=0, sensor_std=sensor_std)
    view = raw_vs_filtered_view(N_STEPS)
    update_raw_vs_filtered(view, model)
    run = model.run
    lo, hi = view.ax.get_ylim()
    for values in (run.truth, run.z, run.mu, run.dead_reckoning):
        assert lo <= values.min() and values.max() <= hi
    assert view.ax_err.get_ylim()[0] == 0.0
    assert max(e.max() for e in model.errors()) <= view.ax_err.get_ylim()[1]


@pytest.mark.pixels
def test_stepping_through_a_run_never_redraws_the_background(shown):
    model, view, renderer = shown
    before = renderer.full_draws
    pictures = set()
    for frame in range(0, N_STEPS, 10):
        model.frame = frame
        update_raw_vs_filtered(view, model)
        pictures.add(renderer.image().tobytes())
    assert renderer.full_draws == before  # the limits hold the whole run: they never move
    assert len(pictures) == len(range(0, N_STEPS, 10))  # and every step looks different


@pytest.mark.pixels
def test_the_background_is_redrawn_exactly_when_a_limit_moves(shown):
    model, view, renderer = shown
    same = moved = 0
    for sensor_std in np.arange(0.45, 3.0, 0.05):
        limits = raw_vs_filtered_limits(model)
        model.set_sensor_std(float(sensor_std))
        before = renderer.full_draws
        update_raw_vs_filtered(view, model)
        renderer.image()
        changed = raw_vs_filtered_limits(model) != limits
        assert renderer.full_draws == before + changed, sensor_std
        same += not changed
        moved += changed
    assert same > 0 and moved > 0  # both cases happened along the slider


def test_a_run_needs_two_steps():
    with pytest.raises(ValueError, match="n_steps"):
        raw_vs_filtered_view(1)
