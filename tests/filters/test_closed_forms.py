"""One exact closed-form check and one property check for every public function of
``kfcourse.filters`` and ``kfcourse.models`` that the worked-number and property files
leave thin: densities, ellipse geometry, the steady-state gain with a, c != 1, the
sigma-point weights with beta, bearings and headings across the +-pi seam, and the
association gate at its edge.

Every closed-form number is derived by hand in the comment next to it.
Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse.models import (
    constant_velocity,
    pose_mean,
    pose_residual,
    range_bearing_mean,
    range_bearing_residual,
)

FAST = settings(max_examples=60, deadline=None)
TWO_PI = 2.0 * math.pi


def reals(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


@st.composite
def spd(draw, n: int) -> np.ndarray:
    """A well-conditioned symmetric positive definite (n, n) matrix."""
    A = np.array(draw(st.lists(reals(-2, 2), min_size=n * n, max_size=n * n))).reshape(n, n)
    return A @ A.T + draw(reals(0.05, 2.0)) * np.eye(n)


def angle_gap(a, b) -> float:
    """Distance between two angles on the circle, computed without kfcourse."""
    return abs(math.remainder(float(a) - float(b), TWO_PI))


# ================================================================ gaussian_pdf
def test_gaussian_pdf_closed_form_with_variance_not_one():
    # N(0; 0, 4) = 1 / sqrt(2 pi 4) = 1 / (2 sqrt(2 pi)); one sigma (x = 2) out it drops by e^-1/2
    assert kf.gaussian_pdf(0.0, 0.0, 4.0) == pytest.approx(1.0 / (2.0 * math.sqrt(TWO_PI)), rel=1e-14)
    assert kf.gaussian_pdf(2.0, 0.0, 4.0) == pytest.approx(math.exp(-0.5) / (2.0 * math.sqrt(TWO_PI)), rel=1e-14)
    # var = 0.25 (sigma = 0.5): peak 1 / sqrt(2 pi / 4) = 2 / sqrt(2 pi); at x = mu + 1 = two sigma: e^-2
    assert kf.gaussian_pdf(4.0, 3.0, 0.25) == pytest.approx(2.0 * math.exp(-2.0) / math.sqrt(TWO_PI), rel=1e-14)


@FAST
@given(mu=reals(-5, 5), var=reals(0.05, 20.0))
@example(mu=0.0, var=4.0)
def test_gaussian_pdf_integrates_to_one_with_the_given_variance(mu, var):
    sd = math.sqrt(var)
    x = np.linspace(mu - 12 * sd, mu + 12 * sd, 20001)
    p = kf.gaussian_pdf(x, mu, var)
    dx = x[1] - x[0]
    assert np.sum(p) * dx == pytest.approx(1.0, rel=1e-9)  # mass 1
    assert np.sum(x * p) * dx == pytest.approx(mu, abs=1e-9 * (1 + abs(mu)))  # mean mu
    assert np.sum((x - mu) ** 2 * p) * dx == pytest.approx(var, rel=1e-9)  # second moment = var


# ================================================================ mvn_pdf
def test_mvn_pdf_closed_form():
    # N(mu; mu, I_2) = det(2 pi I)^-1/2 = 1 / (2 pi)
    assert kf.mvn_pdf([1.0, -2.0], [1.0, -2.0], np.eye(2)) == pytest.approx(1.0 / TWO_PI, rel=1e-14)
    # Sig = diag(4, 1): det(2 pi Sig) = 4 (2 pi)^2, so the peak is 1 / (4 pi); at x = (2, 0) d^2 = 1
    Sig = np.diag([4.0, 1.0])
    assert kf.mvn_pdf([0.0, 0.0], [0.0, 0.0], Sig) == pytest.approx(1.0 / (4.0 * math.pi), rel=1e-14)
    assert kf.mvn_pdf([2.0, 0.0], [0.0, 0.0], Sig) == pytest.approx(math.exp(-0.5) / (4.0 * math.pi), rel=1e-14)
    # 3-D identity: (2 pi)^-3/2
    assert kf.mvn_pdf(np.zeros(3), np.zeros(3), np.eye(3)) == pytest.approx(TWO_PI**-1.5, rel=1e-14)


@FAST
@given(mu=st.tuples(reals(-3, 3), reals(-3, 3)), Sig=spd(2))
def test_mvn_pdf_integrates_to_one_on_a_grid(mu, Sig):
    # Riemann sum over +-9 sigma of each axis: the mass of a density is 1 whatever Sig is
    sd = np.sqrt(np.diag(Sig))
    gx = np.linspace(mu[0] - 9 * sd[0], mu[0] + 9 * sd[0], 201)
    gy = np.linspace(mu[1] - 9 * sd[1], mu[1] + 9 * sd[1], 201)
    X, Y = np.meshgrid(gx, gy, indexing="ij")
    p = kf.mvn_pdf(np.stack([X, Y], axis=-1), np.array(mu), Sig)
    assert p.shape == X.shape
    assert p.sum() * (gx[1] - gx[0]) * (gy[1] - gy[0]) == pytest.approx(1.0, rel=1e-6)


# ================================================================ ellipse_axes
def test_ellipse_axes_closed_form():
    # Sig = diag(4, 1): semi-axes k sqrt(4) = 2k and k sqrt(1) = k; full lengths 4k and 2k, major along x
    w, h, ang = kf.ellipse_axes(np.diag([4.0, 1.0]), nsig=1.0)
    assert (w, h) == pytest.approx((4.0, 2.0), rel=1e-14)
    assert ang == pytest.approx(0.0, abs=1e-12)
    w, h, ang = kf.ellipse_axes(np.diag([9.0, 1.0]), nsig=2.0)  # 2 * 2 * 3 = 12, 2 * 2 * 1 = 4
    assert (w, h) == pytest.approx((12.0, 4.0), rel=1e-14)
    # major along y: tilt 90 degrees, reported as -90 in [-90, 90)
    w, h, ang = kf.ellipse_axes(np.diag([1.0, 16.0]), nsig=1.0)
    assert (w, h, ang) == pytest.approx((8.0, 2.0, -90.0), abs=1e-12)
    # [[5, 3], [3, 5]] has eigenvalues 8 (along (1, 1), 45 degrees) and 2
    w, h, ang = kf.ellipse_axes([[5.0, 3.0], [3.0, 5.0]], nsig=1.0)
    assert (w, h, ang) == pytest.approx((2 * math.sqrt(8.0), 2 * math.sqrt(2.0), 45.0), rel=1e-12)


@FAST
@given(Sig=spd(2), k=reals(0.2, 4.0))
def test_ellipse_axes_ends_lie_on_the_k_sigma_contour(Sig, k):
    w, h, ang = kf.ellipse_axes(Sig, nsig=k)
    assert w >= h > 0 and -90.0 <= ang < 90.0
    t = math.radians(ang)
    major = 0.5 * w * np.array([math.cos(t), math.sin(t)])
    minor = 0.5 * h * np.array([-math.sin(t), math.cos(t)])
    Sinv = np.linalg.inv(Sig)
    # both axis ends sit at Mahalanobis distance exactly k, and the area is pi k^2 sqrt(det Sig)
    assert major @ Sinv @ major == pytest.approx(k * k, rel=1e-8)
    assert minor @ Sinv @ minor == pytest.approx(k * k, rel=1e-8)
    assert math.pi * w * h / 4 == pytest.approx(math.pi * k * k * math.sqrt(np.linalg.det(Sig)), rel=1e-8)


# ================================================================ mass_inside
@FAST
@given(k=reals(0.0, 6.0))
def test_mass_inside_is_the_chi_square_cdf(k):
    # 2-D: P(d <= k) = 1 - exp(-k^2/2) is the chi2(2) cdf at k^2; 1-D: P(|x| <= k) = erf(k / sqrt 2)
    assert kf.mass_inside(k, dim=2) == pytest.approx(-math.expm1(-0.5 * k * k), rel=1e-12, abs=1e-15)
    assert kf.mass_inside(k, dim=1) == pytest.approx(math.erf(k / math.sqrt(2.0)), rel=1e-12, abs=1e-15)
    assert kf.mass_inside(k, dim=1) >= kf.mass_inside(k, dim=2)  # a 2-D contour holds less


def test_mass_inside_closed_form_two_sigma():
    # 1 - e^-2 = 0.8646647..., and the 1-D 95.45 %
    assert kf.mass_inside(2.0) == pytest.approx(1.0 - math.exp(-2.0), rel=1e-14)
    assert kf.mass_inside(2.0, dim=1) == pytest.approx(0.9544997361036416, rel=1e-12)


# ================================================================ affine / add / fuse
@FAST
@given(
    mu=st.tuples(reals(-5, 5), reals(-5, 5)).map(np.array),
    Sig=spd(2),
    A1=st.lists(reals(-2, 2), min_size=4, max_size=4).map(lambda a: np.array(a).reshape(2, 2)),
    A2=st.lists(reals(-2, 2), min_size=4, max_size=4).map(lambda a: np.array(a).reshape(2, 2)),
    b1=st.tuples(reals(-5, 5), reals(-5, 5)).map(np.array),
)
def test_affine_gaussian_composes(mu, Sig, A1, A2, b1):
    # A2 (A1 x + b1) is the single affine map A2 A1 x + A2 b1
    m1, S1 = kf.affine_gaussian(mu, Sig, A1, b1)
    m2, S2 = kf.affine_gaussian(m1, S1, A2)
    m, S = kf.affine_gaussian(mu, Sig, A2 @ A1, A2 @ b1)
    np.testing.assert_allclose(m2, m, rtol=1e-10, atol=1e-10 * (1 + np.abs(m).max()))
    np.testing.assert_allclose(S2, S, rtol=1e-10, atol=1e-10 * (1 + np.abs(S).max()))


def test_add_gaussians_matrix_closed_form():
    m, S = kf.add_gaussians([1.0, 2.0], [[1.0, 0.5], [0.5, 2.0]], [-1.0, 0.5], [[0.5, 0.0], [0.0, 0.25]])
    np.testing.assert_allclose(m, [0.0, 2.5], atol=1e-15)
    np.testing.assert_allclose(S, [[1.5, 0.5], [0.5, 2.25]], atol=1e-15)


@FAST
@given(mu1=reals(-5, 5), mu2=reals(-5, 5), S1=spd(2), S2=spd(2))
def test_add_gaussians_is_the_affine_map_of_the_stacked_pair(mu1, mu2, S1, S2):
    # X1 + X2 = [I I] [X1; X2] with [X1; X2] ~ N([m1; m2], blockdiag(S1, S2))
    m1, m2 = np.array([mu1, -mu2]), np.array([mu2, mu1])
    big = np.block([[S1, np.zeros((2, 2))], [np.zeros((2, 2)), S2]])
    m_aff, S_aff = kf.affine_gaussian(np.concatenate([m1, m2]), big, np.hstack([np.eye(2), np.eye(2)]))
    m, S = kf.add_gaussians(m1, S1, m2, S2)
    np.testing.assert_allclose(m, m_aff, atol=1e-12)
    np.testing.assert_allclose(S, S_aff, rtol=1e-12, atol=1e-12)


@FAST
@given(mu1=reals(-10, 10), var1=reals(1e-3, 10), mu2=reals(-10, 10), var2=reals(1e-3, 10))
def test_fuse_is_symmetric_and_lies_between_the_inputs(mu1, var1, mu2, var2):
    mu, var = kf.fuse(mu1, var1, mu2, var2)
    mu_sw, var_sw = kf.fuse(mu2, var2, mu1, var1)  # the product of densities commutes
    assert (mu, var) == pytest.approx((mu_sw, var_sw), rel=1e-10, abs=1e-10)
    assert min(mu1, mu2) - 1e-9 <= mu <= max(mu1, mu2) + 1e-9
    assert var == pytest.approx(var1 * var2 / (var1 + var2), rel=1e-12)  # 1 / (1/v1 + 1/v2)


# ================================================================ steady_state_1d
# Hand-built fixed points of P = a^2 P Q / (c^2 P + Q) + R (the prior variance):
#  a = 0.5, c = 1, Q = 4, P = 4: a^2 * 16 / 8 = 0.5, so R = 3.5; K = 4 / 8 = 0.5; post (1 - 0.5) 4 = 2
#  a = 1,   c = 2, Q = 4, P = 1: 1 * 4 / 8 = 0.5, so R = 0.5; K = 2 / 8 = 0.25; post (1 - 0.5) 1 = 0.5
#  a = -0.5, c = 2, Q = 8, P = 2: 0.25 * 16 / 16 = 0.25, so R = 1.75; K = 4 / 16 = 0.25; post 0.5 * 2 = 1
@pytest.mark.parametrize(
    ("R", "Q", "a", "c", "expected"),
    [
        (3.5, 4.0, 0.5, 1.0, (0.5, 4.0, 2.0)),
        (0.5, 4.0, 1.0, 2.0, (0.25, 1.0, 0.5)),
        (1.75, 8.0, -0.5, 2.0, (0.25, 2.0, 1.0)),
    ],
)
def test_steady_state_1d_closed_form_with_a_and_c(R, Q, a, c, expected):
    assert kf.steady_state_1d(R, Q, a=a, c=c) == pytest.approx(expected, rel=1e-12)


def test_steady_state_1d_without_a_measurement():
    # c = 0, |a| < 1: P = a^2 P + R, so P = R / (1 - a^2) = 0.75 / 0.75 = 1, and K = 0
    assert kf.steady_state_1d(0.75, 1.0, a=0.5, c=0.0) == pytest.approx((0.0, 1.0, 1.0), abs=1e-14)


@settings(max_examples=100, deadline=None)
@given(R=reals(1e-3, 10), Q=reals(1e-3, 10), a=reals(-1.5, 1.5), c=st.one_of(reals(-3, -0.1), reals(0.1, 3)))
def test_steady_state_1d_is_the_fixed_point_of_the_riccati_map(R, Q, a, c):
    K, P, P_post = kf.steady_state_1d(R, Q, a=a, c=c)
    # written out here, not through kfcourse: one predict and one update from P_post
    P_bar = a * a * P_post + R
    K_next = c * P_bar / (c * c * P_bar + Q)
    assert P_bar == pytest.approx(P, rel=1e-9)
    assert K_next == pytest.approx(K, rel=1e-9)
    assert (1 - K * c) * P == pytest.approx(P_post, rel=1e-9)
    # ... and kf_1d_cycle agrees with that fixed point
    cyc = kf.kf_1d_cycle(0.0, P_post, 0.0, 0.0, a=a, b=1.0, c=c, R=R, Q=Q)
    assert (cyc.var_bar, cyc.K, cyc.var) == pytest.approx((P, K, P_post), rel=1e-9)


# ================================================================ kf_1d_cycle / kf_gain
@FAST
@given(
    mu=reals(-10, 10),
    var=reals(0, 5),
    u=reals(-2, 2),
    z=reals(-10, 10),
    a=reals(-2, 2),
    b=reals(-2, 2),
    c=reals(-2, 2),
    R=reals(0, 2),
    Q=reals(0.01, 2),
)
def test_kf_1d_cycle_fields_follow_the_lesson_equations(mu, var, u, z, a, b, c, R, Q):
    cyc = kf.kf_1d_cycle(mu, var, u, z, a=a, b=b, c=c, R=R, Q=Q)
    assert cyc.mu_bar == pytest.approx(a * mu + b * u, abs=1e-12)
    assert cyc.var_bar == pytest.approx(a * a * var + R, rel=1e-12, abs=1e-15)
    assert cyc.innovation == pytest.approx(z - c * cyc.mu_bar, abs=1e-11)
    assert cyc.K == pytest.approx(c * cyc.var_bar / (c * c * cyc.var_bar + Q), rel=1e-12, abs=1e-15)
    assert cyc.mu == pytest.approx(cyc.mu_bar + cyc.K * cyc.innovation, abs=1e-11)
    assert cyc.var == pytest.approx(cyc.var_bar * Q / (c * c * cyc.var_bar + Q), rel=1e-9, abs=1e-15)
    assert kf.kf_1d_step(mu, var, u, z, a=a, b=b, c=c, R=R, Q=Q) == (cyc.mu, cyc.var)


def test_kf_gain_closed_form_2x2():
    # Sig_bar = diag(2, 1), H = I, Q = diag(2, 3): S = diag(4, 4), K = diag(2/4, 1/4)
    S, K = kf.kf_gain(np.diag([2.0, 1.0]), np.eye(2), np.diag([2.0, 3.0]))
    np.testing.assert_allclose(S, np.diag([4.0, 4.0]), atol=1e-15)
    np.testing.assert_allclose(K, np.diag([0.5, 0.25]), atol=1e-15)


@FAST
@given(data=st.data(), n=st.integers(1, 4), k=st.integers(1, 3))
def test_kf_gain_solves_K_S_equals_Sig_bar_H_T(data, n, k):
    Sig_bar, Q = data.draw(spd(n)), data.draw(spd(k))
    H = np.array(data.draw(st.lists(reals(-2, 2), min_size=k * n, max_size=k * n))).reshape(k, n)
    S, K = kf.kf_gain(Sig_bar, H, Q)
    np.testing.assert_allclose(S, H @ Sig_bar @ H.T + Q, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(K @ S, Sig_bar @ H.T, rtol=1e-9, atol=1e-9 * (1 + np.abs(Sig_bar).max()))


# ================================================================ mahalanobis
@FAST
@given(nu=st.tuples(reals(-5, 5), reals(-5, 5)).map(np.array), S=spd(2), scale=reals(0.1, 10))
def test_mahalanobis_is_the_whitened_length(nu, S, scale):
    L = np.linalg.cholesky(S)
    d = kf.mahalanobis(nu, S)
    assert d == pytest.approx(np.linalg.norm(np.linalg.solve(L, nu)), rel=1e-9, abs=1e-12)
    # a distance, not a squared one: scaling nu scales d linearly
    assert kf.mahalanobis(scale * nu, S) == pytest.approx(scale * d, rel=1e-9, abs=1e-12)


# ================================================================ associate
def _linear_h(x, m):
    return x[:2] - m  # a sensor that reads the offset of the robot from a landmark


def _linear_H(x, m):
    return np.eye(2)


LIN_MAP = np.array([[0.0, 0.0], [100.0, 0.0]])


def test_associate_closed_form_distance_and_gate():
    # Sig_bar = Q = 0.5 I, H = I: S = I, so d is the plain Euclidean length of the innovation.
    # Reading (1.2, 1.6) at the robot (0, 0) against landmark 0: nu = (1.2, 1.6), d = 2 (and d^2 = 4).
    z = np.array([1.2, 1.6])
    for gate, expected in [(2.5, 0), (2.0 + 1e-9, 0), (1.999, None), (1.5, None), (3.9, 0)]:
        idx, dist = kf.associate(z, [0.0, 0.0], 0.5 * np.eye(2), LIN_MAP, _linear_h, _linear_H, 0.5 * np.eye(2), gate)
        assert dist[0] == pytest.approx(2.0, rel=1e-14)
        assert dist[1] == pytest.approx(math.hypot(101.2, 1.6), rel=1e-14)
        assert idx == expected, gate


# ================================================================ sigma points and beta
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


# ================================================================ unscented transform, 1-D and matrix
def test_unscented_1d_closed_form_with_variance_not_one():
    # x ~ N(3, 0.25) through x^2 with lam = 2: mean mu^2 + s2 = 9.25; var 4 mu^2 s2 + lam s2^2 = 9 + 0.125
    assert kf.unscented_1d(3.0, 0.25, lambda x: x * x, lam=2.0) == pytest.approx((9.25, 9.125), rel=1e-12)
    # the same through the matrix transform
    m, S = kf.unscented_transform([3.0], [[0.25]], lambda x: x**2, 2.0)
    assert (m[0], S[0, 0]) == pytest.approx((9.25, 9.125), rel=1e-12)


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


def test_ukf_predict_closed_form_x_squared_with_process_noise():
    # x ~ N(2, 0.5), g(x) = x^2, lam = 2, R = 0.1: mean 4 + 0.5 = 4.5; var 4*4*0.5 + 2*0.25 + 0.1 = 8.6
    m, S = kf.ukf_predict([2.0], [[0.5]], None, lambda x, u: x**2, [[0.1]], 2.0)
    assert (m[0], S[0, 0]) == pytest.approx((4.5, 8.6), rel=1e-12)


def test_ekf_predict_closed_form_x_squared_with_variance_not_one():
    # x ~ N(3, 0.5), g(x) = x^2, G = 2x = 6 at the mean: mean 9, var 6 * 0.5 * 6 + R = 18 + 0.25
    m, S = kf.ekf_predict([3.0], [[0.5]], None, lambda x, u: x**2, lambda x, u: np.array([[2 * x[0]]]), [[0.25]])
    assert (m[0], S[0, 0]) == pytest.approx((9.0, 18.25), rel=1e-14)


def test_ukf_update_closed_form_scalar():
    # h(x) = 2x on x ~ N(1, 1), Q = 4, z = 4: S = 4 + 4 = 8, Sig_xz = 2, K = 1/4,
    # mu = 1 + (4 - 2) / 4 = 1.5, Sig = 1 - K S K = 1 - 0.5 = 0.5
    m, S = kf.ukf_update([1.0], [[1.0]], [4.0], lambda x: 2 * x, [[4.0]], 0.0)
    assert (m[0], S[0, 0]) == pytest.approx((1.5, 0.5), rel=1e-12)


# ================================================================ bearings across the seam
LM_BEHIND = np.array([-5.0, 0.1])  # straight behind a robot at the origin facing +x: bearing pi - 0.02
POSE0 = np.array([0.0, 0.0, 0.0])
SIG_BAR = np.diag([0.2, 0.2, 0.05])
Q_SEAM = np.diag([0.04, 0.01])
h_behind = partial(kf.range_bearing, landmark=LM_BEHIND)
H_behind = partial(kf.range_bearing_jacobian, landmark=LM_BEHIND)


def _textbook_ekf_update(mu_bar, Sig_bar, y, H, Q):
    """The lesson's update with a given (already wrapped) innovation, in plain numpy."""
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ y, (np.eye(mu_bar.size) - K @ H) @ Sig_bar


def test_range_bearing_closed_form_wraps_the_bearing():
    # heading -3 rad, landmark straight along -x: atan2(0, -1) - (-3) = pi + 3 -> wrapped 3 - pi
    r, phi = kf.range_bearing([0.0, 0.0, -3.0], [-2.0, 0.0])
    assert r == pytest.approx(2.0, rel=1e-15)
    assert phi == pytest.approx(3.0 - math.pi, abs=1e-15)
    # heading +3, landmark along +x: 0 - 3 = -3 stays
    assert kf.range_bearing([0.0, 0.0, 3.0], [1.0, 0.0])[1] == pytest.approx(-3.0, abs=1e-15)
    # heading 2 pi + 0.5 (one whole turn more) reads as if the heading were 0.5
    assert kf.range_bearing([0.0, 0.0, TWO_PI + 0.5], [1.0, 1.0])[1] == pytest.approx(math.pi / 4 - 0.5, abs=1e-14)


@FAST
@given(
    pose=st.tuples(reals(-20, 20), reals(-20, 20), reals(-20, 20)).map(np.array),
    lm=st.tuples(reals(-20, 20), reals(-20, 20)).map(np.array),
)
def test_range_bearing_is_distance_and_bearing_in_range(pose, lm):
    dx, dy = lm - pose[:2]
    assume(math.hypot(dx, dy) > 1e-3)
    r, phi = kf.range_bearing(pose, lm)
    assert r == pytest.approx(math.hypot(dx, dy), rel=1e-14)
    assert -math.pi < phi <= math.pi
    assert angle_gap(phi, math.atan2(dy, dx) - pose[2]) < 1e-12
    stacked = kf.range_bearing(np.vstack([pose, pose + np.array([0.0, 0.0, TWO_PI])]), lm)  # (N, 3) in, (N, 2) out
    assert stacked.shape == (2, 2)
    assert np.all((stacked[:, 1] > -math.pi) & (stacked[:, 1] <= math.pi))
    assert stacked[0, 1] == pytest.approx(phi, abs=1e-12)


def test_ekf_update_wraps_a_bearing_innovation_across_pi():
    z_hat = kf.range_bearing(POSE0, LM_BEHIND)
    assert z_hat[1] > math.pi - 0.03  # predicted just below +pi
    z = np.array([z_hat[0] + 0.1, -math.pi + 0.01])  # read just above -pi: 0.03ish further round
    y = np.array([0.1, math.remainder(z[1] - z_hat[1], TWO_PI)])  # the short way round, by hand
    assert abs(y[1]) < 0.05
    mu, Sig = kf.ekf_update(POSE0, SIG_BAR, z, h_behind, H_behind, Q_SEAM, residual=range_bearing_residual)
    mu_ref, Sig_ref = _textbook_ekf_update(POSE0, SIG_BAR, y, kf.range_bearing_jacobian(POSE0, LM_BEHIND), Q_SEAM)
    np.testing.assert_allclose(mu, mu_ref, atol=1e-12)
    np.testing.assert_allclose(Sig, Sig_ref, atol=1e-12)


def test_ukf_update_wraps_a_bearing_innovation_across_pi():
    # with a tiny prior the UKF linearises exactly like the EKF: same wrapped answer
    Sig_bar = 1e-8 * SIG_BAR
    z_hat = kf.range_bearing(POSE0, LM_BEHIND)
    z = np.array([z_hat[0] + 1e-5, -math.pi + 0.01])
    y = np.array([1e-5, math.remainder(z[1] - z_hat[1], TWO_PI)])
    mu_ref, Sig_ref = _textbook_ekf_update(POSE0, Sig_bar, y, kf.range_bearing_jacobian(POSE0, LM_BEHIND), Q_SEAM)
    kw = {"residual": range_bearing_residual, "mean": range_bearing_mean, "x_residual": pose_residual}
    mu, Sig = kf.ukf_update(POSE0, Sig_bar, z, h_behind, Q_SEAM, 1.0, **kw)
    np.testing.assert_allclose(mu, mu_ref, rtol=1e-6, atol=1e-13)
    np.testing.assert_allclose(Sig, Sig_ref, rtol=1e-6, atol=1e-17)


seam_cases = st.tuples(
    reals(2.0, 10.0),  # landmark distance
    reals(-0.05, 0.05),  # landmark direction off straight behind
    reals(-0.05, 0.05),  # reading bearing error
    reals(-math.pi, math.pi),  # robot heading
)


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


# ================================================================ residuals and circular means
def test_residual_closed_forms_wrap_the_angle():
    # (pi - 0.1) - (-pi + 0.1) = 2 pi - 0.2 -> -0.2
    np.testing.assert_allclose(
        pose_residual([1.0, 2.0, math.pi - 0.1], [0.5, 3.0, -math.pi + 0.1]), [0.5, -1.0, -0.2], atol=1e-14
    )
    np.testing.assert_allclose(range_bearing_residual([5.0, -3.0], [4.0, 3.0]), [1.0, TWO_PI - 6.0], atol=1e-14)


@FAST
@given(
    a=st.tuples(reals(-10, 10), reals(-10, 10), reals(-10, 10)).map(np.array),
    b=st.tuples(reals(-10, 10), reals(-10, 10), reals(-10, 10)).map(np.array),
)
def test_pose_and_range_bearing_residuals_are_differences_mod_two_pi(a, b):
    d = pose_residual(a, b)
    np.testing.assert_allclose(d[:2], a[:2] - b[:2], atol=1e-14)
    assert -math.pi < d[2] <= math.pi and angle_gap(d[2], a[2] - b[2]) < 1e-12
    e = range_bearing_residual(a[:2], b[:2])
    assert e[0] == pytest.approx(a[0] - b[0], abs=1e-14)
    assert -math.pi < e[1] <= math.pi and angle_gap(e[1], a[1] - b[1]) < 1e-12


def test_circular_means_closed_form_across_pi():
    # two headings 0.1 either side of pi: the mean heading is pi, not 0 (the linear average)
    pts = np.array([[0.0, 0.0, math.pi - 0.1], [2.0, 4.0, -math.pi + 0.1]])
    m = pose_mean(pts, [0.5, 0.5])
    np.testing.assert_allclose(m[:2], [1.0, 2.0], atol=1e-15)
    assert angle_gap(m[2], math.pi) < 1e-12
    # weights 1/4, 3/4 of headings pi/2 and 0: atan2(1/4, 3/4)
    m = pose_mean(np.array([[0.0, 0.0, math.pi / 2], [4.0, 0.0, 0.0]]), [0.25, 0.75])
    assert m[2] == pytest.approx(math.atan2(0.25, 0.75), abs=1e-15)
    rb = range_bearing_mean(np.array([[4.0, math.pi - 0.2], [6.0, -math.pi + 0.2]]), [0.5, 0.5])
    assert rb[0] == pytest.approx(5.0, abs=1e-15) and angle_gap(rb[1], math.pi) < 1e-12


@FAST
@given(
    centre=reals(-math.pi, math.pi),
    cloud=st.lists(st.tuples(reals(-0.3, 0.3), reals(0.05, 1.0)), min_size=3, max_size=7),
    turn=st.integers(-3, 3),
)
@example(centre=math.pi, cloud=[(-0.3, 1.0), (0.0, 1.0), (0.3, 1.0)], turn=0)
@example(centre=math.pi, cloud=[(-0.3, 0.1), (0.0, 0.1), (0.3, 1.0)], turn=1)
def test_circular_means_follow_a_weighted_cloud_around_the_circle(centre, cloud, turn):
    # a tight cloud of angles around `centre` (written with any number of whole turns) has its weighted
    # mean at centre + the weighted mean offset, to within the cubic term (< 0.01 rad for offsets <= 0.3)
    spread = np.array([c[0] for c in cloud])
    w = np.array([c[1] for c in cloud])
    w = w / w.sum()
    k = len(cloud)
    ang = centre + spread + TWO_PI * turn
    expected = centre + float(w @ spread)
    poses = np.column_stack([np.arange(k, dtype=float), -(np.arange(k, dtype=float) ** 2), ang])
    m = pose_mean(poses, w)
    np.testing.assert_allclose(m[:2], w @ poses[:, :2], atol=1e-12)  # x, y: the plain weighted mean
    assert angle_gap(m[2], expected) < 0.01
    # exact: it is the direction of the weighted sum of unit vectors, however the angles are written
    assert angle_gap(m[2], math.atan2(w @ np.sin(ang), w @ np.cos(ang))) < 1e-12
    rb = range_bearing_mean(np.column_stack([np.ones(k), ang]), w)
    assert rb[0] == pytest.approx(1.0, abs=1e-14) and angle_gap(rb[1], m[2]) < 1e-12


# ================================================================ models: matrices, Jacobians, unicycle
def test_constant_velocity_closed_form_2d():
    F, H = constant_velocity(0.5, dim=2)
    np.testing.assert_array_equal(F, [[1, 0, 0.5, 0], [0, 1, 0, 0.5], [0, 0, 1, 0], [0, 0, 0, 1]])
    np.testing.assert_array_equal(H, [[1, 0, 0, 0], [0, 1, 0, 0]])


@FAST
@given(dt=reals(1e-3, 5.0), dim=st.integers(1, 3), k=st.integers(1, 6))
def test_constant_velocity_k_steps_advance_position_by_k_dt_v(dt, dim, k):
    F, H = constant_velocity(dt, dim)
    eye = np.eye(dim)
    expected = np.block([[eye, k * dt * eye], [np.zeros((dim, dim)), eye]])
    np.testing.assert_allclose(np.linalg.matrix_power(F, k), expected, rtol=1e-12)
    np.testing.assert_array_equal(H @ F @ np.concatenate([np.zeros(dim), np.ones(dim)]), dt * np.ones(dim))


@FAST
@given(
    A=st.lists(reals(-3, 3), min_size=6, max_size=6).map(lambda a: np.array(a).reshape(2, 3)),
    x=st.tuples(reals(-5, 5), reals(-5, 5), reals(-5, 5)).map(np.array),
)
def test_numeric_jacobian_of_a_linear_map_is_the_matrix(A, x):
    np.testing.assert_allclose(kf.numeric_jacobian(lambda s: A @ s + 1.0, x), A, atol=1e-8)


def test_numeric_jacobian_closed_form():
    # f(x, y) = (x y, sin x) at (2, 0): J = [[y, x], [cos x, 0]] = [[0, 2], [cos 2, 0]]
    J = kf.numeric_jacobian(lambda s: np.array([s[0] * s[1], math.sin(s[0])]), [2.0, 0.0])
    np.testing.assert_allclose(J, [[0.0, 2.0], [math.cos(2.0), 0.0]], atol=1e-9)


def test_unicycle_closed_form_quarter_circle():
    # V = 1, omega = pi/2, dt = 1 from the origin facing +x: a quarter of a circle of radius 2/pi
    # ends at (2/pi, 2/pi) facing +y; G[0:2, 2] = (-(y'-y), x'-x) = (-2/pi, 2/pi)
    out = kf.unicycle([0.0, 0.0, 0.0], [1.0, math.pi / 2], 1.0)
    np.testing.assert_allclose(out, [2 / math.pi, 2 / math.pi, math.pi / 2], atol=1e-15)
    G = kf.unicycle_jacobian([0.0, 0.0, 0.0], [1.0, math.pi / 2], 1.0)
    np.testing.assert_allclose(G, [[1, 0, -2 / math.pi], [0, 1, 2 / math.pi], [0, 0, 1]], atol=1e-15)


def test_unicycle_control_jacobian_closed_forms():
    # straight ahead, theta = 0, V = 0.5, dt = 1: speed moves x by dt; the turn rate swings the chord,
    # dy/domega = (dt/2) V dt = 0.25, and turns the heading by dt
    V = kf.unicycle_control_jacobian([0.0, 0.0, 0.0], [0.5, 0.0], 1.0)
    np.testing.assert_allclose(V, [[1.0, 0.0], [0.0, 0.25], [0.0, 1.0]], atol=1e-15)
    # the quarter circle: x' = y' = (V/omega)(1 - 0) with omega = pi/2, so dx'/dV = dy'/dV = 2/pi;
    # dx'/domega = d/domega [V sin(omega)/omega] = V (omega cos omega - sin omega)/omega^2 = -4/pi^2,
    # dy'/domega = d/domega [V (1 - cos omega)/omega] = V (omega sin omega - 1 + cos omega)/omega^2 = 2/pi - 4/pi^2
    V = kf.unicycle_control_jacobian([0.0, 0.0, 0.0], [1.0, math.pi / 2], 1.0)
    c = 4 / math.pi**2
    np.testing.assert_allclose(V, [[2 / math.pi, -c], [2 / math.pi, 2 / math.pi - c], [0.0, 1.0]], atol=1e-15)


def test_wrap_angle_closed_form():
    assert kf.wrap_angle(1.5 * math.pi) == pytest.approx(-0.5 * math.pi, abs=1e-15)
    assert kf.wrap_angle(-math.pi) == math.pi  # the interval is (-pi, pi]
    np.testing.assert_allclose(kf.wrap_angle(np.array([7.0, -7.0])), [7.0 - TWO_PI, TWO_PI - 7.0], atol=1e-15)
