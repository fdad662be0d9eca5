"""kf.ekf_localization_step, chapter 10's step: it reproduces kf.sim.landmark_loop's EKF step by
step over whole laps, and it checks its inputs.

Noise letters: R = process noise (here W M W^T), Q = measurement noise.
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.capstone_world import SIG0


def _noise(world):
    """M and Q as landmark_loop builds them from the world's noise."""
    M = np.diag([world.v_std, world.omega_std]) ** 2
    Q = np.diag([world.range_std, world.bearing_std]) ** 2
    return M, Q


def _lap(world, gate):
    """Run the step over the world's whole drive: the estimate and the used flags at every step."""
    M, Q = _noise(world)
    mu, Sig = world.start, SIG0
    T, L = world.visible.shape
    mus, Sigs, used = np.empty((T, 3)), np.empty((T, 3, 3)), np.zeros((T, L), dtype=bool)
    for k in range(T):
        seen = world.visible[k]  # in range, and the sensor not blind
        mu, Sig, used_k = kf.ekf_localization_step(
            mu, Sig, world.odometry[k], world.z[k, seen], world.landmarks[seen], world.dt, M, Q, gate
        )
        mus[k], Sigs[k], used[k, seen] = mu, Sig, used_k
    return mus, Sigs, used


@pytest.mark.parametrize("seed", range(5))
def test_a_lap_reproduces_the_loop_step_by_step(seed):
    run = kf.sim.landmark_loop(seed, gate=4.0)
    mu, Sig, used = _lap(kf.sim.loop_world(seed), 4.0)
    np.testing.assert_allclose(mu, run.mu, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(Sig, run.Sig, rtol=1e-9, atol=1e-15)
    np.testing.assert_array_equal(used, run.used)


@pytest.mark.parametrize(
    "drive",
    [{"dropout": (40, 70)}, {"kidnap": 60}],
    ids=["blind for 30 steps", "kidnapped: the gate refuses readings"],
)
def test_blind_steps_and_refused_readings_agree_with_the_loop(drive):
    run = kf.sim.landmark_loop(0, gate=4.0, **drive)
    mu, Sig, used = _lap(kf.sim.loop_world(0, **drive), 4.0)
    np.testing.assert_allclose(mu, run.mu, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(Sig, run.Sig, rtol=1e-9, atol=1e-15)
    np.testing.assert_array_equal(used, run.used)
    assert (~used[40:70]).all() if "dropout" in drive else run.rejected.any()


def test_no_gate_uses_every_reading_like_the_ungated_loop():
    run = kf.sim.landmark_loop(0, kidnap=60)  # no gate: every reading in view is used
    mu, _, used = _lap(kf.sim.loop_world(0, kidnap=60), np.inf)
    np.testing.assert_allclose(mu, run.mu, rtol=1e-9, atol=1e-12)
    np.testing.assert_array_equal(used, run.used)
    assert not run.rejected.any()


def test_no_reading_only_predicts():
    mu, Sig, u, dt = np.array([1.0, 2.0, 0.5]), np.diag([0.04, 0.04, 0.01]), np.array([0.8, 0.3]), 0.2
    M, Q = np.diag([0.1, 0.05]) ** 2, np.diag([0.1, 0.03]) ** 2
    W = kf.unicycle_control_jacobian(mu, u, dt)
    mu_bar, Sig_bar = kf.ekf_predict(
        mu, Sig, u, lambda x, c: kf.unicycle(x, c, dt), lambda x, c: kf.unicycle_jacobian(x, c, dt), W @ M @ W.T
    )
    for empty in (np.zeros((0, 2)), []):
        new_mu, new_Sig, used = kf.ekf_localization_step(mu, Sig, u, empty, empty, dt, M, Q, 4.0)
        np.testing.assert_allclose(new_mu, mu_bar)
        np.testing.assert_allclose(new_Sig, Sig_bar)
        assert used.shape == (0,) and used.dtype == bool


def test_the_heading_of_the_result_is_wrapped():
    mu, _, used = kf.ekf_localization_step(
        np.array([0.0, 0.0, np.pi - 0.01]),
        np.diag([0.04, 0.04, 0.01]),
        np.array([1.0, 0.0]),
        np.array([[2.95, 0.05]]),
        np.array([[-3.1, -0.3]]),
        0.2,
        np.diag([0.1, 0.05]) ** 2,
        np.diag([0.1, 0.03]) ** 2,
        4.0,
    )
    assert used.all() and -np.pi < mu[2] < -np.pi + 0.1


GOOD = {
    "mu": np.zeros(3),
    "Sig": np.eye(3) * 0.01,
    "u": np.array([1.0, 0.0]),
    "z": np.array([[3.0, 0.0]]),
    "landmarks": np.array([[3.2, 0.0]]),
    "dt": 0.2,
    "M": np.diag([0.1, 0.05]) ** 2,
    "Q": np.diag([0.1, 0.03]) ** 2,
    "gate": 4.0,
}


@pytest.mark.parametrize(
    ("name", "bad"),
    [
        ("mu", np.zeros(2)),
        ("Sig", -np.eye(3)),
        ("u", np.zeros(3)),
        ("z", np.zeros((1, 3))),
        ("landmarks", np.zeros((2, 2))),
        ("dt", 0.0),
        ("M", np.eye(3)),
        ("Q", np.array([[1.0, 2.0], [0.0, 1.0]])),
        ("gate", 0.0),
        ("gate", np.nan),
        ("gate", "wide"),
        ("mu", np.array([0.0, np.nan, 0.0])),
    ],
)
def test_bad_input_is_refused_by_name(name, bad):
    with pytest.raises(ValueError, match=f"^{name}"):
        kf.ekf_localization_step(**{**GOOD, name: bad})


def test_a_singular_innovation_covariance_is_refused_by_name():
    with pytest.raises(ValueError, match=r"^Q"):
        kf.ekf_localization_step(**{**GOOD, "Sig": np.zeros((3, 3)), "M": np.zeros((2, 2)), "Q": np.zeros((2, 2))})


def test_inputs_are_not_changed():
    inputs = {k: np.array(x, copy=True) if isinstance(x, np.ndarray) else x for k, x in GOOD.items()}
    kf.ekf_localization_step(**inputs)
    for k, x in GOOD.items():
        np.testing.assert_array_equal(inputs[k], x)
