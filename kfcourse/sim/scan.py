"""One scan of a range-bearing sensor on a known map, and which reading belongs to which landmark (chapter 8).

The robot has just predicted: its belief is N(mu_bar, Sig_bar), a few tens of
centimetres off the truth.  Its sensor returns one reading [r, phi] per landmark
of the map and, if a pedestrian stands nearby, one more from a leg.  The readings
come unlabelled: :func:`gated_update` matches each one to the landmark with the
smallest Mahalanobis distance, rejects it if even that one lies outside the
validation gate, and runs the EKF update once per accepted reading
(:func:`landmark_update`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.association import associate
from ..filters.ekf import ekf_update
from ..models import range_bearing, range_bearing_jacobian, range_bearing_residual, wrap_angle
from .records import Record, read_only

# The scene (m, rad).  The belief after the predict step, and where the robot really is.
SCAN_LANDMARKS = read_only([[3.5, 1.5], [0.5, 3.5], [-3.0, 1.0], [0.0, -3.0]])
SCAN_MU_BAR = read_only([0.0, 0.0, 0.5])  # predicted pose [x, y, theta]
SCAN_SIG_BAR = read_only([[0.08, 0.02, 0.0], [0.02, 0.05, 0.0], [0.0, 0.0, 0.008]])  # its covariance
SCAN_TRUTH = read_only([0.3, -0.25, 0.42])  # the true pose, 2.1 standard deviations from mu_bar
SCAN_LEG = read_only([0.85, -2.15])  # a pedestrian's leg, 1.2 m from landmark 3
RANGE_STD = 0.1  # m
BEARING_STD = 0.03  # rad


@dataclass(frozen=True)
class AssociationScan(Record):
    """One predicted belief, the map and one scan of unlabelled readings.

    ``K`` readings (one per landmark, then the leg's if there is one), ``L`` landmarks.
    """

    truth: np.ndarray  #: (3,) true pose [x, y, theta]
    mu_bar: np.ndarray  #: (3,) predicted pose
    Sig_bar: np.ndarray  #: (3, 3) its covariance
    landmarks: np.ndarray  #: (L, 2) the map (m)
    Q: np.ndarray  #: (2, 2) measurement-noise covariance of one reading [r, phi]
    z: np.ndarray  #: (K, 2) the readings [r, phi], in the order the sensor returns them
    source: np.ndarray  #: (K,) int: the landmark that produced each reading, -1 for the leg
    z_hat: np.ndarray  #: (L, 2) each landmark's predicted reading h(mu_bar, m_j)
    S: np.ndarray  #: (L, 2, 2) each landmark's innovation covariance H_j Sig_bar H_j^T + Q
    leg: np.ndarray | None  #: (2,) where the leg stands, or None
    seed: int


@dataclass(frozen=True)
class GatedUpdate(Record):
    """Every reading of a scan matched (or rejected) at one gate, and the EKF estimate after the updates."""

    gate: float  #: the validation gate gamma (standard deviations)
    distances: np.ndarray  #: (K, L) Mahalanobis distance of reading k from landmark j's predicted reading
    match: np.ndarray  #: (K,) int: the landmark each reading was matched to, -1 if rejected
    mu: np.ndarray  #: (3,) estimate after the updates with every accepted reading
    Sig: np.ndarray  #: (3, 3) its covariance
    error_bar: float  #: position error of the prediction mu_bar (m)
    error: float  #: position error of the estimate mu (m)

    @property
    def accepted(self) -> np.ndarray:
        """(K,) bool: the reading passed the gate."""
        return self.match >= 0


def association_scan(seed: int = 0, leg: bool = False) -> AssociationScan:
    """The chapter 8 scene: a predicted belief, a map of four landmarks and one noisy scan.

    The readings are taken from the true pose, with noise of standard deviation
    0.1 m in range and 0.03 rad in bearing.  With ``leg=True`` the sensor also
    sees a pedestrian's leg standing 1.2 m from landmark 3; its reading comes last.
    Introduced in chapter 8.

    Parameters
    ----------
    seed : int
        Seed of the reading noise (>= 0).  The leg's reading gets its own noise,
        so the landmarks' readings are the same with and without it.
    leg : bool
        Add the leg's reading.

    Returns
    -------
    AssociationScan
    """
    seed = v.whole(seed, "seed", 0)
    leg = v.flag(leg, "leg")
    rng = np.random.default_rng(seed)
    Q = np.diag([RANGE_STD, BEARING_STD]) ** 2
    noise = rng.standard_normal((len(SCAN_LANDMARKS) + 1, 2)) * [RANGE_STD, BEARING_STD]  # drawn for the leg too
    z = np.array([range_bearing(SCAN_TRUTH, m) for m in SCAN_LANDMARKS]) + noise[:-1]  # z_j = h(truth, m_j) + noise
    source = np.arange(len(SCAN_LANDMARKS))
    if leg:
        z = np.vstack([z, range_bearing(SCAN_TRUTH, SCAN_LEG) + noise[-1]])
        source = np.append(source, -1)
    z[:, 1] = wrap_angle(z[:, 1])  # a sensor reports bearings in (-pi, pi], as h does
    Hs = [range_bearing_jacobian(SCAN_MU_BAR, m) for m in SCAN_LANDMARKS]
    return AssociationScan(
        truth=SCAN_TRUTH,
        mu_bar=SCAN_MU_BAR,
        Sig_bar=SCAN_SIG_BAR,
        landmarks=SCAN_LANDMARKS,
        Q=Q,
        z=z,
        source=source,
        z_hat=np.array([range_bearing(SCAN_MU_BAR, m) for m in SCAN_LANDMARKS]),  # z_hat_j = h(mu_bar, m_j)
        S=np.array([Hj @ SCAN_SIG_BAR @ Hj.T + Q for Hj in Hs]),  # S_j = H_j Sig_bar H_j^T + Q
        leg=SCAN_LEG if leg else None,
        seed=seed,
    )


def landmark_update(mu_bar, Sig_bar, z, landmark, Q) -> tuple[np.ndarray, np.ndarray]:
    """One EKF update of a pose with the range-bearing reading ``z`` of one known landmark.

    :func:`kfcourse.ekf_update` with chapter 7's ``h`` and ``H`` bound to ``landmark``
    and the bearing innovation wrapped (:func:`kfcourse.models.range_bearing_residual`).
    A scan of several landmarks is a sequence of these.  Introduced in chapter 8.

    Parameters
    ----------
    mu_bar : array_like, shape (3,)
        Predicted pose ``[x, y, theta]``.
    Sig_bar : array_like, shape (3, 3)
        Its covariance.
    z : array_like, shape (2,)
        The reading ``[r, phi]``.
    landmark : array_like, shape (2,)
        Where the landmark stands (m).
    Q : array_like, shape (2, 2)
        Measurement-noise covariance of the reading.

    Returns
    -------
    (mu, Sig)
    """
    m = v.vector(landmark, "landmark", 2)
    return ekf_update(
        mu_bar,
        Sig_bar,
        z,
        lambda x: range_bearing(x, m),
        lambda x: range_bearing_jacobian(x, m),
        Q,
        residual=range_bearing_residual,
    )


def gated_update(scan: AssociationScan, gate: float = 3.0) -> GatedUpdate:
    r"""Match every reading of ``scan`` to the map, then update the EKF with the accepted ones.

    Each reading is matched against the predicted belief (before any update of
    this scan) with :func:`kfcourse.filters.association.associate`: the
    landmark with the smallest Mahalanobis distance
    :math:`d_j = \sqrt{\nu_j^\top S_j^{-1}\nu_j}`, rejected if :math:`d_j > \gamma`.
    Then the accepted readings update the belief one after another, each with
    its matched landmark (bearing innovation wrapped).  Introduced in chapter 8.

    Parameters
    ----------
    scan : AssociationScan
    gate : float
        The validation gate :math:`\gamma` (> 0), in standard deviations.

    Returns
    -------
    GatedUpdate
    """
    if not isinstance(scan, AssociationScan):
        raise ValueError(f"scan must be an AssociationScan (kf.sim.association_scan), got {type(scan).__name__}")
    gate = v.positive(gate, "gate", "a distance", "standard deviations")
    match, distances = [], []
    for z in scan.z:
        j, d = associate(
            z,
            scan.mu_bar,
            scan.Sig_bar,
            scan.landmarks,
            range_bearing,
            range_bearing_jacobian,
            scan.Q,
            gate=gate,
            residual=range_bearing_residual,
        )
        match.append(-1 if j is None else j)
        distances.append(d)
    mu, Sig = scan.mu_bar, scan.Sig_bar
    for z, j in zip(scan.z, match, strict=True):
        if j < 0:
            continue  # outside the gate: not a landmark, not used
        mu, Sig = landmark_update(mu, Sig, z, scan.landmarks[j], scan.Q)
    return GatedUpdate(
        gate=gate,
        distances=np.array(distances, dtype=float),
        match=np.array(match, dtype=int),
        mu=mu,
        Sig=Sig,
        error_bar=float(np.linalg.norm(scan.mu_bar[:2] - scan.truth[:2])),
        error=float(np.linalg.norm(mu[:2] - scan.truth[:2])),
    )
