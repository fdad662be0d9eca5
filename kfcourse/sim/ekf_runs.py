"""An EKF driving a loop past a few landmarks, with the right or a wrong Jacobian (chapter 7).

The EKF's covariance rides the Jacobians.  Flip the sign of one row of ``H`` and
the filter still computes a gain, but it pushes the state the wrong way along the
directions that row describes: this module runs the same seeded drive through
both filters so their errors can be compared.

Chapters 8 and 9 compare loop runs the same way: :func:`wrap_failure_report` reads a
filter that forgets the bearing wrap step by step, :func:`comparison_table` puts the
EKF beside the UKF over several seeds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.ekf import ekf_predict, ekf_update
from ..models import (
    range_bearing,
    range_bearing_jacobian,
    range_bearing_residual,
    unicycle,
    unicycle_jacobian,
    wrap_angle,
)
from .loop_filters import localize
from .records import Record, read_only, text_table
from .robot import simulate_robot
from .scores import nees

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
    d2 = nees(world.truth[:, :2], track.mu[:, :2], track.Sig[:, :2, :2])  # e^T Sig_xy^-1 e
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


# --------------------------------------------------------------------------- chapters 8 and 9: loop runs side by side


def _rms(error) -> float:
    return float(np.sqrt(np.mean(np.square(error))))


def wrap_table(runs: dict) -> str:
    """Chapter 8: the same drives filtered with the bearing innovation wrapped and not wrapped, one line per seed.

    Introduced in chapter 8.

    Parameters
    ----------
    runs : dict
        seed -> (wrapped run, unwrapped run) of the same drive
        (:func:`kfcourse.sim.landmark_loop` with ``wrap_bearing`` True and False).

    Returns
    -------
    str
        For each filter its largest position error (m), its error at the end of the lap
        (cm) and the share of the steps with the truth inside its 3-sigma ellipse.
    """
    rows = []
    for seed, pair in runs.items():
        largest = [f"{run.error.max():.2f}" for run in pair]
        final = [f"{100 * run.error[-1]:.1f}" for run in pair]
        rows.append([str(seed), *largest, *final, *(f"{run.share_inside:.0%}" for run in pair)])
    header = ["seed", "largest error (m), wrapped", "not wrapped", "final error (cm), wrapped", "not wrapped"]
    return text_table([*header, "truth inside 3σ, wrapped", "not wrapped"], rows)


def wrap_failure_report(wrapped, unwrapped, steps: int = 16) -> str:
    r"""Chapter 8: the steps around the first bad reading of a filter that forgets the bearing wrap.

    ``wrapped`` and ``unwrapped`` are the same drive (:func:`kfcourse.sim.landmark_loop`
    with ``wrap_bearing`` True and False).  From the step before the two estimates part,
    one line per step: the landmarks used, the unwrapped filter's heading error
    (estimate minus truth, wrapped), its position error, how far its 3-sigma position
    ellipse reaches, :math:`3\sqrt{\lambda_{\max}(\Sigma_{xy})}`, and whether the truth is
    inside that ellipse.  Then the raw bearing innovations :math:`z - h(\bar\mu)` of the
    first two bad steps, the largest and the final error, when a second landmark is back
    in view after the filter was left with one, and how long the truth stays outside
    the ellipse.  Introduced in chapter 8.

    Parameters
    ----------
    wrapped, unwrapped : LoopRun
        The same drive, filtered with and without the wrap; they must part somewhere.
    steps : int
        Lines of the table (>= 2).

    Returns
    -------
    str
    """
    steps = v.whole(steps, "steps", 2)
    bad = unwrapped
    parted = np.flatnonzero(np.any(wrapped.mu != bad.mu, axis=1))
    if parted.size == 0:
        raise ValueError("wrapped and unwrapped must part somewhere: on this drive the wrap never mattered")
    k0 = int(parted[0])  # the first step where the two filters differ
    heading_err = wrap_angle(bad.mu[:, 2] - bad.truth[:, 2])
    reach = 3 * np.sqrt(np.linalg.eigvalsh(bad.Sig[:, :2, :2])[:, -1])  # how far the 3-sigma ellipse reaches
    rows = [
        [
            str(k),
            f"{bad.t[k]:.1f}",
            ", ".join(str(j) for j in np.flatnonzero(bad.used[k])),
            f"{heading_err[k]:+.2f}",
            f"{bad.error[k]:.2f}",
            f"{reach[k]:.2f}",
            "yes" if bad.inside[k] else "no",
        ]
        for k in range(k0 - 1, min(k0 - 1 + steps, len(bad.t)))
    ]
    header = ["step", "t (s)", "landmarks used", "heading error (rad)", "position error (m)", "3σ reach (m)", "inside"]
    lines = [text_table(header, rows)]
    for k in (k0, k0 + 1):
        raw = [bad.z[k, j, 1] - range_bearing(bad.mu_bar[k], bad.landmarks[j])[1] for j in np.flatnonzero(bad.used[k])]
        lines.append(f"step {k}: raw bearing innovations (z - h(mu_bar)) {np.round(raw, 2)} rad")
    one = k0 + int(np.flatnonzero(bad.used[k0:].sum(axis=1) < 2)[0])  # first step with a single landmark in view
    back = one + int(np.flatnonzero(bad.used[one:].sum(axis=1) >= 2)[0])  # a second landmark comes back
    lines.append(
        f"largest error {bad.error.max():.2f} m at t = {bad.t[bad.error.argmax()]:.1f} s; a second landmark is back "
        f"at t = {bad.t[back]:.1f} s, {bad.t[back] - bad.t[k0]:.1f} s after the first bad step; "
        f"at the end of the lap {100 * bad.error[-1]:.1f} cm"
    )
    last = k0 + int(np.flatnonzero(bad.inside[k0:])[0]) - 1  # last step of the stretch with the truth outside
    lines.append(
        f"truth outside the 3-sigma ellipse from step {k0} to {last} ({bad.t[last] - bad.t[k0] + bad.dt:.1f} s), "
        f"while the ellipse reaches {reach[k0 : last + 1].min():.2f} to {reach[k0 : last + 1].max():.2f} m"
    )
    return "\n".join(lines)


def comparison_table(runs: dict) -> str:
    """Chapter 9: the EKF and the UKF on the same drives, one line per seed, and how often the UKF wins.

    Introduced in chapter 9.

    Parameters
    ----------
    runs : dict
        seed -> (EKF run, UKF run) of the same drive, run records with ``error`` and
        ``share_inside`` (:func:`kfcourse.sim.landmark_loop`).

    Returns
    -------
    str
        The RMS position error of each filter and the share of the steps with the truth
        inside its 3-sigma ellipse; then in how many seeds the UKF's RMS error is smaller.
    """
    rows, wins = [], 0
    for seed, (ekf, ukf) in runs.items():
        wins += _rms(ukf.error) < _rms(ekf.error)
        cells = [f"{_rms(ekf.error):.2f} m", f"{_rms(ukf.error):.2f} m", f"{ekf.share_inside:.0%}"]
        rows.append([str(seed), *cells, f"{ukf.share_inside:.0%}"])
    header = ["seed", "EKF RMS", "UKF RMS", "EKF in 3-sigma", "UKF in 3-sigma"]
    return text_table(header, rows) + f"\nthe UKF's RMS error is smaller in {wins} of {len(runs)} seeds"
