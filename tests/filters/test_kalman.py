"""The matrix Kalman filter (chapter 5): ``kf_predict``, ``kf_gain``, ``kf_update`` and
``kf_step``.  The lesson's constant-velocity numbers, the gain by hand, agreement with
the scalar filter and with ``fuse``, Σ symmetric PSD and consistent (NEES) over 10^5
steps at noise ratios from 1e-8 to 1e8, and the bad input they refuse.
(``kf_step_batch`` has its own file, ``test_batch.py``.)

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy import stats

import kfcourse as kf
from tests.filters.strategies import (
    B2,
    F2,
    FAST,
    H12,
    I2,
    I3,
    INDEFINITE,
    INF,
    MU2,
    NAN,
    NEGVAR,
    NONSYM,
    Q11,
    assert_close,
    assert_raises_naming,
    assert_unique_ids,
    bad_input_cases,
    r3,
    reals,
    spd,
    vectors,
)

# ================================================================ worked numbers (chapter 5)
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


# ================================================================ closed forms
def test_kf_gain_closed_form_2x2():
    # Sig_bar = diag(2, 1), H = I, Q = diag(2, 3): S = diag(4, 4), K = diag(2/4, 1/4)
    S, K = kf.kf_gain(np.diag([2.0, 1.0]), np.eye(2), np.diag([2.0, 3.0]))
    np.testing.assert_allclose(S, np.diag([4.0, 4.0]), atol=1e-15)
    np.testing.assert_allclose(K, np.diag([0.5, 0.25]), atol=1e-15)


# ================================================================ properties
@FAST
@given(data=st.data(), n=st.integers(1, 4), k=st.integers(1, 3))
def test_kf_gain_solves_K_S_equals_Sig_bar_H_T(data, n, k):
    Sig_bar, Q = data.draw(spd(n)), data.draw(spd(k))
    H = np.array(data.draw(st.lists(reals(-2, 2), min_size=k * n, max_size=k * n))).reshape(k, n)
    S, K = kf.kf_gain(Sig_bar, H, Q)
    np.testing.assert_allclose(S, H @ Sig_bar @ H.T + Q, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(K @ S, Sig_bar @ H.T, rtol=1e-9, atol=1e-9 * (1 + np.abs(Sig_bar).max()))


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


@FAST
@given(
    mu=reals(-100, 100),
    var=reals(0, 10),
    u=reals(-10, 10),
    z=reals(-100, 100),
    a=reals(-2, 2),
    b=reals(-2, 2),
    c=reals(-3, 3),
    R=reals(0, 10),
    Q=reals(1e-3, 10),
)
def test_matrix_kf_with_n1_equals_kf_1d_step(mu, var, u, z, a, b, c, R, Q):
    mu1, var1 = kf.kf_1d_step(mu, var, u, z, a=a, b=b, c=c, R=R, Q=Q)
    mu_m, Sig_m = kf.kf_step([mu], [[var]], [u], [z], [[a]], [[b]], [[c]], [[R]], [[Q]])
    assert mu_m.shape == (1,) and Sig_m.shape == (1, 1)
    cyc = kf.kf_1d_cycle(mu, var, u, z, a=a, b=b, c=c, R=R, Q=Q)
    scale = 1.0 + abs(z) + abs(cyc.mu_bar) * (1.0 + abs(c))
    assert mu_m[0] == pytest.approx(mu1, rel=1e-9, abs=1e-9 * scale)
    assert Sig_m[0, 0] == pytest.approx(var1, rel=1e-9, abs=1e-12 * (1.0 + cyc.var_bar))
    mu_bar, Sig_bar = kf.kf_predict([mu], [[var]], [u], [[a]], [[b]], [[R]])
    assert (mu_bar[0], Sig_bar[0, 0]) == pytest.approx((cyc.mu_bar, cyc.var_bar), rel=1e-12, abs=1e-12)


@FAST
@given(data=st.data(), n=st.integers(1, 4))
def test_kf_update_with_identity_H_equals_fuse(data, n):
    mu_bar = data.draw(vectors(n))
    Sig_bar = data.draw(spd(n))
    z = data.draw(vectors(n))
    Q = data.draw(spd(n))
    mu_kf, Sig_kf = kf.kf_update(mu_bar, Sig_bar, z, np.eye(n), Q)
    mu_f, Sig_f = kf.fuse(mu_bar, Sig_bar, z, Q)
    scale = np.abs(Sig_bar).max() + np.abs(Q).max()
    assert_close(mu_kf, mu_f, scale=10.0 + np.abs(z).max())
    assert_close(Sig_kf, Sig_f, scale=scale)
    # the fused covariance is the inverse of the summed information
    assert_close(Sig_f, np.linalg.inv(np.linalg.inv(Sig_bar) + np.linalg.inv(Q)), rtol=1e-7, scale=scale)


def test_kf_step_returns_an_exactly_symmetric_covariance():
    rng = np.random.default_rng(4)
    A = rng.normal(size=(4, 4))
    Sig = A @ A.T + np.eye(4)
    F, H = rng.normal(size=(4, 4)), rng.normal(size=(2, 4))
    _, Sig = kf.kf_step(np.zeros(4), Sig, None, [0.3, -0.2], F, None, H, 0.01 * np.eye(4), 0.2 * I2)
    assert np.array_equal(Sig, Sig.T)
    assert np.linalg.eigvalsh(Sig).min() > 0


# ---------------------------------------------------------------- ... over long runs
N_STEPS = 10**5  # the long run (R/Q = 1)
N_STEPS_SHORT = 10**4  # the other noise ratios
DT = 0.1  # s
NEES_TAIL = 1e-4  # chance that a correct filter's mean NEES falls outside the window, each side


def _min_eig_ok(Sig: np.ndarray) -> bool:
    return np.linalg.eigvalsh(Sig)[0] >= -1e-12 * np.abs(Sig).max()


def nees_window(n_samples: int, dim: int) -> tuple[float, float]:
    """Where the mean of n_samples independent NEES values of a dim-state filter falls
    with probability 1 - 2 NEES_TAIL: their sum is chi-square with n_samples * dim dof."""
    dof = n_samples * dim
    return stats.chi2.ppf(NEES_TAIL, dof) / n_samples, stats.chi2.ppf(1 - NEES_TAIL, dof) / n_samples


def test_nees_window_rejects_a_covariance_2_5_times_off():
    # a covariance 2.5x too small makes the mean NEES 2.5 n = 10; 2.5x too large makes it n / 2.5 = 1.6
    for n_samples in (40, 100):
        lo, hi = nees_window(n_samples, 4)
        assert lo < 4.0 < hi
        assert hi < 4.0 * 2.5 and lo > 4.0 / 2.5, (n_samples, lo, hi)


def _textbook_kf_step(mu, Sig, z, F, H, R, Q):
    """The lesson's equations in plain numpy, no symmetrisation, no Joseph form."""
    mu_bar, Sig_bar = F @ mu, F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(mu.size) - K @ H) @ Sig_bar, Sig_bar


def assert_close_in_correlation_units(Sig, ref, tol):
    """|Sig_ij - ref_ij| <= tol sqrt(ref_ii ref_jj): fair to entries of very different scales."""
    d = np.sqrt(np.diag(ref))
    np.testing.assert_array_less(np.abs(Sig - ref), tol * np.outer(d, d) + 1e-300)


@pytest.mark.parametrize(
    ("ratio", "n_steps", "check_every"),
    [(1.0, N_STEPS, 1000), *[(r, N_STEPS_SHORT, 250) for r in (1e-8, 1e-4, 1e4, 1e8)]],
    ids=lambda p: f"{p:g}",
)
def test_covariance_stays_psd_and_consistent_over_long_runs(ratio, n_steps, check_every):
    F, H = kf.models.constant_velocity(DT, 2)
    Gam = np.vstack([0.5 * DT**2 * np.eye(2), DT * np.eye(2)])  # acceleration -> state
    s = math.sqrt(ratio)
    R = s * Gam @ Gam.T  # white-noise acceleration: singular (rank 2 of 4)
    Q = np.eye(2) / s
    rng = np.random.default_rng(12345)
    # a seeded true trajectory of the same model, and noisy position readings of it
    acc = rng.normal(0.0, math.sqrt(s), (n_steps, 2))
    x = np.zeros(4)
    truths = np.empty((n_steps, 4))
    for t in range(n_steps):
        x = F @ x + Gam @ acc[t]
        truths[t] = x
    zs = truths[:, :2] + rng.normal(0.0, math.sqrt(1.0 / s), (n_steps, 2))

    mu, Sig = np.zeros(4), 100.0 * np.eye(4)
    nees = []
    for t in range(n_steps):
        prev = mu, Sig
        mu, Sig = kf.kf_step(mu, Sig, None, zs[t], F, None, H, R, Q)
        if (t + 1) % check_every == 0:
            # what symmetrising cannot fake: the textbook step from the same belief gives the same
            # numbers, the result is PSD, and the update took uncertainty away (Sig_bar - Sig is PSD)
            mu_tb, Sig_tb, Sig_bar_tb = _textbook_kf_step(*prev, zs[t], F, H, R, Q)
            assert_close_in_correlation_units(Sig, Sig_tb, 1e-6)
            np.testing.assert_allclose(mu, mu_tb, rtol=0, atol=1e-6 * (1 + np.abs(mu_tb).max()))
            assert _min_eig_ok(Sig), (t, np.linalg.eigvalsh(Sig))
            assert np.linalg.eigvalsh(Sig_bar_tb - Sig)[0] >= -1e-9 * np.abs(Sig_bar_tb).max(), t
            assert np.array_equal(Sig, Sig.T), t
            e = mu - truths[t]
            nees.append(e @ np.linalg.solve(Sig, e))
    assert np.all(np.isfinite(mu))
    # Sig describes the error: the mean NEES is chi-square / N with 4 N dof (checks far enough apart to be
    # independent); the window rejects a covariance 2.5x too small (mean 10) or too large (mean 1.6)
    lo, hi = nees_window(len(nees), 4)
    assert lo < np.mean(nees) < hi, (np.mean(nees), lo, hi)


# ================================================================ bad input
BAD_INPUT = [
    ("kf_predict/mu NaN", lambda: kf.kf_predict([NAN, 1.0], I2, [0.0], F2, B2, 0.01 * I2), "mu"),
    ("kf_predict/mu 2-D", lambda: kf.kf_predict([[0.0, 1.0]], I2, [0.0], F2, B2, 0.01 * I2), "mu"),
    ("kf_predict/Sig wrong shape", lambda: kf.kf_predict(MU2, I3, [0.0], F2, B2, 0.01 * I2), "Sig"),
    ("kf_predict/Sig non-symmetric", lambda: kf.kf_predict(MU2, NONSYM, [0.0], F2, B2, 0.01 * I2), "Sig"),
    ("kf_predict/Sig indefinite", lambda: kf.kf_predict(MU2, INDEFINITE, [0.0], F2, B2, 0.01 * I2), "Sig"),
    ("kf_predict/F wrong shape", lambda: kf.kf_predict(MU2, I2, [0.0], np.eye(3), B2, 0.01 * I2), "F"),
    ("kf_predict/F inf", lambda: kf.kf_predict(MU2, I2, [0.0], [[1.0, INF], [0.0, 1.0]], B2, 0.01 * I2), "F"),
    ("kf_predict/B wrong shape", lambda: kf.kf_predict(MU2, I2, [0.0], F2, np.zeros((3, 1)), 0.01 * I2), "B"),
    ("kf_predict/R negative variance", lambda: kf.kf_predict(MU2, I2, [0.0], F2, B2, NEGVAR), "R"),
    ("kf_predict/R non-symmetric", lambda: kf.kf_predict(MU2, I2, [0.0], F2, B2, NONSYM), "R"),
    ("kf_predict/u without B", lambda: kf.kf_predict(MU2, I2, [0.0], F2, None, 0.01 * I2), "u"),
    ("kf_predict/u NaN", lambda: kf.kf_predict(MU2, I2, [NAN], F2, B2, 0.01 * I2), "u"),
    ("kf_update/mu_bar NaN", lambda: kf.kf_update([NAN, 1.0], I2, [1.2], H12, Q11), "mu_bar"),
    ("kf_update/Sig_bar indefinite", lambda: kf.kf_update(MU2, INDEFINITE, [1.2], H12, Q11), "Sig_bar"),
    ("kf_update/Sig_bar non-symmetric", lambda: kf.kf_update(MU2, NONSYM, [1.2], H12, Q11), "Sig_bar"),
    ("kf_update/z NaN", lambda: kf.kf_update(MU2, I2, [NAN], H12, Q11), "z"),
    ("kf_update/z wrong length", lambda: kf.kf_update(MU2, I2, [1.2, 0.3], H12, Q11), "z"),  # H and Q agree on 1
    ("kf_update/H wrong shape", lambda: kf.kf_update(MU2, I2, [1.2], [[1.0, 0.0, 0.0]], Q11), "H"),
    ("kf_update/Q negative", lambda: kf.kf_update(MU2, I2, [1.2], H12, [[-0.5]]), "Q"),
    ("kf_update/Q wrong shape", lambda: kf.kf_update(MU2, I2, [1.2], H12, I2), "Q"),
    ("kf_step/R indefinite", lambda: kf.kf_step(MU2, I2, [0.0], [1.2], F2, B2, H12, INDEFINITE, Q11), "R"),
    ("kf_step/Q non-symmetric", lambda: kf.kf_step(MU2, I2, None, [1.0, 2.0], F2, None, I2, 0.01 * I2, NONSYM), "Q"),
    ("kf_step/H wrong shape", lambda: kf.kf_step(MU2, I2, [0.0], [1.2], F2, B2, [[1.0]], 0.01 * I2, Q11), "H"),
    ("kf_step/z inf", lambda: kf.kf_step(MU2, I2, [0.0], [INF], F2, B2, H12, 0.01 * I2, Q11), "z"),
    ("kf_step/z wrong length", lambda: kf.kf_step(MU2, I2, [0.0], [1.2, 0.3], F2, B2, H12, 0.01 * I2, Q11), "z"),
    (
        "kf_step/Sig negative variance",
        lambda: kf.kf_step(MU2, NEGVAR, [0.0], [1.2], F2, B2, H12, 0.01 * I2, Q11),
        "Sig",
    ),
    ("kf_gain/Sig_bar non-symmetric", lambda: kf.kf_gain(NONSYM, H12, Q11), "Sig_bar"),
    ("kf_gain/H wrong columns", lambda: kf.kf_gain(I2, [[1.0, 0.0, 0.0]], Q11), "H"),
    ("kf_gain/Q wrong shape", lambda: kf.kf_gain(I2, H12, I2), "Q"),
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.kf_step(MU2, I2, [0.0], [1.2], F2, B2, H12, 0.01 * I2, Q11)
    kf.kf_gain(I2, H12, Q11)


def test_empty_covariance():
    with pytest.raises(ValueError, match=r"^Sig must not be empty"):
        kf.kf_predict(np.zeros(0), np.zeros((0, 0)), None, np.zeros((0, 0)), None, np.zeros((0, 0)))


def test_the_predicted_covariance_is_exactly_symmetric():
    rng = np.random.default_rng(6)
    A, F = rng.normal(size=(4, 4)), rng.normal(size=(4, 4))
    for _ in range(20):  # F Sig F^T + R rounds differently above and below the diagonal in most cases
        _, Sig_bar = kf.kf_predict(np.zeros(4), A @ A.T + np.eye(4), None, F, None, 0.01 * np.eye(4))
        assert np.array_equal(Sig_bar, Sig_bar.T)
        A, F = rng.normal(size=(4, 4)), rng.normal(size=(4, 4))
