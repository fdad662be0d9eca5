"""An EKF driving a loop past a few landmarks, with the right or a wrong Jacobian (chapter 7).

The EKF's covariance rides the Jacobians.  Flip the sign of one row of ``H`` and
the filter still computes a gain, but it pushes the state the wrong way along the
directions that row describes: this module runs the same seeded drive through
both filters so their errors can be compared.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.ekf import ekf_predict, ekf_update
from ..models import range_bearing, range_bearing_jacobian, range_bearing_residual, unicycle, unicycle_jacobian
from .localization import localize
from .records import Record, read_only
from .robot import simulate_robot

# Two landmarks inside the default loop (x from -4 to 4 m, y from 0 to 5 m).
TWO_LANDMARKS = read_only([[-2.0, 2.5], [2.0, 2.5]])


@dataclass(frozen=True)
class EkfRun(Record):
    """One EKF over a simulated drive; every array has one row per time step ``k = 0 .. T-1``."""

    t: np.ndarray  #: (T,) time of each pose (s)
    truth: np.ndarray  #: (T, 3) true pose [x, y, theta]
    landmarks: np.ndarray  #: (L, 2) the map (m)
    mu: np.ndarray  #: (T, 3) the filter's estimate after the update of step k
    Sig: np.ndarray  #: (T, 3, 3) its covariance
    error: np.ndarray  #: (T,) distance between estimated and true position (m)
    inside: np.ndarray  #: (T,) bool: the true position lies inside the estimate's 3-sigma ellipse
    flipped: bool  #: True if the filter used H with its bearing row's sign flipped
    seed: int

    @property
    def final_error(self) -> float:
        """Position error at the last step (m)."""
        return float(self.error[-1])

    @property
    def share_inside(self) -> float:
        """Share of the steps with the truth inside the 3-sigma ellipse (0 to 1)."""
        return float(self.inside.mean())


def flipped_bearing_jacobian(state, landmark) -> np.ndarray:
    """:func:`~kfcourse.models.range_bearing_jacobian` with its bearing row's sign flipped: a deliberate bug.

    Introduced in chapter 7.

    Returns
    -------
    ndarray, shape (2, 3)
    """
    H = range_bearing_jacobian(state, landmark)
    H[1] = -H[1]  # the wrong sign on every bearing derivative
    return H


def run_ekf(flipped: bool = False, seed: int = 0, landmarks=None) -> EkfRun:
    r"""Drive one lap of the default loop past ``landmarks`` and filter it with the EKF.

    Predict with :func:`~kfcourse.models.unicycle` and its Jacobian from the noisy
    odometry, update with every visible range-bearing reading (bearing innovation
    wrapped).  The filter's noise matrices are the simulation's true ones:
    :math:`R = \mathrm{diag}(0.05, 0.05, 0.01)^2` per step,
    :math:`Q = \mathrm{diag}(\sigma_r^2, \sigma_\phi^2)`.  The truth counts as inside
    the 3-sigma ellipse when :math:`e^\top \Sigma_{xy}^{-1} e \le 9`, ``e`` the
    position error and :math:`\Sigma_{xy}` the position block.  Introduced in chapter 7.

    Parameters
    ----------
    flipped : bool
        Use :func:`flipped_bearing_jacobian` instead of the true ``H``.
    seed : int
        Seed of the simulation (>= 0).
    landmarks : array_like, shape (L, 2), optional
        The map (m); by default :data:`TWO_LANDMARKS`.

    Returns
    -------
    EkfRun
    """
    flipped = v.flag(flipped, "flipped")
    seed = v.whole(seed, "seed", 0)
    world = simulate_robot(landmarks=TWO_LANDMARKS if landmarks is None else landmarks, sensor_range=6.0, seed=seed)
    H_of = flipped_bearing_jacobian if flipped else range_bearing_jacobian
    dt = world.dt
    R = np.diag([0.05, 0.05, 0.01]) ** 2  # process noise per step (x, y, theta)
    Q = np.diag([world.range_std, world.bearing_std]) ** 2  # measurement noise (r, phi)

    def predict(mu, Sig, u):
        return ekf_predict(mu, Sig, u, lambda x, c: unicycle(x, c, dt), lambda x, c: unicycle_jacobian(x, c, dt), R)

    def update(mu_bar, Sig_bar, z, m):
        h, H = lambda x: range_bearing(x, m), lambda x: H_of(x, m)
        return ekf_update(mu_bar, Sig_bar, z, h, H, Q, residual=range_bearing_residual)

    track = localize(world, predict, update, np.diag([0.01, 0.01, 0.001]))
    e = world.truth[:, :2] - track.mu[:, :2]
    d2 = np.einsum("ti,tij,tj->t", e, np.linalg.inv(track.Sig[:, :2, :2]), e)  # e^T Sig_xy^-1 e
    return EkfRun(
        t=world.t,
        truth=world.truth,
        landmarks=world.landmarks,
        mu=track.mu,
        Sig=track.Sig,
        error=np.linalg.norm(e, axis=1),
        inside=d2 <= 9.0,
        flipped=flipped,
        seed=seed,
    )
