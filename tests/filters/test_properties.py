"""Property tests: the filters agree with each other, Jacobians agree with finite
differences, probability is conserved, and Σ stays symmetric PSD over long runs.

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from scipy import stats

import kfcourse as kf
from kfcourse.models import pose_residual, range_bearing_residual

FAST = settings(max_examples=60, deadline=None)


def reals(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


@st.composite
def matrices(draw, rows: int, cols: int, bound: float = 2.0) -> np.ndarray:
    vals = draw(st.lists(reals(-bound, bound), min_size=rows * cols, max_size=rows * cols))
    return np.array(vals).reshape(rows, cols)


@st.composite
def vectors(draw, n: int, bound: float = 10.0) -> np.ndarray:
    return np.array(draw(st.lists(reals(-bound, bound), min_size=n, max_size=n)))


@st.composite
def spd(draw, n: int) -> np.ndarray:
    """A well-conditioned symmetric positive definite (n, n) matrix."""
    A = draw(matrices(n, n))
    ridge = draw(reals(0.05, 2.0))
    return A @ A.T + ridge * np.eye(n)


def assert_close(actual, desired, rtol=1e-8, scale=1.0):
    np.testing.assert_allclose(actual, desired, rtol=rtol, atol=rtol * scale)


# ---------------------------------------------------------------- KF identities
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


@st.composite
def linear_models(draw):
    n = draw(st.integers(1, 4))
    m = draw(st.integers(1, 2))
    k = draw(st.integers(1, 3))
    return {
        "n": n,
        "mu": draw(vectors(n)),
        "Sig": draw(spd(n)),
        "u": draw(vectors(m)),
        "F": draw(matrices(n, n)),
        "B": draw(matrices(n, m)),
        "R": draw(spd(n)),
        "z": draw(vectors(k)),
        "H": draw(matrices(k, n)),
        "Q": draw(spd(k)),
    }


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


@FAST
@given(mu=vectors(3), Sig=spd(3), lam=st.sampled_from([0.0, 1.0, 2.0, -1.0, 0.5]))
def test_sigma_points_reproduce_mean_and_covariance(mu, Sig, lam):
    chi, wm, wc = kf.sigma_points(mu, Sig, lam)
    assert chi.shape == (7, 3) and wm.shape == wc.shape == (7,)
    assert wm.sum() == pytest.approx(1.0, abs=1e-12)
    assert_close(wm @ chi, mu, scale=10.0)
    d = chi - mu
    assert_close((wc[:, None] * d).T @ d, Sig, scale=np.abs(Sig).max())


# ---------------------------------------------------------------- Jacobians
poses = st.tuples(reals(-50, 50), reals(-50, 50), reals(-10, 10)).map(np.array)


@settings(max_examples=100, deadline=None)
@given(pose=poses, r=reals(0.1, 60.0), angle=reals(-math.pi, math.pi))
@example(pose=np.array([0.0, 0.0, 0.0]), r=1.0, angle=math.pi)  # landmark straight behind: bearing = pi
@example(pose=np.array([0.0, 0.0, -math.pi / 2]), r=0.1, angle=math.pi / 2 + 1e-9)  # closest allowed
def test_range_bearing_jacobian_equals_numeric(pose, r, angle):
    landmark = pose[:2] + r * np.array([math.cos(angle), math.sin(angle)])
    assume(np.hypot(*(landmark - pose[:2])) >= 0.1)
    H = kf.range_bearing_jacobian(pose, landmark)
    J = kf.numeric_jacobian(lambda s: kf.range_bearing(s, landmark), pose, residual=range_bearing_residual)
    assert H.shape == J.shape == (2, 3)
    np.testing.assert_allclose(H, J, rtol=1e-6, atol=1e-6)


omegas = st.one_of(
    st.just(0.0),
    st.just(-0.0),
    reals(1e-300, 1e-8),  # tiny
    reals(-1e-8, -1e-300),
    reals(-5.0, 5.0),
    reals(50.0, 1e3),  # large
    reals(-1e3, -50.0),
)


@settings(max_examples=150, deadline=None)
@given(pose=poses, V=reals(-5, 5), omega=omegas, dt=reals(1e-3, 2.0))
@example(pose=np.array([0.0, 0.0, math.pi]), V=1.0, omega=0.0, dt=1.0)  # heading right at the wrap
@example(pose=np.array([1.0, 2.0, 0.3]), V=2.0, omega=5e-324, dt=1.0)  # smallest subnormal
def test_unicycle_jacobian_equals_numeric(pose, V, omega, dt):
    u = np.array([V, omega])
    G = kf.unicycle_jacobian(pose, u, dt)
    J = kf.numeric_jacobian(lambda s: kf.unicycle(s, u, dt), pose, residual=pose_residual)
    assert G.shape == J.shape == (3, 3)
    np.testing.assert_allclose(G, J, rtol=1e-6, atol=1e-6)


@settings(max_examples=150, deadline=None)
@given(pose=poses, V=reals(-5, 5), omega=omegas, dt=reals(1e-3, 2.0))
@example(pose=np.array([1.0, 2.0, 0.3]), V=2.0, omega=5e-324, dt=1.0)  # smallest subnormal
@example(pose=np.array([1.0, 2.0, 0.3]), V=2.0, omega=2e-3, dt=1.0)  # just past the series' switch
def test_unicycle_control_jacobian_equals_numeric(pose, V, omega, dt):
    u = np.array([V, omega])
    Vu = kf.unicycle_control_jacobian(pose, u, dt)
    J = kf.numeric_jacobian(lambda c: kf.unicycle(pose, c, dt), u, residual=pose_residual)
    assert Vu.shape == J.shape == (3, 2)
    np.testing.assert_allclose(Vu, J, rtol=1e-6, atol=1e-6)


# ---------------------------------------------------------------- Bayes filter
@st.composite
def probability_vectors(draw, min_size=1, max_size=20):
    w = np.array(draw(st.lists(reals(0.0, 1.0), min_size=min_size, max_size=max_size)))
    assume(w.sum() > 1e-3)
    return w / w.sum()


@st.composite
def kernels(draw):
    offsets = draw(st.lists(st.integers(-25, 25), min_size=1, max_size=6, unique=True))
    p = draw(probability_vectors(len(offsets), len(offsets)))
    return dict(zip(offsets, p.tolist(), strict=True))


def reference_predict(bel, kernel, boundary):
    """Plain loops, one source cell at a time."""
    n = len(bel)
    out = [0.0] * n
    for i, b in enumerate(bel):
        for off, p in kernel.items():
            j = (i + off) % n if boundary == "wrap" else min(max(i + off, 0), n - 1)
            out[j] += p * b
    return np.array(out)


@settings(max_examples=100, deadline=None)
@given(bel=probability_vectors(), kernel=kernels(), boundary=st.sampled_from(["wall", "wrap"]))
def test_bayes_predict_conserves_probability(bel, kernel, boundary):
    out = kf.bayes_predict(bel, kernel, boundary=boundary)
    assert out.shape == bel.shape
    assert np.all(out >= 0)
    assert out.sum() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(out, reference_predict(bel, kernel, boundary), atol=1e-12)


@FAST
@given(bel=probability_vectors(2, 20), data=st.data())
def test_bayes_update_normalises_and_is_proportional(bel, data):
    lik = np.array(data.draw(st.lists(reals(0.0, 5.0), min_size=bel.size, max_size=bel.size)))
    assume((lik * bel).sum() > 1e-6)
    post, eta = kf.bayes_update(bel, lik, return_eta=True)
    assert post.sum() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(post, eta * lik * bel, rtol=1e-12, atol=1e-15)
    assert eta == pytest.approx(1.0 / (lik * bel).sum(), rel=1e-12)


# ---------------------------------------------------------------- long runs
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


# ---------------------------------------------------------------- association
MAP = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
SIG_POSE = np.diag([0.05, 0.05, 0.01])
Q_RB = np.diag([0.01, 0.001])


def _associate(z, pose, gate=3.0):
    return kf.associate(
        z,
        pose,
        SIG_POSE,
        MAP,
        kf.range_bearing,
        kf.range_bearing_jacobian,
        Q_RB,
        gate=gate,
        residual=range_bearing_residual,
    )


@FAST
@given(
    pose=st.tuples(reals(2, 8), reals(2, 8), reals(-math.pi, math.pi)).map(np.array),
    j=st.integers(0, len(MAP) - 1),
    noise=st.tuples(reals(-1, 1), reals(-1, 1)),
    spurious_range=reals(0.2, 1.0),
    spurious_bearing=reals(-math.pi, math.pi),
)
def test_mahalanobis_gate(pose, j, noise, spurious_range, spurious_bearing):
    # a good reading of landmark j, off by at most one sensor sigma per channel
    z_good = kf.range_bearing(pose, MAP[j]) + np.array(noise) * np.sqrt(np.diag(Q_RB))
    z_good[1] = kf.wrap_angle(z_good[1])
    idx, dist = _associate(z_good, pose)
    assert idx == j
    assert dist.shape == (len(MAP),)
    assert dist[j] <= 3.0
    for i, m in enumerate(MAP):  # each distance is the Mahalanobis length of its innovation
        S, _ = kf.kf_gain(SIG_POSE, kf.range_bearing_jacobian(pose, m), Q_RB)
        nu = range_bearing_residual(z_good, kf.range_bearing(pose, m))
        assert dist[i] == pytest.approx(kf.mahalanobis(nu, S), rel=1e-9)
    # a pedestrian's leg: closer than any landmark (all >= 2.8 m away) -> gated out
    z_bad = np.array([spurious_range, spurious_bearing])
    idx_bad, dist_bad = _associate(z_bad, pose)
    assert idx_bad is None
    assert dist_bad.min() > 3.0
    # ... and it is the gate that rejects it: without one, the nearest landmark is taken
    idx_open, _ = _associate(z_bad, pose, gate=1e9)
    assert idx_open == int(np.argmin(dist_bad))


@settings(max_examples=80, deadline=None)
@given(
    pose=st.tuples(reals(2, 8), reals(2, 8), reals(-math.pi, math.pi)).map(np.array),
    j=st.integers(0, len(MAP) - 1),
    direction=reals(-math.pi, math.pi),
    gate=reals(0.3, 5.0),
    side=st.sampled_from([1 - 1e-6, 1 + 1e-6]),
)
def test_associate_accepts_just_inside_and_rejects_just_outside_the_gate(pose, j, direction, gate, side):
    z_hat = kf.range_bearing(pose, MAP[j])
    H = kf.range_bearing_jacobian(pose, MAP[j])
    S = H @ SIG_POSE @ H.T + Q_RB  # textbook innovation covariance
    # an innovation of Mahalanobis length exactly side * gate: L e with |e| = side * gate, L L^T = S
    nu = np.linalg.cholesky(S) @ (side * gate * np.array([math.cos(direction), math.sin(direction)]))
    z = z_hat + nu
    z[1] = math.remainder(z[1], 2 * math.pi)
    idx, dist = _associate(z, pose, gate=gate)
    assert dist[j] == pytest.approx(side * gate, rel=1e-9)
    assume(np.delete(dist, j).min() > gate * 1.01)  # no other landmark competes (true in practice)
    assert idx == (j if side < 1 else None)


def test_mahalanobis_matches_closed_form_on_a_diagonal():
    assert kf.mahalanobis([3.0, -4.0], np.diag([9.0, 4.0])) == pytest.approx(math.sqrt(1.0 + 4.0), rel=1e-12)


# ---------------------------------------------------------------- wrap_angle
@settings(max_examples=300, deadline=None)
@given(a=reals(-1e6, 1e6))
@example(a=math.pi)
@example(a=-math.pi)
@example(a=float(np.nextafter(-math.pi, 0.0)))
@example(a=float(np.nextafter(math.pi, 4.0)))
@example(a=3 * math.pi)
@example(a=-3 * math.pi)
@example(a=0.0)
def test_wrap_angle_range_and_congruence(a):
    w = kf.wrap_angle(a)
    assert isinstance(w, float)
    assert -math.pi < w <= math.pi
    k = (a - w) / (2 * math.pi)  # a whole number of turns
    assert abs(k - round(k)) <= 1e-15 * (1.0 + abs(a)) / (2 * math.pi) * 8
    if -math.pi < a <= math.pi:
        assert w == a  # an angle already in range is left alone


@settings(max_examples=100, deadline=None)
@given(a=st.floats(allow_nan=False, allow_infinity=False))
def test_wrap_angle_range_for_any_finite_float(a):
    assert -math.pi < kf.wrap_angle(a) <= math.pi


@FAST
@given(angles=st.lists(reals(-1e4, 1e4), min_size=1, max_size=30))
def test_wrap_angle_array_elementwise(angles):
    a = np.array(angles)
    w = kf.wrap_angle(a)
    assert isinstance(w, np.ndarray) and w.shape == a.shape
    assert np.all((w > -np.pi) & (w <= np.pi))
    np.testing.assert_array_equal(w, [kf.wrap_angle(x) for x in angles])


# ---------------------------------------------------------------- unicycle
@FAST
@given(pose=poses, V=reals(-5, 5), dt=reals(1e-3, 2.0))
def test_unicycle_at_zero_omega_is_the_straight_line(pose, V, dt):
    x, y, th = pose
    out = kf.unicycle(pose, [V, 0.0], dt)
    np.testing.assert_allclose(
        out[:2], [x + V * dt * math.cos(th), y + V * dt * math.sin(th)], rtol=0, atol=1e-12 * (1 + abs(x) + abs(y))
    )
    assert out[2] == pytest.approx(kf.wrap_angle(th), abs=1e-15)
    G = kf.unicycle_jacobian(pose, [V, 0.0], dt)
    np.testing.assert_allclose(G[:2, 2], [-V * dt * math.sin(th), V * dt * math.cos(th)], atol=1e-12)


@FAST
@given(pose=poses, V=reals(-5, 5), dt=reals(1e-3, 2.0), sign=st.sampled_from([-1.0, 1.0]))
def test_unicycle_is_continuous_as_omega_goes_to_zero(pose, V, dt, sign):
    g0 = kf.unicycle(pose, [V, 0.0], dt)
    G0 = kf.unicycle_jacobian(pose, [V, 0.0], dt)
    tol0 = 1e-12 * (1.0 + np.abs(pose[:2]).max() + abs(V) * dt)
    for w in sign * np.logspace(-1, -12, 12):
        gap = np.abs(pose_residual(kf.unicycle(pose, [V, w], dt), g0))
        # |chord drift| <= |V| dt^2 |w| (turning by w dt/2 and shortening by the sinc)
        assert np.all(gap[:2] <= abs(V) * dt * dt * abs(w) + tol0), (w, gap)
        assert gap[2] <= abs(w) * dt * (1 + 1e-12) + 1e-14  # a few ulps from the two wraps
        Ggap = np.abs(kf.unicycle_jacobian(pose, [V, w], dt) - G0)
        assert np.all(Ggap <= abs(V) * dt * dt * abs(w) + tol0), (w, Ggap)


@FAST
@given(pose=poses, V=reals(-5, 5), omega=st.one_of(reals(0.01, 20), reals(-20, -0.01)), dt=reals(0.05, 2.0))
def test_unicycle_matches_the_lessons_arc_formula(pose, V, omega, dt):
    x, y, th = pose
    expected = [
        x + V / omega * (math.sin(th + omega * dt) - math.sin(th)),
        y + V / omega * (math.cos(th) - math.cos(th + omega * dt)),
    ]
    out = kf.unicycle(pose, [V, omega], dt)
    np.testing.assert_allclose(out[:2], expected, rtol=0, atol=1e-9 * (1 + abs(x) + abs(y) + abs(V / omega)))
    assert pose_residual(out, [*expected, th + omega * dt])[2] == pytest.approx(0.0, abs=1e-12)
