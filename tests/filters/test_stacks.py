"""The models take stacks of poses, the UKF calls them on every sigma point at once, and kf_gain."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual

LANDMARK = np.array([4.0, 6.0])
DT = 0.1  # s


def g(x, u):
    return kf.unicycle(x, u, DT)


def h(x):
    return kf.range_bearing(x, LANDMARK)


def test_models_take_stacks_of_poses():
    rng = np.random.default_rng(1)
    poses = rng.uniform(-3, 3, size=(7, 3))
    u = np.array([0.7, -0.4])
    assert kf.unicycle(poses, u, DT) == pytest.approx(np.array([kf.unicycle(p, u, DT) for p in poses]))
    assert kf.range_bearing(poses, LANDMARK) == pytest.approx(np.array([kf.range_bearing(p, LANDMARK) for p in poses]))
    a, b = rng.uniform(-4, 4, size=(7, 3)), rng.uniform(-4, 4, size=3)
    assert pose_residual(a, b) == pytest.approx(np.array([pose_residual(r, b) for r in a]))
    with pytest.raises(ValueError, match="state"):
        kf.unicycle(np.zeros((2, 4)), u, DT)
    with pytest.raises(ValueError, match="state"):
        kf.range_bearing_jacobian(poses, LANDMARK)  # a Jacobian is for one pose


@pytest.mark.parametrize("lam", [0.0, 1.0, 2.0])
def test_the_ukf_takes_every_sigma_point_at_once_as_one_per_point_would(lam):
    mu, Sig = np.array([1.0, 2.0, 3.0]), np.diag([0.3, 0.2, 0.4])
    R, Q = np.diag([0.01, 0.01, 0.02]), np.diag([0.04, 0.01])
    u, z = np.array([0.5, 0.8]), np.array([5.2, -2.0])
    one_by_one = {"g": lambda chi, u: np.array([g(x, u) for x in chi]), "h": lambda chi: np.array([h(x) for x in chi])}
    for models in ({"g": g, "h": h}, one_by_one):
        mb, Sb = kf.ukf_predict(mu, Sig, u, models["g"], R, lam, pose_residual, pose_mean)
        m, S = kf.ukf_update(mb, Sb, z, models["h"], Q, lam, range_bearing_residual, range_bearing_mean, pose_residual)
        if models["g"] is g:
            expected = (mb, Sb, m, S)
    for got, want in zip((mb, Sb, m, S), expected, strict=True):
        assert got == pytest.approx(want, abs=1e-12)


def test_a_model_with_the_wrong_shape_is_named():
    with pytest.raises(ValueError, match="the result of g"):
        kf.ukf_predict(np.zeros(3), np.eye(3), None, lambda x, u: x[:, :2], np.eye(3), 0.0)
    with pytest.raises(ValueError, match="the result of h"):
        kf.ukf_update(np.zeros(3), np.eye(3), [1.0], lambda x: x[0, :1], [[1.0]], 0.0)  # one point's, not all 7


def test_kf_gain_matches_the_formula_for_one_two_and_three_readings():
    rng = np.random.default_rng(3)
    for k in (1, 2, 3):
        A = rng.normal(size=(4, 4))
        Sig_bar = A @ A.T + np.eye(4)
        H = rng.normal(size=(k, 4))
        Q = np.eye(k) * 0.3
        S, K = kf.kf_gain(Sig_bar, H, Q)
        assert S == pytest.approx(H @ Sig_bar @ H.T + Q)
        assert K == pytest.approx(Sig_bar @ H.T @ np.linalg.inv(S))
