"""The RTS smoother (chapter 12): ``rts_smoother`` and ``ekf_rts_smoother``.

On a linear-Gaussian model the smoother equals the exact posterior of every state given every
reading, computed in one batch; its last step is the filter's, and it is never less sure than the
filter.  The extended form equals the linear one on a linear model, and on the unicycle a heading
that crosses +-pi is smoothed the short way round.  Bad input is refused by name.

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.models import pose_residual
from tests.filters.strategies import INDEFINITE, NAN, NONSYM, angle_gap, assert_close, assert_raises_naming

DT = 0.5
F_CV = np.array([[1.0, DT], [0.0, 1.0]])  # constant velocity: position and speed
B_CV = np.array([[DT**2 / 2], [DT]])  # pushed by an acceleration
R_CV = 0.3 * np.array([[DT**3 / 3, DT**2 / 2], [DT**2 / 2, DT]])  # white-acceleration noise: invertible
H_POS, Q_POS = np.array([[1.0, 0.0]]), np.array([[0.4]])  # the position is read


# ================================================================ a linear-Gaussian run and its exact posterior
def linear_case(n: int, T: int = 6):
    """A model of n states (1: a random walk read directly; 2: constant velocity, its position read), a prior,
    T controls and T readings (a local generator's draws: any draws must pass)."""
    rng = np.random.default_rng(3)
    if n == 1:
        F, B, R, H, Q = np.array([[0.9]]), np.array([[1.0]]), np.array([[0.2]]), np.array([[1.0]]), np.array([[0.5]])
    else:
        F, B, R, H, Q = F_CV, B_CV, R_CV, H_POS, Q_POS
    m0, P0 = rng.normal(size=n), np.diag(rng.uniform(0.5, 2.0, size=n))
    u, z = rng.normal(size=(T, 1)), rng.normal(size=(T, 1)) * 2.0
    return dict(F=F, B=B, R=R, H=H, Q=Q, m0=m0, P0=P0, u=u, z=z)


def run_filter(F, B, R, H, Q, m0, P0, u, z):
    """The Kalman filter forward: step 0 updates the prior, step k predicts with u[k] and updates with z[k]."""
    T, n = len(z), m0.size
    mu, Sig, mu_bar, Sig_bar = np.empty((T, n)), np.empty((T, n, n)), np.empty((T, n)), np.empty((T, n, n))
    mu_bar[0], Sig_bar[0] = m0, P0
    for k in range(T):
        if k:
            mu_bar[k], Sig_bar[k] = kf.kf_predict(mu[k - 1], Sig[k - 1], u[k], F, B, R)
        mu[k], Sig[k] = kf.kf_update(mu_bar[k], Sig_bar[k], z[k], H, Q)
    return mu, Sig, mu_bar, Sig_bar


def batch_posterior(F, B, R, H, Q, m0, P0, u, z):
    """The posterior of all T states given all T readings, in one solve of the joint Gaussian's information form.

    -log p(x_0..x_{T-1} | z) = 1/2 sum of |A_i X - b_i|^2 weighted by W_i^-1 over the prior, each motion step and
    each reading, so the information is J = sum A_i^T W_i^-1 A_i and the mean solves J X = sum A_i^T W_i^-1 b_i."""
    T, n = len(z), m0.size
    rows = []  # (A_i, b_i, W_i), A_i of shape (rows, T n)

    def block(k, M):
        A = np.zeros((M.shape[0], T * n))
        A[:, k * n : (k + 1) * n] = M
        return A

    rows.append((block(0, np.eye(n)), m0, P0))  # x_0 ~ N(m0, P0)
    for k in range(1, T):  # x_k - F x_{k-1} ~ N(B u_k, R)
        rows.append((block(k, np.eye(n)) - block(k - 1, F), B @ u[k], R))
    for k in range(T):  # z_k - H x_k ~ N(0, Q)
        rows.append((block(k, H), z[k], Q))
    J = sum(A.T @ np.linalg.solve(W, A) for A, _, W in rows)
    h = sum(A.T @ np.linalg.solve(W, b) for A, b, W in rows)
    cov = np.linalg.inv(J)
    mean = cov @ h
    Sig = np.array([cov[k * n : (k + 1) * n, k * n : (k + 1) * n] for k in range(T)])
    return mean.reshape(T, n), Sig


@pytest.mark.parametrize("n", [1, 2])
def test_equals_the_exact_posterior_of_every_state_given_every_reading(n):
    case = linear_case(n)
    mu, Sig, mu_bar, Sig_bar = run_filter(**case)
    mu_s, Sig_s = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, case["F"])
    mean, cov = batch_posterior(**case)
    assert_close(mu_s, mean, rtol=1e-9, scale=np.abs(mean).max())
    assert_close(Sig_s, cov, rtol=1e-9, scale=np.abs(cov).max())


@pytest.mark.parametrize("n", [1, 2])
def test_agrees_with_filterpys_rts_smoother(n):
    """filterpy's rts_smoother (its Q is the course's R, the process noise) on the same filtered run.  filterpy
    predicts the mean as F x, with no control: the run has none."""
    from filterpy.kalman import rts_smoother as filterpy_rts

    case = {**linear_case(n), "u": np.zeros((6, 1))}
    mu, Sig, mu_bar, Sig_bar = run_filter(**case)
    T = len(mu)
    x, P, _, _ = filterpy_rts(mu, Sig, [case["F"]] * T, [case["R"]] * T)
    mu_s, Sig_s = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, case["F"])
    assert_close(mu_s, x, rtol=1e-10, scale=np.abs(x).max())
    assert_close(Sig_s, P, rtol=1e-10, scale=np.abs(P).max())


def test_the_last_step_is_the_filters_and_no_step_is_less_sure():
    case = linear_case(2)
    mu, Sig, mu_bar, Sig_bar = run_filter(**case)
    mu_s, Sig_s = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, case["F"])
    np.testing.assert_array_equal(mu_s[-1], mu[-1])
    np.testing.assert_array_equal(Sig_s[-1], Sig[-1])
    assert mu_s.shape == mu.shape and Sig_s.shape == Sig.shape
    for k in range(len(mu)):
        np.testing.assert_array_equal(Sig_s[k], Sig_s[k].T)  # exactly symmetric
        gained = np.linalg.eigvalsh(Sig[k] - Sig_s[k])  # filtered - smoothed is PSD
        assert gained.min() >= -1e-12 * np.abs(Sig[k]).max()
    assert np.trace(Sig_s[0]) < np.trace(Sig[0])  # and the future readings do teach the first step something


def test_one_F_and_a_stack_of_it_agree():
    case = linear_case(2)
    mu, Sig, mu_bar, Sig_bar = run_filter(**case)
    one = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, case["F"])
    stack = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, np.stack([case["F"]] * len(mu)))
    for a, b in zip(one, stack, strict=True):
        np.testing.assert_array_equal(a, b)


def test_row_0_of_the_predictions_and_of_F_is_not_used():
    case = linear_case(2)
    mu, Sig, mu_bar, Sig_bar = run_filter(**case)
    F = np.stack([case["F"]] * len(mu))
    want = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, F)
    mu_bar[0], Sig_bar[0], F[0] = [9.0, -9.0], np.zeros((2, 2)), np.zeros((2, 2))  # singular too: not inverted
    got = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, F)
    for a, b in zip(want, got, strict=True):
        np.testing.assert_array_equal(a, b)


def test_one_step_is_the_filtered_belief():
    mu_s, Sig_s = kf.rts_smoother([[1.0, 2.0]], [np.eye(2)], [[0.0, 0.0]], [2 * np.eye(2)], F_CV)
    np.testing.assert_array_equal(mu_s, [[1.0, 2.0]])
    np.testing.assert_array_equal(Sig_s, [np.eye(2)])
    assert mu_s.dtype == Sig_s.dtype == float


def test_the_inputs_are_not_modified():
    case = linear_case(2)
    inputs = (*run_filter(**case), np.stack([case["F"]] * 6))
    copies = [a.copy() for a in inputs]
    mu_s, Sig_s = kf.rts_smoother(*inputs)
    for a, b in zip(inputs, copies, strict=True):
        np.testing.assert_array_equal(a, b)
    assert not np.shares_memory(mu_s, inputs[0]) and not np.shares_memory(Sig_s, inputs[1])


# ================================================================ the extended form
def test_the_extended_form_with_a_linear_model_is_the_linear_one():
    case = linear_case(2)
    mu, Sig, mu_bar, Sig_bar = run_filter(**case)
    seen = []

    def G(x, u):
        seen.append((np.array(x), np.array(u)))
        return case["F"]

    want = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, case["F"])
    got = kf.ekf_rts_smoother(mu, Sig, mu_bar, Sig_bar, G, case["u"])
    for a, b in zip(want, got, strict=True):
        np.testing.assert_array_equal(a, b)
    # G is taken at each filtered mean with the control of the next prediction: G(mu_{k-1}, u_k), k = 1..T-1
    assert len(seen) == len(mu) - 1
    for k, (x, u) in enumerate(seen, start=1):
        np.testing.assert_array_equal(x, mu[k - 1])
        np.testing.assert_array_equal(u, case["u"][k])


def test_a_heading_difference_is_wrapped_and_so_is_the_smoothed_heading():
    """By hand, C = I/2: the heading goes from pi - 0.01 (predicted) to -pi + 0.09 (filtered), 0.1 the short way,
    so step 0 (at pi - 0.01) moves by +0.05, past pi: to -pi + 0.04."""
    mu = [[0.0, 0.0, math.pi - 0.01], [0.0, 0.0, -math.pi + 0.09]]
    mu_bar = [[0.0, 0.0, 0.0], [0.0, 0.0, math.pi - 0.01]]
    Sig, Sig_bar = [np.eye(3)] * 2, [2 * np.eye(3)] * 2
    mu_s, _ = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, np.eye(3), pose_residual)
    assert mu_s[0, 2] == pytest.approx(-math.pi + 0.04, abs=1e-12)
    naive, _ = kf.rts_smoother(mu, Sig, mu_bar, Sig_bar, np.eye(3))  # no residual: the long way round
    assert naive[0, 2] == pytest.approx(0.04, abs=1e-12)


def unicycle_run(T: int = 10):
    """An EKF on the unicycle turning through heading pi (3.0 rad up by 0.1 a step), its position read; each
    filtered heading wrapped as ekf_localization_step does."""
    rng = np.random.default_rng(3)
    u = np.tile([1.0, 0.1 / DT], (T, 1))  # V = 1 m/s, omega dt = 0.1 rad
    g = lambda x, c: kf.unicycle(x, c, DT)  # noqa: E731
    G = lambda x, c: kf.unicycle_jacobian(x, c, DT)  # noqa: E731
    R, Q = np.diag([0.01, 0.01, 0.004]), np.diag([0.05, 0.05])
    h, H = lambda x: x[:2], lambda x: np.eye(3)[:2]
    truth = np.empty((T, 3))
    truth[0] = [0.0, 0.0, 3.0]
    for k in range(1, T):
        truth[k] = kf.unicycle(truth[k - 1], u[k], DT)
    z = truth[:, :2] + rng.normal(scale=0.2, size=(T, 2))
    mu, Sig, mu_bar, Sig_bar = np.empty((T, 3)), np.empty((T, 3, 3)), np.empty((T, 3)), np.empty((T, 3, 3))
    mu_bar[0], Sig_bar[0] = truth[0], np.diag([0.1, 0.1, 0.05])
    for k in range(T):
        if k:
            mu_bar[k], Sig_bar[k] = kf.ekf_predict(mu[k - 1], Sig[k - 1], u[k], g, G, R)
        mu[k], Sig[k] = kf.ekf_update(mu_bar[k], Sig_bar[k], z[k], h, H, Q)
        mu[k, 2] = kf.wrap_angle(mu[k, 2])
    return mu, Sig, mu_bar, Sig_bar, G, u, truth


def test_the_unicycle_run_is_smoothed_the_short_way_round_the_seam():
    mu, Sig, mu_bar, Sig_bar, G, u, truth = unicycle_run()
    assert (mu[:, 2] > 3.0).any() and (mu[:, 2] < -3.0).any()  # the filtered headings cross the seam
    mu_s, Sig_s = kf.ekf_rts_smoother(mu, Sig, mu_bar, Sig_bar, G, u, pose_residual)
    theta = mu_s[:, 2]
    assert ((theta > -math.pi) & (theta <= math.pi)).all()
    for k in range(len(mu)):
        assert angle_gap(theta[k], truth[k, 2]) < 3 * math.sqrt(Sig_s[k, 2, 2])  # near the true heading
        if k:
            assert angle_gap(theta[k], theta[k - 1]) < 0.2  # and its neighbours: 0.1 a step
    # the same run with the headings unwrapped needs no residual: it gives the same, wrapped
    turns = np.unwrap(mu[:, 2]) - mu[:, 2]
    mu_u, mu_bar_u = mu.copy(), mu_bar.copy()
    mu_u[:, 2] += turns
    mu_bar_u[:, 2] = mu_u[:, 2] + kf.wrap_angle(mu_bar[:, 2] - mu[:, 2])
    mu_plain, Sig_plain = kf.ekf_rts_smoother(mu_u, Sig, mu_bar_u, Sig_bar, G, u)
    assert_close(mu_s[:, :2], mu_plain[:, :2], rtol=1e-9, scale=10.0)
    assert np.max([angle_gap(a, b) for a, b in zip(theta, mu_plain[:, 2], strict=True)]) < 1e-9
    assert_close(Sig_s, Sig_plain, rtol=1e-9, scale=np.abs(Sig).max())


# ================================================================ bad input
T3_MU, T3_SIG = np.zeros((3, 2)), np.stack([np.eye(2)] * 3)
T3_BAR = np.stack([2 * np.eye(2)] * 3)


def rts(**changed):
    return lambda: kf.rts_smoother(
        **{"mu": T3_MU, "Sig": T3_SIG, "mu_bar": T3_MU, "Sig_bar": T3_BAR, "F": F_CV, **changed}
    )


def ekf_rts(**changed):
    G = lambda x, u: F_CV  # noqa: E731
    args = {"mu": T3_MU, "Sig": T3_SIG, "mu_bar": T3_MU, "Sig_bar": T3_BAR, "G": G, "u": np.zeros((3, 1)), **changed}
    return lambda: kf.ekf_rts_smoother(**args)


def spoilt(stack, k, M):
    out = np.array(stack)
    out[k] = M
    return out


BAD = [
    ("mu-one-axis", rts(mu=np.zeros(3)), "mu"),
    ("mu-no-step", rts(mu=np.zeros((0, 2))), "mu"),
    ("mu-nan", rts(mu=[[0.0, NAN], [0.0, 0.0], [0.0, 0.0]]), "mu"),
    ("Sig-T", rts(Sig=T3_SIG[:2]), "Sig"),
    ("Sig-n", rts(Sig=np.stack([np.eye(3)] * 3)), "Sig"),
    ("Sig-not-psd", rts(Sig=spoilt(T3_SIG, 2, INDEFINITE)), "Sig"),
    ("Sig-asymmetric", rts(Sig=spoilt(T3_SIG, 1, NONSYM)), "Sig"),
    ("mu_bar-T", rts(mu_bar=np.zeros((4, 2))), "mu_bar"),
    ("mu_bar-n", rts(mu_bar=np.zeros((3, 3))), "mu_bar"),
    ("Sig_bar-T", rts(Sig_bar=T3_BAR[:2]), "Sig_bar"),
    ("Sig_bar-not-psd", rts(Sig_bar=spoilt(T3_BAR, 1, INDEFINITE)), "Sig_bar"),
    ("Sig_bar-singular", rts(Sig_bar=spoilt(T3_BAR, 2, np.diag([1.0, 0.0]))), "Sig_bar"),
    ("F-n", rts(F=np.eye(3)), "F"),
    ("F-T", rts(F=np.stack([F_CV] * 4)), "F"),
    ("F-inf", rts(F=[[1.0, math.inf], [0.0, 1.0]]), "F"),
    ("residual-not-callable", rts(residual="x"), "residual"),
    ("residual-result", rts(residual=lambda a, b: np.zeros(3)), "residual"),
    ("ekf-mu_bar-T", ekf_rts(mu_bar=np.zeros((2, 2))), "mu_bar"),
    ("ekf-Sig-not-psd", ekf_rts(Sig=spoilt(T3_SIG, 0, INDEFINITE)), "Sig"),
    ("ekf-G-not-callable", ekf_rts(G=F_CV), "G"),
    ("ekf-G-result", ekf_rts(G=lambda x, u: np.eye(3)), "G"),
    ("ekf-u-T", ekf_rts(u=np.zeros((2, 1))), "u"),
    ("ekf-u-nan", ekf_rts(u=[[NAN], [0.0], [0.0]]), "u"),
    ("ekf-u-scalar", ekf_rts(u=0.0), "u"),
    ("ekf-residual", ekf_rts(residual=3.0), "residual"),
]


def test_bad_input_ids_are_unique():
    assert len({i for i, _, _ in BAD}) == len(BAD)


@pytest.mark.parametrize(("call", "arg"), [c[1:] for c in BAD], ids=[c[0] for c in BAD])
def test_bad_input_is_refused_by_name(call, arg):
    assert_raises_naming(call, arg)
