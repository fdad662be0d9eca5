"""Every worked number of COURSE.md chapters 1-9, computed through ``import kfcourse as kf``.

Where the lesson prints a rounded number, the test rounds the package's output the
same way (3 decimal places unless noted) and compares with the printed value; the
exact value is checked too wherever the lesson's rounding hides something.

Monte-Carlo checks use a seeded ``numpy.random.Generator`` and a tolerance of
``Z_TOL`` standard errors computed from the sample size, so they are deterministic
and fail only if the package's formula is wrong.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import kfcourse as kf

Z_TOL = 5.0  # standard errors allowed in a sampled check
N_SAMPLES = 400_000


def r3(x) -> float:
    """Round as the lesson prints: 3 decimal places."""
    return round(float(x), 3)


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20240611)


# --------------------------------------------------------------------- chapter 1
HALLWAY_PRIOR = [0.5, 0.3, 0.2]
MOVE_RIGHT = {1: 0.8, 0: 0.2}  # 80 % one cell right, 20 % stall
DOOR_LIKELIHOOD = [0.1, 0.6, 0.3]


def test_ch1_hallway_predict_with_wall():
    bel_bar = kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT, boundary="wall")
    # A: only the stalled 20 % of 0.5; B: 0.8*0.5 + 0.2*0.3; C: 0.8*0.3 + all of 0.2 (wall)
    np.testing.assert_allclose(bel_bar, [0.10, 0.46, 0.44], rtol=0, atol=1e-12)


def test_ch1_hallway_predict_default_boundary_is_wall():
    np.testing.assert_allclose(kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT), [0.10, 0.46, 0.44], atol=1e-12)


def test_ch1_hallway_predict_with_wrap_differs_from_wall():
    # On a ring the 0.8 * 0.2 leaving C re-enters at A.
    np.testing.assert_allclose(
        kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT, boundary="wrap"), [0.26, 0.46, 0.28], atol=1e-12
    )


def test_ch1_hallway_update_eta_and_posterior():
    bel_bar = kf.bayes_predict(HALLWAY_PRIOR, MOVE_RIGHT, boundary="wall")
    bel, eta = kf.bayes_update(bel_bar, DOOR_LIKELIHOOD, return_eta=True)
    assert eta == pytest.approx(1 / 0.418, rel=1e-12)  # 0.1*0.10 + 0.6*0.46 + 0.3*0.44 = 0.418
    assert [r3(p) for p in bel] == [0.024, 0.660, 0.316]
    np.testing.assert_allclose(bel, np.array([0.010, 0.276, 0.132]) / 0.418, rtol=1e-12)
    assert bel.sum() == pytest.approx(1.0, abs=1e-12)


def test_ch1_update_without_eta_returns_the_same_posterior():
    bel = kf.bayes_update([0.10, 0.46, 0.44], DOOR_LIKELIHOOD)
    np.testing.assert_allclose(bel, np.array([0.010, 0.276, 0.132]) / 0.418, rtol=1e-12)


# --------------------------------------------------------------------- chapter 2
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


# --------------------------------------------------------------------- chapter 3
def test_ch3_cycle_one():
    c = kf.kf_1d_cycle(2.0, 0.40, u=1.0, z=3.6, R=0.20, Q=0.10)
    assert c.mu_bar == pytest.approx(3.0, abs=1e-12)
    assert c.var_bar == pytest.approx(0.60, abs=1e-12)
    assert c.innovation == pytest.approx(0.6, abs=1e-12)
    assert (r3(c.K), r3(c.mu), r3(c.var)) == (0.857, 3.514, 0.086)
    assert c.K == pytest.approx(6 / 7, rel=1e-12)  # 0.60 / 0.70


def test_ch3_kf_1d_step_reproduces_the_lesson_print():
    mu, var = kf.kf_1d_step(2.0, 0.4, u=1.0, z=3.6, R=0.2, Q=0.1)
    assert (r3(mu), r3(var)) == (3.514, 0.086)


def test_ch3_kf_1d_step_defaults_are_the_lessons():
    # a = b = c = 1, R = 0.2, Q = 0.1 by default, written out by hand:
    # var_bar = 0.4 + 0.2 = 0.6, K = 0.6 / 0.7 = 6/7, mu = 3 + 6/7 * 0.6, var = (1 - 6/7) 0.6 = 0.6/7
    mu, var = kf.kf_1d_step(2.0, 0.4, 1.0, 3.6)
    assert mu == pytest.approx(3.0 + 6.0 / 7.0 * 0.6, rel=1e-14)
    assert var == pytest.approx(0.6 / 7.0, rel=1e-14)
    # a default that is not 1 would show: with a = 2 the prediction is 2 * 2 + 1 = 5, not 3
    assert kf.kf_1d_cycle(2.0, 0.4, 1.0, None, a=2.0).mu_bar == pytest.approx(5.0, abs=1e-14)
    assert r3(mu) == 3.514


def test_ch3_cycle_two_continues_from_cycle_one():
    mu, var = kf.kf_1d_step(2.0, 0.40, u=1.0, z=3.6, R=0.20, Q=0.10)
    c = kf.kf_1d_cycle(mu, var, u=1.0, z=4.7, R=0.20, Q=0.10)
    assert r3(c.mu_bar) == 4.514
    assert (r3(c.var_bar), r3(c.K), r3(c.mu), r3(c.var)) == (0.286, 0.741, 4.652, 0.074)
    assert kf.kf_1d_step(mu, var, 1.0, 4.7, R=0.20, Q=0.10) == pytest.approx((c.mu, c.var), rel=1e-14)


def test_ch3_predict_only_tick_skips_the_update():
    c = kf.kf_1d_cycle(2.0, 0.40, u=1.0, z=None, R=0.20, Q=0.10)
    assert (c.mu, c.var, c.K) == pytest.approx((3.0, 0.60, 0.0), abs=1e-12)


# --------------------------------------------------------------------- chapter 4
def test_ch4_gain_limit_trust_the_measurement():
    # var_bar = 10, Q = 0.01 -> K = 10 / 10.01
    c = kf.kf_1d_cycle(0.0, 10.0, u=0.0, z=1.0, R=0.0, Q=0.01)
    assert r3(c.K) == 0.999
    assert c.mu == pytest.approx(c.K * 1.0) and c.mu > 0.998  # essentially the raw reading
    _, K = kf.kf_gain([[10.0]], [[1.0]], [[0.01]])
    assert K[0, 0] == pytest.approx(10 / 10.01, rel=1e-12)


def test_ch4_gain_limit_trust_the_prediction():
    # var_bar = 0.01, Q = 10 -> K = 0.01 / 10.01
    c = kf.kf_1d_cycle(0.0, 0.01, u=0.0, z=1.0, R=0.0, Q=10.0)
    assert r3(c.K) == 0.001
    assert c.mu < 0.002  # the noisy reading barely moves the estimate
    _, K = kf.kf_gain([[0.01]], [[1.0]], [[10.0]])
    assert K[0, 0] == pytest.approx(0.01 / 10.01, rel=1e-12)


STATIC = {"a": 1.0, "b": 0.0, "R": 0.04, "Q": 0.25}  # a robot at rest


def test_ch4_steady_state_ticks():
    var, gains, post = 4.0, [], []
    for _ in range(4):
        c = kf.kf_1d_cycle(0.0, var, u=0.0, z=0.0, **STATIC)
        gains.append(r3(c.K))
        post.append(r3(c.var))
        var = c.var
    assert gains == [0.942, 0.524, 0.406, 0.362]
    # The lesson's table shows 0.091 at tick 4 because it carried rounded values forward.
    assert post == [0.235, 0.131, 0.102, 0.090]


def test_ch4_steady_state_values():
    K, P_prior, P_post = kf.steady_state_1d(0.04, 0.25)
    assert (r3(K), r3(P_prior), r3(P_post)) == (0.328, 0.122, 0.082)
    # closed form for a = c = 1: P = (R + sqrt(R^2 + 4 R Q)) / 2
    assert P_prior == pytest.approx((0.04 + math.sqrt(0.04**2 + 4 * 0.04 * 0.25)) / 2, rel=1e-12)
    assert K == pytest.approx(P_prior / (P_prior + 0.25), rel=1e-12)
    assert P_post == pytest.approx((1 - K) * P_prior, rel=1e-12)


def test_ch4_steady_state_is_a_fixed_point_of_one_cycle():
    K, P_prior, P_post = kf.steady_state_1d(0.04, 0.25)
    c = kf.kf_1d_cycle(0.0, P_post, u=0.0, z=0.0, **STATIC)
    assert c.var_bar == pytest.approx(P_prior, rel=1e-12)
    assert c.K == pytest.approx(K, rel=1e-12)
    assert c.var == pytest.approx(P_post, rel=1e-12)


def test_ch4_iterating_converges_to_the_steady_state():
    K, _, P_post = kf.steady_state_1d(0.04, 0.25)
    var, errors = 4.0, []
    for _ in range(60):
        c = kf.kf_1d_cycle(0.0, var, u=0.0, z=0.0, **STATIC)
        var = c.var
        errors.append(abs(c.K - K))
    assert var == pytest.approx(P_post, rel=1e-10)
    assert errors[-1] < 1e-12
    assert all(b <= a for a, b in itertools.pairwise(errors))  # monotone from a vague prior


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


# --------------------------------------------------------------------- chapter 5
CV_F = np.array([[1.0, 1.0], [0.0, 1.0]])
CV_B = np.zeros((2, 1))
CV_H = np.array([[1.0, 0.0]])
CV_R = 0.01 * np.eye(2)
CV_Q = np.array([[0.5]])
CV_MU = np.array([0.0, 1.0])
CV_SIG = np.eye(2)
CV_Z = np.array([1.2])
CV_SIG_POST = np.array([[0.40039841, 0.19920319], [0.19920319, 0.61159363]])


def test_ch5_predict():
    mu_bar, Sig_bar = kf.kf_predict(CV_MU, CV_SIG, [0.0], CV_F, CV_B, CV_R)
    np.testing.assert_allclose(mu_bar, [1.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(Sig_bar, [[2.01, 1.0], [1.0, 1.01]], atol=1e-12)


def test_ch5_predict_without_control_matches():
    mu_bar, Sig_bar = kf.kf_predict(CV_MU, CV_SIG, None, CV_F, None, CV_R)
    np.testing.assert_allclose(mu_bar, [1.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(Sig_bar, [[2.01, 1.0], [1.0, 1.01]], atol=1e-12)


def test_ch5_gain_and_update():
    mu_bar, Sig_bar = kf.kf_predict(CV_MU, CV_SIG, [0.0], CV_F, CV_B, CV_R)
    S, K = kf.kf_gain(Sig_bar, CV_H, CV_Q)
    assert S.shape == (1, 1) and K.shape == (2, 1)
    assert S[0, 0] == pytest.approx(2.51, abs=1e-12)
    assert [r3(k) for k in K[:, 0]] == [0.801, 0.398]
    # the velocity gain is non-zero only because prediction correlated p and v
    assert K[1, 0] == pytest.approx(1.0 / 2.51, rel=1e-12)
    mu, Sig = kf.kf_update(mu_bar, Sig_bar, CV_Z, CV_H, CV_Q)
    assert [r3(m) for m in mu] == [1.160, 1.080]
    # the posterior by hand: (I - K H) Sig_bar
    Sig_hand = (np.eye(2) - K @ CV_H) @ Sig_bar
    np.testing.assert_allclose(Sig_hand, CV_SIG_POST, atol=1e-8)
    np.testing.assert_allclose(Sig, CV_SIG_POST, atol=1e-8)


def test_ch5_kf_step_equals_predict_then_update():
    mu, Sig = kf.kf_step(CV_MU, CV_SIG, [0.0], CV_Z, CV_F, CV_B, CV_H, CV_R, CV_Q)
    np.testing.assert_allclose(mu, [2.01 * 0.2 / 2.51 + 1.0, 0.2 / 2.51 + 1.0], rtol=1e-12)
    np.testing.assert_allclose(Sig, CV_SIG_POST, atol=1e-8)


def test_ch5_constant_velocity_model_matches_the_worked_matrices():
    F, H = kf.models.constant_velocity(1.0)
    np.testing.assert_array_equal(F, CV_F)
    np.testing.assert_array_equal(H, CV_H)


# --------------------------------------------------------------------- chapter 7
POSE = np.array([1.0, 2.0, 0.0])
LANDMARK = np.array([4.0, 6.0])
H_WORKED = np.array([[-0.6, -0.8, 0.0], [0.16, -0.12, -1.0]])


def test_ch7_range_bearing():
    r, phi = kf.range_bearing(POSE, LANDMARK)
    assert r == pytest.approx(5.0, abs=1e-12)
    assert r3(phi) == 0.927
    assert phi == pytest.approx(math.atan2(4.0, 3.0), abs=1e-15)


def test_ch7_range_bearing_jacobian():
    np.testing.assert_allclose(kf.range_bearing_jacobian(POSE, LANDMARK), H_WORKED, atol=1e-12)


def test_ch7_numeric_jacobian_agrees():
    J = kf.numeric_jacobian(lambda s: kf.range_bearing(s, LANDMARK), POSE)
    np.testing.assert_allclose(J, H_WORKED, atol=1e-7)
    assert np.allclose(kf.range_bearing_jacobian(POSE, LANDMARK), J)


def test_ch7_numeric_jacobian_catches_a_wrong_jacobian():
    # The #1 cause of a diverging EKF: the bearing row with its signs flipped.  The check the lesson
    # teaches must pass for range_bearing_jacobian and fail for the flipped one.
    J = kf.numeric_jacobian(lambda s: kf.range_bearing(s, LANDMARK), POSE)
    H = kf.range_bearing_jacobian(POSE, LANDMARK)
    np.testing.assert_allclose(H, J, atol=1e-7)
    wrong = H.copy()
    wrong[1, :2] *= -1
    assert np.abs(wrong - J).max() > 0.2  # 2 * 0.16 off in the bearing row


# --------------------------------------------------------------------- chapter 8
def test_ch8_unicycle_jacobian_worked():
    G = kf.unicycle_jacobian([0.0, 0.0, 0.0], [0.5, 0.0], 1.0)
    np.testing.assert_allclose(G, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]], atol=1e-15)
    assert G[1, 2] == pytest.approx(0.5)  # heading error leaks into y


def test_ch8_unicycle_straight_line_worked():
    np.testing.assert_allclose(kf.unicycle([0.0, 0.0, 0.0], [0.5, 0.0], 1.0), [0.5, 0.0, 0.0], atol=1e-15)


Z_CH8 = np.array([4.6, 0.95])
SIG_BAR_CH8 = np.diag([0.3, 0.3, 0.1])
Q_CH8 = np.diag([0.04, 0.01])


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


def test_ch8_mahalanobis_of_the_worked_innovation():
    H = kf.range_bearing_jacobian(POSE, LANDMARK)
    S, _ = kf.kf_gain(SIG_BAR_CH8, H, Q_CH8)
    nu = kf.models.range_bearing_residual(Z_CH8, kf.range_bearing(POSE, LANDMARK))
    d = kf.mahalanobis(nu, S)
    assert d == pytest.approx(math.sqrt(nu @ np.linalg.inv(S) @ nu), rel=1e-12)
    assert d < 3.0  # a plausible reading


# --------------------------------------------------------------------- chapter 9
def square(x):
    return x**2


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
