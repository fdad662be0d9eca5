"""The matrix Kalman filter of chapter 5: equations (1)-(5) on vectors and matrices.

Noise letters follow the course: ``R`` is the process (motion) noise covariance,
``Q`` the measurement (sensor) noise covariance.  The scalar filter of chapters 3
and 4 is in :mod:`kfcourse.filters.kalman_1d`.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as v

__all__ = ["kf_gain", "kf_predict", "kf_step", "kf_update"]


# ---------------------------------------------------------------- matrix form
# Equations (1)-(5) of chapter 5.  Each function below checks every input first, then writes
# its equations one per line, numbered as in the chapter.

SINGULAR_S = "Q: the innovation covariance S = H Sig_bar H^T + Q is singular, so the gain S^-1 is undefined"


def _predict_inputs(mu, Sig, u, F, B, R):
    """``mu, Sig, u, F, B, R`` checked, as float arrays; no control (``u`` and ``B`` None) becomes ``B u = 0``."""
    mu = v.vector(mu, "mu")
    n = mu.size
    F = v.matrix(F, "F", n, n)
    if (B is None) != (u is None):
        raise ValueError("u and B must be given together (or both None for no control)")
    u = np.zeros(0) if u is None else v.vector(u, "u")
    B = np.zeros((n, 0)) if B is None else v.matrix(B, "B", n, u.size)
    return mu, v.covariance(Sig, "Sig", n), u, F, B, v.covariance(R, "R", n)


def kf_predict(mu, Sig, u, F, B, R) -> tuple[np.ndarray, np.ndarray]:
    r"""Kalman predict step, equations (1) and (2) of chapter 5.

    .. math:: \bar\mu = F\mu + Bu, \qquad \bar\Sigma = F\Sigma F^\top + R

    Introduced in chapter 5.

    Parameters
    ----------
    mu : array_like, shape (n,)
    Sig : array_like, shape (n, n)
    u : array_like, shape (m,), or None for no control
    F : array_like, shape (n, n)
        State-transition matrix.
    B : array_like, shape (n, m), or None for no control
        Control matrix.
    R : array_like, shape (n, n)
        Process-noise covariance.

    Returns
    -------
    (mu_bar, Sig_bar) : shapes (n,), (n, n)
    """
    mu, Sig, u, F, B, R = _predict_inputs(mu, Sig, u, F, B, R)
    mu_bar = F @ mu + B @ u  # (1) predict mean
    Sig_bar = F @ Sig @ F.T + R  # (2) predict covariance
    return mu_bar, (Sig_bar + Sig_bar.T) / 2  # symmetric, also in the last bit


def kf_gain(Sig_bar, H, Q) -> tuple[np.ndarray, np.ndarray]:
    r"""Innovation covariance and Kalman gain, equation (3) of chapter 5.

    .. math:: S = H\bar\Sigma H^\top + Q, \qquad K = \bar\Sigma H^\top S^{-1}

    Introduced in chapter 5.

    Parameters
    ----------
    Sig_bar : array_like, shape (n, n)
    H : array_like, shape (k, n)
    Q : array_like, shape (k, k)

    Returns
    -------
    (S, K) : shapes (k, k), (n, k)
    """
    Sig_bar = v.covariance(Sig_bar, "Sig_bar")
    H = v.matrix(H, "H", None, Sig_bar.shape[0])
    Q = v.covariance(Q, "Q", H.shape[0])
    S = H @ Sig_bar @ H.T + Q  # (3) innovation covariance
    try:
        K = Sig_bar @ H.T @ np.linalg.inv(S)  # (3) Kalman gain
    except np.linalg.LinAlgError:
        raise ValueError(SINGULAR_S) from None
    return S, K


def kf_update(mu_bar, Sig_bar, z, H, Q) -> tuple[np.ndarray, np.ndarray]:
    r"""Kalman update (correction) step, equations (3) to (5) of chapter 5.

    .. math::
        K = \bar\Sigma H^\top (H\bar\Sigma H^\top + Q)^{-1},\quad
        \mu = \bar\mu + K(z - H\bar\mu),\quad
        \Sigma = (I - KH)\bar\Sigma

    Equation (5) is computed in its Joseph form
    :math:`(I-KH)\bar\Sigma(I-KH)^\top + KQK^\top`: equal to :math:`(I-KH)\bar\Sigma` for
    the optimal gain, and a sum of two terms :math:`A M A^\top` with :math:`M` a covariance,
    so it is symmetric positive semi-definite for any gain :math:`K`, up to the rounding of
    its own products (it does not make rounding vanish).  A gain error :math:`\Delta K`
    moves it only by :math:`\Delta K\, S\, \Delta K^\top`.  The result is averaged with its
    transpose, so it is exactly symmetric.  Introduced in chapter 5.

    Parameters
    ----------
    mu_bar : array_like, shape (n,)
    Sig_bar : array_like, shape (n, n)
    z : array_like, shape (k,)
    H : array_like, shape (k, n)
        Measurement matrix.
    Q : array_like, shape (k, k)
        Measurement-noise covariance.

    Returns
    -------
    (mu, Sig) : shapes (n,), (n, n)
    """
    mu_bar, Sig_bar, z, Q = v.update_inputs(mu_bar, Sig_bar, z, Q)
    H = v.matrix(H, "H", None, mu_bar.size)
    v.reading_size(z=(z.size, v.LENGTH), H=(H.shape[0], v.ROWS), Q=(Q.shape[0], v.SQUARE))
    S = H @ Sig_bar @ H.T + Q  # (3) innovation covariance
    try:
        K = Sig_bar @ H.T @ np.linalg.inv(S)  # (3) Kalman gain
    except np.linalg.LinAlgError:
        raise ValueError(SINGULAR_S) from None
    mu = mu_bar + K @ (z - H @ mu_bar)  # (4) update mean by the innovation z - H mu_bar
    I_KH = np.eye(mu_bar.size) - K @ H
    Sig = I_KH @ Sig_bar @ I_KH.T + K @ Q @ K.T  # (5) update covariance, Joseph form of (I - K H) Sig_bar
    return mu, (Sig + Sig.T) / 2


def kf_step(mu, Sig, u, z, F, B, H, R, Q) -> tuple[np.ndarray, np.ndarray]:
    r"""One full Kalman cycle, equations (1) to (5) of chapter 5.

    .. math::
        \bar\mu = F\mu + Bu,\quad \bar\Sigma = F\Sigma F^\top + R,\quad
        K = \bar\Sigma H^\top (H\bar\Sigma H^\top + Q)^{-1},\quad
        \mu' = \bar\mu + K(z - H\bar\mu),\quad \Sigma' = (I - KH)\bar\Sigma

    :func:`kf_predict` then :func:`kf_update` in one function, equation (5) in its Joseph
    form (see :func:`kf_update`).  Introduced in chapter 5.

    Parameters
    ----------
    mu, Sig, u, F, B, R
        As in :func:`kf_predict`.
    z : array_like, shape (k,), or None
        The reading; ``None`` skips the update (a predict-only tick).
    H, Q
        As in :func:`kf_update`.

    Returns
    -------
    (mu, Sig) : shapes (n,), (n, n)
    """
    mu, Sig, u, F, B, R = _predict_inputs(mu, Sig, u, F, B, R)
    if z is not None:
        z, H, Q = v.vector(z, "z"), v.matrix(H, "H", None, mu.size), v.covariance(Q, "Q")
        v.reading_size(z=(z.size, v.LENGTH), H=(H.shape[0], v.ROWS), Q=(Q.shape[0], v.SQUARE))

    mu_bar = F @ mu + B @ u  # (1) predict mean
    Sig_bar = F @ Sig @ F.T + R  # (2) predict covariance
    if z is None:
        return mu_bar, (Sig_bar + Sig_bar.T) / 2
    S = H @ Sig_bar @ H.T + Q  # (3) innovation covariance
    try:
        K = Sig_bar @ H.T @ np.linalg.inv(S)  # (3) Kalman gain
    except np.linalg.LinAlgError:
        raise ValueError(SINGULAR_S) from None
    mu_new = mu_bar + K @ (z - H @ mu_bar)  # (4) update mean by the innovation z - H mu_bar
    I_KH = np.eye(mu.size) - K @ H
    Sig_new = I_KH @ Sig_bar @ I_KH.T + K @ Q @ K.T  # (5) update covariance, Joseph form of (I - K H) Sig_bar
    return mu_new, (Sig_new + Sig_new.T) / 2
