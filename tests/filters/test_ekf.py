"""The extended Kalman filter (chapters 8 and 9): ``ekf_predict`` and ``ekf_update``.
The lesson's range-bearing update and linearisation, a bearing innovation wrapped the
short way round across +-pi, agreement with the linear filter on a linear model, and
the bad input they refuse.  (Long runs: ``test_long_runs.py``.)

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse.models import pose_residual, range_bearing_mean, range_bearing_residual
from tests.filters.strategies import (
    FAST,
    H12,
    I2,
    I3,
    INDEFINITE,
    INF,
    LANDMARK,
    LM_BEHIND,
    MU2,
    NAN,
    NEGVAR,
    NONSYM,
    POSE,
    POSE0,
    Q_CH8,
    Q_SEAM,
    SIG_BAR,
    SIG_BAR_CH8,
    TWO_PI,
    Z_CH8,
    G_ok,
    H_behind,
    H_rb,
    assert_close,
    assert_raises_naming,
    assert_unique_ids,
    bad_input_cases,
    g_ok,
    h_behind,
    h_rb,
    linear_models,
    r3,
    seam_cases,
    square,
    textbook_update,
)


# ================================================================ worked numbers (chapters 8 and 9)
def test_ch8_innovation():
    nu = kf.models.range_bearing_residual(Z_CH8, kf.range_bearing(POSE, LANDMARK))
    assert r3(nu[0]) == -0.4
    assert r3(nu[1]) == 0.023


def test_ch8_range_channel_gain_and_correction():
    H = kf.range_bearing_jacobian(POSE, LANDMARK)
    S, _ = kf.kf_gain(SIG_BAR_CH8, H, Q_CH8)
    assert S[0, 0] == pytest.approx(0.34, abs=1e-12)
    # the lesson's shortcut: range gain into x = Sig_xx H_rx / S_rr
    k_rx = SIG_BAR_CH8[0, 0] * H[0, 0] / S[0, 0]
    assert round(k_rx, 2) == -0.53
    # ... which is exactly the x-gain of a range-only update
    _, K_range = kf.kf_gain(SIG_BAR_CH8, H[:1], Q_CH8[:1, :1])
    assert K_range[0, 0] == pytest.approx(k_rx, rel=1e-12)
    nu_r = Z_CH8[0] - kf.range_bearing(POSE, LANDMARK)[0]
    assert round(k_rx * nu_r, 2) == 0.21  # + 0.21 m, toward the landmark


def test_ch8_full_ekf_update_moves_toward_landmark_and_shrinks_along_line_of_sight():
    mu, Sig = kf.ekf_update(
        POSE,
        SIG_BAR_CH8,
        Z_CH8,
        h=lambda x: kf.range_bearing(x, LANDMARK),
        H=lambda x: kf.range_bearing_jacobian(x, LANDMARK),
        Q=Q_CH8,
        residual=kf.models.range_bearing_residual,
    )
    assert mu[0] > POSE[0] and mu[1] > POSE[1]  # both toward (4, 6)
    assert mu[0] - POSE[0] == pytest.approx(0.21, abs=0.02)  # close to the range-only estimate
    along = np.array([0.6, 0.8, 0.0])  # unit line of sight
    across = np.array([-0.8, 0.6, 0.0])
    shrink_along = along @ SIG_BAR_CH8 @ along - along @ Sig @ along
    shrink_across = across @ SIG_BAR_CH8 @ across - across @ Sig @ across
    assert shrink_along > shrink_across > 0
    assert np.all(np.linalg.eigvalsh(SIG_BAR_CH8 - Sig) >= -1e-12)  # an update never adds uncertainty


def test_ch9_ekf_linearisation():
    J = kf.numeric_jacobian(lambda x: np.asarray(x) ** 2, [2.0])
    assert J.shape == (1, 1)
    assert J[0, 0] == pytest.approx(4.0, rel=1e-8)  # d(x^2)/dx = 2x = 4 at x = 2
    # through ekf_predict: mean on the curve, variance on the tangent, J^2 var = 16 var
    for var in (1.0, 0.25, 3.0):  # a variance other than 1 shows whether it is used
        mu, Sig = kf.ekf_predict(
            [2.0], [[var]], None, lambda x, u: x**2, lambda x, u: kf.numeric_jacobian(square, x), [[0.0]]
        )
        assert (mu[0], Sig[0, 0]) == pytest.approx((4.0, 16.0 * var), rel=1e-7)


# ================================================================ closed forms
def test_ekf_predict_closed_form_x_squared_with_variance_not_one():
    # x ~ N(3, 0.5), g(x) = x^2, G = 2x = 6 at the mean: mean 9, var 6 * 0.5 * 6 + R = 18 + 0.25
    m, S = kf.ekf_predict([3.0], [[0.5]], None, lambda x, u: x**2, lambda x, u: np.array([[2 * x[0]]]), [[0.25]])
    assert (m[0], S[0, 0]) == pytest.approx((9.0, 18.25), rel=1e-14)


def test_ekf_update_wraps_a_bearing_innovation_across_pi():
    z_hat = kf.range_bearing(POSE0, LM_BEHIND)
    assert z_hat[1] > math.pi - 0.03  # predicted just below +pi
    z = np.array([z_hat[0] + 0.1, -math.pi + 0.01])  # read just above -pi: 0.03ish further round
    y = np.array([0.1, math.remainder(z[1] - z_hat[1], TWO_PI)])  # the short way round, by hand
    assert abs(y[1]) < 0.05
    mu, Sig = kf.ekf_update(POSE0, SIG_BAR, z, h_behind, H_behind, Q_SEAM, residual=range_bearing_residual)
    mu_ref, Sig_ref = textbook_update(POSE0, SIG_BAR, y, kf.range_bearing_jacobian(POSE0, LM_BEHIND), Q_SEAM)
    np.testing.assert_allclose(mu, mu_ref, atol=1e-12)
    np.testing.assert_allclose(Sig, Sig_ref, atol=1e-12)


# ================================================================ properties
@FAST
@given(lm=linear_models())
def test_ekf_on_a_linear_model_equals_kf(lm):
    F, B, H = lm["F"], lm["B"], lm["H"]
    mu_bar, Sig_bar = kf.ekf_predict(
        lm["mu"], lm["Sig"], lm["u"], lambda chi, u: chi @ F.T + B @ u, lambda x, u: F, lm["R"]
    )
    mu_bar_kf, Sig_bar_kf = kf.kf_predict(lm["mu"], lm["Sig"], lm["u"], F, B, lm["R"])
    assert_close(mu_bar, mu_bar_kf, scale=1e2)
    assert_close(Sig_bar, Sig_bar_kf, scale=np.abs(Sig_bar_kf).max())
    mu, Sig = kf.ekf_update(mu_bar, Sig_bar, lm["z"], lambda x: H @ x, lambda x: H, lm["Q"])
    mu_kf, Sig_kf = kf.kf_update(mu_bar_kf, Sig_bar_kf, lm["z"], H, lm["Q"])
    assert_close(mu, mu_kf, scale=1e2 + np.abs(mu_kf).max())
    assert_close(Sig, Sig_kf, scale=np.abs(Sig_bar_kf).max())


@FAST
@given(case=seam_cases, turns=st.sampled_from([-2, -1, 1, 3]))
def test_ekf_and_ukf_updates_do_not_care_how_a_bearing_is_written(case, turns):
    # Readings behind the robot: the bearing sits at +-pi, and z and z + 2 pi k are the same reading.
    dist, off, err, heading = case
    pose = np.array([1.0, -2.0, heading])
    a = heading + math.pi + off
    lm = pose[:2] + dist * np.array([math.cos(a), math.sin(a)])
    h, H = partial(kf.range_bearing, landmark=lm), partial(kf.range_bearing_jacobian, landmark=lm)
    z = kf.range_bearing(pose, lm) + np.array([0.05, err])
    z_turned = z + np.array([0.0, turns * TWO_PI])
    e1 = kf.ekf_update(pose, SIG_BAR, z, h, H, Q_SEAM, residual=range_bearing_residual)
    e2 = kf.ekf_update(pose, SIG_BAR, z_turned, h, H, Q_SEAM, residual=range_bearing_residual)
    np.testing.assert_allclose(e1[0], e2[0], atol=1e-9)
    assert np.linalg.norm(e1[0][:2] - pose[:2]) < 1.0  # a small innovation moves the robot a little
    kw = {"residual": range_bearing_residual, "mean": range_bearing_mean, "x_residual": pose_residual}
    u1 = kf.ukf_update(pose, SIG_BAR, z, h, Q_SEAM, 0.0, **kw)
    u2 = kf.ukf_update(pose, SIG_BAR, z_turned, h, Q_SEAM, 0.0, **kw)
    np.testing.assert_allclose(u1[0], u2[0], atol=1e-9)
    np.testing.assert_allclose(u1[1], u2[1], atol=1e-12)
    assert np.linalg.norm(u1[0][:2] - pose[:2]) < 1.0


# ================================================================ bad input
BAD_INPUT = [
    ("ekf_predict/g not callable", lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], "g", G_ok, 0.01 * I3), "g"),
    ("ekf_predict/G not callable", lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], g_ok, np.eye(3), 0.01 * I3), "G"),
    (
        "ekf_predict/g wrong shape",
        lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], lambda x, u: x[:2], G_ok, 0.01 * I3),
        "g",
    ),
    (
        "ekf_predict/g returns NaN",
        lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], lambda x, u: x * NAN, G_ok, 0.01 * I3),
        "g",
    ),
    ("ekf_predict/G wrong shape", lambda: kf.ekf_predict(POSE, I3, [0.5, 0.0], g_ok, lambda x, u: I2, 0.01 * I3), "G"),
    ("ekf_predict/R indefinite", lambda: kf.ekf_predict(MU2, I2, None, g_ok, G_ok, INDEFINITE), "R"),
    ("ekf_predict/Sig non-symmetric", lambda: kf.ekf_predict(MU2, NONSYM, None, g_ok, G_ok, I2), "Sig"),
    ("ekf_predict/mu inf", lambda: kf.ekf_predict([INF, 0.0], I2, None, g_ok, G_ok, I2), "mu"),
    ("ekf_update/h not callable", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], None, H_rb, Q_CH8), "h"),
    ("ekf_update/H not callable", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H12, Q_CH8), "H"),
    ("ekf_update/h wrong shape", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], lambda x: x, H_rb, Q_CH8), "h"),
    ("ekf_update/H wrong shape", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, lambda x: I3, Q_CH8), "H"),
    ("ekf_update/Q negative variance", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, NEGVAR), "Q"),
    (
        "ekf_update/Sig_bar indefinite",
        lambda: kf.ekf_update(POSE, np.diag([1.0, -1.0, 1.0]), [4.6, 0.95], h_rb, H_rb, Q_CH8),
        "Sig_bar",
    ),
    ("ekf_update/z NaN", lambda: kf.ekf_update(POSE, I3, [4.6, NAN], h_rb, H_rb, Q_CH8), "z"),
    ("ekf_update/z wrong length", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95, 1.0], h_rb, H_rb, Q_CH8), "z"),
    ("ekf_update/Q wrong shape", lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, I3), "Q"),
    (
        "ekf_update/residual wrong shape",
        lambda: kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, Q_CH8, residual=lambda a, b: [0.0]),
        "residual",
    ),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.ekf_predict(POSE, I3, [0.5, 0.0], g_ok, G_ok, 0.01 * I3)
    kf.ekf_update(POSE, I3, [4.6, 0.95], h_rb, H_rb, Q_CH8)


@pytest.mark.parametrize(
    "call",
    [lambda: kf.ekf_update(np.zeros(3), np.eye(3), [5.0, 0.9], h_rb, H_rb, np.eye(2), residual=3)],
    ids=["ekf_update"],
)
def test_hook_that_is_not_callable(call):
    with pytest.raises(ValueError, match=r"\b(residual|mean) must be callable"):
        call()


def test_the_predicted_covariance_is_exactly_symmetric():
    rng = np.random.default_rng(7)
    A = rng.normal(size=(3, 3))
    g, G = (lambda x, u: kf.unicycle(x, u, 0.5)), (lambda x, u: kf.unicycle_jacobian(x, u, 0.5))
    _, Sig_bar = kf.ekf_predict(rng.normal(size=3), A @ A.T + np.eye(3), [0.7, 0.4], g, G, 0.01 * np.eye(3))
    assert np.array_equal(Sig_bar, Sig_bar.T)
