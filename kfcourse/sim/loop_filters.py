"""The localization loop of chapter 8 and the course's filters that run in it (chapters 8-11).

:func:`localize` predicts with the odometry, then for each reading in view finds its landmark (its label, or
the nearest neighbour of :func:`nearest_landmark`), gates it (:func:`gate_within`) and updates with it.
:func:`loop_filter` gives the ``predict`` and ``update`` of the course's EKF and UKF, whose process noise is the
odometry noise mapped into the pose (:func:`process_noise_of_odometry`).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v
from ..filters.association import associate, mahalanobis
from ..filters.ekf import ekf_predict, ekf_update
from ..filters.ukf import ukf_predict, ukf_update
from ..models import (
    pose_mean,
    pose_residual,
    range_bearing,
    range_bearing_jacobian,
    range_bearing_mean,
    range_bearing_residual,
    unicycle,
    unicycle_control_jacobian,
    unicycle_jacobian,
    wrap_angle,
)
from .loop_records import LoopRun, Track
from .robot import RobotRun

FILTERS = ("ekf", "ukf")
UKF_LAM = 0.0  # lambda = 3 - n for the pose (n = 3): centre weight 0, six points of weight 1/6


def process_noise_of_odometry(mu, u, dt: float, M) -> np.ndarray:
    r"""Process noise R of one step when the noise is in the odometry: the control noise mapped into the pose.

    .. math:: R = W M W^\top, \qquad W = \partial g / \partial u \text{ at } (\mu, u)

    ``W`` is :func:`~kfcourse.models.unicycle_control_jacobian`.  R has rank 2 (two noisy
    controls move three pose numbers).  Introduced in chapter 8.

    Parameters
    ----------
    mu : array_like, shape (3,)
        Pose at which to linearize.
    u : array_like, shape (2,)
        Odometry ``[V, omega]``.
    dt : float
        Time step (s).
    M : array_like, shape (2, 2)
        Covariance of the odometry noise.

    Returns
    -------
    ndarray, shape (3, 3)
    """
    mu = v.vector(mu, "mu", 3)  # each argument by its own name (the Jacobian would call mu "state")
    u = v.vector(u, "u", 2)
    dt = v.positive(dt, "dt", "a time step", "s")
    M = v.covariance(M, "M", 2)
    W = unicycle_control_jacobian(mu, u, dt)  # (3, 2): how each control moves the pose
    return W @ M @ W.T  # R = W M W^T


def localize(
    world: RobotRun,
    predict: Callable,
    update: Callable,
    Sig0,
    accept: Callable | None = None,
    *,
    mu0=None,
    identify: Callable | None = None,
    known: tuple[int, Track] | None = None,
) -> Track:
    """The localization loop of chapter 8: at each step predict with the odometry, then for each
    reading in view, find which landmark it belongs to, gate it and update with it, one landmark at a time.

    Introduced in chapter 8; chapter 7's :func:`~kfcourse.sim.run_ekf` and chapter 10's
    :func:`landmark_loop` run it.

    Parameters
    ----------
    world : RobotRun
        The drive (:func:`~kfcourse.sim.simulate_robot`): odometry, readings and the map.
    predict : callable ``predict(mu, Sig, odometry) -> (mu_bar, Sig_bar)``
    update : callable ``update(mu_bar, Sig_bar, z, landmark) -> (mu, Sig)``
    Sig0 : array_like, shape (n, n)
        The filter's covariance at the start.
    accept : callable ``accept(mu_bar, Sig_bar, z, landmark) -> bool``, optional
        The validation gate: a reading it refuses is not used.  By default every reading is.
    mu0 : array_like, shape (n,), optional
        The filter's mean at the start; by default the true start ``world.start``.
    identify : callable ``identify(mu_bar, Sig_bar, z) -> int or None``, optional
        Which landmark of the map a reading belongs to, worked out by the filter
        (:func:`nearest_landmark`), or ``None`` to refuse it.  By default the readings
        are labelled: the reading of landmark ``j`` is used as landmark ``j``'s.
    known : (int, Track), optional
        ``(k0, track)``: the first ``k0`` steps are already known, from a track of this filter
        over a world that is the same up to step ``k0``; they are copied, and the loop carries on
        from the estimate after step ``k0 - 1`` (a demo that changes only what comes later).

    Returns
    -------
    Track
    """
    world = _world(world)
    predict, update = v.function(predict, "predict"), v.function(update, "update")
    Sig0 = v.covariance(Sig0, "Sig0", len(world.start) if mu0 is None else None)
    accept = v.optional_function(accept, "accept")
    mu0 = world.start if mu0 is None else v.vector(mu0, "mu0", len(Sig0))
    identify = v.optional_function(identify, "identify")
    T, L = world.visible.shape
    known = None if known is None else _known(known, T)
    mu, Sig = np.array(mu0, dtype=float), np.array(Sig0, dtype=float)
    mu_bar, Sig_bar = np.empty((T, *mu.shape)), np.empty((T, *Sig.shape))
    mus, Sigs, used = np.empty_like(mu_bar), np.empty_like(Sig_bar), np.zeros((T, L), dtype=bool)
    matched = np.full((T, L), -1)
    k0 = 0
    if known is not None:  # copy the steps already known, then carry on from the last of them
        k0, track = known
        mine = {"mu_bar": mu_bar, "Sig_bar": Sig_bar, "mu": mus, "Sig": Sigs, "used": used, "matched": matched}
        for name, rows in mine.items():
            rows[:k0] = getattr(track, name)[:k0]
        if k0:
            mu, Sig = mus[k0 - 1].copy(), Sigs[k0 - 1].copy()
    for k in range(k0, T):
        mu, Sig = predict(mu, Sig, world.odometry[k])  # 1. predict with the odometry
        mu_bar[k], Sig_bar[k] = mu, Sig
        for j in np.flatnonzero(world.visible[k]):  # sequential updates, one reading at a time
            z = world.z[k, j]
            i = j if identify is None else identify(mu, Sig, z)  # 2. which landmark: the label, or the filter's guess
            if i is not None and (accept is None or accept(mu, Sig, z, world.landmarks[i])):  # 3. gate
                mu, Sig = update(mu, Sig, z, world.landmarks[i])  # 4. update as landmark i's reading
                used[k, j], matched[k, j] = True, i
        mus[k], Sigs[k] = mu, Sig
    return Track(mu_bar=mu_bar, Sig_bar=Sig_bar, mu=mus, Sig=Sigs, used=used, matched=matched)


def _world(world) -> RobotRun:
    if not isinstance(world, RobotRun):
        raise ValueError(f"world must be a RobotRun (kf.sim.simulate_robot), got {type(world).__name__}")
    return world


def _known(known, T: int) -> tuple[int, Track]:
    """``known`` of :func:`localize`: a pair (k0, track), the track's first k0 steps of the T to copy."""
    if not (isinstance(known, tuple) and len(known) == 2 and isinstance(known[1], Track | LoopRun)):
        got = type(known).__name__
        raise ValueError(f"known must be a pair (k0, track) of a step count and a Track or LoopRun, got {got}")
    k0, track = v.whole(known[0], "known[0]"), known[1]
    if k0 > min(T, len(track.mu)):
        raise ValueError(f"known[0] must be a step count up to {min(T, len(track.mu))}, the steps known; got {k0}")
    return k0, track


def loop_filter(filter: str, dt: float, M, Q, wrap_bearing: bool = True) -> tuple[Callable, Callable]:
    """The ``predict`` and ``update`` of the course's EKF or UKF on the unicycle and the range-bearing sensor.

    Both call the public filter steps.  The process noise is the odometry noise ``M``
    mapped into the pose (:func:`process_noise_of_odometry`); the update wraps the
    bearing innovation (unless ``wrap_bearing`` is False, chapter 8's bug) and the
    heading of the result.  The UKF uses λ = 0 and averages headings on the circle.
    Introduced in chapter 8 (EKF) and chapter 9 (UKF).
    """
    if not isinstance(filter, str) or filter not in FILTERS:
        raise ValueError(f"filter must be one of {FILTERS}, got {filter!r}")
    dt = v.positive(dt, "dt", "a time step", "s")
    M, Q = v.covariance(M, "M", 2), v.covariance(Q, "Q", 2)
    wrap_bearing = v.flag(wrap_bearing, "wrap_bearing")
    z_residual = range_bearing_residual if wrap_bearing else None
    z_mean = range_bearing_mean if wrap_bearing else None

    def predict(mu, Sig, u):
        R = process_noise_of_odometry(mu, u, dt, M)
        if filter == "ekf":
            return ekf_predict(mu, Sig, u, lambda x, c: unicycle(x, c, dt), lambda x, c: unicycle_jacobian(x, c, dt), R)
        return ukf_predict(mu, Sig, u, lambda X, c: unicycle(X, c, dt), R, UKF_LAM, pose_residual, pose_mean)

    def update(mu_bar, Sig_bar, z, m):
        h = lambda x: range_bearing(x, m)  # noqa: E731
        if filter == "ekf":
            H = lambda x: range_bearing_jacobian(x, m)  # noqa: E731
            mu, Sig = ekf_update(mu_bar, Sig_bar, z, h, H, Q, z_residual)
        else:
            mu, Sig = ukf_update(mu_bar, Sig_bar, z, h, Q, UKF_LAM, z_residual, z_mean, pose_residual)
        mu[2] = wrap_angle(mu[2])  # the update may push the heading past pi
        return mu, Sig

    return predict, update


def gate_within(gate: float, Q, wrap_bearing: bool = True) -> Callable:
    """A validation gate (chapter 8): accept a reading whose Mahalanobis distance from the landmark's
    predicted reading, with the linearized ``S = H Sig_bar H^T + Q``, is at most ``gate``."""
    gate = v.positive(gate, "gate", "a distance", "standard deviations")
    Q = v.covariance(Q, "Q", 2)
    wrap_bearing = v.flag(wrap_bearing, "wrap_bearing")

    def accept(mu_bar, Sig_bar, z, m) -> bool:
        z_hat, H = range_bearing(mu_bar, m), range_bearing_jacobian(mu_bar, m)
        y = range_bearing_residual(z, z_hat) if wrap_bearing else z - z_hat  # innovation
        return mahalanobis(y, H @ Sig_bar @ H.T + Q) <= gate

    return accept


def nearest_landmark(landmarks, gate: float | None, Q, wrap_bearing: bool = True) -> Callable:
    """Data association (chapter 8) for readings without labels: match a reading to the landmark of the map
    nearest in Mahalanobis distance (:func:`~kfcourse.associate`), or refuse it if even that one lies
    beyond ``gate``; with no gate (``None``) always the nearest.  Introduced in chapter 11."""
    residual = range_bearing_residual if wrap_bearing else None

    def identify(mu_bar, Sig_bar, z) -> int | None:
        h, H = range_bearing, range_bearing_jacobian
        best, dist = associate(z, mu_bar, Sig_bar, landmarks, h, H, Q, 1.0 if gate is None else gate, residual)
        return int(np.argmin(dist)) if gate is None else best  # no gate: the nearest, however far

    return identify
