"""The particle hallway demo (chapter 11): its model replays the run record, its controls move
the picture, its extremes draw, and its texts and picture fit."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.particle_hallway import N_MAX, N_MIN, ParticleHallwayModel
from kfcourse.plots.particle_hallway_view import particle_hallway_view, update_particle_hallway
from kfcourse.sim.particle_hallway_run import simulate_particle_hallway
from tests.demos.particle_drive import presses

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.


def test_model_replays_the_run_record():
    for seed in (0, 5):
        model = ParticleHallwayModel(seed, n_particles=300)
        run = simulate_particle_hallway(300, n_cycles=6, seed=seed)
        for k in range(7):
            if k:
                presses(model, 1)
            assert model.true_cell == run.true_cell[k]
            assert np.array_equal(model.saw_door, run.saw_door[k])
            assert model.belief == pytest.approx(run.belief[k])
            assert np.array_equal(model.cells, run.particles[k])
            assert model.tv == pytest.approx(run.tv[k])
            assert model.n_eff == pytest.approx(run.n_eff[k])


@pytest.mark.fact
def test_predict_compares_the_predicted_cloud_with_the_predicted_bars():
    model = ParticleHallwayModel(1, n_particles=5000)
    before = model.belief.copy()
    model.predict()
    assert model.phase == "predicted" and model.steps == 1
    assert model.belief == pytest.approx(kf.bayes_predict(before, kf.sim.motion_kernel(0.9), "wrap"))
    assert np.all(model.weights == model.weights[0])  # no reading yet: equal weights
    assert model.n_eff == pytest.approx(5000)
    assert model.tv < 0.1


def test_particle_count_replays_the_same_readings():
    model = ParticleHallwayModel(2, n_particles=10)
    presses(model, 4)
    model.predict()
    truth, bars, readings = model.true_cell, model.belief.copy(), list(model.actions)
    model.set_n_particles(777.4)
    assert model.n_particles == 777 and model.cells.size == 777 and model.dots.size == 777
    assert model.true_cell == truth and model.belief == pytest.approx(bars)
    assert model.actions == readings and model.phase == "predicted"
    model.set_n_particles(1.0)  # below the slider's range: held at its ends
    assert model.n_particles == N_MIN
    model.set_n_particles(1e6)
    assert model.n_particles == N_MAX


def test_reset_and_new_run():
    demo = kf.demos.particle_hallway(seed=0)
    first = bytes(demo.image.value)
    demo.controls["predict"].click()
    demo.controls["update"].click()
    assert bytes(demo.image.value) != first
    demo.controls["reset"].click()
    assert bytes(demo.image.value) == first and demo.model.actions == ["update"]
    demo.controls["new_run"].click()
    assert demo.model.seed == 1
    assert demo.model.true_cell == kf.sim.simulate_hallway(0, seed=1).true_cell[0]


@pytest.mark.fact
def test_slider_extremes_draw_finite_pictures():
    demo = kf.demos.particle_hallway(seed=3)
    control = demo.controls["n_particles"]
    for value in (control.base**control.min, control.base**control.max):
        control.value = value
        for key in ("update", "predict", "predict", "update"):
            demo.controls[key].click()
            offsets = demo.renderer.dynamic[2 * 12].get_offsets()  # the dots, after the bars and outlines
            assert len(offsets) == demo.model.n_particles
            assert np.isfinite(offsets).all() and np.isfinite(demo.model.tv)
    assert demo.model.n_particles == N_MAX  # 10**log10(5000), rounded


@pytest.mark.fact
def test_texts_clear_the_bars():
    model = ParticleHallwayModel(0, n_particles=10)
    view = particle_hallway_view(model.doors)
    renderer = view.fig.canvas.get_renderer()
    for press in ["update", "predict"] * 6:
        getattr(model, press)()
        update_particle_hallway(view, model)
        view.fig.canvas.draw()
        for text, bar in itertools.product((view.readout, view.legend), [*view.bars, *view.cloud]):
            assert not text.get_window_extent(renderer).overlaps(bar.get_window_extent(renderer)), press


def test_fits_a_laptop():
    demo = kf.demos.particle_hallway(seed=0)
    width, height = demo.renderer.fig.get_size_inches()
    shown = min(demo.display_width, 848) * height / width  # px tall at the 848 px output
    assert shown + 2 * 40 + 60 <= 680  # two control rows, the folded caption and the description
