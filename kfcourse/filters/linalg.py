"""The linear-algebra steps that every Kalman-family update shares.

Introduced in chapter 5 and reused by the EKF (chapter 7), data association
(chapter 8) and the UKF (chapter 9).  These functions take arrays that the
public functions have already checked, so they check nothing themselves.
They write ``A.dot(B)`` for the matrix product ``A @ B``: on the small matrices
of a filter it costs half as much.
"""

from __future__ import annotations

import numpy as np

__all__ = ["gain", "innovation_covariance", "joseph_correct", "symmetric"]


def symmetric(A: np.ndarray) -> np.ndarray:
    r"""The symmetric part :math:`(A + A^\top)/2` of a square matrix.

    A covariance computed as a product of matrices is symmetric only up to
    rounding; this makes it exactly symmetric.  Introduced in chapter 5.

    Parameters
    ----------
    A : ndarray, shape (n, n)

    Returns
    -------
    ndarray, shape (n, n)
    """
    return 0.5 * (A + A.T.copy())  # a contiguous copy of A^T adds faster than the transposed view


def innovation_covariance(Sig_bar: np.ndarray, H: np.ndarray, Q: np.ndarray) -> np.ndarray:
    r"""Covariance of the innovation :math:`z - H\bar\mu`.

    .. math:: S = H\bar\Sigma H^\top + Q

    Introduced in chapter 5.

    Parameters
    ----------
    Sig_bar : ndarray, shape (n, n)
        Predicted covariance.
    H : ndarray, shape (k, n)
        Measurement matrix (or the Jacobian of the measurement model).
    Q : ndarray, shape (k, k)
        Measurement-noise covariance.

    Returns
    -------
    ndarray, shape (k, k)
    """
    return H.dot(Sig_bar).dot(H.T) + Q  # S = H Sig_bar H^T + Q


def gain(Sig_xz: np.ndarray, S: np.ndarray) -> np.ndarray:
    r"""Kalman gain from the state-measurement cross-covariance.

    .. math:: K = \Sigma_{xz} S^{-1}

    For the linear filter and the EKF :math:`\Sigma_{xz} = \bar\Sigma H^\top`;
    the UKF computes it from its sigma points.  Introduced in chapter 5.

    Parameters
    ----------
    Sig_xz : ndarray, shape (n, k)
        Cross-covariance of state and measurement.
    S : ndarray, shape (k, k)
        Innovation covariance.

    Returns
    -------
    ndarray, shape (n, k)

    Raises
    ------
    ValueError
        If ``S`` is singular (a measurement that is exact in some direction the
        prediction is also certain of); the message names ``Q``.
    """
    try:
        return Sig_xz.dot(np.linalg.inv(S))  # K = Sig_xz S^-1
    except np.linalg.LinAlgError:
        raise ValueError("Q: the innovation covariance S is singular, so the gain S^-1 is undefined") from None


def joseph_correct(mu_bar, Sig_bar, y, H, Q, K) -> tuple[np.ndarray, np.ndarray]:
    r"""The correction step with a given gain, covariance in Joseph form.

    .. math::
        \mu = \bar\mu + K y, \qquad
        \Sigma = (I - KH)\bar\Sigma(I - KH)^\top + KQK^\top

    The Joseph form equals :math:`(I - KH)\bar\Sigma` for the optimal gain but
    stays symmetric positive semi-definite under rounding.  Introduced in chapter 5.

    Parameters
    ----------
    mu_bar : ndarray, shape (n,)
    Sig_bar : ndarray, shape (n, n)
    y : ndarray, shape (k,)
        Innovation, ``z - H mu_bar`` (or ``z - h(mu_bar)`` in the EKF).
    H : ndarray, shape (k, n)
    Q : ndarray, shape (k, k)
    K : ndarray, shape (n, k)
        Gain.

    Returns
    -------
    (mu, Sig) : shapes (n,), (n, n)
    """
    mu = mu_bar + K.dot(y)  # mu = mu_bar + K y
    I_KH = 0.0 - K.dot(H)  # I - K H: 0 - K H, and 1 added down the diagonal (quicker than building I)
    I_KH.ravel()[:: mu_bar.size + 1] += 1.0
    Sig = I_KH.dot(Sig_bar).dot(I_KH.T) + K.dot(Q).dot(K.T)  # Joseph form of (I - K H) Sig_bar
    return mu, symmetric(Sig)
