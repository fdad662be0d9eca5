"""Many Kalman filters at once: the five matrix equations on a stack of N beliefs.

Every filter shares the model matrices (F, B, H, R, Q) but has its own mean,
covariance, control and reading.  NumPy's ``@`` broadcasts over the leading
axis, so the code reads like :func:`kf_step` with one more index.  Used for
Monte-Carlo checks such as the NEES in chapter 6.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as v

__all__ = ["kf_step_batch"]


def _stack(x, name: str, N: int | None, n: int | None) -> np.ndarray:
    """A finite (N, n) array: one row per filter."""
    a = v.finite(x, name)
    if a.ndim != 2 or (N is not None and a.shape[0] != N) or (n is not None and a.shape[1] != n):
        want = f"({'N' if N is None else N}, {'n' if n is None else n})"
        raise ValueError(f"{name} must have shape {want}, one row per filter, got {a.shape}")
    return a


def kf_step_batch(mu, Sig, u, z, F, B, H, R, Q) -> tuple[np.ndarray, np.ndarray]:
    r"""One full Kalman cycle for N filters at once, equal to N calls of :func:`kf_step`.

    .. math::
        \bar\mu_i = F\mu_i + Bu_i,\quad \bar\Sigma_i = F\Sigma_iF^\top + R,\quad
        K_i = \bar\Sigma_iH^\top(H\bar\Sigma_iH^\top + Q)^{-1},\quad
        \mu_i' = \bar\mu_i + K_i(z_i - H\bar\mu_i),\quad
        \Sigma_i' = (I - K_iH)\bar\Sigma_i

    for every filter :math:`i = 1 \dots N`; the covariance is computed in the Joseph
    form, as in :func:`kf_update`.  Introduced in chapter 6.

    Parameters
    ----------
    mu : array_like, shape (N, n)
        One mean per row.
    Sig : array_like, shape (N, n, n)
        One covariance per filter.
    u : array_like, shape (N, k), or None for no control
    z : array_like, shape (N, m), or None to predict only
    F : array_like, shape (n, n)
    B : array_like, shape (n, k), or None for no control
    H : array_like, shape (m, n)
    R : array_like, shape (n, n)
        Process-noise covariance, shared by all filters.
    Q : array_like, shape (m, m)
        Measurement-noise covariance, shared by all filters.

    Returns
    -------
    (mu, Sig) : shapes (N, n), (N, n, n)
    """
    mu = _stack(mu, "mu", None, None)
    N, n = mu.shape
    Sig = v.covariance_stack(Sig, "Sig", N, n)
    F = v.matrix(F, "F", n, n)
    R = v.covariance(R, "R", n)
    if (B is None) != (u is None):
        raise ValueError("u and B must be given together (or both None for no control)")

    mu_bar = mu @ F.T  # mu_bar = F mu (+ B u), one row per filter
    if B is not None:
        u = _stack(u, "u", N, None)
        B = v.matrix(B, "B", n, u.shape[1])
        mu_bar = mu_bar + u @ B.T
    Sig_bar = F @ Sig @ F.T + R  # Sig_bar = F Sig F^T + R
    if z is None:
        return mu_bar, 0.5 * (Sig_bar + Sig_bar.transpose(0, 2, 1))

    z = _stack(z, "z", N, None)
    m = z.shape[1]
    H = v.matrix(H, "H", m, n)
    Q = v.covariance(Q, "Q", m)
    PHt = Sig_bar @ H.T  # (N, n, m)
    S = H @ PHt + Q  # innovation covariance S = H Sig_bar H^T + Q, (N, m, m)
    try:
        K = np.linalg.solve(S, PHt.transpose(0, 2, 1)).transpose(0, 2, 1)  # K = Sig_bar H^T S^-1 (S symmetric)
    except np.linalg.LinAlgError:
        raise ValueError("Q: an innovation covariance S = H Sig_bar H^T + Q is singular") from None
    y = z - mu_bar @ H.T  # innovation y = z - H mu_bar
    mu_new = mu_bar + (K @ y[:, :, None])[:, :, 0]  # mu = mu_bar + K y
    I_KH = np.eye(n) - K @ H
    Sig_new = I_KH @ Sig_bar @ I_KH.transpose(0, 2, 1) + K @ Q @ K.transpose(0, 2, 1)  # Joseph form
    return mu_new, 0.5 * (Sig_new + Sig_new.transpose(0, 2, 1))
