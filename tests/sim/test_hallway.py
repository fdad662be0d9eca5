"""The hallway of chapter 1: door map, motion, sensor, and the run the chapter promises."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim import hallway_world as hw

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def test_door_map_has_both_walls():
    doors = hw.hallway_doors()
    assert doors.shape == (2, hw.N_CELLS) and doors.dtype == bool
    assert np.flatnonzero(doors[0]).tolist() == list(hw.LEFT_DOORS)
    assert np.flatnonzero(doors[1]).tolist() == list(hw.RIGHT_DOORS)
    with pytest.raises(ValueError, match="door cells"):
        hw.hallway_doors(5, left=(7,))
    with pytest.raises(ValueError, match="n_cells"):
        hw.hallway_doors(0)


def test_every_cell_looks_different_from_its_neighbours():
    """What lets the filter notice a stall: the cell it stalled in looks different from the one it
    was told to reach, on at least one wall."""
    doors = hw.hallway_doors()
    assert (doors != np.roll(doors, -1, axis=1)).any(axis=0).all()


def test_motion_kernel_moves_or_stalls():
    assert hw.motion_kernel(0.9) == pytest.approx({1: 0.9, 0: 0.1})
    assert hw.motion_kernel(1.0) == {1: 1.0, 0: 0.0}
    for bad in (-0.1, 1.5, float("nan")):
        with pytest.raises(ValueError, match="reliability"):
            hw.motion_kernel(bad)


def test_the_true_robot_moves_with_the_kernel():
    rng = np.random.default_rng(1)
    kernel = hw.motion_kernel(0.9)
    steps = [(hw.move(5, kernel, rng, 12, "wrap") - 5) % 12 for _ in range(4000)]
    assert set(steps) == {0, 1}
    assert np.mean(steps) == pytest.approx(0.9, abs=5 * np.sqrt(0.09 / 4000))
    assert hw.move(11, {1: 1.0}, rng, 12, "wrap") == 0  # a loop
    assert hw.move(11, {1: 1.0}, rng, 12, "wall") == 11  # a wall stops it


def test_sensor_reads_both_walls_with_the_reliability():
    doors = hw.hallway_doors()
    rng = np.random.default_rng(2)
    assert hw.read_door(0, doors, 1.0, rng).tolist() == [True, True]
    assert hw.read_door(1, doors, 1.0, rng).tolist() == [False, False]
    assert hw.read_door(1, doors, 0.0, rng).tolist() == [True, True]
    reads = np.array([hw.read_door(3, doors, 0.8, rng) for _ in range(4000)])
    right_share = (reads == doors[:, 3]).mean(axis=0)
    assert right_share == pytest.approx([0.8, 0.8], abs=5 * np.sqrt(0.16 / 4000))
    assert isinstance(hw.read_door(3, doors[0], 0.8, rng), bool)  # one wall: one bool, as before


def test_two_looks_multiply():
    doors = hw.hallway_doors()
    lik = hw.door_likelihood(doors, [True, False], 0.95)
    left = hw.door_likelihood(doors[0], True, 0.95)
    right = hw.door_likelihood(doors[1], False, 0.95)
    np.testing.assert_allclose(lik, left * right)
    np.testing.assert_allclose(hw.door_likelihood(doors, [True, True], 0.5), 0.25)  # a coin flip says nothing
    with pytest.raises(ValueError, match="saw_door"):
        hw.door_likelihood(doors, [True], 0.95)


def test_run_record():
    run = hw.simulate_hallway(6, seed=4)
    assert run.true_cell.shape == (7,) and run.saw_door.shape == (7, 2) and run.belief.shape == (7, hw.N_CELLS)
    np.testing.assert_allclose(run.belief.sum(axis=1), 1.0)
    first = hw.door_likelihood(run.doors, run.saw_door[0], run.sensor_reliability)
    np.testing.assert_allclose(run.belief[0], first / first.sum())  # a flat prior times the first look
    assert set(np.diff(run.true_cell) % hw.N_CELLS) <= {0, 1}
    again = hw.simulate_hallway(6, seed=4)
    np.testing.assert_array_equal(run.belief, again.belief)
    assert not np.array_equal(run.belief, hw.simulate_hallway(6, seed=5).belief)
    with pytest.raises(ValueError):
        run.belief[0, 0] = 1.0
    with pytest.raises(ValueError, match="n_cycles"):
        hw.simulate_hallway(-1)
    with pytest.raises(ValueError, match="boundary"):
        hw.simulate_hallway(boundary="moat")


def test_the_run_is_the_filter_step_by_step():
    run = hw.simulate_hallway(3, seed=7)
    kernel = hw.motion_kernel(run.motion_reliability)
    bel = run.belief[0]
    for k in range(1, 4):
        bel = kf.bayes_predict(bel, kernel, run.boundary)
        bel = kf.bayes_update(bel, hw.door_likelihood(run.doors, run.saw_door[k], run.sensor_reliability))
        np.testing.assert_allclose(run.belief[k], bel)


def test_after_ten_cycles_the_peak_is_on_the_true_cell_for_nearly_every_seed():
    """The chapter's promise: alternate Predict and Update ten times at the defaults and the
    belief settles on the true cell, for at least 18 of seeds 0..19."""
    hits = [hw.simulate_hallway(10, seed=s).peak_on_truth()[-1] for s in range(20)]
    assert sum(hits) >= 18


def test_the_promise_needs_the_sensor():
    """The same count with a coin-flip sensor: the belief cannot find the robot."""
    hits = [hw.simulate_hallway(10, sensor_reliability=0.5, seed=s).peak_on_truth()[-1] for s in range(20)]
    assert sum(hits) <= 6


def test_predicting_against_a_wall_piles_the_belief_into_the_end_cell():
    kernel = hw.motion_kernel(hw.MOTION_RELIABILITY)
    flat = np.full(hw.N_CELLS, 1 / hw.N_CELLS)
    wall, ring = flat, flat
    for _ in range(10):
        wall = kf.bayes_predict(wall, kernel, "wall")
        ring = kf.bayes_predict(ring, kernel, "wrap")
    assert wall.argmax() == hw.N_CELLS - 1 and wall[-1] > 0.5
    np.testing.assert_allclose(ring, flat)  # on a loop nothing piles up


def test_peak_cells_names_every_cell_tied_for_the_top():
    assert hw.peak_cells([0.1, 0.4, 0.1, 0.4]).tolist() == [1, 3]  # a mirrored belief: both peaks
    assert hw.peak_cells([0.2, 0.5, 0.3]).tolist() == [1]
    assert hw.peak_cells(np.full(4, 0.25)).tolist() == [0, 1, 2, 3]  # flat: every cell
    with pytest.raises(ValueError, match="histogram"):
        hw.peak_cells([0.5, 0.6])
