"""The extended Kalman filter.

Introduced in chapter 7: means go through the nonlinear models ``g`` and ``h``,
covariances through their Jacobians ``G`` and ``H``.  Each step checks its inputs
and the models' results, then writes the chapter's equations, one a line.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v


def ekf_predict(mu, Sig, u, g: Callable, G: Callable, R) -> tuple[np.ndarray, np.ndarray]:
    r"""EKF predict step.

    .. math:: \bar\mu = g(\mu, u), \qquad \bar\Sigma = G\Sigma G^\top + R,
              \qquad G = \left.\partial g/\partial x\right|_{\mu}

    Introduced in chapter 7.

    Parameters
    ----------
    mu : array_like, shape (n,)
    Sig : array_like, shape (n, n)
    u : array_like
        Control, passed to ``g`` and ``G`` unchanged.
    g : callable ``g(x, u) -> array (n,)``
        Motion model.
    G : callable ``G(x, u) -> array (n, n)``
        Its Jacobian with respect to ``x``.
    R : array_like, shape (n, n)
        Process-noise covariance.

    Returns
    -------
    (mu_bar, Sig_bar) : shapes (n,), (n, n)
    """
    mu = v.vector(mu, "mu")
    n = mu.size
    Sig, R = v.covariance(Sig, "Sig", n), v.covariance(R, "R", n)
    g, G = v.function(g, "g"), v.function(G, "G")
    mu_bar = v.output(g(mu, u), "g", n)  # mu_bar = g(mu, u): the mean rides the real curve
    G_t = v.output_matrix(G(mu, u), "G", n, n)  # G at the previous mean
    Sig_bar = G_t @ Sig @ G_t.T + R  # Sig_bar = G Sig G^T + R: the covariance rides the tangent
    return mu_bar, (Sig_bar + Sig_bar.T) / 2


def ekf_update(
    mu_bar, Sig_bar, z, h: Callable, H: Callable, Q, residual: Callable | None = None
) -> tuple[np.ndarray, np.ndarray]:
    r"""EKF update step.

    .. math::
        K = \bar\Sigma H^\top (H\bar\Sigma H^\top + Q)^{-1},\quad
        \mu = \bar\mu + K\,(z - h(\bar\mu)),\quad
        \Sigma = (I - KH)\bar\Sigma,\qquad H = \left.\partial h/\partial x\right|_{\bar\mu}

    The covariance is computed in Joseph form.  Introduced in chapter 7.

    Parameters
    ----------
    mu_bar : array_like, shape (n,)
    Sig_bar : array_like, shape (n, n)
    z : array_like, shape (k,)
    h : callable ``h(x) -> array (k,)``
        Measurement model (bind a landmark with ``functools.partial`` or a lambda).
    H : callable ``H(x) -> array (k, n)``
        Its Jacobian.
    Q : array_like, shape (k, k)
        Measurement-noise covariance.
    residual : callable ``residual(a, b) -> a - b``, optional
        Innovation; pass :func:`kfcourse.models.range_bearing_residual` so that a
        bearing innovation is wrapped to (-pi, pi].

    Returns
    -------
    (mu, Sig) : shapes (n,), (n, n)
    """
    mu_bar, Sig_bar, z, Q = v.update_inputs(mu_bar, Sig_bar, z, Q)
    n, k = mu_bar.size, z.size
    h, H = v.function(h, "h"), v.function(H, "H")
    residual = v.optional_function(residual, "residual")
    z_hat = v.output(h(mu_bar), "h")  # predicted reading h(mu_bar)
    v.reading_size(z=(k, v.LENGTH), **{"the result of h": (z_hat.size, v.LENGTH)}, Q=(Q.shape[0], v.SQUARE))
    H_t = v.output_matrix(H(mu_bar), "H", k, n)  # H at the predicted mean
    y = z - z_hat if residual is None else v.output(residual(z, z_hat), "residual", k)  # innovation
    S = H_t @ Sig_bar @ H_t.T + Q  # S = H Sig_bar H^T + Q
    try:
        K = Sig_bar @ H_t.T @ np.linalg.inv(S)  # K = Sig_bar H^T S^-1
    except np.linalg.LinAlgError:
        raise ValueError("Q: the innovation covariance S = H Sig_bar H^T + Q is singular") from None
    mu = mu_bar + K @ y  # mu = mu_bar + K (z - h(mu_bar))
    I_KH = np.eye(n) - K @ H_t
    Sig = I_KH @ Sig_bar @ I_KH.T + K @ Q @ K.T  # Joseph form of (I - K H) Sig_bar
    return mu, (Sig + Sig.T) / 2
