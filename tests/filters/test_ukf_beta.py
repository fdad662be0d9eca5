"""``beta`` (the extra weight on the centre sigma point's covariance term) reaches
``sigma_points`` and the UKF functions and changes the covariances by exactly the
hand-computed amount; a bad ``beta`` is named.

The worked example: x ~ N(2, 1), n = 1, lam = 0, so the sigma points are 2, 3, 1
with mean weights 0, 1/2, 1/2 and covariance weights beta, 1/2, 1/2.  Through
x -> x² they land on 4, 9, 1: mean 5, deviations -1, 4, -4, so the covariance is
beta * 1 + 16.
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse.models import pose_mean, pose_residual, range_bearing_mean, range_bearing_residual
from tests.filters.strategies import FAST, reals, spd, square

MU, SIG, LAM = np.array([2.0]), np.array([[1.0]]), 0.0
R = np.array([[0.5]])  # process noise of the 1-D example
Q = np.array([[1.0]])  # measurement noise of the 1-D example


def square_motion(x, u):
    return x**2


# ================================================================ worked numbers
# none from the lesson: chapter 9 uses beta = 0 (test_ukf.py); the example above is worked below


# ================================================================ closed forms
@pytest.mark.parametrize("beta", [0.0, 0.5, 2.0])
def test_unscented_transform_covariance_grows_by_beta(beta):
    mu_y, Sig_y = kf.unscented_transform(MU, SIG, square, LAM, beta=beta)
    assert mu_y == pytest.approx([5.0], abs=1e-12)  # the mean weights do not depend on beta
    assert Sig_y == pytest.approx(np.array([[16.0 + beta]]), abs=1e-12)


@pytest.mark.parametrize("beta", [0.0, 0.5, 2.0])
def test_ukf_predict_covariance_grows_by_beta(beta):
    mu_bar, Sig_bar = kf.ukf_predict(MU, SIG, None, square_motion, R, LAM, beta=beta)
    assert mu_bar == pytest.approx([5.0], abs=1e-12)
    assert Sig_bar == pytest.approx(np.array([[16.0 + beta + 0.5]]), abs=1e-12)  # + R


@pytest.mark.parametrize("beta", [0.0, 0.5, 2.0])
def test_ukf_update_by_hand(beta):
    """Predicted readings 4, 9, 1 give z_hat = 5 and S = beta + 16 + Q = 17 + beta;
    the state deviations 0, 1, -1 give Sig_xz = (1 * 4 + (-1) * (-4)) / 2 = 4 (the
    centre point's state deviation is 0, so beta does not enter Sig_xz); then
    K = 4 / (17 + beta), mu = 2 + K (6 - 5) and Sig = 1 - K S K = 1 - 16 / (17 + beta)."""
    mu, Sig = kf.ukf_update(MU, SIG, [6.0], square, Q, LAM, beta=beta)
    K = 4.0 / (17.0 + beta)
    assert mu == pytest.approx([2.0 + K], abs=1e-12)
    assert Sig == pytest.approx(np.array([[1.0 - 16.0 / (17.0 + beta)]]), abs=1e-12)


def test_beta_is_zero_by_default():
    assert kf.unscented_transform(MU, SIG, square, LAM)[1] == pytest.approx(np.array([[16.0]]), abs=1e-12)
    assert kf.ukf_predict(MU, SIG, None, square_motion, R, LAM)[1] == pytest.approx(np.array([[16.5]]), abs=1e-12)
    assert kf.ukf_update(MU, SIG, [6.0], square, Q, LAM)[1] == pytest.approx(np.array([[1.0 / 17.0]]), abs=1e-12)


def test_sigma_points_beta_closed_form():
    # n = 1, lam = 2: w_0 = 2/3, w_i = 1/6; beta = 2 adds to the covariance weight only: wc_0 = 8/3
    chi, wm, wc = kf.sigma_points([1.0], [[3.0]], 2.0, beta=2.0)
    np.testing.assert_allclose(chi[:, 0], [1.0, 4.0, -2.0], rtol=1e-14)  # 1 +- sqrt(3 * 3)
    np.testing.assert_allclose(wm, [2 / 3, 1 / 6, 1 / 6], rtol=1e-14)
    np.testing.assert_allclose(wc, [8 / 3, 1 / 6, 1 / 6], rtol=1e-14)


def test_sigma_points_beta_changes_the_variance_of_x_squared_by_beta_sigma4():
    # y = x^2 for x ~ N(mu, s2) through the 3 sigma points (hand algebra, see the unscented_1d tests):
    #   mean mu^2 + s2, variance 4 mu^2 s2 + (lam + beta) s2^2.   mu = 1, s2 = 0.5, lam = 2, beta = 2:
    #   4 * 0.5 + 4 * 0.25 = 3
    chi, wm, wc = kf.sigma_points([1.0], [[0.5]], 2.0, beta=2.0)
    y = chi[:, 0] ** 2
    y_mean = wm @ y
    assert y_mean == pytest.approx(1.5, rel=1e-14)
    assert wc @ (y - y_mean) ** 2 == pytest.approx(3.0, rel=1e-12)


# ================================================================ properties
@FAST
@given(
    mu=st.tuples(reals(-5, 5), reals(-5, 5), reals(-5, 5)).map(np.array),
    Sig=spd(3),
    lam=st.sampled_from([0.0, 1.0, -1.0, 0.5]),
    beta=reals(-1, 4),
)
def test_sigma_points_beta_only_moves_the_centre_covariance_weight(mu, Sig, lam, beta):
    chi0, wm0, _ = kf.sigma_points(mu, Sig, lam)
    chi, wm, wc = kf.sigma_points(mu, Sig, lam, beta=beta)
    np.testing.assert_array_equal(chi, chi0)
    np.testing.assert_array_equal(wm, wm0)
    np.testing.assert_allclose(wc - wm, np.eye(7)[0] * beta, atol=1e-14)
    assert wc[0] == pytest.approx(lam / (3 + lam) + beta, abs=1e-14)


def test_beta_adds_the_centre_outer_product_in_several_dimensions():
    """In n dimensions beta adds beta * d0 d0^T to the predicted covariance, where d0
    is the centre point's deviation g(mu, u) - mu_bar, with the hooks."""
    mu, Sig = np.array([1.0, 2.0, 0.3]), np.diag([0.3, 0.2, 0.4])
    R3, u, lam, beta = np.diag([0.01, 0.01, 0.02]), np.array([0.8, 1.5]), 1.0, 2.0

    def g(x, u):
        return kf.unicycle(x, u, 0.5)

    hooks = {"residual": pose_residual, "mean": pose_mean}
    mb0, Sb0 = kf.ukf_predict(mu, Sig, u, g, R3, lam, **hooks)
    mb2, Sb2 = kf.ukf_predict(mu, Sig, u, g, R3, lam, **hooks, beta=beta)
    d0 = pose_residual(g(mu, u), mb0)
    assert mb2 == pytest.approx(mb0, abs=1e-12)
    assert Sb2 - Sb0 == pytest.approx(beta * np.outer(d0, d0), abs=1e-12)
    assert np.abs(d0).max() > 1e-3  # the nonlinear model moves the centre: the change is not zero


def test_beta_changes_the_update_as_a_larger_innovation_covariance():
    """The update with beta equals the Kalman correction with S + beta dz0 dz0^T,
    dz0 the centre point's predicted-reading deviation."""
    mu_bar, Sig_bar = np.array([1.0, 2.0, 0.3]), np.diag([0.3, 0.2, 0.4])
    Q2, z, lam, beta = np.diag([0.04, 0.01]), np.array([5.2, 0.9]), 1.0, 2.0
    landmark = np.array([4.0, 6.0])

    def h(x):
        return kf.range_bearing(x, landmark)

    n = mu_bar.size
    chi, wm, wc = kf.sigma_points(mu_bar, Sig_bar, lam)
    Z = np.array([h(x) for x in chi])
    z_hat = range_bearing_mean(Z, wm)
    dZ = range_bearing_residual(Z, z_hat)
    dX = pose_residual(chi, mu_bar)
    S = (wc[:, None] * dZ).T @ dZ + Q2 + beta * np.outer(dZ[0], dZ[0])
    Sxz = (wc[:, None] * dX).T @ dZ  # dX[0] = 0: beta does not enter
    K = Sxz @ np.linalg.inv(S)
    want_mu = mu_bar + K @ range_bearing_residual(z, z_hat)
    want_Sig = Sig_bar - K @ S @ K.T
    mu, Sig = kf.ukf_update(
        mu_bar, Sig_bar, z, h, Q2, lam, range_bearing_residual, range_bearing_mean, pose_residual, beta=beta
    )
    assert dX[0] == pytest.approx(np.zeros(n), abs=0)
    assert mu == pytest.approx(want_mu, abs=1e-12)
    assert Sig == pytest.approx(want_Sig, abs=1e-12)
    assert not np.allclose(
        Sig, kf.ukf_update(mu_bar, Sig_bar, z, h, Q2, lam, range_bearing_residual, range_bearing_mean, pose_residual)[1]
    )


def test_beta_is_an_optional_keyword():
    for fn in (kf.unscented_transform, kf.ukf_predict, kf.ukf_update):
        p = inspect.signature(fn).parameters["beta"]
        assert p.default == 0.0 and p.kind is p.KEYWORD_ONLY, fn.__name__


# ================================================================ bad input
@pytest.mark.parametrize("bad", [float("nan"), float("inf"), "two", [1.0, 2.0]])
def test_bad_beta_is_named(bad):
    with pytest.raises(ValueError, match=r"^beta\b"):
        kf.ukf_predict(MU, SIG, None, square_motion, R, LAM, beta=bad)
    with pytest.raises(ValueError, match=r"^beta\b"):
        kf.ukf_update(MU, SIG, [6.0], square, Q, LAM, beta=bad)
    with pytest.raises(ValueError, match=r"^beta\b"):
        kf.unscented_transform(MU, SIG, square, LAM, beta=bad)
