"""Data association: which landmark produced a reading?

Introduced in chapter 8.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v


def mahalanobis(nu, S) -> float:
    r"""Mahalanobis length of an innovation (a distance, not squared).

    .. math:: d = \sqrt{\nu^\top S^{-1} \nu}

    It counts "how many standard deviations of surprise" ``nu`` is, given its
    covariance ``S``.  Introduced in chapter 4 (chapter 8 gates readings with it).

    Parameters
    ----------
    nu : array_like, shape (k,)
        Innovation.
    S : array_like, shape (k, k)
        Innovation covariance, positive definite.

    Returns
    -------
    float
    """
    nu = v.vector(nu, "nu")
    S = v.covariance(S, "S", nu.size)
    try:
        m2 = float(nu @ np.linalg.solve(S, nu))  # nu^T S^-1 nu
    except np.linalg.LinAlgError:
        raise ValueError("S must be positive definite (invertible)") from None
    return float(np.sqrt(max(m2, 0.0)))


def associate(
    z,
    mu_bar,
    Sig_bar,
    landmarks,
    h: Callable,
    H: Callable,
    Q,
    gate: float = 3.0,
    residual: Callable | None = None,
) -> tuple[int | None, np.ndarray]:
    r"""Gated nearest-neighbour association of one reading to a map.

    For each landmark :math:`j` the predicted reading :math:`\hat z_j = h(\bar\mu, m_j)`
    and its innovation covariance :math:`S_j = H_j \bar\Sigma H_j^\top + Q` give a
    Mahalanobis distance :math:`d_j`.  The reading is matched to the landmark with
    the smallest :math:`d_j`, unless even that one lies outside the validation
    gate :math:`d_j > \gamma`; then it is rejected (a pedestrian's leg, not a
    landmark).  Introduced in chapter 8.

    Parameters
    ----------
    z : array_like, shape (k,)
        The reading.
    mu_bar : array_like, shape (n,)
    Sig_bar : array_like, shape (n, n)
    landmarks : array_like, shape (L, d)
        Map, one landmark a row.
    h : callable ``h(x, landmark) -> array (k,)``
    H : callable ``H(x, landmark) -> array (k, n)``
    Q : array_like, shape (k, k)
    gate : float
        Largest accepted distance γ (> 0), in standard deviations.  For a 2-D
        reading the default 3 keeps 98.9 % of true matches; exactly 99 % needs
        γ = sqrt(-2 ln 0.01) = 3.035.
    residual : callable ``residual(a, b) -> a - b``, optional
        Innovation with angles wrapped.

    Returns
    -------
    (index or None, distances) : the matched row of ``landmarks`` (``None`` when
        gated out) and every landmark's distance, shape (L,).
    """
    mu_bar, Sig_bar, z, Q = v.update_inputs(mu_bar, Sig_bar, z, Q)
    v.reading_size(z=(z.size, v.LENGTH), Q=(Q.shape[0], v.SQUARE))
    lms = v.matrix(landmarks, "landmarks")
    gate = v.positive(gate, "gate", "a distance", "standard deviations")
    h, H = v.function(h, "h"), v.function(H, "H")
    residual = v.optional_function(residual, "residual")
    dist = np.empty(lms.shape[0])
    for j, m in enumerate(lms):
        z_hat = v.output(h(mu_bar, m), "h", z.size)
        Hj = v.output_matrix(H(mu_bar, m), "H", z.size, mu_bar.size)
        nu = z - z_hat if residual is None else v.output(residual(z, z_hat), "residual", z.size)
        S = Hj @ Sig_bar @ Hj.T + Q  # S_j = H_j Sig_bar H_j^T + Q
        dist[j] = mahalanobis(nu, S)  # d_j = sqrt(nu^T S^-1 nu)
    best = int(np.argmin(dist))
    return (best if dist[best] <= gate else None), dist
