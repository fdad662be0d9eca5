"""Gaussians (chapters 2 and 4): ``gaussian_pdf``, ``mvn_pdf``, ``ellipse_axes``,
``mass_inside``, ``affine_gaussian``, ``add_gaussians`` and ``fuse``.  The lesson's
numbers (checked against seeded samples too), densities and ellipses by hand, the
composition laws, and the bad input they refuse.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import kfcourse as kf
from tests.filters.strategies import (
    F2,
    FAST,
    I2,
    I3,
    INDEFINITE,
    INF,
    MU2,
    N_SAMPLES,
    NAN,
    NONSYM,
    TWO_PI,
    Z_TOL,
    assert_raises_naming,
    assert_raises_saying,
    assert_unique_ids,
    bad_input_cases,
    r3,
    reals,
    spd,
)


# ================================================================ worked numbers (chapters 2 and 4)
def test_ch2_affine_shift():
    # X ~ N(2, 0.5); Y = 1 * X + 3
    mu, var = kf.affine_gaussian(2.0, 0.5, 1.0, 3.0)
    assert (mu, var) == pytest.approx((5.0, 0.5), abs=1e-12)


def test_ch2_affine_scale_squares_the_variance():
    # Z = 2 X: the variance scales by A^2 = 4
    mu, var = kf.affine_gaussian(2.0, 0.5, 2.0)
    assert (mu, var) == pytest.approx((4.0, 2.0), abs=1e-12)


def test_ch2_affine_matrix_form_uses_the_transpose():
    # A Sig A^T with a non-symmetric A: forgetting the transpose gives a different answer.
    A = np.array([[1.0, 2.0], [0.0, 1.0]])
    Sig = np.array([[1.0, 0.0], [0.0, 2.0]])
    mu_y, Sig_y = kf.affine_gaussian([1.0, 1.0], Sig, A, [0.5, -0.5])
    np.testing.assert_allclose(mu_y, [3.5, 0.5], atol=1e-12)
    np.testing.assert_allclose(Sig_y, [[9.0, 4.0], [4.0, 2.0]], atol=1e-12)


def _assert_sample_matches(samples: np.ndarray, mean: float, var: float) -> None:
    """Sample mean and variance of Gaussian data within Z_TOL standard errors."""
    n = samples.size
    se_mean = math.sqrt(var / n)
    se_var = var * math.sqrt(2.0 / (n - 1))  # sd of the sample variance of Gaussian data
    assert abs(samples.mean() - mean) < Z_TOL * se_mean
    assert abs(samples.var(ddof=1) - var) < Z_TOL * se_var


def test_ch2_closure_properties_match_sampled_data(rng):
    x = rng.normal(2.0, math.sqrt(0.5), N_SAMPLES)
    _assert_sample_matches(x + 3.0, *kf.affine_gaussian(2.0, 0.5, 1.0, 3.0))
    _assert_sample_matches(2.0 * x, *kf.affine_gaussian(2.0, 0.5, 2.0))


def test_ch2_sum_of_independent_gaussians_matches_sampled_data(rng):
    mu, var = kf.add_gaussians(2.0, 0.5, -1.0, 0.25)
    assert (mu, var) == pytest.approx((1.0, 0.75), abs=1e-12)
    s = rng.normal(2.0, math.sqrt(0.5), N_SAMPLES) + rng.normal(-1.0, 0.5, N_SAMPLES)
    _assert_sample_matches(s, mu, var)


def test_ch2_mass_inside_one_sigma_2d():
    assert kf.mass_inside(1.0, dim=2) == pytest.approx(1.0 - math.exp(-0.5), rel=1e-12)
    assert r3(kf.mass_inside(1.0, dim=2)) == 0.393
    # ... while in 1-D the familiar 68 %
    assert kf.mass_inside(1.0, dim=1) == pytest.approx(0.6826894921370859, rel=1e-12)


def test_ch2_mass_inside_matches_sampled_2d_gaussian(rng):
    Sig = np.array([[2.0, 1.2], [1.2, 1.0]])  # tilted, as in the ellipse demo
    pts = rng.multivariate_normal([0.5, -1.0], Sig, N_SAMPLES) - [0.5, -1.0]
    d2 = np.einsum("ni,ij,nj->n", pts, np.linalg.inv(Sig), pts)
    for k in (1.0, 2.0, 3.0):
        p = kf.mass_inside(k, dim=2)
        frac = float(np.mean(d2 <= k * k))
        assert abs(frac - p) < Z_TOL * math.sqrt(p * (1 - p) / N_SAMPLES), k


@pytest.mark.parametrize(
    ("mu1", "var1", "mu2", "var2"),
    [(3.0, 0.60, 3.6, 0.10), (4.514, 0.286, 4.7, 0.10), (0.0, 10.0, 1.0, 0.01), (-2.0, 0.5, 7.0, 3.0)],
)
def test_ch4_fuse_equals_the_kalman_update(mu1, var1, mu2, var2):
    mu, var = kf.fuse(mu1, var1, mu2, var2)
    # inverse-variance formulas, written out independently of the package
    assert var == pytest.approx(1.0 / (1.0 / var1 + 1.0 / var2), rel=1e-12)
    assert mu == pytest.approx(var * (mu1 / var1 + mu2 / var2), rel=1e-12)
    # the Kalman update with prediction (mu1, var1) and reading mu2 of noise var2
    c = kf.kf_1d_cycle(mu1, var1, u=0.0, z=mu2, R=0.0, Q=var2)
    assert (c.mu, c.var) == pytest.approx((mu, var), rel=1e-12)
    mu_m, Sig_m = kf.kf_update([mu1], [[var1]], [mu2], [[1.0]], [[var2]])
    assert (mu_m[0], Sig_m[0, 0]) == pytest.approx((mu, var), rel=1e-12)
    assert var < min(var1, var2)  # fused is sharper than either input


def test_ch4_fuse_ch3_numbers():
    mu, var = kf.fuse(3.0, 0.60, 3.6, 0.10)
    assert (r3(mu), r3(var)) == (3.514, 0.086)


# ================================================================ closed forms
def test_gaussian_pdf_closed_form_with_variance_not_one():
    # N(0; 0, 4) = 1 / sqrt(2 pi 4) = 1 / (2 sqrt(2 pi)); one sigma (x = 2) out it drops by e^-1/2
    assert kf.gaussian_pdf(0.0, 0.0, 4.0) == pytest.approx(1.0 / (2.0 * math.sqrt(TWO_PI)), rel=1e-14)
    assert kf.gaussian_pdf(2.0, 0.0, 4.0) == pytest.approx(math.exp(-0.5) / (2.0 * math.sqrt(TWO_PI)), rel=1e-14)
    # var = 0.25 (sigma = 0.5): peak 1 / sqrt(2 pi / 4) = 2 / sqrt(2 pi); at x = mu + 1 = two sigma: e^-2
    assert kf.gaussian_pdf(4.0, 3.0, 0.25) == pytest.approx(2.0 * math.exp(-2.0) / math.sqrt(TWO_PI), rel=1e-14)


def test_mvn_pdf_closed_form():
    # N(mu; mu, I_2) = det(2 pi I)^-1/2 = 1 / (2 pi)
    assert kf.mvn_pdf([1.0, -2.0], [1.0, -2.0], np.eye(2)) == pytest.approx(1.0 / TWO_PI, rel=1e-14)
    # Sig = diag(4, 1): det(2 pi Sig) = 4 (2 pi)^2, so the peak is 1 / (4 pi); at x = (2, 0) d^2 = 1
    Sig = np.diag([4.0, 1.0])
    assert kf.mvn_pdf([0.0, 0.0], [0.0, 0.0], Sig) == pytest.approx(1.0 / (4.0 * math.pi), rel=1e-14)
    assert kf.mvn_pdf([2.0, 0.0], [0.0, 0.0], Sig) == pytest.approx(math.exp(-0.5) / (4.0 * math.pi), rel=1e-14)
    # 3-D identity: (2 pi)^-3/2
    assert kf.mvn_pdf(np.zeros(3), np.zeros(3), np.eye(3)) == pytest.approx(TWO_PI**-1.5, rel=1e-14)


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


def test_mass_inside_closed_form_two_sigma():
    # 1 - e^-2 = 0.8646647..., and the 1-D 95.45 %
    assert kf.mass_inside(2.0) == pytest.approx(1.0 - math.exp(-2.0), rel=1e-14)
    assert kf.mass_inside(2.0, dim=1) == pytest.approx(0.9544997361036416, rel=1e-12)


def test_add_gaussians_matrix_closed_form():
    m, S = kf.add_gaussians([1.0, 2.0], [[1.0, 0.5], [0.5, 2.0]], [-1.0, 0.5], [[0.5, 0.0], [0.0, 0.25]])
    np.testing.assert_allclose(m, [0.0, 2.5], atol=1e-15)
    np.testing.assert_allclose(S, [[1.5, 0.5], [0.5, 2.25]], atol=1e-15)


# ================================================================ properties
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


@FAST
@given(k=reals(0.0, 6.0))
def test_mass_inside_is_the_chi_square_cdf(k):
    # 2-D: P(d <= k) = 1 - exp(-k^2/2) is the chi2(2) cdf at k^2; 1-D: P(|x| <= k) = erf(k / sqrt 2)
    assert kf.mass_inside(k, dim=2) == pytest.approx(-math.expm1(-0.5 * k * k), rel=1e-12, abs=1e-15)
    assert kf.mass_inside(k, dim=1) == pytest.approx(math.erf(k / math.sqrt(2.0)), rel=1e-12, abs=1e-15)
    assert kf.mass_inside(k, dim=1) >= kf.mass_inside(k, dim=2)  # a 2-D contour holds less


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


# ================================================================ bad input
BAD_INPUT = [
    ("fuse/var1 negative", lambda: kf.fuse(1.0, -0.5, 2.0, 0.5), "var1"),
    ("fuse/var2 NaN", lambda: kf.fuse(1.0, 0.5, 2.0, NAN), "var2"),
    ("fuse/var2 indefinite", lambda: kf.fuse(MU2, I2, MU2, INDEFINITE), "var2"),
    ("fuse/var1 non-symmetric", lambda: kf.fuse(MU2, NONSYM, MU2, I2), "var1"),
    ("fuse/mu2 wrong length", lambda: kf.fuse(MU2, I2, [1.0, 2.0, 3.0], I2), "mu2"),
    ("fuse/mu1 inf", lambda: kf.fuse([INF, 0.0], I2, MU2, I2), "mu1"),
    ("fuse/both exact", lambda: kf.fuse(1.0, 0.0, 2.0, 0.0), "var1"),
    ("affine_gaussian/Sig negative", lambda: kf.affine_gaussian(2.0, -0.5, 1.0, 3.0), "Sig"),
    ("affine_gaussian/Sig non-symmetric", lambda: kf.affine_gaussian(MU2, NONSYM, F2), "Sig"),
    ("affine_gaussian/A wrong shape", lambda: kf.affine_gaussian(MU2, I2, np.ones((2, 3))), "A"),
    ("affine_gaussian/b wrong length", lambda: kf.affine_gaussian(MU2, I2, F2, [1.0, 2.0, 3.0]), "b"),
    ("affine_gaussian/mu NaN", lambda: kf.affine_gaussian(NAN, 0.5, 1.0), "mu"),
    ("add_gaussians/Sig2 negative", lambda: kf.add_gaussians(1.0, 0.5, 2.0, -0.1), "Sig2"),
    ("add_gaussians/Sig1 indefinite", lambda: kf.add_gaussians(MU2, INDEFINITE, MU2, I2), "Sig1"),
    ("add_gaussians/mu2 wrong length", lambda: kf.add_gaussians(MU2, I2, [1.0], I2), "mu2"),
    ("gaussian_pdf/var zero", lambda: kf.gaussian_pdf(0.0, 0.0, 0.0), "var"),
    ("gaussian_pdf/var negative", lambda: kf.gaussian_pdf(0.0, 0.0, -1.0), "var"),
    ("gaussian_pdf/x NaN", lambda: kf.gaussian_pdf([0.0, NAN], 0.0, 1.0), "x"),
    ("gaussian_pdf/mu inf", lambda: kf.gaussian_pdf(0.0, INF, 1.0), "mu"),
    ("mvn_pdf/x wrong last dimension", lambda: kf.mvn_pdf([0.0, 1.0, 2.0], MU2, I2), "x"),
    ("mvn_pdf/Sig non-symmetric", lambda: kf.mvn_pdf(MU2, MU2, NONSYM), "Sig"),
    ("mvn_pdf/Sig indefinite", lambda: kf.mvn_pdf(MU2, MU2, INDEFINITE), "Sig"),
    ("mvn_pdf/Sig singular", lambda: kf.mvn_pdf(MU2, MU2, np.diag([1.0, 0.0])), "Sig"),
    ("ellipse_axes/Sig 3x3", lambda: kf.ellipse_axes(I3), "Sig"),
    ("ellipse_axes/Sig indefinite", lambda: kf.ellipse_axes(INDEFINITE), "Sig"),
    ("ellipse_axes/nsig negative", lambda: kf.ellipse_axes(I2, nsig=-1.0), "nsig"),
    ("mass_inside/nsig negative", lambda: kf.mass_inside(-1.0), "nsig"),
    ("mass_inside/nsig NaN", lambda: kf.mass_inside(NAN), "nsig"),
    ("mass_inside/dim 3", lambda: kf.mass_inside(1.0, dim=3), "dim"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.fuse(MU2, I2, MU2, I2)
    kf.affine_gaussian(MU2, I2, F2, [1.0, 2.0])
    kf.mvn_pdf(MU2, MU2, I2)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: kf.gaussian_pdf(0.0, 0.0, 0.0), "var must be a variance > 0"),
        (lambda: kf.ellipse_axes(I2, nsig=0.0), "nsig must be a number of standard deviations > 0"),
    ],
)
def test_message_says_what_the_argument_is(call, message):
    """A step, a distance or a standard deviation is not called a variance."""
    assert_raises_saying(call, message)
