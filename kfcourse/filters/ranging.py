"""One EKF update of a pose with a radio's range to a beacon at a known position (chapter 12).

Chapter 12's exercise (a) writes this update by hand; ``kf.check.range_update`` compares an answer
with it.  The equations live in one place: :func:`kfcourse.ekf_update` with the range-only model
:func:`kfcourse.models.range_only` and its Jacobian.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from .. import _validate as v
from ..models import range_only, range_only_jacobian
from .ekf import ekf_update


def range_update(mu_bar, Sig_bar, z, beacon, Q) -> tuple[np.ndarray, np.ndarray]:
    r"""EKF update of a pose ``[x, y, theta]`` with one range to a beacon at a known position.

    With :math:`p = (x, y)` the predicted position and :math:`r = \lVert p - b \rVert`:

    .. math::
        \hat z = r, \quad H = \begin{bmatrix} \dfrac{x - b_x}{r} & \dfrac{y - b_y}{r} & 0 \end{bmatrix},
        \quad S = H\bar\Sigma H^\top + Q, \quad K = \bar\Sigma H^\top S^{-1},

    .. math:: \mu = \bar\mu + K\,(z - \hat z), \qquad \Sigma = (I - KH)\,\bar\Sigma

    (the covariance in Joseph form, as :func:`kfcourse.ekf_update` computes it).  A range does not
    depend on the heading, so it moves :math:`\theta` only through :math:`\bar\Sigma`'s correlation of
    :math:`\theta` with :math:`x` and :math:`y`; with none, :math:`\theta` comes back unchanged.  The
    heading is returned as the update leaves it, not wrapped (wrap it with :func:`kfcourse.wrap_angle`
    where a loop needs it).  A robot exactly at the beacon (``r = 0``) is refused with a ``ValueError``:
    there the range has no direction, and ``H`` is undefined.

    Introduced in chapter 12 (the student writes it; ``kf.sim.range_localize``'s EKF takes the same
    update, then wraps the heading).

    Parameters
    ----------
    mu_bar : array_like, shape (3,)
        Predicted pose ``[x, y, theta]``.
    Sig_bar : array_like, shape (3, 3)
        Its covariance.
    z : array_like, shape (1,)
        The range read, in metres.
    beacon : array_like, shape (2,)
        The beacon's position ``[bx, by]``.
    Q : array_like, shape (1, 1)
        Variance of the range noise.

    Returns
    -------
    (mu, Sig) : shapes (3,), (3, 3)
    """
    mu_bar, Sig_bar = v.vector(mu_bar, "mu_bar", 3), v.covariance(Sig_bar, "Sig_bar", 3)
    z, beacon, Q = v.vector(z, "z", 1), v.vector(beacon, "beacon", 2), v.covariance(Q, "Q", 1)
    h = partial(range_only, beacon=beacon)  # z_hat = ||p - b||
    H = partial(range_only_jacobian, beacon=beacon)  # H = [(x - bx)/r, (y - by)/r, 0]; r = 0 raises
    return ekf_update(mu_bar, Sig_bar, z, h, H, Q)
