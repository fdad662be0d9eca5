"""One step of EKF localization on a map of known landmarks: the capstone's filter (chapter 10).

Chapter 10 writes this step as the student's exercise; ``kf.check.localization_step``
compares an answer with it, and ``kf.sim.landmark_loop``'s EKF takes the same steps.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from .. import _validate as v
from ..models import (
    range_bearing,
    range_bearing_jacobian,
    range_bearing_residual,
    unicycle,
    unicycle_control_jacobian,
    unicycle_jacobian,
    wrap_angle,
)
from .ekf import ekf_predict, ekf_update


def _pairs(x, name: str, k: int | None = None) -> np.ndarray:
    """A finite (k, 2) array, one reading or landmark a row; any empty array is (0, 2)."""
    a = v.finite(x, name)
    if a.size == 0:
        a = a.reshape(0, 2)
    if a.ndim != 2 or a.shape[1] != 2 or (k is not None and a.shape[0] != k):
        want = "(k, 2)" if k is None else f"({k}, 2), one row per reading of z"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    return a


def _gate(x) -> float:
    """A gate in standard deviations: a number > 0, np.inf allowed (no gate)."""
    try:
        gate = float(np.asarray(x, dtype=float).reshape(()))
    except (TypeError, ValueError):
        raise ValueError(f"gate must be a number of standard deviations > 0 (np.inf: no gate), got {x!r}") from None
    if not gate > 0:
        raise ValueError(f"gate must be a number of standard deviations > 0 (np.inf: no gate), got {gate}")
    return gate


def ekf_localization_step(mu, Sig, u, z, landmarks, dt, M, Q, gate) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""One step of EKF localization: predict with the odometry, then gate and update with each reading in turn.

    .. math::
        \bar\mu = g(\mu, u), \quad \bar\Sigma = G\Sigma G^\top + W M W^\top; \qquad
        \text{for each reading } z_j:\ \nu = [z_j - h_j(\mu)]_{\text{wrapped}},\
        S = H_j \Sigma H_j^\top + Q,\ \text{used if } \nu^\top S^{-1} \nu \le \gamma^2

    with ``g`` the unicycle, ``G`` and ``W`` its Jacobians with respect to the pose and the
    control, ``h_j`` the range-bearing model of landmark ``j`` and ``H_j`` its Jacobian.
    Each reading is linearized at the *current* mean (after the previous reading's update),
    and the heading of each update's result is wrapped into (-pi, pi].

    Introduced in chapter 10 (the student writes it; ``kf.sim.landmark_loop``'s EKF with
    ``gate=4`` takes the same steps).

    Parameters
    ----------
    mu : array_like, shape (3,)
        Estimate ``[x, y, theta]`` after the previous step.
    Sig : array_like, shape (3, 3)
        Its covariance.
    u : array_like, shape (2,)
        Odometry ``[V, omega]`` for this step (m/s, rad/s).
    z : array_like, shape (k, 2)
        Readings ``[r, phi]`` of the k landmarks in view; k may be 0 (then only the prediction happens).
    landmarks : array_like, shape (k, 2)
        Those landmarks' positions, row j the landmark of ``z[j]``.
    dt : float
        Time step (s), > 0.
    M : array_like, shape (2, 2)
        Covariance of the odometry noise.
    Q : array_like, shape (2, 2)
        Covariance of the reading noise.
    gate : float
        Validation gate in standard deviations, > 0; ``np.inf`` uses every reading.

    Returns
    -------
    mu : ndarray, shape (3,)
    Sig : ndarray, shape (3, 3)
    used : ndarray of bool, shape (k,)
        Which readings were used (inside the gate).
    """
    mu, u = v.vector(mu, "mu", 3), v.vector(u, "u", 2)
    Sig = v.covariance(Sig, "Sig", 3)
    z = _pairs(z, "z")
    landmarks = _pairs(landmarks, "landmarks", z.shape[0])
    dt = v.positive(dt, "dt", "a time step", "s")
    M, Q = v.covariance(M, "M", 2), v.covariance(Q, "Q", 2)
    gate = _gate(gate)

    # (1) predict with the unicycle; the odometry noise M reaches the pose through W: R = W M W^T
    W = unicycle_control_jacobian(mu, u, dt)
    R = W @ M @ W.T
    g = lambda x, c: unicycle(x, c, dt)  # noqa: E731
    G = lambda x, c: unicycle_jacobian(x, c, dt)  # noqa: E731
    mu, Sig = ekf_predict(mu, Sig, u, g, G, R)

    used = np.zeros(z.shape[0], dtype=bool)
    for j, (z_j, m) in enumerate(zip(z, landmarks, strict=True)):  # one reading at a time
        h, H = partial(range_bearing, landmark=m), partial(range_bearing_jacobian, landmark=m)
        # (2) linearize at the current mean: innovation nu (bearing wrapped) and its covariance S
        H_j = H(mu)
        nu = range_bearing_residual(z_j, h(mu))  # nu = z_j - h_j(mu), bearing wrapped
        S = H_j @ Sig @ H_j.T + Q  # S = H_j Sig H_j^T + Q
        # (3) gate: use the reading only if nu^T S^-1 nu <= gate^2
        try:
            d2 = nu @ np.linalg.solve(S, nu)  # the squared Mahalanobis distance nu^T S^-1 nu
        except np.linalg.LinAlgError:
            raise ValueError("Q: the innovation covariance S = H Sig H^T + Q is singular") from None
        if d2 > gate**2:
            continue
        # (4) update with it, the bearing innovation wrapped
        mu, Sig = ekf_update(mu, Sig, z_j, h, H, Q, range_bearing_residual)
        # (5) wrap the heading: the update may push it past pi
        mu[2] = wrap_angle(mu[2])
        used[j] = True
    return mu, Sig, used
