"""The unscented Kalman filter (chapter 9): ``sigma_points``, ``unscented_1d``,
``unscented_transform``, ``ukf_predict`` and ``ukf_update``.  The lesson's x -> x² example
(checked against seeded samples too), the transforms by hand, a bearing innovation
wrapped across +-pi, agreement with the linear filter, models called on every sigma
point at once, and the bad input they refuse.  (``beta``: ``test_ukf_beta.py``; long
runs: ``test_long_runs.py``.)

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual
from tests.filters.strategies import (
    FAST,
    I2,
    I3,
    INDEFINITE,
    INF,
    LM_BEHIND,
    MU2,
    N_SAMPLES,
    NAN,
    NONSYM,
    POSE0,
    Q11,
    Q_SEAM,
    SIG_BAR,
    TWO_PI,
    Z_TOL,
    assert_close,
    assert_raises_naming,
    assert_unique_ids,
    bad_input_cases,
    g_ok,
    h_behind,
    h_rb,
    lin,
    linear_models,
    reals,
    spd,
    square,
    textbook_update,
    vectors,
)


# ================================================================ worked numbers (chapter 9)
def test_ch9_unscented_1d_worked():
    assert kf.unscented_1d(2.0, 1.0, square) == pytest.approx((5.0, 16.0), abs=1e-12)
    assert kf.unscented_1d(2, 1, lambda x: x**2) == pytest.approx((5.0, 16.0), abs=1e-12)


def test_ch9_sigma_points_lam0_n1_weights():
    chi, wm, wc = kf.sigma_points([2.0], [[1.0]], 0.0)
    np.testing.assert_allclose(chi[:, 0], [2.0, 3.0, 1.0])
    np.testing.assert_allclose(wm, [0.0, 0.5, 0.5])
    np.testing.assert_allclose(wc, [0.0, 0.5, 0.5])


def test_ch9_unscented_transform_matches_unscented_1d():
    mu_y, Sig_y = kf.unscented_transform([2.0], [[1.0]], lambda x: x**2, 0.0)
    assert (mu_y[0], Sig_y[0, 0]) == pytest.approx((5.0, 16.0), abs=1e-12)


def test_ch9_monte_carlo_truth(rng):
    y = rng.normal(2.0, 1.0, N_SAMPLES) ** 2
    n = y.size
    var_hat = y.var(ddof=1)
    m4_hat = np.mean((y - y.mean()) ** 4)
    se_mean = math.sqrt(var_hat / n)
    se_var = math.sqrt((m4_hat - var_hat**2) / n)  # sd of the sample variance, any distribution
    # true moments: E[x^2] = mu^2 + s^2 = 5, Var[x^2] = 4 mu^2 s^2 + 2 s^4 = 18
    assert abs(y.mean() - 5.0) < Z_TOL * se_mean
    assert abs(var_hat - 18.0) < Z_TOL * se_var
    # the UKF (lam = 0) mean is right, the EKF mean is not; the UKF variance 4 mu^2 s^2 = 16 and the
    # EKF's (2 mu)^2 s^2 = 16 both miss the 2 s^4 term, by 2 = many standard errors
    ukf_mean, ukf_var = kf.unscented_1d(2.0, 1.0, square)
    assert (ukf_mean, ukf_var) == pytest.approx((5.0, 16.0), rel=1e-12)
    assert abs(y.mean() - ukf_mean) < Z_TOL * se_mean
    assert abs(y.mean() - 4.0) > 20 * se_mean
    assert abs(var_hat - ukf_var) > 5 * se_var
    # with lam = 2 (n + lam = 3) the sigma points catch the 2 s^4 term: 4 mu^2 s^2 + lam s^4 = 18
    m3, v3 = kf.unscented_1d(2.0, 1.0, square, lam=2.0)
    assert (m3, v3) == pytest.approx((5.0, 18.0), rel=1e-12)
    assert abs(var_hat - v3) < Z_TOL * se_var


def test_ch9_monte_carlo_truth_with_variance_not_one(rng):
    # x ~ N(1, 0.25) through x^2: E = mu^2 + s2 = 1.25, Var = 4 mu^2 s2 + 2 s2^2 = 1 + 0.125
    x = rng.normal(1.0, 0.5, N_SAMPLES)
    y = x**2
    se_var = math.sqrt((np.mean((y - y.mean()) ** 4) - y.var() ** 2) / y.size)
    assert abs(y.var(ddof=1) - 1.125) < Z_TOL * se_var
    m, s = kf.unscented_1d(1.0, 0.25, square, lam=2.0)
    assert (m, s) == pytest.approx((1.25, 1.125), rel=1e-12)
    mu, Sig = kf.ukf_predict([1.0], [[0.25]], None, lambda v, u: v**2, [[0.0]], 2.0)
    assert (mu[0], Sig[0, 0]) == pytest.approx((1.25, 1.125), rel=1e-12)


# ================================================================ closed forms
def test_unscented_1d_closed_form_with_variance_not_one():
    # x ~ N(3, 0.25) through x^2 with lam = 2: mean mu^2 + s2 = 9.25; var 4 mu^2 s2 + lam s2^2 = 9 + 0.125
    assert kf.unscented_1d(3.0, 0.25, lambda x: x * x, lam=2.0) == pytest.approx((9.25, 9.125), rel=1e-12)
    # the same through the matrix transform
    m, S = kf.unscented_transform([3.0], [[0.25]], lambda x: x**2, 2.0)
    assert (m[0], S[0, 0]) == pytest.approx((9.25, 9.125), rel=1e-12)


def test_ukf_predict_closed_form_x_squared_with_process_noise():
    # x ~ N(2, 0.5), g(x) = x^2, lam = 2, R = 0.1: mean 4 + 0.5 = 4.5; var 4*4*0.5 + 2*0.25 + 0.1 = 8.6
    m, S = kf.ukf_predict([2.0], [[0.5]], None, lambda x, u: x**2, [[0.1]], 2.0)
    assert (m[0], S[0, 0]) == pytest.approx((4.5, 8.6), rel=1e-12)


def test_ukf_update_closed_form_scalar():
    # h(x) = 2x on x ~ N(1, 1), Q = 4, z = 4: S = 4 + 4 = 8, Sig_xz = 2, K = 1/4,
    # mu = 1 + (4 - 2) / 4 = 1.5, Sig = 1 - K S K = 1 - 0.5 = 0.5
    m, S = kf.ukf_update([1.0], [[1.0]], [4.0], lambda x: 2 * x, [[4.0]], 0.0)
    assert (m[0], S[0, 0]) == pytest.approx((1.5, 0.5), rel=1e-12)


def test_ukf_update_wraps_a_bearing_innovation_across_pi():
    # with a tiny prior the UKF linearises exactly like the EKF: same wrapped answer
    Sig_bar = 1e-8 * SIG_BAR
    z_hat = kf.range_bearing(POSE0, LM_BEHIND)
    z = np.array([z_hat[0] + 1e-5, -math.pi + 0.01])
    y = np.array([1e-5, math.remainder(z[1] - z_hat[1], TWO_PI)])
    mu_ref, Sig_ref = textbook_update(POSE0, Sig_bar, y, kf.range_bearing_jacobian(POSE0, LM_BEHIND), Q_SEAM)
    kw = {"residual": range_bearing_residual, "mean": range_bearing_mean, "x_residual": pose_residual}
    mu, Sig = kf.ukf_update(POSE0, Sig_bar, z, h_behind, Q_SEAM, 1.0, **kw)
    np.testing.assert_allclose(mu, mu_ref, rtol=1e-6, atol=1e-13)
    np.testing.assert_allclose(Sig, Sig_ref, rtol=1e-6, atol=1e-17)


# ================================================================ properties
@FAST
@given(mu=vectors(3), Sig=spd(3), lam=st.sampled_from([0.0, 1.0, 2.0, -1.0, 0.5]))
def test_sigma_points_reproduce_mean_and_covariance(mu, Sig, lam):
    chi, wm, wc = kf.sigma_points(mu, Sig, lam)
    assert chi.shape == (7, 3) and wm.shape == wc.shape == (7,)
    assert wm.sum() == pytest.approx(1.0, abs=1e-12)
    assert_close(wm @ chi, mu, scale=10.0)
    d = chi - mu
    assert_close((wc[:, None] * d).T @ d, Sig, scale=np.abs(Sig).max())


@FAST
@given(mu=reals(-5, 5), var=reals(0.01, 5), lam=reals(-0.9, 4))
def test_unscented_1d_of_x_squared_matches_the_hand_formula(mu, var, lam):
    m, s = kf.unscented_1d(mu, var, lambda x: x * x, lam=lam)
    assert m == pytest.approx(mu * mu + var, rel=1e-10, abs=1e-10)
    assert s == pytest.approx(4 * mu * mu * var + lam * var * var, rel=1e-8, abs=1e-8 * (1 + var * var))


@FAST
@given(
    mu=st.tuples(reals(-5, 5), reals(-5, 5)).map(np.array),
    Sig=spd(2),
    A=st.lists(reals(-2, 2), min_size=6, max_size=6).map(lambda a: np.array(a).reshape(3, 2)),
    lam=st.sampled_from([0.0, 1.0, -1.0, 0.5]),
)
def test_unscented_transform_is_exact_for_affine_maps(mu, Sig, A, lam):
    b = np.array([1.0, -2.0, 0.5])
    m, S = kf.unscented_transform(mu, Sig, lambda chi: chi @ A.T + b, lam)
    np.testing.assert_allclose(m, A @ mu + b, atol=1e-9 * (1 + np.abs(mu).max()))
    np.testing.assert_allclose(S, A @ Sig @ A.T, rtol=1e-8, atol=1e-8 * np.abs(Sig).max())


@FAST
@given(lm=linear_models(), lam_choice=st.sampled_from(["0", "1", "3-n", "free"]), lam_free=reals(-0.9, 5.0))
def test_ukf_on_a_linear_model_equals_kf(lm, lam_choice, lam_free):
    n = lm["n"]
    lam = {"0": 0.0, "1": 1.0, "3-n": 3.0 - n, "free": lam_free - n + 1.0}[lam_choice]
    assume(n + lam > 0.05)
    F, B, H = lm["F"], lm["B"], lm["H"]
    mu_bar, Sig_bar = kf.ukf_predict(lm["mu"], lm["Sig"], lm["u"], lambda chi, u: chi @ F.T + B @ u, lm["R"], lam)
    mu_bar_kf, Sig_bar_kf = kf.kf_predict(lm["mu"], lm["Sig"], lm["u"], F, B, lm["R"])
    weight = 1.0 + abs(lam) / (n + lam)  # cancellation grows with |w_0|
    assert_close(mu_bar, mu_bar_kf, rtol=1e-8 * weight, scale=1e2)
    assert_close(Sig_bar, Sig_bar_kf, rtol=1e-8 * weight, scale=np.abs(Sig_bar_kf).max())
    mu, Sig = kf.ukf_update(mu_bar_kf, Sig_bar_kf, lm["z"], lambda chi: chi @ H.T, lm["Q"], lam)
    mu_kf, Sig_kf = kf.kf_update(mu_bar_kf, Sig_bar_kf, lm["z"], H, lm["Q"])
    assert_close(mu, mu_kf, rtol=1e-8 * weight, scale=1e2 + np.abs(mu_kf).max())
    assert_close(Sig, Sig_kf, rtol=1e-8 * weight, scale=np.abs(Sig_bar_kf).max())


DT = 0.1  # s


def g(x, u):
    return kf.unicycle(x, u, DT)


h = h_rb  # range and bearing to LANDMARK


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


# ================================================================ bad input
BAD_INPUT = [
    ("sigma_points/lam with n+lam=0", lambda: kf.sigma_points(MU2, I2, -2.0), "lam"),
    ("sigma_points/lam with n+lam<0", lambda: kf.sigma_points(MU2, I2, -3.0), "lam"),
    ("sigma_points/lam NaN", lambda: kf.sigma_points(MU2, I2, NAN), "lam"),
    ("sigma_points/Sig indefinite", lambda: kf.sigma_points(MU2, INDEFINITE, 1.0), "Sig"),
    ("sigma_points/Sig wrong shape", lambda: kf.sigma_points(MU2, I3, 1.0), "Sig"),
    ("sigma_points/beta inf", lambda: kf.sigma_points(MU2, I2, 1.0, beta=INF), "beta"),
    ("unscented_transform/f not callable", lambda: kf.unscented_transform(MU2, I2, [1, 2], 1.0), "f"),
    ("unscented_transform/lam with n+lam=0", lambda: kf.unscented_transform([2.0], [[1.0]], lin, -1.0), "lam"),
    ("unscented_transform/Sig non-symmetric", lambda: kf.unscented_transform(MU2, NONSYM, lin, 1.0), "Sig"),
    ("unscented_transform/f returns a matrix", lambda: kf.unscented_transform(MU2, I2, lambda x: np.eye(2), 1.0), "f"),
    ("unscented_1d/var negative", lambda: kf.unscented_1d(2.0, -1.0, lin), "var"),
    ("unscented_1d/lam with 1+lam=0", lambda: kf.unscented_1d(2.0, 1.0, lin, lam=-1.0), "lam"),
    ("unscented_1d/f not callable", lambda: kf.unscented_1d(2.0, 1.0, 4.0), "f"),
    ("unscented_1d/f returns a vector", lambda: kf.unscented_1d(2.0, 1.0, lambda x: [x, x]), "f"),
    ("unscented_1d/mu NaN", lambda: kf.unscented_1d(NAN, 1.0, lin), "mu"),
    ("ukf_predict/g not callable", lambda: kf.ukf_predict(MU2, I2, None, "g", 0.01 * I2, 1.0), "g"),
    ("ukf_predict/g wrong shape", lambda: kf.ukf_predict(MU2, I2, None, lambda x, u: x[:1], 0.01 * I2, 1.0), "g"),
    ("ukf_predict/lam with n+lam=0", lambda: kf.ukf_predict(MU2, I2, None, g_ok, 0.01 * I2, -2.0), "lam"),
    ("ukf_predict/R indefinite", lambda: kf.ukf_predict(MU2, I2, None, g_ok, INDEFINITE, 1.0), "R"),
    ("ukf_predict/Sig non-symmetric", lambda: kf.ukf_predict(MU2, NONSYM, None, g_ok, I2, 1.0), "Sig"),
    ("ukf_update/h not callable", lambda: kf.ukf_update(MU2, I2, [1.2], 1.0, Q11, 1.0), "h"),
    ("ukf_update/h wrong shape", lambda: kf.ukf_update(MU2, I2, [1.2], lin, Q11, 1.0), "h"),
    ("ukf_update/lam with n+lam<0", lambda: kf.ukf_update(MU2, I2, [1.2], lambda x: x[:1], Q11, -2.5), "lam"),
    ("ukf_update/Q negative", lambda: kf.ukf_update(MU2, I2, [1.2], lambda x: x[:1], [[-0.5]], 1.0), "Q"),
    (
        "ukf_update/Sig_bar non-symmetric",
        lambda: kf.ukf_update(MU2, NONSYM, [1.2], lambda x: x[:1], Q11, 1.0),
        "Sig_bar",
    ),
    ("ukf_update/Sig_bar wrong shape", lambda: kf.ukf_update(MU2, I3, [1.2], lambda x: x[:1], Q11, 1.0), "Sig_bar"),
    ("ukf_update/z inf", lambda: kf.ukf_update(MU2, I2, [INF], lambda x: x[:1], Q11, 1.0), "z"),
    ("ukf_update/z wrong length", lambda: kf.ukf_update(MU2, I2, [1.2, 0.3], lambda X: X[:, :1], Q11, 1.0), "z"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.sigma_points(MU2, I2, 1.0)
    kf.unscented_transform(MU2, I2, lin, 1.0)
    kf.unscented_1d(2.0, 1.0, lin)
    kf.ukf_predict(MU2, I2, None, g_ok, 0.01 * I2, 1.0)
    kf.ukf_update(MU2, I2, [1.2], lambda chi: chi[:, :1], Q11, 1.0)


@pytest.mark.parametrize(
    "call",
    [
        lambda: kf.ukf_update(np.zeros(3), np.eye(3), [5.0, 0.9], h_rb, np.eye(2), 0.0, residual="wrap"),
        lambda: kf.ukf_predict(np.zeros(3), np.eye(3), None, lambda x, u: x, np.eye(3), 0.0, mean=1),
    ],
    ids=["ukf_update", "ukf_predict-mean"],
)
def test_hook_that_is_not_callable(call):
    with pytest.raises(ValueError, match=r"\b(residual|mean) must be callable"):
        call()


def test_a_model_with_the_wrong_shape_is_named():
    with pytest.raises(ValueError, match="the result of g"):
        kf.ukf_predict(np.zeros(3), np.eye(3), None, lambda x, u: x[:, :2], np.eye(3), 0.0)
    with pytest.raises(ValueError, match="the result of h"):
        kf.ukf_update(np.zeros(3), np.eye(3), [1.0], lambda x: x[0, :1], [[1.0]], 0.0)  # one point's, not all 7


def test_a_mean_hook_that_is_not_callable_is_named():
    with pytest.raises(ValueError, match=r"^mean must be callable"):
        kf.ukf_update(np.zeros(2), np.eye(2), [1.0], lambda chi: chi[:, :1], [[1.0]], 1.0, mean="circular")


@pytest.mark.parametrize("lam", [0.0, 1.0])
def test_the_predicted_covariance_is_exactly_symmetric(lam):
    rng = np.random.default_rng(5)
    A = rng.normal(size=(3, 3))
    g = lambda chi, u: kf.unicycle(chi, u, 0.5)  # noqa: E731
    _, Sig_bar = kf.ukf_predict(rng.normal(size=3), A @ A.T + np.eye(3), [0.7, 0.4], g, 0.01 * np.eye(3), lam)
    assert np.array_equal(Sig_bar, Sig_bar.T)
