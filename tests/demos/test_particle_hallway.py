"""The particle hallway demo (chapter 11): its model replays the run record, its controls move
the picture, its extremes draw, and the "Try this" prompts it is built for come true."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.particle_hallway import N_MAX, N_MIN, ParticleHallwayModel
from kfcourse.plots.particle_hallway import particle_hallway_view, update_particle_hallway
from kfcourse.sim.particle_hallway import simulate_particle_hallway

SEEDS = range(20)


def presses(model, cycles: int) -> None:
    for _ in range(cycles):
        model.predict()
        model.update()


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
    assert shown + 2 * 40 + 60 <= 680  # two control rows and the caption


# "Try this" prompts (chapter 11), each driven on the model as the prompt says, over seeds 0-19.


def test_prompt_few_particles_wander_many_sit_on_the_bars():
    """Set N to 10 and press Predict and Update ten times: the outlines stray far from the bars
    (TV above 0.25 at some step) in most runs; at 5 000 they stay on them (TV below 0.1) at every step."""
    strays, sits = 0, 0
    for seed in SEEDS:
        few, many = ParticleHallwayModel(seed, n_particles=10), ParticleHallwayModel(seed, n_particles=5000)
        worst_few, worst_many = few.tv, many.tv
        for press in ["predict", "update"] * 10:
            getattr(few, press)()
            getattr(many, press)()
            worst_few, worst_many = max(worst_few, few.tv), max(worst_many, many.tv)
        strays += worst_few > 0.25
        sits += worst_many < 0.1
    assert strays >= 16 and sits == 20


def test_prompt_ten_particles_can_lose_the_robot():
    """With 10 particles, after ten Predict/Update pairs the cloud has sat down on a wrong cell in
    about half the runs (TV near 1): resampling lost every particle near the robot."""
    lost = 0
    for seed in SEEDS:
        model = ParticleHallwayModel(seed, n_particles=10)
        presses(model, 10)
        lost += model.tv > 0.9
    assert 5 <= lost <= 15  # 9 of seeds 0-19


def test_prompt_more_particles_same_bars_smaller_distance():
    """After ten Predict/Update pairs at N = 10, slide N to 5 000: the bars and the robot stay
    where they are (the same readings), the outlines move onto the bars and TV falls."""
    falls = 0
    for seed in SEEDS:
        model = ParticleHallwayModel(seed, n_particles=10)
        presses(model, 10)
        bars, truth, tv_few = model.belief.copy(), model.true_cell, model.tv
        model.set_n_particles(5000)
        assert model.belief == pytest.approx(bars) and model.true_cell == truth
        falls += model.tv < tv_few
    assert falls >= 18  # 19 of seeds 0-19: a lucky 10-particle cloud may already sit on the bars


def test_prompt_predict_spreads_bars_and_cloud_together():
    """At N = 5 000, press Predict five times without Update: the bars spread out and flatten,
    and the particle outlines spread with them (TV stays below 0.1)."""
    for seed in SEEDS:
        model = ParticleHallwayModel(seed, n_particles=5000)
        peak = model.belief.max()
        for _ in range(5):
            model.predict()
            assert model.tv < 0.1, seed
        assert model.belief.max() < peak and model.cloud.max() < peak + 0.1
