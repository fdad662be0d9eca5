r"""The particle filter: a cloud of weighted samples on the unicycle and the range-bearing sensor (chapter 11).

Chapter 1's histogram kept one probability per cell; the particle filter keeps N poses
:math:`x^{[i]}` (the particles, an (N, 3) array) and their weights :math:`w^{[i]}`.  One step,
with the chapter's equation numbers:

.. math::
    (1)\ \tilde u^{[i]} \sim \mathcal N(u, M) \qquad
    (2)\ \bar x^{[i]} = g(x^{[i]}, \tilde u^{[i]}) \qquad
    (3)\ \ell^{[i]} \mathrel{+}= \textstyle\sum_j \log \mathcal N(\nu_j^{[i]}; 0, Q),\
         \nu_j^{[i]} = [z_j - h_j(\bar x^{[i]})]_{\text{wrapped}}

    (3')\ \ell^{[i]} \mathrel{+}= \textstyle\sum_j \log \frac1J \sum_{j'=1}^{J} \mathcal N(\nu_{jj'}^{[i]}; 0, Q),\
         \nu_{jj'}^{[i]} = [z_j - h_{j'}(\bar x^{[i]})]_{\text{wrapped}}
         \quad (\text{unlabelled readings: any of the map's } J \text{ landmarks})

    (4)\ w^{[i]} = \frac{e^{\ell^{[i]} - \ell_{\max}}}{\sum_k e^{\ell^{[k]} - \ell_{\max}}} \qquad
    (5)\ N_{\text{eff}} = 1 / \textstyle\sum_i (w^{[i]})^2 \qquad
    (6)\ \text{resample: } c_i = \textstyle\sum_{k \le i} w^{[k]},\ c_N = 1,\
         \text{position } p \mapsto \text{the } i \text{ with } c_{i-1} \le p < c_i

    (7)\ \mu = \textstyle\sum_i w^{[i]} x^{[i]}\ (\text{heading on the circle}),\quad
         \Sigma = \textstyle\sum_i w^{[i]} d^{[i]} d^{[i]\top},\ d^{[i]} = [x^{[i]} - \mu]_{\text{wrapped}}

    (8)\ \text{injection: a share of the particles replaced by poses drawn uniformly over the map}

Weights are kept as logarithms :math:`\ell` until they are normalised, so that the product of
many small likelihoods never underflows to 0.  Every function is seeded by the ``rng`` it is
given (``np.random.default_rng(seed)``), works on the whole cloud at once, and returns new arrays.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as v
from ..models import pose_mean, pose_residual, range_bearing, unicycle, wrap_angle
from .localization import _pairs

__all__ = [
    "effective_sample_size",
    "inject_random",
    "normalise",
    "pf_estimate",
    "pf_predict",
    "pf_weight",
    "resample_multinomial",
    "resample_stratified",
    "resample_systematic",
]

_SUM_ATOL = 1e-6  # how far weights may be from summing to 1
_BELOW_ONE = np.nextafter(1.0, 0.0)  # the largest number below 1


# ---------------------------------------------------------------- input checks
def _particles(x, name: str = "particles") -> np.ndarray:
    """A finite (N, 3) array of poses [x, y, theta], N >= 1."""
    p = v.finite(x, name)
    if p.ndim != 2 or p.shape[1] != 3 or p.shape[0] < 1:
        raise ValueError(f"{name} must have shape (N, 3), one pose [x, y, theta] a row, N >= 1; got {p.shape}")
    return p


def _log_weights(x, name: str, N: int | None = None) -> np.ndarray:
    """A 1-D array of log-weights, at least one: -inf (a weight of 0) allowed, NaN and +inf not."""
    a = np.atleast_1d(v._floats(x, name))
    if a.ndim != 1 or a.size < 1 or (N is not None and a.size != N):
        want = "(N,) with N >= 1" if N is None else f"({N},), one per particle"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    if np.isnan(a).any() or (a == np.inf).any():
        raise ValueError(f"{name} must hold log-weights: numbers or -inf (a weight of 0), no NaN or +inf")
    return a


def _weights(x, name: str = "w") -> np.ndarray:
    """Normalised weights: a 1-D array of N >= 1 finite numbers >= 0 that sum to 1."""
    w = v._floats(x, name)
    if w.ndim != 1 or w.size < 1:
        raise ValueError(f"{name} must have shape (N,), one weight per particle, N >= 1; got {w.shape}")
    if not np.isfinite(w).all():
        raise ValueError(f"{name} must be finite weights (no NaN or inf)")
    if (w < 0).any():
        raise ValueError(f"{name} must be weights >= 0, got {w.min():.3g} at index {int(w.argmin())}")
    total = float(w.sum())
    if total == 0:
        raise ValueError(f"{name}: every weight is 0, so no particle can be drawn")
    if abs(total - 1.0) > _SUM_ATOL:
        raise ValueError(f"{name} must sum to 1 (normalise them first), but sums to {total:.6g}")
    return w


# ---------------------------------------------------------------- predict and weight
def pf_predict(particles, u, dt, M, rng: np.random.Generator) -> np.ndarray:
    r"""Move every particle by the unicycle with its own noisy copy of the odometry: equations (1) and (2).

    .. math:: \tilde u^{[i]} \sim \mathcal N(u, M), \qquad \bar x^{[i]} = g(x^{[i]}, \tilde u^{[i]})

    ``g`` is the unicycle of :func:`kfcourse.unicycle` (chapter 8), given N poses and N
    controls at once.  Each particle draws its own ``[V, omega]``, so the cloud
    spreads as the odometry noise says: no Jacobian, no linearization.  Introduced in chapter 11.

    Parameters
    ----------
    particles : array_like, shape (N, 3)
        Poses ``[x, y, theta]`` (m, m, rad), one a row.
    u : array_like, shape (2,)
        Odometry ``[V, omega]`` for this step (m/s, rad/s).
    dt : float
        Time step (s), > 0.
    M : array_like, shape (2, 2)
        Covariance of the odometry noise (a zero matrix moves every particle exactly by ``u``).
    rng : numpy.random.Generator
        Source of the draws, e.g. ``np.random.default_rng(seed)``.

    Returns
    -------
    ndarray, shape (N, 3)
        The moved particles, headings wrapped to (-pi, pi].
    """
    x = _particles(particles)
    u = v.vector(u, "u", 2)
    dt = v.positive(dt, "dt", "a time step", "s")
    M = v.covariance(M, "M", 2)
    rng = v.generator(rng, "rng")
    u_i = u + rng.multivariate_normal(np.zeros(2), M, size=len(x), check_valid="ignore")  # (1) u_i ~ N(u, M)
    return unicycle(x, u_i, dt)  # (2) x_bar_i = g(x_i, u_i), each particle with its own control


def pf_weight(particles, z, landmarks, Q, log_w=None, labelled: bool = True) -> np.ndarray:
    r"""Weigh every particle by the likelihood of the readings, in log space: equation (3), or (3').

    Labelled readings, each with the landmark it came from (``labelled=True``), equation (3):

    .. math:: \ell^{[i]} \leftarrow \ell^{[i]} + \sum_j \log \mathcal N(\nu_j^{[i]}; 0, Q), \qquad
              \nu_j^{[i]} = [z_j - h_j(\bar x^{[i]})]_{\text{bearing wrapped}}

    with ``h_j`` the range-bearing model of landmark ``j`` (:func:`kfcourse.range_bearing`).
    The logarithm turns the product of the readings' likelihoods into a sum: twenty readings
    of a particle 10 σ off multiply to about :math:`e^{-1000}`, which is 0 in floating point,
    while its log-weight, about -1000, is an ordinary number.  :func:`normalise` turns the
    log-weights into weights.

    Unlabelled readings (``labelled=False``): the sensor does not say which landmark it saw, so
    a reading may come from any of the map's J landmarks, each as likely a priori (Thrun's
    unknown correspondence).  Its likelihood is the mixture over the map, equation (3'):

    .. math:: \ell^{[i]} \leftarrow \ell^{[i]} + \sum_j \log \frac1J \sum_{j'=1}^{J}
              \mathcal N(\nu_{jj'}^{[i]}; 0, Q), \qquad
              \nu_{jj'}^{[i]} = [z_j - h_{j'}(\bar x^{[i]})]_{\text{bearing wrapped}}

    The inner sum is taken by the log-sum-exp trick of (4), so it never underflows: a particle
    far from every landmark keeps a finite log-weight.  On a map that looks the same from two
    poses, both poses get the same weight.  Introduced in chapter 11.

    Parameters
    ----------
    particles : array_like, shape (N, 3)
        Poses ``[x, y, theta]``, one a row.
    z : array_like, shape (k, 2)
        Readings ``[r, phi]`` (m, rad); k may be 0 (then the weights do not change).
    landmarks : array_like, shape (k, 2) or (J, 2)
        Labelled: the landmark of each reading, row j the landmark of ``z[j]``.
        Unlabelled: the whole map, J >= 1 landmarks (any J, whatever k).
    Q : array_like, shape (2, 2)
        Covariance of the reading noise, positive definite.
    log_w : array_like, shape (N,), optional
        Log-weights before these readings (``-inf`` for a weight of 0); by default all
        equal (0), as after resampling.
    labelled : bool
        True: each reading comes with its landmark, (3).  False: it may come from any landmark
        of the map, (3').

    Returns
    -------
    ndarray, shape (N,)
        Log-weights after the readings (not normalised).
    """
    x = _particles(particles)
    z = _pairs(z, "z")
    labelled = v.flag(labelled, "labelled")
    landmarks = _pairs(landmarks, "landmarks", z.shape[0] if labelled else None)
    if not labelled and len(z) > 0 and len(landmarks) == 0:
        raise ValueError("landmarks must be the whole map, shape (J, 2) with J >= 1, for unlabelled readings")
    Q = v.covariance(Q, "Q", 2)
    sign, logdet = np.linalg.slogdet(2.0 * np.pi * Q)
    if sign <= 0:
        raise ValueError("Q must be positive definite: a reading with no noise gives no likelihood")
    Q_inv = np.linalg.inv(Q)
    log_w = np.zeros(len(x)) if log_w is None else _log_weights(log_w, "log_w", len(x))
    if len(z) == 0:
        return log_w  # no reading: the weights do not change
    h = range_bearing(x, landmarks)  # h_j(x): each landmark's reading, every particle: (J, N, 2)
    # reading j against its own landmark j (labelled: (k, N)), or against every landmark j' of the map ((k, J, N))
    z = z[:, None, :] if labelled else z[:, None, None, :]
    dr = z[..., 0] - h[..., 0]  # the range of nu = z_j - h_j(x)
    dphi = wrap_angle(z[..., 1] - h[..., 1])  # and its bearing, wrapped
    d2 = Q_inv[0, 0] * dr**2 + 2.0 * Q_inv[0, 1] * dr * dphi + Q_inv[1, 1] * dphi**2  # nu^T Q^-1 nu, Q^-1 symmetric
    log_p = -0.5 * (d2 + logdet)  # log N(nu; 0, Q) = -(nu^T Q^-1 nu + log det 2 pi Q) / 2
    if labelled:
        return log_w + log_p.sum(axis=0)  # (3) add every reading's log N(nu_j; 0, Q)
    top = log_p.max(axis=1)  # the likeliest landmark j' for each reading and particle: (k, N)
    # exp floored at e^-700: a term that small adds nothing to a sum >= 1, and exp is slow where it underflows to 0
    terms = np.exp(np.maximum(log_p - top[:, None], -700.0))  # N(nu_jj'; 0, Q) / N(nu_j,top; 0, Q) <= 1
    mix = top + np.log(terms.sum(axis=1) / len(landmarks))  # log (1/J) sum_j' N(nu_jj'; 0, Q)
    return log_w + mix.sum(axis=0)  # (3') add every reading's log-mixture, by the log-sum-exp of (4)


def normalise(log_w) -> np.ndarray:
    r"""Weights that sum to 1 from log-weights, by the log-sum-exp trick: equation (4).

    .. math:: w^{[i]} = \frac{e^{\ell^{[i]} - \ell_{\max}}}{\sum_k e^{\ell^{[k]} - \ell_{\max}}}

    Subtracting the largest log-weight first changes nothing in exact arithmetic and keeps
    the best particle's term at :math:`e^0 = 1`, so the sum never underflows to 0 however
    unlikely every particle is.  Introduced in chapter 11.

    Parameters
    ----------
    log_w : array_like, shape (N,)
        Log-weights (``-inf`` for a weight of 0), at least one finite.

    Returns
    -------
    ndarray, shape (N,)
        Weights >= 0 summing to 1.
    """
    log_w = _log_weights(log_w, "log_w")
    top = log_w.max()
    if top == -np.inf:
        raise ValueError("log_w: every weight is 0 (every log-weight is -inf), so the weights cannot be normalised")
    e = np.exp(log_w - top)  # e^(l_i - l_max): the largest is exactly 1
    return e / e.sum()  # (4)


def effective_sample_size(w) -> float:
    r"""How many equally weighted particles the cloud is worth: equation (5).

    .. math:: N_{\text{eff}} = \frac{1}{\sum_i (w^{[i]})^2}

    N for equal weights, 1 when one particle holds all the weight.  Resampling only when
    it falls below a threshold (often N/2) spares the cloud needless resampling noise.
    Introduced in chapter 11.

    Parameters
    ----------
    w : array_like, shape (N,)
        Normalised weights.

    Returns
    -------
    float
        Between 1 and N.
    """
    w = _weights(w)
    return float(1.0 / (w @ w))  # (5)


# ---------------------------------------------------------------- resampling
def resample_multinomial(w, rng: np.random.Generator) -> np.ndarray:
    r"""Multinomial resampling: N independent draws from the weights, equation (6).

    .. math:: p_i \sim U[0, 1) \text{ independently}, \qquad i = 0, \dots, N-1

    Each position picks the particle whose slice :math:`[c_{i-1}, c_i)` of the cumulative
    weights holds it.  Unbiased (particle i is drawn N·w_i times on average), but its counts
    vary the most of the three schemes: the same particle may be drawn twice as often as it
    deserves, or not at all.  Needs N random numbers.  Introduced in chapter 11.

    Parameters
    ----------
    w : array_like, shape (N,)
        Normalised weights (:func:`normalise`).
    rng : numpy.random.Generator

    Returns
    -------
    ndarray of int, shape (N,)
        The indices of the particles drawn: the new cloud is ``particles[idx]``, every
        weight 1/N.
    """
    w, rng = _weights(w), v.generator(rng, "rng")
    p = rng.random(len(w))  # (6) N independent positions in [0, 1)
    c = np.cumsum(w)  # c_i = w_0 + ... + w_i
    c /= c[-1]  # c_N = 1 exactly (c_N / c_N): a sum that rounds to 0.9999... would let an index run past the end
    return np.searchsorted(c, p, side="right")  # the first i with c_{i-1} <= p < c_i; a weight of 0 is never drawn


def resample_stratified(w, rng: np.random.Generator) -> np.ndarray:
    r"""Stratified resampling: one draw in each of N equal strata, equation (6).

    .. math:: p_i = \frac{i + U_i}{N}, \qquad U_i \sim U[0, 1) \text{ independently}

    Unbiased, and each particle's count differs from N·w_i by less than 2 (the positions
    are spread evenly, so no particle is drawn far more or less often than it deserves).
    Needs N random numbers.  Introduced in chapter 11.

    Parameters
    ----------
    w : array_like, shape (N,)
        Normalised weights (:func:`normalise`).
    rng : numpy.random.Generator

    Returns
    -------
    ndarray of int, shape (N,)
        The indices of the particles drawn (ascending); every new weight is 1/N.
    """
    w, rng = _weights(w), v.generator(rng, "rng")
    N = len(w)
    p = (np.arange(N) + rng.random(N)) / N  # (6) p_i = (i + U_i) / N
    c = np.cumsum(w)  # c_i = w_0 + ... + w_i
    c /= c[-1]  # c_N = 1 exactly (c_N / c_N): a sum that rounds to 0.9999... would let an index run past the end
    p = np.minimum(p, _BELOW_ONE)  # (i + U_i) / N < 1, but its rounding can reach 1.0
    return np.searchsorted(c, p, side="right")  # the first i with c_{i-1} <= p < c_i; a weight of 0 is never drawn


def resample_systematic(w, rng: np.random.Generator) -> np.ndarray:
    r"""Systematic (low-variance) resampling: N evenly spaced positions, one random offset, equation (6).

    .. math:: p_i = \frac{i + U}{N}, \qquad U \sim U[0, 1) \text{ drawn once}

    The usual choice, for three reasons:

    - it is unbiased, and its counts vary the least possible: particle i is drawn
      :math:`\lfloor N w_i \rfloor` or :math:`\lceil N w_i \rceil` times, never further
      from N·w_i than 1 (multinomial's counts scatter freely, stratified's by up to 2);
    - its positions come in order, so one walk along the cumulative sum finds every index:
      O(N) steps (``np.searchsorted`` does that walk here);
    - it needs one random number.

    The cumulative sum's last entry is made exactly 1: left to rounding, it may end just
    below the last position and send an index past the end.  Introduced in chapter 11.

    Parameters
    ----------
    w : array_like, shape (N,)
        Normalised weights (:func:`normalise`).
    rng : numpy.random.Generator

    Returns
    -------
    ndarray of int, shape (N,)
        The indices of the particles drawn (ascending); every new weight is 1/N.
    """
    w, rng = _weights(w), v.generator(rng, "rng")
    N = len(w)
    p = (np.arange(N) + rng.random()) / N  # (6) p_i = (i + U) / N, one U for all
    c = np.cumsum(w)  # c_i = w_0 + ... + w_i
    c /= c[-1]  # c_N = 1 exactly (c_N / c_N): a sum that rounds to 0.9999... would let an index run past the end
    p = np.minimum(p, _BELOW_ONE)  # (i + U) / N < 1, but its rounding can reach 1.0
    return np.searchsorted(c, p, side="right")  # the first i with c_{i-1} <= p < c_i; a weight of 0 is never drawn


# ---------------------------------------------------------------- estimate and injection
def pf_estimate(particles, w) -> tuple[np.ndarray, np.ndarray]:
    r"""The cloud's mean and covariance, the heading averaged on the circle: equation (7).

    .. math:: \mu_{xy} = \sum_i w^{[i]} x^{[i]}_{xy}, \quad
              \mu_\theta = \operatorname{atan2}\!\Big(\sum_i w^{[i]} \sin\theta^{[i]},
                                                     \sum_i w^{[i]} \cos\theta^{[i]}\Big), \quad
              \Sigma = \sum_i w^{[i]} d^{[i]} d^{[i]\top},\ d^{[i]} = [x^{[i]} - \mu]_{\text{wrapped}}

    Headings of 179° and -179° average to 180°, not 0°.  A summary, not a pose the robot
    must be at: the mean of a cloud with two modes lies between them, where no particle is,
    and its covariance is wide enough to cover both.  Introduced in chapter 11.

    Parameters
    ----------
    particles : array_like, shape (N, 3)
        Poses ``[x, y, theta]``, one a row.
    w : array_like, shape (N,)
        Normalised weights.

    Returns
    -------
    mu : ndarray, shape (3,)
        Weighted mean, heading in (-pi, pi].
    Sig : ndarray, shape (3, 3)
        Weighted covariance, heading residuals wrapped.
    """
    x = _particles(particles)
    w = _weights(w)
    if len(w) != len(x):
        raise ValueError(f"w must have shape ({len(x)},), one weight per particle, got {w.shape}")
    mu = pose_mean(x, w)  # (7) weighted mean, heading atan2(sum w sin, sum w cos)
    mu[2] = wrap_angle(mu[2])
    d = pose_residual(x, mu)  # d_i = x_i - mu, heading wrapped: (N, 3)
    Sig = (w[:, None] * d).T @ d  # (7) Sig = sum_i w_i d_i d_i^T
    return mu, (Sig + Sig.T) / 2


def inject_random(particles, share, bounds, rng: np.random.Generator) -> np.ndarray:
    r"""Replace a share of the particles by poses drawn uniformly over a rectangle and every heading: (8).

    .. math:: x^{[i]} \sim U[x_{\min}, x_{\max}) \times U[y_{\min}, y_{\max}) \times U[-\pi, \pi)
              \quad \text{for } \operatorname{round}(s N) \text{ particles chosen at random}

    Call it after resampling, when every weight is 1/N: the new particles take 1/N like the
    rest.  ``share=1`` spreads the whole cloud over the map: a global start.

    Injection is what lets a cloud recover from a kidnapping: once every particle sits in the
    wrong place (particle deprivation), nothing else puts one near the truth.  Its price: the
    injected particles are nearly all in the wrong place, so at every step a share ``s`` of the
    cloud is spent on poses the readings will reject, the same accuracy needs about
    N/(1 - s) particles, and on a map with look-alike places an injected particle at the wrong
    look-alike may be kept and split the cloud.  Injecting only when the readings' average
    likelihood drops (Thrun's augmented MCL) pays it only when the robot may be lost.
    Introduced in chapter 11.

    Parameters
    ----------
    particles : array_like, shape (N, 3)
        Poses ``[x, y, theta]``, one a row.
    share : float
        Share of the particles replaced, from 0 to 1.
    bounds : array_like, shape (2, 2)
        The rectangle ``[[x_min, x_max], [y_min, y_max]]`` (m), each min < max.
    rng : numpy.random.Generator

    Returns
    -------
    ndarray, shape (N, 3)
        A new cloud: the particles, with ``round(share * N)`` of them, chosen at random,
        replaced.
    """
    x = _particles(particles)
    share = v.probability(share, "share")
    b = v.matrix(bounds, "bounds", 2, 2)
    if not (b[:, 0] < b[:, 1]).all():
        raise ValueError(f"bounds must be [[x_min, x_max], [y_min, y_max]] with each min < max, got {b.tolist()}")
    rng = v.generator(rng, "rng")
    N = len(x)
    n = round(share * N)
    rows = rng.choice(N, size=n, replace=False)  # which particles go: any, not the first n of a sorted cloud
    low, high = np.array([*b[:, 0], -np.pi]), np.array([*b[:, 1], np.pi])
    out = x.copy()
    out[rows] = rng.uniform(low, high, size=(n, 3))  # (8) uniform over the map and every heading
    out[rows, 2] = wrap_angle(out[rows, 2])
    return out
