"""Wrong (and a few right) solutions to chapter 12's exercise (a): the EKF update of a pose with one range.

The exercise: ``range_update(mu_bar, Sig_bar, z, beacon, Q) -> (mu, Sig)``, with (1) ẑ = ‖p − b‖ = r and
H = [(x − bx)/r, (y − by)/r, 0]; (2) S = HΣ̄Hᵀ + Q, K = Σ̄HᵀS⁻¹; (3) μ = μ̄ + K(z − ẑ); (4) Σ = (I − KH)Σ̄;
a robot exactly at the beacon (r = 0) refused with a ValueError.

Unlike the sets of chapters 0-11, this one was written by the checker's author, from the exercise's
equations as a student would read them, not by a reader who had not seen the checker: it measures less.
One mistake per wrong solution; the right ones take a style of their own.  The solutions may call
``kf.models.range_only`` and its Jacobian, as the exercise lets students do.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

import kfcourse as kf
from tests.check.wrong_set import right, wrong


def _offset(mu_bar, beacon):
    """x − bx, y − by and r, refusing r = 0 (as the exercise asks)."""
    dx, dy = mu_bar[0] - beacon[0], mu_bar[1] - beacon[1]
    r = math.hypot(dx, dy)
    if r == 0.0:
        raise ValueError("beacon: the robot stands on the beacon (r = 0), where the range has no direction")
    return dx, dy, r


def _gain(Sig_bar, H, Q):
    """K = Sig_bar H^T S^-1 with S = H Sig_bar H^T + Q."""
    S = H @ Sig_bar @ H.T + Q
    return Sig_bar @ H.T @ np.linalg.inv(S)


# ---------------------------------------------------------------- range_update (chapter 12)
@wrong(
    "range_update",
    equation="(1)",
    inputs=("beacon",),
    what="H from the robot to the beacon, (b - p)/r, as chapter 7's dx = m - x without the range row's minus",
)
def ro_offset_to_beacon(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[-dx / r, -dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(3)", inputs=("z",), what="the innovation backwards: z_hat - z")
def ro_innovation_backwards(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (np.array([r]) - z), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(2)", inputs=("Q",), what="S = H Sig_bar H^T, the range's noise Q left out")
def ro_S_without_Q(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(2)", inputs=("Q",), what="Q taken for the standard deviation and squared")
def ro_Q_squared(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q @ Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(1)", what="the predicted reading is q = dx^2 + dy^2, the square root forgotten")
def ro_squared_range(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - (dx**2 + dy**2)), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(1)", what="H = [x - bx, y - by, 0]: the offset not divided by r")
def ro_H_unnormalised(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx, dy, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(1)", what="H keeps the -1 of the bearing row's heading entry, from chapter 7")
def ro_heading_entry_from_bearing(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, -1.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(4)", inputs=("Sig_bar",), what="Sig = I - K H, Sig_bar forgotten")
def ro_forgets_Sig_bar(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), np.eye(3) - K @ H


@wrong("range_update", equation="(4)", what="the mean is updated, the covariance returned as it came")
def ro_covariance_unchanged(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), Sig_bar


@wrong("range_update", equation="(4)", what="Sig = Sig_bar (I - K H): the product the wrong way round")
def ro_covariance_product_reversed(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), Sig_bar @ (np.eye(3) - K @ H)


@wrong("range_update", equation="(3)", what="only x and y are updated: a range cannot move the heading, it thinks")
def ro_position_only(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    mu = np.array(mu_bar, dtype=float)
    mu[:2] += (K @ (z - r))[:2]
    return mu, (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(4)", what="H and K as 1-D arrays, so K @ H in I - K H is a dot product, a number")
def ro_one_d_arrays(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([dx / r, dy / r, 0.0])
    S = H @ Sig_bar @ H + Q[0, 0]
    K = Sig_bar @ H / S
    return mu_bar + K * (z[0] - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(1)", what="no test of r = 0: at the beacon 0/0 gives NaN")
def ro_no_guard_at_beacon(mu_bar, Sig_bar, z, beacon, Q):
    d = np.asarray(mu_bar[:2], dtype=float) - np.asarray(beacon, dtype=float)
    r = np.sqrt(d @ d)
    H = np.array([[d[0] / r, d[1] / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(1)", what="at the beacon the reading is skipped: the prediction is returned")
def ro_skips_at_beacon(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy = mu_bar[0] - beacon[0], mu_bar[1] - beacon[1]
    r = math.hypot(dx, dy)
    if r == 0.0:
        return mu_bar, Sig_bar
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(1)", what="r + 1e-9 everywhere, to keep clear of r = 0")
def ro_epsilon_in_r(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy = mu_bar[0] - beacon[0], mu_bar[1] - beacon[1]
    r = math.hypot(dx, dy) + 1e-9
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    return mu_bar + K @ (z - r), (np.eye(3) - K @ H) @ Sig_bar


@wrong("range_update", equation="(3)", inputs=("mu_bar",), what="the mean updated in place: mu_bar += K nu")
def ro_updates_in_place(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    K = _gain(Sig_bar, H, Q)
    mu_bar += K @ (z - r)
    return mu_bar, (np.eye(3) - K @ H) @ Sig_bar


@right("range_update", what="by hand on Python floats, K by np.linalg.solve, the Joseph-form covariance")
def ro_joseph_by_hand(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    H = np.array([[dx / r, dy / r, 0.0]])
    S = H @ Sig_bar @ H.T + Q
    K = np.linalg.solve(S, H @ Sig_bar).T  # K = Sig_bar H^T S^-1, S and Sig_bar symmetric
    A = np.eye(3) - K @ H
    return mu_bar + K @ (z - r), A @ Sig_bar @ A.T + K @ Q @ K.T


@right("range_update", what="kf.ekf_update with the range-only model and its Jacobian bound to the beacon")
def ro_with_the_package(mu_bar, Sig_bar, z, beacon, Q):
    h = partial(kf.models.range_only, beacon=beacon)
    H = partial(kf.models.range_only_jacobian, beacon=beacon)
    return kf.ekf_update(mu_bar, Sig_bar, z, h, H, Q)


@right("range_update", what="the scalar update written entry by entry, the heading wrapped with atan2(sin, cos)")
def ro_scalar_wrapped(mu_bar, Sig_bar, z, beacon, Q):
    dx, dy, r = _offset(mu_bar, beacon)
    h = np.array([dx / r, dy / r, 0.0])
    P = np.asarray(Sig_bar, dtype=float)
    Ph = P @ h  # Sig_bar H^T as a vector
    s = h @ Ph + float(np.ravel(Q)[0])  # S, a number
    k = Ph / s
    mu = np.asarray(mu_bar, dtype=float) + k * (float(np.ravel(z)[0]) - r)
    mu[2] = math.atan2(math.sin(mu[2]), math.cos(mu[2]))
    return mu, P - np.outer(k, Ph)  # (I - K H) Sig_bar = Sig_bar - K (H Sig_bar)
