"""Sigma points, the unscented transform and the unscented Kalman filter.

Introduced in chapter 9: "it is easier to approximate a distribution than a
function".  Sigma points use the lower Cholesky factor of ``(n + lam) Sig``.

The public functions check their inputs and the models' results, then call the
private cores, which take checked arrays and models (and hooks) that take every
sigma point at once, one a row, and are trusted to return finite arrays of the
right shape (a run engine that checked its inputs once calls the cores on every
step).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v
from .linalg import gain, symmetric


def _sqrt_psd(A: np.ndarray) -> np.ndarray:
    """Lower Cholesky factor; a symmetric square root where A is only semi-definite."""
    try:
        return np.linalg.cholesky(A)
    except np.linalg.LinAlgError:
        w, V = np.linalg.eigh(A)
        return V * np.sqrt(np.clip(w, 0.0, None))


def sigma_points(mu, Sig, lam: float, beta: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""The 2n+1 sigma points of ``N(mu, Sig)`` and their weights (Julier).

    .. math::
        \chi_0 = \mu,\quad \chi_{i} = \mu + L_{:,i},\quad \chi_{n+i} = \mu - L_{:,i},
        \quad L L^\top = (n + \lambda)\Sigma

        w_0 = \frac{\lambda}{n + \lambda},\qquad w_i = \frac{1}{2(n + \lambda)}

    With n = 1 and λ = 0 the weights are 0, ½, ½.  Introduced in chapter 9.

    Parameters
    ----------
    mu : array_like, shape (n,)
    Sig : array_like, shape (n, n)
    lam : float
        Spread parameter; ``n + lam`` must be > 0.
    beta : float
        Added to the centre covariance weight, ``wc_0 = w_0 + beta`` (0 by
        default, the plain transform of the lesson).  The scaled unscented
        transform with parameters α, κ and β (β = 2 is optimal for a Gaussian
        prior) is this one with ``lam = α²(n + κ) - n`` and ``beta = 1 - α² + β``.

    Returns
    -------
    (chi, wm, wc) : shapes (2n+1, n), (2n+1,), (2n+1,)
        Points (one a row), mean weights, covariance weights.
    """
    mu = v.vector(mu, "mu")
    Sig = v.covariance(Sig, "Sig", mu.size)
    lam = v.scalar(lam, "lam")
    beta = v.scalar(beta, "beta")
    return _sigma_points(mu, Sig, lam, beta)


def _sigma_points(mu, Sig, lam, beta=0.0):
    n = mu.size
    if n + lam <= 0:
        raise ValueError(f"lam must be > -n = {-n} so that n + lam > 0, got {lam}")
    L = _sqrt_psd((n + lam) * Sig)  # L L^T = (n + lam) Sig
    chi = np.vstack([mu, mu + L.T, mu - L.T])  # 2n + 1 points, one a row
    wm = np.full(2 * n + 1, 0.5 / (n + lam))  # w_i = 1 / (2 (n + lam))
    wm[0] = lam / (n + lam)  # w_0 = lam / (n + lam)
    wc = wm.copy()
    wc[0] += beta
    return chi, wm, wc


def _push(f, chi, name, k=None, vectorized=False):
    """f at every sigma point: one call per point, or one call on all rows at once."""
    if vectorized:
        return v.matrix(f(chi), f"the result of {name}", chi.shape[0], k)
    Y = [v.vector(f(x), f"the result of {name}", k) for x in chi]
    if k is None and len({y.size for y in Y}) != 1:
        raise ValueError(f"{name} must return vectors of one length")
    return np.array(Y)  # rows checked to be equal-length vectors: cheaper than vstack


def _on_points(f, name, k, vectorized):
    """The model as the cores take it: on every sigma point (a row of chi) at once, its result checked."""
    return lambda chi: _push(f, chi, name, k, vectorized)


def _differences(points, centre, residual, vectorized):
    """Rows of ``points`` minus ``centre`` through the residual hook, its result checked."""
    if vectorized:
        return v.matrix(residual(points, centre), "the result of residual", *points.shape)
    return np.array([residual(p, centre) for p in points], dtype=float)


def _on_rows(residual, vectorized):
    """The residual hook as the cores take it: on a stack of rows against one centre, its result checked
    (one call per row unless ``vectorized``); no hook stays None."""
    return None if residual is None else lambda points, centre: _differences(points, centre, residual, vectorized)


def _recombine(Y, wm, wc, residual, mean):
    """Weighted mean and covariance of transformed points (rows of Y); ``residual`` takes the stack."""
    y_mean = wm @ Y if mean is None else np.asarray(mean(Y, wm), dtype=float)  # sum w_i Y_i
    dY = Y - y_mean if residual is None else residual(Y, y_mean)  # Y_i - y
    cov = (wc[:, None] * dY).T @ dY  # sum w_i (Y_i - y)(Y_i - y)^T
    return y_mean, symmetric(cov), dY


def unscented_transform(
    mu,
    Sig,
    f: Callable,
    lam: float,
    residual: Callable | None = None,
    mean: Callable | None = None,
    vectorized: bool = False,
    *,
    beta: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    r"""Push ``N(mu, Sig)`` through a nonlinear ``f`` with sigma points.

    .. math:: \mu_y = \sum_i w_i f(\chi_i), \qquad
              \Sigma_y = \sum_i w_i \left(f(\chi_i) - \mu_y\right)\left(f(\chi_i) - \mu_y\right)^\top

    Introduced in chapter 9.

    Parameters
    ----------
    mu : array_like, shape (n,)
    Sig : array_like, shape (n, n)
    f : callable ``f(x) -> array (k,)``
        Applied to each sigma point (a row of shape (n,)).
    lam : float
        Spread parameter, ``n + lam > 0``.
    residual : callable ``residual(a, b) -> a - b``, optional
        Difference of outputs (wrap angles here).
    mean : callable ``mean(points, weights) -> array (k,)``, optional
        Weighted mean of outputs (average angles on the circle here).
    vectorized : bool
        Call the model (and ``residual``) once with every sigma point as a row of
        a ``(2n+1, n)`` array instead of once per point; the models in
        :mod:`kfcourse.models` accept such stacks.  Same result, much faster.
    beta : float
        Added to the centre covariance weight, ``wc_0 = w_0 + beta`` (0 by
        default, the plain transform of the lesson).  The scaled unscented
        transform with parameters α, κ and β is this one with
        ``lam = α²(n + κ) - n`` and ``beta = 1 - α² + β``.

    Returns
    -------
    (mu_y, Sig_y) : shapes (k,), (k, k)
    """
    f = v.function(f, "f")
    residual, mean = v.optional_function(residual, "residual"), v.optional_function(mean, "mean")
    chi, wm, wc = sigma_points(mu, Sig, lam, beta)
    y_mean, cov, _ = _recombine(_push(f, chi, "f", None, vectorized), wm, wc, _on_rows(residual, vectorized), mean)
    return y_mean, cov


def unscented_1d(mu: float, var: float, f: Callable, lam: float = 0.0) -> tuple[float, float]:
    r"""The unscented transform of a scalar Gaussian, as in the lesson.

    Three sigma points :math:`\mu,\ \mu \pm \sqrt{(1 + \lambda)\sigma^2}` with
    weights :math:`\lambda/(1+\lambda),\ \tfrac{1}{2(1+\lambda)},\ \tfrac{1}{2(1+\lambda)}`.
    For x ~ N(2, 1) through y = x² it returns (5.0, 16.0).  Introduced in chapter 9.

    Parameters
    ----------
    mu : float
    var : float
        Variance, >= 0.
    f : callable ``f(float) -> float``
    lam : float
        ``1 + lam > 0``.

    Returns
    -------
    (mu_y, var_y) : floats
    """
    mu = v.scalar(mu, "mu")
    var = v.variance(var, "var")
    f = v.function(f, "f")
    lam = v.scalar(lam, "lam")
    chi, wm, wc = _sigma_points(np.array([mu]), np.array([[var]]), lam)
    Y = np.array([v.scalar(f(float(x[0])), "the result of f") for x in chi])
    mu_y = float(wm @ Y)  # sum w_i f(chi_i)
    var_y = float(wc @ (Y - mu_y) ** 2)  # sum w_i (f(chi_i) - mu_y)^2
    return mu_y, var_y


def ukf_predict(
    mu,
    Sig,
    u,
    g: Callable,
    R,
    lam: float,
    residual: Callable | None = None,
    mean: Callable | None = None,
    vectorized: bool = False,
    *,
    beta: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    r"""UKF predict step: sigma points of the belief through the motion model.

    .. math:: \bar\mu = \sum_i w_i\, g(\chi_i, u), \qquad
              \bar\Sigma = \sum_i w_i (g(\chi_i, u) - \bar\mu)(g(\chi_i, u) - \bar\mu)^\top + R

    Introduced in chapter 9.

    Parameters
    ----------
    mu : array_like, shape (n,)
    Sig : array_like, shape (n, n)
    u : array_like
        Control, passed to ``g`` unchanged.
    g : callable ``g(x, u) -> array (n,)``
    R : array_like, shape (n, n)
        Process-noise covariance.
    lam : float
        Spread parameter, ``n + lam > 0``.
    residual, mean : callable, optional
        State difference and weighted state mean (for a heading, use
        :func:`kfcourse.models.pose_residual` and :func:`kfcourse.models.pose_mean`).
    vectorized : bool
        Call the model and the residual hooks once with every sigma point as a
        row of a ``(2n+1, n)`` array instead of once per point (the models in
        :mod:`kfcourse.models` accept such stacks).  Same result, much faster.
    beta : float
        Added to the centre covariance weight, ``wc_0 = w_0 + beta`` (0 by
        default, the plain transform of the lesson).  The scaled unscented
        transform with parameters α, κ and β is this one with
        ``lam = α²(n + κ) - n`` and ``beta = 1 - α² + β``.

    Returns
    -------
    (mu_bar, Sig_bar) : shapes (n,), (n, n)
    """
    mu = v.vector(mu, "mu")
    n = mu.size
    Sig, R = v.covariance(Sig, "Sig", n), v.covariance(R, "R", n)
    g = v.function(g, "g")
    residual, mean = v.optional_function(residual, "residual"), v.optional_function(mean, "mean")
    lam, beta = v.scalar(lam, "lam"), v.scalar(beta, "beta")
    g_rows = _on_points(lambda x: g(x, u), "g", n, vectorized)
    return _ukf_predict(mu, Sig, g_rows, R, lam, beta, _on_rows(residual, vectorized), mean)


def _ukf_predict(mu, Sig, g, R, lam, beta, residual, mean):
    """:func:`ukf_predict` for checked arrays; ``g(chi)`` moves every sigma point (a row of chi) with the
    control bound in, and ``residual`` takes the stack."""
    chi, wm, wc = _sigma_points(mu, Sig, lam, beta)
    Y = g(chi)  # Y_i = g(chi_i, u)
    mu_bar, Sig_bar, _ = _recombine(Y, wm, wc, residual, mean)  # sum w_i Y_i, sum w_i (Y_i - mu_bar)(...)^T
    return mu_bar, Sig_bar + R  # Sig_bar = sum w_i (Y_i - mu_bar)(Y_i - mu_bar)^T + R


def ukf_update(
    mu_bar,
    Sig_bar,
    z,
    h: Callable,
    Q,
    lam: float,
    residual: Callable | None = None,
    mean: Callable | None = None,
    x_residual: Callable | None = None,
    vectorized: bool = False,
    *,
    beta: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    r"""UKF update step: the gain from the cross-covariance of the sigma clouds.

    .. math::
        \hat z = \sum_i w_i Z_i,\quad S = \sum_i w_i (Z_i - \hat z)(Z_i - \hat z)^\top + Q,\quad
        \Sigma_{xz} = \sum_i w_i (\chi_i - \bar\mu)(Z_i - \hat z)^\top

        K = \Sigma_{xz} S^{-1},\quad \mu = \bar\mu + K(z - \hat z),\quad \Sigma = \bar\Sigma - K S K^\top

    with :math:`Z_i = h(\chi_i)`.  Introduced in chapter 9.

    Parameters
    ----------
    mu_bar : array_like, shape (n,)
    Sig_bar : array_like, shape (n, n)
    z : array_like, shape (k,)
    h : callable ``h(x) -> array (k,)``
    Q : array_like, shape (k, k)
        Measurement-noise covariance.
    lam : float
        Spread parameter, ``n + lam > 0``.
    residual, mean : callable, optional
        Measurement difference and weighted mean (for a bearing, use
        :func:`kfcourse.models.range_bearing_residual` and
        :func:`kfcourse.models.range_bearing_mean`).
    x_residual : callable, optional
        State difference, for the cross-covariance.
    vectorized : bool
        Call the model and the residual hooks once with every sigma point as a
        row of a ``(2n+1, n)`` array instead of once per point (the models in
        :mod:`kfcourse.models` accept such stacks).  Same result, much faster.
    beta : float
        Added to the centre covariance weight, ``wc_0 = w_0 + beta`` (0 by
        default, the plain transform of the lesson).  The scaled unscented
        transform with parameters α, κ and β is this one with
        ``lam = α²(n + κ) - n`` and ``beta = 1 - α² + β``.

    Returns
    -------
    (mu, Sig) : shapes (n,), (n, n)
    """
    mu_bar, Sig_bar, z, Q = v.update_inputs(mu_bar, Sig_bar, z, Q)
    k = z.size
    h = v.function(h, "h")
    residual, mean = v.optional_function(residual, "residual"), v.optional_function(mean, "mean")
    x_residual = v.optional_function(x_residual, "x_residual")
    lam, beta = v.scalar(lam, "lam"), v.scalar(beta, "beta")
    h_rows = _on_points(h, "h", k, vectorized)
    z_residual, x_rows = _on_rows(residual, vectorized), _on_rows(x_residual, vectorized)
    z_hat, S, Sig_xz = _ukf_moments(mu_bar, Sig_bar, h_rows, Q, lam, beta, z_residual, mean, x_rows)
    K = gain(Sig_xz, S)  # K = Sig_xz S^-1
    y = z - z_hat if residual is None else np.asarray(residual(z, z_hat), dtype=float)  # innovation
    return _ukf_correct(mu_bar, Sig_bar, y, S, K)


def _ukf_moments(mu_bar, Sig_bar, h, Q, lam, beta, residual, mean, x_residual):
    """The sigma-point half of :func:`ukf_update` for checked arrays: the predicted measurement ``z_hat``, its
    covariance ``S`` and the cross-covariance ``Sig_xz``; ``h`` and both residual hooks take stacks of rows."""
    chi, wm, wc = _sigma_points(mu_bar, Sig_bar, lam, beta)
    Z = h(chi)  # Z_i = h(chi_i)
    z_hat, S, dZ = _recombine(Z, wm, wc, residual, mean)  # z_hat = sum w_i Z_i
    S = S + Q  # S = sum w_i (Z_i - z_hat)(Z_i - z_hat)^T + Q
    dX = chi - mu_bar if x_residual is None else x_residual(chi, mu_bar)  # chi_i - mu_bar
    Sig_xz = (wc[:, None] * dX).T @ dZ  # Sig_xz = sum w_i (chi_i - mu_bar)(Z_i - z_hat)^T
    return z_hat, S, Sig_xz


def _ukf_correct(mu_bar, Sig_bar, y, S, K):
    """The correction of :func:`ukf_update` with the innovation ``y``, its covariance ``S`` and the gain ``K``."""
    mu = mu_bar + K @ y  # mu = mu_bar + K y
    Sig = Sig_bar - K @ S @ K.T  # Sig = Sig_bar - K S K^T
    return mu, symmetric(Sig)
