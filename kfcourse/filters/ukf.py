"""Sigma points, the unscented transform and the unscented Kalman filter.

Introduced in chapter 9: "it is easier to approximate a distribution than a
function".  Sigma points use the lower Cholesky factor of ``(n + lam) Sig``.

The models and hooks take every sigma point at once, one a row of a ``(2n+1, n)``
array, and return one row per point (the models in :mod:`kfcourse.models` take such
stacks).  Each step checks its inputs and the models' results, then writes the
chapter's equations, one a line.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v


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
    lam, beta = v.scalar(lam, "lam"), v.scalar(beta, "beta")
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


def _on_points(result, name: str, rows: int, cols: int | None = None) -> np.ndarray:
    """The result of a model or hook called on every sigma point: one finite row per point."""
    return v.matrix(result, f"the result of {name}", rows, cols)


def _weighted_moments(Y, wm, wc, residual, mean):
    """Weighted mean and covariance of the transformed points (rows of Y), and the deviations from the mean."""
    y_mean = wm @ Y if mean is None else v.vector(mean(Y, wm), "the result of mean", Y.shape[1])  # sum w_i Y_i
    dY = Y - y_mean if residual is None else _on_points(residual(Y, y_mean), "residual", *Y.shape)  # Y_i - y
    cov = (wc[:, None] * dY).T @ dY  # sum w_i (Y_i - y)(Y_i - y)^T
    return y_mean, (cov + cov.T) / 2, dY


def unscented_transform(
    mu,
    Sig,
    f: Callable,
    lam: float,
    residual: Callable | None = None,
    mean: Callable | None = None,
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
    f : callable ``f(chi) -> array (2n+1, k)``
        Applied to every sigma point at once, one a row of ``chi``.
    lam : float
        Spread parameter, ``n + lam > 0``.
    residual : callable ``residual(points, b) -> points - b``, optional
        Difference of outputs, one a row (wrap angles here).
    mean : callable ``mean(points, weights) -> array (k,)``, optional
        Weighted mean of outputs (average angles on the circle here).
    beta : float
        Added to the centre covariance weight, as in :func:`sigma_points` (0 by default).

    Returns
    -------
    (mu_y, Sig_y) : shapes (k,), (k, k)
    """
    f = v.function(f, "f")
    residual, mean = v.optional_function(residual, "residual"), v.optional_function(mean, "mean")
    chi, wm, wc = sigma_points(mu, Sig, lam, beta)
    Y = _on_points(f(chi), "f", len(chi))  # Y_i = f(chi_i)
    y_mean, Sig_y, _ = _weighted_moments(Y, wm, wc, residual, mean)  # sum w_i Y_i, sum w_i (Y_i - y)(Y_i - y)^T
    return y_mean, Sig_y


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
    chi, wm, wc = sigma_points([mu], [[var]], lam)
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
    g : callable ``g(chi, u) -> array (2n+1, n)``
        Motion model, applied to every sigma point at once, one a row of ``chi``.
    R : array_like, shape (n, n)
        Process-noise covariance.
    lam : float
        Spread parameter, ``n + lam > 0``.
    residual, mean : callable, optional
        State difference and weighted state mean (for a heading, use
        :func:`kfcourse.models.pose_residual` and :func:`kfcourse.models.pose_mean`).
    beta : float
        Added to the centre covariance weight, as in :func:`sigma_points` (0 by default).

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
    chi, wm, wc = sigma_points(mu, Sig, lam, beta)
    Y = _on_points(g(chi, u), "g", len(chi), n)  # Y_i = g(chi_i, u)
    mu_bar, Sig_Y, _ = _weighted_moments(Y, wm, wc, residual, mean)  # mu_bar = sum w_i Y_i
    return mu_bar, Sig_Y + R  # Sig_bar = sum w_i (Y_i - mu_bar)(Y_i - mu_bar)^T + R


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
    h : callable ``h(chi) -> array (2n+1, k)``
        Measurement model, applied to every sigma point at once, one a row of ``chi``.
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
    beta : float
        Added to the centre covariance weight, as in :func:`sigma_points` (0 by default).

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
    chi, wm, wc = sigma_points(mu_bar, Sig_bar, lam, beta)
    Z = _on_points(h(chi), "h", len(chi))  # Z_i = h(chi_i)
    v.reading_size(z=(k, v.LENGTH), **{"the result of h": (Z.shape[1], "{} columns")}, Q=(Q.shape[0], v.SQUARE))
    z_hat, S_Z, dZ = _weighted_moments(Z, wm, wc, residual, mean)  # predicted reading z_hat = sum w_i Z_i
    S = S_Z + Q  # S = sum w_i (Z_i - z_hat)(Z_i - z_hat)^T + Q
    dX = chi - mu_bar if x_residual is None else _on_points(x_residual(chi, mu_bar), "x_residual", *chi.shape)
    Sig_xz = (wc[:, None] * dX).T @ dZ  # Sig_xz = sum w_i (chi_i - mu_bar)(Z_i - z_hat)^T
    try:
        K = Sig_xz @ np.linalg.inv(S)  # K = Sig_xz S^-1
    except np.linalg.LinAlgError:
        raise ValueError("Q: the innovation covariance S is singular, so the gain S^-1 is undefined") from None
    y = z - z_hat if residual is None else v.vector(residual(z, z_hat), "the result of residual", k)  # innovation
    mu = mu_bar + K @ y  # mu = mu_bar + K (z - z_hat)
    Sig = Sig_bar - K @ S @ K.T  # Sig = Sig_bar - K S K^T
    return mu, (Sig + Sig.T) / 2
