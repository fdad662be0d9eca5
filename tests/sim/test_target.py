"""The turning target and the constant-velocity tracks: reproducible, immutable, and the
filter runs over them equal step-by-step kf_step; the NEES band is right."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.models import constant_velocity
from kfcourse.sim.scores import nees, nees_band
from kfcourse.sim.target import (
    DT,
    SPEED,
    START_SPEED_VAR,
    START_STD,
    START_STEPS,
    TargetEstimates,
    TargetRun,
    TrackBatch,
    filter_target,
    filter_tracks,
    process_noise,
    roughness,
    simulate_target,
    simulate_tracks,
)

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def arrays(record):
    return {
        f.name: getattr(record, f.name)
        for f in dataclasses.fields(record)
        if isinstance(getattr(record, f.name), np.ndarray)
    }


def test_target_is_seeded_and_immutable():
    a, b, c = simulate_target(3), simulate_target(3), simulate_target(4)
    for name, x in arrays(a).items():
        assert np.array_equal(x, getattr(b, name)), name
        assert not x.flags.writeable, name
        with pytest.raises(ValueError):
            x[...] = 0
    assert np.array_equal(a.truth, c.truth)  # the same path for every seed
    assert not np.allclose(a.z, c.z)  # other noise
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.z = None  # type: ignore[misc]


def test_target_turns_at_constant_speed_and_readings_have_the_stated_noise():
    run = simulate_target(0)
    assert isinstance(run, TargetRun)
    T = run.t.size
    assert run.truth.shape == (T, 4) and run.z.shape == (T, 2) and run.turning.shape == (T,)
    assert np.allclose(np.linalg.norm(run.truth[:, 2:], axis=1), SPEED)
    assert np.allclose(np.diff(run.truth[:, :2], axis=0), DT * run.truth[1:, 2:])  # p_k = p_{k-1} + v_k dt
    heading = np.unwrap(np.arctan2(run.truth[:, 3], run.truth[:, 2]))
    turned = np.abs(np.diff(heading)) > 1e-9
    assert np.array_equal(turned, run.turning[1:])
    assert 0.2 < run.turning.mean() < 0.6  # turns and straights both
    err = run.z - run.truth[:, :2]
    assert np.std(err) == pytest.approx(run.sensor_std, rel=0.15)


def test_filter_target_is_kf_step_and_keeps_the_world():
    run = simulate_target(1)
    R, Q = process_noise(DT, 10.0), np.eye(2)
    est = filter_target(run, R, Q)
    assert isinstance(est, TargetEstimates)
    assert all(not a.flags.writeable for a in arrays(est).values())
    F, H = constant_velocity(DT, dim=2)
    mu, Sig = est.mu[0], est.Sig[0]
    assert np.array_equal(mu, [*run.z[0], 0.0, 0.0])  # the first reading, velocity unknown
    np.testing.assert_array_equal(np.diag(Sig), [START_STD**2] * 2 + [START_SPEED_VAR] * 2)
    for k in range(1, 30):
        # start-up: a straight line through the readings (no process noise, the sensor's rated noise)
        R_k, Q_k = (np.zeros((4, 4)), START_STD**2 * np.eye(2)) if k < START_STEPS else (R, Q)
        mu, Sig = kf.kf_step(mu, Sig, None, run.z[k], F, None, H, R_k, Q_k)
        np.testing.assert_allclose(est.mu[k], mu, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(est.Sig[k], Sig, rtol=1e-9, atol=1e-9)
        Sig_bar = F @ est.Sig[k - 1] @ F.T + R_k
        K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q_k)
        np.testing.assert_allclose(est.K[k], K, rtol=1e-9, atol=1e-12)
    z_before = run.z.copy()
    other = filter_target(run, 100 * R, 0.01 * Q)
    assert np.array_equal(run.z, z_before)
    # the start-up does not depend on the assumed noise; the tracking after it does
    np.testing.assert_array_equal(other.mu[:START_STEPS], est.mu[:START_STEPS])
    assert not np.allclose(other.mu[START_STEPS:], est.mu[START_STEPS:])


def test_start_up_fits_the_least_squares_line():
    run = simulate_target(3)
    est = filter_target(run, process_noise(DT, 10.0), 1e4 * np.eye(2))
    k = START_STEPS - 1
    A = np.column_stack([np.ones(k + 1), run.t[: k + 1] - run.t[k]])  # p(t) = p_k + v (t - t_k)
    coef, *_ = np.linalg.lstsq(A, run.z[: k + 1], rcond=None)  # rows: position at t_k, velocity
    np.testing.assert_allclose(est.mu[k, :2], coef[0], atol=1e-3)  # the diffuse start is nearly exact
    np.testing.assert_allclose(est.mu[k, 2:], coef[1], atol=1e-2)


def test_process_noise_is_a_random_acceleration():
    dt, var = 0.5, 2.0
    Gamma = np.array([[dt**2 / 2, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])  # how an acceleration moves [p, v]
    np.testing.assert_allclose(process_noise(dt, var), var * Gamma @ Gamma.T)
    with pytest.raises(ValueError, match="accel_var"):
        process_noise(dt, -1.0)


def test_tracks_follow_the_constant_velocity_model():
    batch = simulate_tracks(50, 30, accel_std=0.0, seed=2)
    assert isinstance(batch, TrackBatch)
    assert batch.truth.shape == (50, 30, 4) and batch.z.shape == (50, 30, 2)
    F, _ = constant_velocity(batch.dt, dim=2)
    np.testing.assert_allclose(batch.truth[:, 1:], batch.truth[:, :-1] @ F.T)  # no acceleration: exact
    assert not batch.truth.flags.writeable
    noisy = simulate_tracks(2000, 2, accel_std=1.5, seed=2)
    step = noisy.truth[:, 1] - noisy.truth[:, 0] @ F.T  # G a: its covariance is R
    np.testing.assert_allclose(np.cov(step.T), noisy.R, rtol=0.15, atol=1e-4)


def test_filter_tracks_row_equals_filter_target_like_run():
    batch = simulate_tracks(4, 20, seed=5)
    mu, Sig = filter_tracks(batch, batch.R, batch.Q)
    F, H = constant_velocity(batch.dt, dim=2)
    m, S = mu[2, 0], Sig[2, 0]
    for k in range(1, 20):
        m, S = kf.kf_step(m, S, None, batch.z[2, k], F, None, H, batch.R, batch.Q)
        np.testing.assert_allclose(mu[2, k], m, rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(Sig[2, k], S, rtol=1e-10, atol=1e-12)


def test_nees_by_hand():
    Sig = np.diag([4.0, 1.0])
    assert nees([2.0, 1.0], [0.0, 0.0], Sig) == pytest.approx(2.0**2 / 4 + 1.0)
    with pytest.raises(ValueError, match="Sig"):
        nees([1.0, 2.0], [0.0, 0.0], np.eye(3))


def test_nees_band_matches_chi_square_quantiles():
    # chi-square quantiles of 400 and 40 degrees of freedom (published tables)
    low, high = nees_band(100, 4)
    assert 100 * low == pytest.approx(346.48, abs=0.05) and 100 * high == pytest.approx(457.31, abs=0.05)
    low, high = nees_band(10, 4)
    assert 10 * low == pytest.approx(24.433, abs=0.02) and 10 * high == pytest.approx(59.342, abs=0.02)
    low, high = nees_band(1, 1)
    assert low >= 0.0 and high == pytest.approx(5.02, abs=0.3)  # crude for 1 d.o.f., never negative
    with pytest.raises(ValueError, match="level"):
        nees_band(10, 4, level=1.5)


def test_honest_filter_nees_is_chi_square():
    batch = simulate_tracks(2000, 15, seed=7)
    mu, Sig = filter_tracks(batch, batch.R, batch.Q)
    eps = nees(batch.truth, mu, Sig)[:, -1]  # one value per track at the last step
    assert eps.mean() == pytest.approx(4.0, abs=0.25)  # chi2(4): mean 4, variance 8
    assert eps.var() == pytest.approx(8.0, rel=0.2)


# --------------------------------------------------------------------------- what a run record says of itself
def test_estimates_measure_themselves_against_their_run():
    run = simulate_target(2)
    est = filter_target(run, process_noise(DT, 10.0), np.eye(2))
    assert est.run is run
    dist = np.hypot(*(est.mu[:, :2] - run.truth[:, :2]).T)
    np.testing.assert_allclose(est.position_error(), dist)
    assert est.lag_in_turns() == pytest.approx(dist[run.turning].mean())
    p = est.mu[START_STEPS:, :2]
    assert est.roughness() == pytest.approx(
        np.mean([np.linalg.norm(p[i + 1] - 2 * p[i] + p[i - 1]) for i in range(1, len(p) - 1)])
    )
    assert roughness(run.z) > 5 * est.roughness()  # the tuned estimate is far smoother than the readings
    sx, sy = np.sqrt(np.linalg.eigvalsh(est.Sig[50, :2, :2]))
    assert est.ellipse_radius(50) == pytest.approx(2 * max(sx, sy))
    assert est.ellipse_radius(50, nsig=1.0) == pytest.approx(max(sx, sy))


def test_honesty_averages_the_position_nees_and_counts_one_draw_per_second():
    run = simulate_target(4)
    est = filter_target(run, process_noise(DT, 10.0), np.eye(2))
    h = est.honesty()
    k = np.arange(START_STEPS, run.t.size)
    err = est.mu[k, :2] - run.truth[k, :2]
    nees_k = [e @ np.linalg.inv(S) @ e for e, S in zip(err, est.Sig[k, :2, :2], strict=True)]
    assert h.mean_nees == pytest.approx(np.mean(nees_k))
    assert h.draws == round(k.size * DT / 1.0) == 14
    assert (h.low, h.high) == nees_band(14, 2, 0.95)
    assert h.verdict == "honest"
    assert filter_target(run, process_noise(DT, 10.0), 100 * np.eye(2)).honesty().verdict == "timid"
    assert filter_target(run, process_noise(DT, 1e-3), np.eye(2)).honesty().verdict == "over-confident"
    assert filter_target(run, process_noise(DT, 10.0), 0.01 * np.eye(2)).honesty().verdict == "over-confident"


def test_tuning_table_prints_one_line_per_filter_and_the_readings():
    run = simulate_target(0)
    ests = {
        "a": filter_target(run, process_noise(DT, 10.0), np.eye(2)),
        "b": filter_target(run, process_noise(DT, 1e-3), np.eye(2)),
    }
    lines = run.tuning_table(ests).splitlines()
    assert lines[0].split() == [
        "filter",
        "assumes",
        "K",
        "lag",
        "in",
        "turns",
        "(m)",
        "roughness",
        "(m)",
        "mean",
        "NEES",
        "verdict",
    ]
    assert [line.split()[0] for line in lines[2:]] == ["a", "b", "the"]
    a = ests["a"]
    assert lines[2].split()[1:] == [f"{a.K[-1, 0, 0]:.3f}", f"{a.lag_in_turns():.2f}", f"{a.roughness():.2f}",
                                     f"{a.honesty().mean_nees:.2f}", "honest"]  # fmt: skip
    assert lines[3].split()[-1] == "over-confident"
    assert lines[4].split()[2:] == [f"{np.linalg.norm(run.z - run.truth[:, :2], axis=1)[run.turning].mean():.2f}",
                                    f"{roughness(run.z):.2f}"]  # fmt: skip


def test_nees_table_prints_the_band_and_one_line_per_assumption():
    batch = simulate_tracks(50, 30, seed=1)
    text = batch.nees_table({"true": (batch.R, batch.Q), "small Q": (batch.R, 0.1 * batch.Q)})
    low, high = nees_band(50, 4)
    lines = text.splitlines()
    assert lines[0] == f"band [{low:.2f}, {high:.2f}] for 50 tracks"
    mu, Sig = filter_tracks(batch, batch.R, 0.1 * batch.Q)
    avg_nees = nees(batch.truth, mu, Sig).mean(axis=0)
    small = lines[-1].split()
    assert small[:3] == ["small", "Q", f"{avg_nees.mean():.2f}"] and small[-2] == "100%"  # all above the band
