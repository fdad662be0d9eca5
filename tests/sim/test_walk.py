"""The chapter 3 walk: seeded, read-only, exact without noise, and the failure
cases behave as the chapter says."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.walk import simulate_walk

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

ARRAYS = ("t", "u", "truth", "z", "mu_bar", "var_bar", "innovation", "S", "K", "mu", "var")


def test_same_seed_same_run_other_seed_other_run():
    a, b, c = simulate_walk(seed=3), simulate_walk(seed=3), simulate_walk(seed=4)
    for name in ARRAYS:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert not np.allclose(a.z, c.z)
    assert not np.allclose(a.truth, c.truth)


def test_shorter_run_is_the_start_of_a_longer_one():
    short, long = simulate_walk(20, seed=1), simulate_walk(80, seed=1)
    np.testing.assert_array_equal(short.z, long.z[:20])
    np.testing.assert_array_equal(short.mu, long.mu[:20])


def test_changing_the_filter_leaves_the_world_alone():
    base, mistuned = simulate_walk(seed=2), simulate_walk(seed=2, Q=25.0, mu0=7.0)
    np.testing.assert_array_equal(base.truth, mistuned.truth)
    np.testing.assert_array_equal(base.z, mistuned.z)
    assert not np.allclose(base.mu, mistuned.mu)


def test_run_record_is_read_only():
    run = simulate_walk(10)
    for name in ARRAYS:
        with pytest.raises(ValueError):
            getattr(run, name)[0] = 1.0
    with pytest.raises(AttributeError):
        run.Q = 1.0


def test_shapes_and_time_steps():
    run = simulate_walk(7)
    for name in ARRAYS:
        assert getattr(run, name).shape == (7,), name
    np.testing.assert_array_equal(run.t, np.arange(1, 8))


def test_every_step_is_kf_1d_cycle():
    run = simulate_walk(5, seed=9, R=0.05, Q=0.5, mu0=1.0, var0=2.0)
    mu, var = 1.0, 2.0
    for k in range(5):
        cyc = kf.kf_1d_cycle(mu, var, 1.0, run.z[k], R=0.05, Q=0.5)
        assert (run.mu_bar[k], run.var_bar[k], run.innovation[k], run.K[k], run.mu[k], run.var[k]) == tuple(cyc)
        assert run.S[k] == pytest.approx(cyc.var_bar + 0.5)
        mu, var = cyc.mu, cyc.var


def test_no_noise_and_a_right_guess_track_the_truth_exactly():
    run = simulate_walk(30, R_true=0.0, Q_true=0.0, R=0.01, Q=0.25, x0=2.0, u=1.0)
    np.testing.assert_array_equal(run.truth, 2.0 + np.arange(1, 31))
    np.testing.assert_array_equal(run.z, run.truth)
    np.testing.assert_allclose(run.mu, run.truth, rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.innovation, 0.0, atol=1e-12)


def test_filter_beats_raw_readings_when_tuned():
    run = simulate_walk(seed=0)
    assert run.rms_error(20) < 0.6 * run.rms_reading_error(20)
    assert abs(run.mean_innovation(20)) < 0.1


def test_an_honest_large_initial_variance_recovers_at_once():
    overconfident = simulate_walk(seed=0, mu0=10.0, var0=0.25)
    honest = simulate_walk(seed=0, mu0=10.0, var0=100.0)
    assert abs(honest.error()[0]) < 0.5 < abs(overconfident.error()[0])
    assert honest.K[0] > 0.99
    # both forget the bad guess in the end: after the transient they agree
    np.testing.assert_allclose(overconfident.mu[60:], honest.mu[60:], atol=1e-3)


def test_too_small_Q_follows_the_readings_and_is_overconfident():
    base, small = simulate_walk(seed=0), simulate_walk(seed=0, Q=0.0025)
    assert small.K[-1] > 0.8 > 0.2 > base.K[-1]
    assert small.rms_error(20) > 1.5 * base.rms_error(20)
    assert small.innovations_inside(20) < 0.3  # the band it expects is far too narrow
    assert small.truth_inside(20) < 0.3


def test_too_large_Q_is_sluggish_and_underconfident():
    base, large = simulate_walk(seed=0), simulate_walk(seed=0, Q=25.0)
    assert large.K[-1] < 0.05
    assert large.rms_error(20) > base.rms_error(20)
    assert large.innovations_inside(20) > 0.95  # the band it expects is far too wide


def test_unmodelled_velocity_without_noise_lags_by_v_times_1_minus_K_over_K():
    """With steady gain K the error obeys e = (1 - K)(e - v): it settles at
    e = -v (1 - K) / K (behind the robot) and the innovation at v / K."""
    v, R, Q = 0.1, 0.01, 0.25
    K, _, _ = kf.steady_state_1d(R, Q)
    run = simulate_walk(200, R_true=0.0, Q_true=0.0, R=R, Q=Q, velocity=v)
    assert run.error()[-1] == pytest.approx(-v * (1 - K) / K, rel=1e-9)  # -0.452 m: behind
    assert run.innovation[-1] == pytest.approx(v / K, rel=1e-9)  # +0.552 m: always surprised the same way
    assert -v * (1 - K) / K == pytest.approx(-0.4525, abs=1e-4)


def test_unmodelled_velocity_with_noise_lags_and_biases_the_innovations():
    v = 0.1
    K, _, _ = kf.steady_state_1d(0.01, 0.25)
    for seed in range(5):
        run = simulate_walk(seed=seed, velocity=v)
        tuned = simulate_walk(seed=seed)
        lag = -run.error()[20:].mean()
        assert 0.5 * v * (1 - K) / K < lag < 1.5 * v * (1 - K) / K
        assert run.mean_innovation(20) > 0.4 > 0.1 > abs(tuned.mean_innovation(20))


@pytest.mark.parametrize(
    "kwargs",
    [
        {"n_steps": 0},
        {"n_steps": 2.5},
        {"n_steps": True},
        {"R_true": -1.0},
        {"Q_true": float("nan")},
        {"R": -0.1},
        {"Q": "a lot"},
        {"var0": -1.0},
        {"velocity": float("inf")},
        {"R": 0.0, "Q": 0.0, "var0": 0.0},
    ],
)
def test_bad_input_names_the_argument(kwargs):
    name = next(iter(kwargs)) if len(kwargs) == 1 else "Q"
    with pytest.raises(ValueError, match=name):
        simulate_walk(**kwargs)


def test_innovation_correlation_of_known_sequences():
    """Alternating innovations predict each other perfectly negatively, a ramp perfectly positively."""
    from dataclasses import replace

    run = simulate_walk(10, seed=0)
    alternating = replace(run, innovation=np.array([1.0, -1.0] * 5))
    ramp = replace(run, innovation=np.arange(10.0))
    assert alternating.innovation_correlation() == pytest.approx(-1.0)
    assert ramp.innovation_correlation(start=4) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="start"):
        run.innovation_correlation(start=8)


def test_innovation_correlation_tells_overcorrecting_from_sluggish():
    """Q too small over-corrects (consecutive innovations swing apart), Q too large leaves the same
    error step after step (they lean the same way); the tuned filter sits near 0."""
    tuned, small, large = simulate_walk(seed=0), simulate_walk(seed=0, Q=0.0025), simulate_walk(seed=0, Q=25.0)
    assert small.innovation_correlation(20) < -0.2
    assert large.innovation_correlation(20) > 0.15
    assert abs(tuned.innovation_correlation(20)) < 0.15


def test_health_line_reports_the_run_from_start_on():
    run = simulate_walk(seed=0, velocity=0.1)
    line = run.health(start=20)
    assert f"K {run.K[-1]:.3f}" in line
    assert f"RMS error {run.rms_error(20):.3f} m" in line
    assert f"mean ν {run.mean_innovation(20):+.3f} m" in line
    assert f"corr {run.innovation_correlation(20):+.2f}" in line
    assert f"mean ν {run.mean_innovation(0):+.3f} m" not in line  # the window matters: all steps differ
