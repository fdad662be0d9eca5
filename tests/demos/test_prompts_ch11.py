"""Chapter 11's "Try this" prompts, each driven as its text says over runs 0 to 19 (seeds), on the
demo's model: the particle hallway (prompts 1-4 of "From bars to samples") and the particle cloud
(prompts 1-4 of its demo).

Each prompt's claims hold in every run unless its text says how often; where it says so for "the
first 20 runs", the count is checked."""

from __future__ import annotations

import numpy as np
import pytest

from kfcourse.demos.particle_cloud import FIRST_FRAME
from kfcourse.demos.particle_hallway import ParticleHallwayModel
from tests.demos.particle_drive import model_with, presses

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

SEEDS = range(20)


# --------------------------------------------------------------------------- the hallway
def test_hallway_1_few_particles_stray_many_sit_on_the_bars():
    """Set N to 10 and press Predict and Update ten times: the outlines stray (TV above 0.25 at some
    step) in each of the first 20 runs; at 5 000 particles TV stays below 0.1 at every step, in every run."""
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
    assert strays == 20 and sits == 20


def test_hallway_2_ten_particles_can_lose_the_robot():
    """With 10 particles, after ten Predict/Update pairs the outlines stand on one wrong place, one to three
    cells wide, TV near 1, in 9 of the first 20 runs: resampling lost every particle near the robot."""
    lost = 0
    for seed in SEEDS:
        model = ParticleHallwayModel(seed, n_particles=10)
        presses(model, 10)
        if model.tv > 0.9:
            lost += 1
            held = np.flatnonzero(model.cloud)
            assert 1 <= held.size <= 3 and model.belief[held].sum() < 0.1  # a few cells, away from the bars
    assert lost == 9


def test_hallway_3_more_particles_same_bars_smaller_distance():
    """Then slide N to 5 000: the bars and the robot stay where they were (the same readings), and the
    outlines land on the bars, TV 0.03 or less, in every one of the first 20 runs; it falls from near 1
    where 10 particles had lost the robot."""
    for seed in SEEDS:
        model = ParticleHallwayModel(seed, n_particles=10)
        presses(model, 10)
        bars, truth, tv_few = model.belief.copy(), model.true_cell, model.tv
        model.set_n_particles(5000)
        assert model.belief == pytest.approx(bars) and model.true_cell == truth
        assert round(model.tv, 2) <= 0.03  # as the readout shows it
        if tv_few > 0.9:
            assert model.tv < tv_few


def test_hallway_4_predict_spreads_bars_and_cloud_together():
    """At 5 000 particles press Predict five times without Update: the bars spread and flatten, and the
    outlines spread with them (TV stays under 0.1)."""
    for seed in SEEDS:
        model = ParticleHallwayModel(seed, n_particles=5000)
        peak = model.belief.max()
        for _ in range(5):
            model.predict()
            assert model.tv < 0.1, seed
        assert model.belief.max() < peak and model.cloud.max() < peak + 0.1


# --------------------------------------------------------------------------- the cloud on the map
def test_cloud_1_global_start_finds_the_robot_within_the_lap():
    """Press Global start and go to step 0: the cloud covers the map; within the lap it finds the robot,
    in all of the first 20 runs."""
    runs = [model_with(seed, global_start=True).run for seed in SEEDS]
    assert all(run.particles[0, :, :2].std(axis=0).min() > 1.5 for run in runs)  # spread over the map
    assert all(np.ptp(run.particles[0, :, 2]) > 6.0 for run in runs)  # every heading
    assert sum(run.localized() for run in runs) == 20


def test_cloud_2_kidnap_is_found_again_only_with_injection():
    """Drag step back to 60 and press Kidnap: the cloud drives on along the old path, metres from the robot,
    to the end of the lap (all of the first 20 runs). With inject 5% on, the cloud jumps to the robot (19 of
    the first 20 runs)."""
    assert FIRST_FRAME == 60
    lost = [model_with(seed, kidnap=FIRST_FRAME).run for seed in SEEDS]
    found = [model_with(seed, kidnap=FIRST_FRAME, injection=True).run for seed in SEEDS]
    assert all(run.error[FIRST_FRAME + 5 :].min() > 1.0 for run in lost)
    assert sum(run.localized() for run in found) == 19


def settled(run) -> int:
    """The step from which the error stays under 0.5 m to the end of the lap (T if it never does)."""
    off = np.flatnonzero(run.error >= 0.5)
    return 0 if off.size == 0 else int(off[-1]) + 1


def test_cloud_3_few_particles_find_a_global_start_late():
    """Undo kidnap, inject off, Global start with 100 particles, New run a few times: about one run in three
    finds the robot only late, in the last quarter of the lap (6 of the first 20 runs, run 0 among them, at
    step 120). Back at 2 000 particles (1995 on the slider) every run is on the robot, to stay, by step 40."""
    late = {}
    for seed in SEEDS:
        run = model_with(seed, global_start=True, n_particles=100).run
        if not run.localized():
            late[seed] = settled(run)
    assert len(late) == 6 and late[0] == 120
    quarter = 122 - 122 // 4  # step 92: the last quarter of the 122-step lap
    assert all(quarter <= k < 122 for k in late.values())  # found, but only in the last quarter
    assert all(settled(model_with(seed, global_start=True, n_particles=1995).run) <= 40 for seed in SEEDS)


def test_cloud_4_ess_rises_after_resampling():
    """Global start off (1995 particles on the slider): whenever N_eff falls under the N/2 line the cloud is
    resampled, and at the next step N_eff is mostly higher again."""
    for seed in SEEDS:
        run = model_with(seed, n_particles=1995).run
        assert (run.resampled == (run.ess < run.n_particles / 2)).all()
        after = run.resampled[:-1]
        assert after.sum() > 10
        assert np.mean(run.ess[1:][after] > run.ess[:-1][after]) > 0.6
