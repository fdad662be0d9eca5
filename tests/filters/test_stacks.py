"""The vectorized paths (all sigma points in one model call) change no result and skip no check."""

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
def test_vectorized_ukf_equals_per_point(lam):
    mu, Sig = np.array([1.0, 2.0, 3.0]), np.diag([0.3, 0.2, 0.4])
    R, Q = np.diag([0.01, 0.01, 0.02]), np.diag([0.04, 0.01])
    u, z = np.array([0.5, 0.8]), np.array([5.2, -2.0])
    for vectorized in (False, True):
        mb, Sb = kf.ukf_predict(mu, Sig, u, g, R, lam, pose_residual, pose_mean, vectorized=vectorized)
        m, S = kf.ukf_update(
            mb, Sb, z, h, Q, lam, range_bearing_residual, range_bearing_mean, pose_residual, vectorized=vectorized
        )
        if not vectorized:
            expected = (mb, Sb, m, S)
    for got, want in zip((mb, Sb, m, S), expected, strict=True):
        assert got == pytest.approx(want, abs=1e-12)
    y_v = kf.unscented_transform(mu, Sig, h, lam, range_bearing_residual, range_bearing_mean, vectorized=True)
    y_p = kf.unscented_transform(mu, Sig, h, lam, range_bearing_residual, range_bearing_mean)
    assert y_v[0] == pytest.approx(y_p[0]) and y_v[1] == pytest.approx(y_p[1])


def test_vectorized_model_with_wrong_shape_is_named():
    with pytest.raises(ValueError, match="the result of g"):
        kf.ukf_predict(np.zeros(3), np.eye(3), None, lambda x, u: x[:, :2], np.eye(3), 0.0, vectorized=True)


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
