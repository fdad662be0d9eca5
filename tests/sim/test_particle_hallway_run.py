"""Chapter 11's 1-D particle filter in chapter 1's hallway: the same readings and bars as the
histogram run, and a particle histogram that approaches the bars as the cloud grows."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.particle_hallway_run import (
    hallway_particles_predict,
    hallway_particles_weight,
    particle_histogram,
    simulate_particle_hallway,
    total_variation,
)

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

SEEDS = range(20)
DOORS = kf.sim.hallway_doors()
CLOSE = 0.1  # 5 000 particles: the worst step of seeds 0-19 is 0.06; a particle moved flips 0.0002
FAR = 0.25  # 10 particles: the worst step of a run passes this in 18 of seeds 0-19


def test_same_world_and_bars_as_chapter_1():
    for seed in (0, 7):
        run = simulate_particle_hallway(300, n_cycles=8, seed=seed)
        hall = kf.sim.simulate_hallway(8, seed=seed)
        assert np.array_equal(run.true_cell, hall.true_cell)
        assert np.array_equal(run.saw_door, hall.saw_door)
        assert np.array_equal(run.belief, hall.belief)


def test_record_shapes_and_ranges():
    run = simulate_particle_hallway(50, n_cycles=6, seed=3)
    assert run.particles.shape == (7, 50) and run.cloud.shape == (7, 12)
    assert run.cloud.sum(axis=1) == pytest.approx(np.ones(7))
    assert ((run.tv >= 0) & (run.tv <= 1)).all()
    assert ((run.n_eff >= 1 - 1e-9) & (run.n_eff <= 50 + 1e-9)).all()
    for k in range(7):
        assert run.tv[k] == pytest.approx(total_variation(run.cloud[k], run.belief[k]))
    with pytest.raises(ValueError):
        run.tv[0] = 0.0  # a record is read-only


def test_predict_is_chapter_1s_kernel():
    rng = np.random.default_rng(0)
    cells = np.array([0, 5, 11, 11])
    assert hallway_particles_predict(cells, 1.0, rng, 12, "wrap").tolist() == [1, 6, 0, 0]
    assert hallway_particles_predict(cells, 1.0, rng, 12, "wall").tolist() == [1, 6, 11, 11]
    assert hallway_particles_predict(cells, 0.0, rng, 12, "wrap").tolist() == cells.tolist()
    moved = hallway_particles_predict(np.zeros(20000, int), 0.9, rng, 12, "wrap")
    assert moved.mean() == pytest.approx(0.9, abs=0.01)  # one cell right 90 % of the time
    with pytest.raises(ValueError, match="boundary"):
        hallway_particles_predict(cells, 0.9, rng, 12, "bounce")
    with pytest.raises(ValueError, match="reliability"):
        hallway_particles_predict(cells, 1.5, rng, 12, "wrap")


def test_weights_follow_the_door_likelihood():
    cells = np.arange(12)
    saw = np.array([True, False])
    w = hallway_particles_weight(cells, DOORS, saw, 0.95)
    lik = kf.sim.door_likelihood(DOORS, saw, 0.95)
    assert w == pytest.approx(lik / lik.sum())
    sure = hallway_particles_weight(cells, DOORS, saw, 1.0)  # a sensor never wrong: weight 0 where it does not fit
    assert sure.sum() == pytest.approx(1.0) and (sure[lik < lik.max()] == 0).all()


def test_histogram_and_total_variation():
    assert particle_histogram([0, 0, 2, 3], 4).tolist() == [0.5, 0.0, 0.25, 0.25]
    assert particle_histogram([0, 1], 3, weights=[0.25, 0.75]).tolist() == [0.25, 0.75, 0.0]
    assert total_variation([1, 0, 0], [0, 0, 1]) == 1.0
    assert total_variation([0.5, 0.5], [0.5, 0.5]) == 0.0
    assert total_variation([0.2, 0.8], [0.5, 0.5]) == pytest.approx(0.3)


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="n_particles"):
        simulate_particle_hallway(0)
    with pytest.raises(ValueError, match="boundary"):
        simulate_particle_hallway(10, boundary="bounce")


def test_many_particles_sit_on_the_bars_at_every_step():
    for seed in SEEDS:
        run = simulate_particle_hallway(5000, n_cycles=10, seed=seed)
        assert run.tv.max() < CLOSE, seed


def test_ten_particles_are_visibly_off_in_most_seeds():
    off = [simulate_particle_hallway(10, n_cycles=10, seed=seed).tv.max() > FAR for seed in SEEDS]
    assert sum(off) >= 16


def test_boundary_wall_runs():
    run = simulate_particle_hallway(500, n_cycles=10, boundary="wall", seed=2)
    assert run.boundary == "wall" and np.isfinite(run.tv).all()
    assert (run.particles >= 0).all() and (run.particles <= 11).all()
