"""The extended Kalman filter.

Introduced in chapter 7: means go through the nonlinear models ``g`` and ``h``,
covariances through their Jacobians ``G`` and ``H``.

The public steps check their inputs and the models' results, then call the
private cores below them, which take checked arrays and models trusted to
return finite arrays of the right shape (a run engine that checked its inputs
once calls the cores on every step).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v
from .linalg import gain, innovation_covariance, joseph_correct, symmetric


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
    return _ekf_predict(
        mu,
        Sig,
        u,
        lambda x, c: v.output(g(x, c), "g", n),  # the models' results checked
        lambda x, c: v.output_matrix(G(x, c), "G", n, n),
        R,
    )


def _ekf_predict(mu, Sig, u, g, G, R):
    """:func:`ekf_predict` for checked arrays and models that return an (n,) vector and an (n, n) matrix."""
    mu_bar = g(mu, u)  # mu_bar = g(mu, u): the mean rides the real curve
    Gt = G(mu, u)  # G at the previous mean
    Sig_bar = Gt @ Sig @ Gt.T + R  # Sig_bar = G Sig G^T + R: the covariance rides the tangent
    return mu_bar, symmetric(Sig_bar)


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
    y, Ht, S = _ekf_innovation(
        mu_bar,
        Sig_bar,
        z,
        lambda x: v.output(h(x), "h", k),  # the models' results checked
        lambda x: v.output_matrix(H(x), "H", k, n),
        Q,
        None if residual is None else lambda a, b: v.output(residual(a, b), "residual", k),
    )
    return _ekf_correct(mu_bar, Sig_bar, y, Ht, S, Q)


def _ekf_innovation(mu_bar, Sig_bar, z, h, H, Q, residual):
    """The first half of :func:`ekf_update` for checked arrays and trusted models: the innovation ``y``, the
    Jacobian ``H`` at ``mu_bar`` and the innovation covariance ``S``, all a validation gate needs."""
    z_hat = h(mu_bar)  # predicted measurement h(mu_bar)
    Ht = H(mu_bar)  # H at the predicted mean
    y = z - z_hat if residual is None else residual(z, z_hat)  # innovation
    S = innovation_covariance(Sig_bar, Ht, Q)  # S = H Sig_bar H^T + Q
    return y, Ht, S


def _ekf_correct(mu_bar, Sig_bar, y, Ht, S, Q):
    """The second half of :func:`ekf_update`: gain and correction, from :func:`_ekf_innovation`'s results."""
    K = gain(Sig_bar @ Ht.T, S)  # K = Sig_bar H^T S^-1
    return joseph_correct(mu_bar, Sig_bar, y, Ht, Q, K)
