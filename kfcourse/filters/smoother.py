"""The Rauch–Tung–Striebel (RTS) smoother of chapter 12: what we know afterwards.

A filter's belief at step k uses the readings up to step k.  Once the run is over, the
readings after step k say something about it too: the smoother runs backwards over the
filter's stored results and gives each step the belief given *every* reading of the run,
equations (5)-(7) of the section "Smoothing: what we know afterwards" (the chapter's (1)-(4)
are the range update of its exercise).  It needs the future, so it is for afterwards (mapping,
a log's replay), never for a robot in motion.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v

__all__ = ["ekf_rts_smoother", "rts_smoother"]


def _run(x, name: str, T: int | None = None, n: int | None = None) -> np.ndarray:
    """A finite (T, n) array, one vector a row, T >= 1 and n >= 1 (a 1-D array is refused, not read as one row:
    the T means of a scalar state would pass for one mean of length T)."""
    a = v.finite(x, name)
    T_want, n_want = "T" if T is None else T, "n" if n is None else n
    if a.ndim != 2 or (T is not None and a.shape[0] != T) or (n is not None and a.shape[1] != n):
        raise ValueError(f"{name} must have shape ({T_want}, {n_want}), one step a row, got {a.shape}")
    if a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError(f"{name} must have at least one step and one state, got shape {a.shape}")
    return a


def _smoother_inputs(mu, Sig, mu_bar, Sig_bar, residual):
    """``mu, Sig, mu_bar, Sig_bar, residual`` checked: (T, n), (T, n, n), (T, n), (T, n, n), callable or None."""
    mu = _run(mu, "mu")
    T, n = mu.shape
    Sig = v.covariance_stack(Sig, "Sig", T, n)
    mu_bar = _run(mu_bar, "mu_bar", T, n)
    Sig_bar = v.covariance_stack(Sig_bar, "Sig_bar", T, n)
    return mu, Sig, mu_bar, Sig_bar, v.optional_function(residual, "residual")


def _transitions(F, T: int, n: int) -> np.ndarray:
    """``F`` as a (T, n, n) stack: one (n, n) matrix is used at every step."""
    F = v.finite(F, "F")
    if F.ndim == 2 and F.shape == (n, n):
        return np.broadcast_to(F, (T, n, n))
    if F.ndim == 3 and F.shape == (T, n, n):
        return F
    raise ValueError(f"F must have shape ({n}, {n}) or ({T}, {n}, {n}), one transition per step, got {F.shape}")


def rts_smoother(mu, Sig, mu_bar, Sig_bar, F, residual: Callable | None = None) -> tuple[np.ndarray, np.ndarray]:
    r"""The Rauch–Tung–Striebel smoother, equations (5) to (7) of chapter 12.

    Runs backwards over a filter's stored results, for k = T-2 down to 0, from
    :math:`\mu^s_{T-1} = \mu_{T-1}`, :math:`\Sigma^s_{T-1} = \Sigma_{T-1}`:

    .. math::
        C_k = \Sigma_k F_{k+1}^\top \bar\Sigma_{k+1}^{-1},\quad
        \mu^s_k = \mu_k + C_k(\mu^s_{k+1} - \bar\mu_{k+1}),\quad
        \Sigma^s_k = \Sigma_k + C_k(\Sigma^s_{k+1} - \bar\Sigma_{k+1})C_k^\top

    Step k's smoothed belief is its belief given every reading of the run, past and
    future: the smoother is for afterwards, not for a robot in motion.  The smoothed
    covariances are averaged with their transposes, so they are exactly symmetric.
    Introduced in chapter 12.

    Parameters
    ----------
    mu : array_like, shape (T, n)
        The filtered means, one step a row (T >= 1).
    Sig : array_like, shape (T, n, n)
        The filtered covariances.
    mu_bar : array_like, shape (T, n)
        The predicted means: row k is the prediction of step k made from step k-1.
        Row 0 is not used, but must be given.
    Sig_bar : array_like, shape (T, n, n)
        The predicted covariances, as ``mu_bar``; rows 1 to T-1 must be invertible.
    F : array_like, shape (n, n) or (T, n, n)
        The state-transition matrix, or one per step: ``F[k]`` is the transition (or the
        motion Jacobian) of the prediction that made ``mu_bar[k]`` from ``mu[k-1]``;
        ``F[0]`` is not used.
    residual : callable ``residual(a, b) -> a - b``, optional
        Difference of states; pass :func:`kfcourse.models.pose_residual` so that a heading
        difference is wrapped to (-pi, pi].  Each smoothed mean of (6) is then given back
        as ``residual(mu_s, 0)``: its angles wrapped, as the filter keeps them.

    Returns
    -------
    (mu_s, Sig_s) : shapes (T, n), (T, n, n)
        The smoothed means and covariances; the last row is the filtered one.
    """
    mu, Sig, mu_bar, Sig_bar, residual = _smoother_inputs(mu, Sig, mu_bar, Sig_bar, residual)
    T, n = mu.shape
    F = _transitions(F, T, n)
    mu_s, Sig_s = mu.copy(), Sig.copy()  # the last step: nothing comes after it
    for k in range(T - 2, -1, -1):
        try:  # C_k^T = Sig_bar_{k+1}^-1 F_{k+1} Sig_k, both covariances symmetric
            C = np.linalg.solve(Sig_bar[k + 1], F[k + 1] @ Sig[k]).T  # (5) smoother gain
        except np.linalg.LinAlgError:
            raise ValueError(
                f"Sig_bar[{k + 1}] must be invertible: the predicted covariance is singular, "
                "so the smoother gain C = Sig F^T Sig_bar^-1 is undefined"
            ) from None
        if residual is None:
            d = mu_s[k + 1] - mu_bar[k + 1]  # what the future taught step k+1
        else:
            d = v.output(residual(mu_s[k + 1], mu_bar[k + 1]), "residual", n)  # the same, angles wrapped
        mu_s[k] = mu[k] + C @ d  # (6) smoothed mean: mu_k + C_k (mu^s_{k+1} - mu_bar_{k+1})
        if residual is not None:
            mu_s[k] = v.output(residual(mu_s[k], np.zeros(n)), "residual", n)  # its angles wrapped, as mu's
        Sig_k = Sig[k] + C @ (Sig_s[k + 1] - Sig_bar[k + 1]) @ C.T  # (7) smoothed covariance
        Sig_s[k] = (Sig_k + Sig_k.T) / 2  # symmetric, also in the last bit
    return mu_s, Sig_s


def ekf_rts_smoother(
    mu, Sig, mu_bar, Sig_bar, G: Callable, u, residual: Callable | None = None
) -> tuple[np.ndarray, np.ndarray]:
    r"""The extended RTS smoother: :func:`rts_smoother` with the motion Jacobians of an EKF run.

    .. math::
        F_{k+1} = G(\mu_k, u_{k+1}),\quad
        C_k = \Sigma_k F_{k+1}^\top \bar\Sigma_{k+1}^{-1},\quad
        \mu^s_k = \mu_k + C_k(\mu^s_{k+1} - \bar\mu_{k+1}),\quad
        \Sigma^s_k = \Sigma_k + C_k(\Sigma^s_{k+1} - \bar\Sigma_{k+1})C_k^\top

    The Jacobian of each prediction is taken at the filtered mean it started from, as
    :func:`kfcourse.filters.ekf.ekf_predict` took it; equations (5) to (7) are then those
    of :func:`rts_smoother`.  Step k's smoothed belief is its belief given every reading
    of the run, past and future: the smoother is for afterwards, not for a robot in motion.
    Introduced in chapter 12.

    Parameters
    ----------
    mu, Sig, mu_bar, Sig_bar
        As in :func:`rts_smoother`: the EKF's filtered and predicted beliefs, T steps.
    G : callable ``G(x, u) -> array (n, n)``
        The motion model's Jacobian with respect to ``x``, as given to ``ekf_predict``
        (for the robot, :func:`kfcourse.unicycle_jacobian` with ``dt`` bound).
    u : array_like, shape (T, m)
        The controls, one step a row: row k is the control of the prediction into step k
        (for the robot ``[V, omega]`` in m/s and rad/s); row 0 is not used.
    residual : callable ``residual(a, b) -> a - b``, optional
        As in :func:`rts_smoother`: :func:`kfcourse.models.pose_residual` for a pose.

    Returns
    -------
    (mu_s, Sig_s) : shapes (T, n), (T, n, n)
    """
    mu, Sig, mu_bar, Sig_bar, residual = _smoother_inputs(mu, Sig, mu_bar, Sig_bar, residual)
    T, n = mu.shape
    G = v.function(G, "G")
    u = v.finite(u, "u")
    if u.ndim == 0 or u.shape[0] != T:
        raise ValueError(f"u must have {T} rows, one control per step as mu has, got shape {u.shape}")
    F = np.empty((T, n, n))
    F[0] = np.eye(n)  # not used: nothing is predicted into step 0
    for k in range(1, T):
        F[k] = v.output_matrix(G(mu[k - 1], u[k]), "G", n, n)  # F_k = G(mu_{k-1}, u_k)
    return rts_smoother(mu, Sig, mu_bar, Sig_bar, F, residual)
