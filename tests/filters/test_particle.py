"""The particle filter's engine (chapter 11): sampling predict, log-space weights, the three
resamplers, the estimate and random injection.

Every sampled check uses a fixed seed and a margin that holds whatever the rounding: the
resamplers are unbiased by a chi-square test that a biased resampler fails; a bootstrap filter
built from these pieces approaches the Kalman posterior as 1/sqrt(N).

Noise letters: R = process noise, Q = measurement noise; M = odometry noise (chapter 10).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

import kfcourse as kf
from kfcourse.sim.capstone_world import BEARING_STD, OMEGA_STD, RANGE_STD, V_STD

M = np.diag([V_STD, OMEGA_STD]) ** 2  # the capstone's odometry noise
Q = np.diag([RANGE_STD, BEARING_STD]) ** 2  # and its reading noise
DT = 0.2  # s
RESAMPLERS = {
    "multinomial": kf.resample_multinomial,
    "stratified": kf.resample_stratified,
    "systematic": kf.resample_systematic,
}
W8 = np.array([0.02, 0.05, 0.08, 0.10, 0.15, 0.20, 0.25, 0.15])  # eight unequal weights


def cloud(rng, N=500, spread=(1.0, 1.0, 0.5)):
    """N poses scattered around (1, 2, 0.3)."""
    return np.array([1.0, 2.0, 0.3]) + rng.standard_normal((N, 3)) * spread


# ---------------------------------------------------------------- predict
def test_predict_without_noise_is_the_unicycle(rng):
    x = cloud(rng)
    for u in ([1.0, 0.4], [0.8, 0.0], [0.0, -1.2]):
        moved = kf.pf_predict(x, u, DT, np.zeros((2, 2)), rng)
        np.testing.assert_allclose(moved, kf.unicycle(x, u, DT), rtol=0, atol=1e-14)


def test_each_particle_moves_by_its_own_draw_of_the_odometry():
    x, u = cloud(np.random.default_rng(1), N=50), np.array([1.0, 0.4])
    moved = kf.pf_predict(x, u, DT, M, np.random.default_rng(7))
    u_i = u + np.random.default_rng(7).multivariate_normal(np.zeros(2), M, size=50)  # the same draws
    for x_i, c, out in zip(x, u_i, moved, strict=True):
        np.testing.assert_allclose(out, kf.unicycle(x_i, c, DT), rtol=0, atol=1e-14)


def test_the_cloud_spreads_as_the_odometry_noise_says():
    """The heading of a particle turns by (omega + noise) dt: its spread is OMEGA_STD dt."""
    x = np.zeros((40_000, 3))
    moved = kf.pf_predict(x, [1.0, 0.5], DT, M, np.random.default_rng(3))
    turn = moved[:, 2] - 0.5 * DT
    assert abs(turn.mean()) < 4 * OMEGA_STD * DT / math.sqrt(len(x))
    assert turn.std() == pytest.approx(OMEGA_STD * DT, rel=0.03)
    assert np.all((moved[:, 2] > -np.pi) & (moved[:, 2] <= np.pi))


def test_predict_is_seeded_and_leaves_its_input_alone():
    x = cloud(np.random.default_rng(2))
    before = x.copy()
    a = kf.pf_predict(x, [1.0, 0.3], DT, M, np.random.default_rng(5))
    b = kf.pf_predict(x, [1.0, 0.3], DT, M, np.random.default_rng(5))
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(x, before)


# ---------------------------------------------------------------- weight and normalise
LANDMARKS = np.array([[4.0, 1.0], [-2.0, 3.0], [1.0, 6.0]])
TRUE_POSE = np.array([1.0, 2.0, 0.3])


def readings(pose, landmarks, rng):
    """Noisy readings of ``landmarks`` from ``pose``, bearing wrapped."""
    z = np.array([kf.range_bearing(pose, m) for m in landmarks])
    z += rng.standard_normal(z.shape) * [RANGE_STD, BEARING_STD]
    z[:, 1] = kf.wrap_angle(z[:, 1])
    return z


def direct_product(particles, z, landmarks):
    """The likelihood of every particle as a plain product of Gaussian densities."""
    like = np.ones(len(particles))
    for z_j, m in zip(z, landmarks, strict=True):
        nu = kf.models.range_bearing_residual(z_j, kf.range_bearing(particles, m))
        like *= kf.mvn_pdf(nu, np.zeros(2), Q)
    return like


def test_log_weights_are_the_log_of_the_direct_product_where_it_does_not_underflow(rng):
    x = TRUE_POSE + rng.standard_normal((200, 3)) * [0.1, 0.1, 0.03]
    z = readings(TRUE_POSE, LANDMARKS, rng)
    like = direct_product(x, z, LANDMARKS)
    assert like.min() > 1e-250  # nothing underflows here
    log_w = kf.pf_weight(x, z, LANDMARKS, Q)
    np.testing.assert_allclose(log_w, np.log(like), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(kf.normalise(log_w), like / like.sum(), rtol=1e-9, atol=1e-300)


def test_a_particle_many_sigma_off_keeps_a_finite_log_weight(rng):
    """Ten readings of a particle 2 m off (20 range sigmas each): the product underflows to 0."""
    landmarks = np.array(
        [[5.0 * math.cos(a), 5.0 * math.sin(a)] for a in np.linspace(0, 2 * np.pi, 10, endpoint=False)]
    )
    truth = np.array([0.0, 0.0, 0.0])
    x = np.array([truth, [2.0, 0.0, 0.0], [0.0, -2.0, 1.0]])
    z = readings(truth, landmarks, rng)
    assert direct_product(x, z, landmarks)[1:].max() == 0.0  # the plain product has lost them
    log_w = kf.pf_weight(x, z, landmarks, Q)
    assert np.isfinite(log_w).all() and log_w[1] < log_w[0] - 1000
    w = kf.normalise(log_w)
    assert not np.isnan(w).any() and w.sum() == pytest.approx(1.0, abs=1e-15)
    assert w[0] == pytest.approx(1.0)


def test_every_particle_far_off_still_normalises(rng):
    """No particle near the truth: every likelihood underflows, the log-weights do not."""
    landmarks = LANDMARKS[[0, 1, 2, 0, 1, 2, 0, 1, 2, 0]]
    z = readings(TRUE_POSE, landmarks, rng)
    x = TRUE_POSE + np.array([[3.0, 0.0, 0.0], [0.0, 3.5, 0.0], [-4.0, 0.0, 2.0]])
    assert direct_product(x, z, landmarks).max() == 0.0
    w = kf.normalise(kf.pf_weight(x, z, landmarks, Q))
    assert np.isfinite(w).all() and w.sum() == pytest.approx(1.0, abs=1e-15)


def test_the_bearing_residual_is_wrapped():
    """A landmark straight behind: a particle reading -pi + 0.01 where pi - 0.01 was read is 0.02 off."""
    m = np.array([[-3.0, 0.0]])
    x = np.array([[0.0, 0.0, 0.01], [0.0, 0.0, -0.01]])  # bearings pi - 0.01 and -pi + 0.01
    z = np.array([[3.0, np.pi - 0.01]])
    log_w = kf.pf_weight(x, z, m, Q)
    d2 = (0.02 / BEARING_STD) ** 2
    assert log_w[0] - log_w[1] == pytest.approx(0.5 * d2, rel=1e-9)


def test_weights_accumulate_and_no_reading_changes_nothing(rng):
    x = cloud(rng, N=100)
    z = readings(TRUE_POSE, LANDMARKS, rng)
    both = kf.pf_weight(x, z, LANDMARKS, Q)
    one_then_two = kf.pf_weight(x, z[1:], LANDMARKS[1:], Q, kf.pf_weight(x, z[:1], LANDMARKS[:1], Q))
    np.testing.assert_allclose(one_then_two, both, rtol=1e-12)
    log_w = rng.standard_normal(100)
    np.testing.assert_array_equal(kf.pf_weight(x, np.empty((0, 2)), np.empty((0, 2)), Q, log_w), log_w)
    np.testing.assert_array_equal(kf.pf_weight(x, [], [], Q), np.zeros(100))


# ---------------------------------------------------------------- unlabelled readings, equation (3')
MAP = np.asarray(kf.sim.DEFAULT_LANDMARKS)  # chapter 10's map: point-symmetric about C
C = np.array([0.0, 2.5])


def mirror(pose):
    """The pose turned half a turn about C: (x, y, theta) -> (2 c - (x, y), theta + pi)."""
    pose = np.asarray(pose, float)
    return np.array([*(2 * C - pose[:2]), kf.wrap_angle(pose[2] + np.pi)])


def direct_mixture(particles, z, landmarks):
    """The likelihood of every particle as a plain product over readings of (1/L) sum_m N(z_j - h_m(x); 0, Q)."""
    like = np.ones(len(particles))
    for z_j in z:
        mix = sum(
            kf.mvn_pdf(kf.models.range_bearing_residual(z_j, kf.range_bearing(particles, m)), np.zeros(2), Q)
            for m in landmarks
        )
        like *= mix / len(landmarks)
    return like


def test_unlabelled_log_weights_are_the_log_of_the_direct_mixture_where_it_does_not_underflow(rng):
    x = TRUE_POSE + rng.standard_normal((300, 3)) * [0.3, 0.3, 0.1]  # near the truth, and some far from it
    z = readings(TRUE_POSE, LANDMARKS[:2], rng)
    like = direct_mixture(x, z, LANDMARKS)
    assert like.min() > 1e-250  # nothing underflows here
    log_w = kf.pf_weight(x, z, LANDMARKS, Q, labelled=False)
    np.testing.assert_allclose(log_w, np.log(like), rtol=1e-12, atol=1e-9)
    labelled = kf.pf_weight(x, z, LANDMARKS[:2], Q)
    assert not np.allclose(log_w, labelled)  # (3') is not (3): the mixture counts every landmark


def test_one_landmark_on_the_map_makes_unlabelled_readings_labelled(rng):
    x = cloud(rng, N=100)
    m = LANDMARKS[:1]
    z = readings(TRUE_POSE, m[[0, 0]], rng)  # two readings, both of the only landmark
    np.testing.assert_allclose(
        kf.pf_weight(x, z, m, Q, labelled=False), kf.pf_weight(x, z, m[[0, 0]], Q), rtol=1e-12, atol=1e-12
    )


def test_the_mirror_pose_weighs_as_much_as_the_true_pose_on_the_symmetric_map(rng):
    """The map turned half a turn about C is the map: unlabelled, the readings cannot tell the two poses apart."""
    np.testing.assert_allclose(np.sort(2 * C - MAP, axis=0), np.sort(MAP, axis=0), atol=1e-12)
    for truth in ([0.2, 0.0, 0.0], [4.0, 2.6, 1.57], [-2.4, 5.0, -3.1]):
        seen = MAP[np.linalg.norm(MAP - truth[:2], axis=1) < 4.0]
        z = readings(truth, seen, rng)
        x = np.array([truth, mirror(truth)])
        log_w = kf.pf_weight(x, z, MAP, Q, labelled=False)
        assert log_w[1] == pytest.approx(log_w[0], rel=1e-12, abs=1e-9)
        labelled = kf.pf_weight(x, z, seen, Q)  # told which landmark it saw, the filter knows better
        assert labelled[1] < labelled[0] - 100


def test_a_particle_far_from_every_landmark_keeps_a_finite_unlabelled_log_weight(rng):
    z = readings(TRUE_POSE, LANDMARKS, rng)
    x = np.array([TRUE_POSE, [60.0, -40.0, 2.0], [-300.0, 500.0, -1.0]])
    assert direct_mixture(x, z, LANDMARKS)[1:].max() == 0.0  # the plain mixture has lost them
    log_w = kf.pf_weight(x, z, LANDMARKS, Q, labelled=False)
    assert np.isfinite(log_w).all() and log_w[1] < log_w[0] - 1000
    w = kf.normalise(log_w)
    assert np.isfinite(w).all() and w[0] == pytest.approx(1.0)
    assert np.isfinite(kf.pf_weight(x[1:], z, LANDMARKS, Q, labelled=False)).all()  # every particle far off


def test_unlabelled_weights_accumulate_and_no_reading_changes_nothing(rng):
    x = cloud(rng, N=100)
    z = readings(TRUE_POSE, LANDMARKS, rng)
    both = kf.pf_weight(x, z, MAP, Q, labelled=False)
    first = kf.pf_weight(x, z[:1], MAP, Q, labelled=False)
    np.testing.assert_allclose(kf.pf_weight(x, z[1:], MAP, Q, first, labelled=False), both, rtol=1e-12)
    log_w = rng.standard_normal(100)
    np.testing.assert_array_equal(kf.pf_weight(x, [], MAP, Q, log_w, labelled=False), log_w)


def test_normalise_ignores_a_common_shift_and_gives_zero_to_minus_infinity():
    log_w = np.array([-1.0, -2.0, -np.inf, -3.0])
    w = kf.normalise(log_w)
    np.testing.assert_allclose(kf.normalise(log_w - 1e6), w, rtol=1e-12)
    np.testing.assert_allclose(w, np.exp(log_w) / np.exp(log_w).sum(), rtol=1e-12)
    assert w[2] == 0.0
    np.testing.assert_array_equal(kf.normalise(np.zeros(4)), np.full(4, 0.25))


def test_effective_sample_size():
    assert kf.effective_sample_size(np.full(50, 0.02)) == pytest.approx(50.0)
    assert kf.effective_sample_size([0.0, 1.0, 0.0]) == 1.0
    assert kf.effective_sample_size([0.5, 0.25, 0.25]) == pytest.approx(1 / 0.375)


# ---------------------------------------------------------------- resampling
def pearson_p_value(resample, w, draws=4000, seed=11) -> float:
    """p-value of the chi-square test that the counts, over many draws, are N w on average.

    For multinomial resampling the summed counts are exactly multinomial and the test is exact;
    the other two schemes' counts vary less, so their statistic is smaller and the test conservative.
    """
    rng, N = np.random.default_rng(seed), len(w)
    counts = sum(np.bincount(resample(w, rng), minlength=N) for _ in range(draws))
    expected = draws * N * np.asarray(w)
    return float(stats.chi2.sf(((counts - expected) ** 2 / expected).sum(), df=N - 1))


@pytest.mark.parametrize("name", list(RESAMPLERS))
def test_each_resampler_is_unbiased_by_a_chi_square_test(name):
    assert pearson_p_value(RESAMPLERS[name], W8) > 1e-3


def forgot_the_offset(w, rng):
    """Systematic resampling with positions i / N: the random offset U left out."""
    c = np.cumsum(w)
    return np.searchsorted(c / c[-1], np.arange(len(w)) / len(w), side="right")


def squared_weights(w, rng):
    """Multinomial resampling from w^2 (normalised): favours the heavy particles."""
    return kf.resample_multinomial(np.square(w) / np.square(w).sum(), rng)


@pytest.mark.parametrize("biased", [forgot_the_offset, squared_weights])
def test_the_chi_square_test_catches_a_biased_resampler(biased):
    assert pearson_p_value(biased, W8) < 1e-6


def count_deviations(resample, N=50, draws=300, seed=4) -> np.ndarray:
    """|count_i - N w_i| of every particle over many draws, with fresh random weights each time."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(draws):
        w = rng.dirichlet(np.full(N, 0.5))
        out.append(np.abs(np.bincount(resample(w, rng), minlength=N) - N * w))
    return np.array(out)


def test_systematic_counts_never_stray_from_n_w_by_one():
    dev = count_deviations(kf.resample_systematic)
    assert dev.max() < 1.0


def test_stratified_counts_stray_by_less_than_two():
    """One draw in each stratum: a particle's slice of length N w overlaps at most N w + 2 strata."""
    dev = count_deviations(kf.resample_stratified)
    assert 1.0 <= dev.max() < 2.0


def test_multinomial_counts_stray_further():
    assert count_deviations(kf.resample_multinomial).max() >= 2.0


@pytest.mark.parametrize("name", list(RESAMPLERS))
def test_indices_are_in_range_and_skip_zero_weights(name, rng):
    w = np.array([0.0, 0.3, 0.0, 0.0, 0.5, 0.2, 0.0])
    for _ in range(200):
        idx = RESAMPLERS[name](w, rng)
        assert idx.shape == (7,) and np.issubdtype(idx.dtype, np.integer)
        assert set(idx.tolist()) <= {1, 4, 5}


class AlmostOne(np.random.Generator):
    """Every uniform draw is the largest number below 1."""

    def random(self, size=None, dtype=np.float64, out=None):
        return np.full(size, np.nextafter(1.0, 0.0)) if size is not None else np.nextafter(1.0, 0.0)


@pytest.mark.parametrize("name", list(RESAMPLERS))
def test_no_index_runs_past_the_end(name):
    """Ten weights of 0.1 sum to 0.9999999999999999, and (9 + U) / 10 rounds to 1.0 for U just below 1."""
    w = np.full(10, 0.1)
    assert np.cumsum(w)[-1] < 1.0
    idx = RESAMPLERS[name](w, AlmostOne(np.random.PCG64(0)))
    assert idx.max() == 9
    trailing_zero = np.array([0.25, 0.25, 0.25, 0.25, 0.0])
    assert RESAMPLERS[name](trailing_zero, AlmostOne(np.random.PCG64(0))).max() == 3


def test_systematic_draws_equal_weights_once_each(rng):
    np.testing.assert_array_equal(kf.resample_systematic(np.full(1000, 1e-3), rng), np.arange(1000))


# ---------------------------------------------------------------- estimate
def test_headings_average_on_the_circle():
    x = np.array([[1.0, 2.0, np.deg2rad(179.0)], [3.0, 2.0, np.deg2rad(-179.0)]])
    mu, Sig = kf.pf_estimate(x, [0.5, 0.5])
    assert mu[2] == pytest.approx(np.pi, abs=1e-12)
    np.testing.assert_allclose(mu[:2], [2.0, 2.0])
    assert Sig[2, 2] == pytest.approx(np.deg2rad(1.0) ** 2, rel=1e-9)
    assert Sig[0, 0] == pytest.approx(1.0) and Sig[0, 2] == pytest.approx(np.deg2rad(1.0), rel=1e-9)


def test_estimate_is_the_weighted_mean_and_covariance(rng):
    x = cloud(rng, N=300, spread=(0.5, 0.3, 0.2))
    w = kf.normalise(rng.standard_normal(300))
    mu, Sig = kf.pf_estimate(x, w)
    np.testing.assert_allclose(mu[:2], w @ x[:, :2], rtol=1e-12)
    assert mu[2] == pytest.approx(math.atan2(w @ np.sin(x[:, 2]), w @ np.cos(x[:, 2])), abs=1e-15)
    np.testing.assert_allclose(Sig[:2, :2], np.cov(x[:, :2].T, aweights=w, bias=True), rtol=1e-9, atol=1e-15)
    d = x - mu
    d[:, 2] = [math.remainder(a, 2 * math.pi) for a in d[:, 2]]
    np.testing.assert_allclose(Sig, (w * d.T) @ d, rtol=1e-9, atol=1e-15)
    assert np.linalg.eigvalsh(Sig).min() > 0


def test_the_mean_of_two_modes_lies_between_them():
    x = np.array([[-3.0, 0.0, 0.0]] * 50 + [[3.0, 0.0, 0.0]] * 50)
    mu, Sig = kf.pf_estimate(x, np.full(100, 0.01))
    assert mu[0] == pytest.approx(0.0) and np.abs(x[:, 0] - mu[0]).min() == 3.0  # no particle is there
    assert Sig[0, 0] == pytest.approx(9.0)


# ---------------------------------------------------------------- injection
BOUNDS = [[-6.0, 6.0], [-2.0, 7.0]]


def test_injection_replaces_the_share_asked_for_uniformly_over_the_map(rng):
    x = cloud(rng, N=1000)
    new = kf.inject_random(x, 0.1, BOUNDS, rng)
    changed = (new != x).any(axis=1)
    assert changed.sum() == 100
    assert changed[:500].sum() < 100  # any particles, not the first hundred
    spread = kf.inject_random(x, 1.0, BOUNDS, np.random.default_rng(0))
    assert (spread[:, 0] >= -6).all() and (spread[:, 0] < 6).all() and (spread[:, 1] >= -2).all()
    assert (spread[:, 1] < 7).all() and (np.abs(spread[:, 2]) <= np.pi).all()
    assert spread[:, 0].mean() == pytest.approx(0.0, abs=0.5) and spread[:, 2].std() == pytest.approx(1.81, abs=0.1)
    np.testing.assert_array_equal(kf.inject_random(x, 0.0, BOUNDS, rng), x)


def test_injection_leaves_its_input_alone(rng):
    x = cloud(rng, N=20)
    before = x.copy()
    kf.inject_random(x, 0.5, BOUNDS, rng)
    np.testing.assert_array_equal(x, before)


# ---------------------------------------------------------------- against the Kalman filter
def bootstrap_error(N: int, seed: int, steps: int = 5) -> tuple[np.ndarray, float]:
    """Errors of a bootstrap filter's mean against the Kalman posterior mean, one per step.

    The problem is linear and Gaussian on x alone: the robot heads along +x (theta = 0, no turn
    noise), so x' = x + V dt with V noisy, and it reads the range to a landmark far ahead on the
    x axis, r = L - x + noise, with a bearing of exactly 0 for every particle.
    """
    rng = np.random.default_rng(seed)
    L, V, sv, sr = 100.0, 1.0, 0.5, 0.5  # m, m/s, m/s, m
    M_lin, Q_lin = np.diag([sv**2, 0.0]), np.diag([sr**2, BEARING_STD**2])
    x_true, mu, Sig = 0.0, np.zeros(1), np.eye(1)
    particles = np.zeros((N, 3))
    particles[:, 0] = rng.standard_normal(N)  # the prior N(0, 1)
    err = []
    for _ in range(steps):
        x_true += (V + sv * rng.standard_normal()) * DT
        z = np.array([[L - x_true + sr * rng.standard_normal(), 0.0]])
        particles = kf.pf_predict(particles, [V, 0.0], DT, M_lin, rng)
        w = kf.normalise(kf.pf_weight(particles, z, [[L, 0.0]], Q_lin))
        mu, Sig = kf.kf_step(mu, Sig, [V], [z[0, 0] - L], [[1.0]], [[DT]], [[-1.0]], [[(sv * DT) ** 2]], [[sr**2]])
        err.append(kf.pf_estimate(particles, w)[0][0] - mu[0])
        particles = particles[kf.resample_systematic(w, rng)]
    assert not particles[:, 1:].any()  # y and theta stayed exactly 0: the problem stayed linear
    return np.array(err), math.sqrt(Sig[0, 0])


def test_a_bootstrap_filter_approaches_the_kalman_posterior_as_one_over_root_n():
    Ns = np.array([100, 300, 1000, 3000, 10_000])
    rms = []
    for N in Ns:
        errors = np.concatenate([bootstrap_error(int(N), seed)[0] for seed in range(8)])
        rms.append(math.sqrt(np.mean(errors**2)))
    slope = np.polyfit(np.log(Ns), np.log(rms), 1)[0]
    assert -0.7 < slope < -0.3, (slope, rms)
    sigma = bootstrap_error(100, 0)[1]
    assert rms[-1] < 0.05 * sigma  # at 10 000 particles the means agree to a few hundredths of a sigma


# ---------------------------------------------------------------- bad input
X3 = np.zeros((4, 3))
W4 = np.full(4, 0.25)
GEN = np.random.default_rng(0)
BAD = [
    (lambda: kf.normalise([0.0, np.nan]), "log_w"),
    (lambda: kf.normalise([-np.inf, -np.inf]), "log_w: every weight is 0"),
    (lambda: kf.normalise([]), "log_w"),
    (lambda: kf.resample_systematic([0.0, 0.0, 0.0], GEN), "w: every weight is 0"),
    (lambda: kf.resample_multinomial([0.5, np.nan, 0.5], GEN), "w must be finite"),
    (lambda: kf.resample_stratified([0.6, -0.1, 0.5], GEN), "w must be weights >= 0"),
    (lambda: kf.resample_systematic([], GEN), "w must have shape \\(N,\\).*N >= 1"),
    (lambda: kf.resample_systematic([0.2, 0.2], GEN), "w must sum to 1"),
    (lambda: kf.resample_systematic([[0.5, 0.5]], GEN), "w must have shape"),
    (lambda: kf.resample_systematic(W4, 0), "rng must be a numpy random Generator"),
    (lambda: kf.effective_sample_size([0.0, 0.0]), "w: every weight is 0"),
    (lambda: kf.pf_predict(np.zeros((0, 3)), [1.0, 0.0], DT, M, GEN), "particles must have shape \\(N, 3\\)"),
    (lambda: kf.pf_predict(np.zeros((4, 2)), [1.0, 0.0], DT, M, GEN), "particles must have shape"),
    (lambda: kf.pf_predict(X3, [1.0], DT, M, GEN), "u must have length 2"),
    (lambda: kf.pf_predict(X3, [1.0, 0.0], 0.0, M, GEN), "dt must be a time step > 0"),
    (lambda: kf.pf_predict(X3, [1.0, 0.0], DT, -M, GEN), "M must be positive semi-definite"),
    (lambda: kf.pf_predict(X3, [1.0, 0.0], DT, M, 3), "rng must be"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], [[1.0, 0.0], [2.0, 0.0]], Q), "landmarks must have shape \\(1, 2\\)"),
    (lambda: kf.pf_weight(X3, [1.0, 0.0, 2.0], [[1.0, 0.0]], Q), "z must have shape"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], [[1.0, 0.0]], np.diag([0.01, 0.0])), "Q must be positive definite"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], [[1.0, 0.0]], Q, np.zeros(3)), "log_w must have shape \\(4,\\)"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], [[1.0, 0.0]], Q, [0, np.nan, 0, 0]), "log_w must hold log-weights"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], [[1.0, 0.0]], Q, labelled=0), "labelled must be True or False"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], np.empty((0, 2)), Q, labelled=False), "landmarks must be the whole map"),
    (lambda: kf.pf_weight(X3, [[1.0, 0.0]], [[1.0, 0.0, 0.0]], Q, labelled=False), "landmarks must have shape"),
    (lambda: kf.pf_estimate(X3, [0.5, 0.5]), "w must have shape \\(4,\\)"),
    (lambda: kf.pf_estimate(X3, [0.25, 0.25, np.nan, 0.25]), "w must be finite"),
    (lambda: kf.pf_estimate([[0.0, 0.0, np.nan]], [1.0]), "particles must be finite"),
    (lambda: kf.inject_random(X3, 1.5, BOUNDS, GEN), "share must be a probability in \\[0, 1\\]"),
    (lambda: kf.inject_random(X3, -0.1, BOUNDS, GEN), "share must be a probability"),
    (lambda: kf.inject_random(X3, 0.5, [[1.0, 0.0], [0.0, 1.0]], GEN), "bounds must be .* min < max"),
    (lambda: kf.inject_random(X3, 0.5, [0.0, 1.0, 0.0, 1.0], GEN), "bounds must have shape \\(2, 2\\)"),
]


@pytest.mark.parametrize(("call", "match"), BAD, ids=[m for _, m in BAD])
def test_bad_input_names_the_argument(call, match):
    with pytest.raises(ValueError, match=match):
        call()
