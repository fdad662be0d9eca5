"""The robot on a line (chapter 0): the run record, and the dead-reckoning trace beside it."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def rms(a) -> float:
    return float(np.sqrt(np.mean(np.square(a))))


def test_chapter0_numbers_are_unchanged():
    run = kf.sim.simulate_line(seed=0)
    assert round(100 * rms(run.z - run.truth), 1) == 42.9  # cm, trusting each reading
    assert round(100 * rms(run.mu - run.truth), 1) == 15.5  # cm, filtered, from the known start
    assert round(float(run.mu[-1]), 2) == 0.39
    assert round(float(run.truth[-1]), 2) == 0.47


def test_dead_reckoning_sums_the_commands_from_the_true_start():
    run = kf.sim.simulate_line(seed=3)
    assert run.dead_reckoning.shape == run.truth.shape
    assert run.dead_reckoning[0] == run.truth[0]
    np.testing.assert_allclose(run.dead_reckoning, np.cumsum(run.u))
    with pytest.raises(ValueError):
        run.dead_reckoning[0] = 1.0  # frozen like every other array of the run


def test_dead_reckoning_ignores_the_sensor():
    quiet = kf.sim.simulate_line(sensor_std=0.05, seed=1)
    noisy = kf.sim.simulate_line(sensor_std=3.0, seed=1)
    np.testing.assert_array_equal(quiet.dead_reckoning, noisy.dead_reckoning)
    assert not np.allclose(quiet.mu, noisy.mu)


def test_dead_reckoning_error_spreads_like_sqrt_t():
    """Across seeds, the error at step t has standard deviation step_std * sqrt(t)."""
    n_runs, n_steps, step_std = 200, 101, 0.05
    err = np.array(
        [
            (lambda r: r.dead_reckoning - r.truth)(kf.sim.simulate_line(n_steps, step_std, 0.4, seed=s))
            for s in range(n_runs)
        ]
    )
    for t in (4, 25, 100):
        expected = kf.sim.drift_sigma(step_std, t)
        standard_error = expected / np.sqrt(2 * n_runs)  # of a standard deviation from n_runs samples
        assert abs(err[:, t].std(ddof=1) - expected) < 5 * standard_error


def test_at_the_default_noise_the_filter_beats_both_witnesses_by_the_end():
    """The picture chapter 0 opens with: dead reckoning drifts, raw readings jitter, the filter holds."""
    run = kf.sim.simulate_line(seed=0)
    half = slice(run.t.size // 2, None)
    dr = rms((run.dead_reckoning - run.truth)[half])
    raw = rms((run.z - run.truth)[half])
    filt = rms((run.mu - run.truth)[half])
    assert filt < 0.5 * min(dr, raw)
    first_tenth = slice(1, run.t.size // 10)
    assert rms((run.dead_reckoning - run.truth)[first_tenth]) < 0.5 * dr  # it drifts: small at first, large later


def test_filter_starts_from_the_same_known_start_as_dead_reckoning():
    run = kf.sim.simulate_line(seed=0, sensor_std=3.0)
    assert run.mu[0] == run.dead_reckoning[0] == run.truth[0]
    assert run.var[0] == pytest.approx(run.step_std**2)  # one step's disturbance, not the sensor's
