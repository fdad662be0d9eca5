"""The records of a drive round the loop (chapters 8-11): what a filter made of it (:class:`Track`), and the whole lap
with the truth measured against the filter (:class:`LoopRun`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .records import Record, text_table
from .scores import verdict


@dataclass(frozen=True)
class Track(Record):
    """What a filter made of a drive (:func:`localize`); one row per step ``k = 0 .. T-1``."""

    mu_bar: np.ndarray  #: (T, n) predicted mean, before the updates of step k
    Sig_bar: np.ndarray  #: (T, n, n) predicted covariance
    mu: np.ndarray  #: (T, n) estimate after the updates of step k
    Sig: np.ndarray  #: (T, n, n) its covariance
    used: np.ndarray  #: (T, L) bool: the readings the filter used (in view and inside the gate)
    matched: np.ndarray  #: (T, L) int: the landmark the reading of landmark j was used as, -1 where not used


@dataclass(frozen=True)
class LoopRun(Record):
    """One drive round the loop and the filter that followed it; arrays have one row per step ``k = 0 .. T-1``.

    Step ``k``: the filter predicts with ``odometry[k]`` (giving ``mu_bar[k]``,
    ``Sig_bar[k]``), then updates with the readings ``z[k, used[k]]`` one landmark
    at a time (giving ``mu[k]``, ``Sig[k]``), each as the reading of the landmark
    ``matched[k, j]``: its own with labelled readings, the one it was matched to without.
    """

    t: np.ndarray  #: (T,) time after each step (s)
    dt: float  #: time step (s)
    truth: np.ndarray  #: (T, 3) true pose [x, y, theta] after each step
    odometry: np.ndarray  #: (T, 2) the controls [V, omega] the filter is told
    landmarks: np.ndarray  #: (L, 2) the map (m)
    z: np.ndarray  #: (T, L, 2) readings [r, phi]; zeros where out of range
    used: np.ndarray  #: (T, L) bool: readings the filter used (in range, the sensor not blind, inside the gate)
    rejected: np.ndarray  #: (T, L) bool: readings in range while the sensor could see, but outside the gate
    matched: np.ndarray  #: (T, L) int: the map index the reading of landmark j was used as, -1 where not used
    start: np.ndarray  #: (3,) the true pose before the first step
    mu0: np.ndarray  #: (3,) the filter's mean at the start: the true start unless it was told otherwise
    Sig0: np.ndarray  #: (3, 3) the filter's covariance at the start
    mu_bar: np.ndarray  #: (T, 3) predicted mean, before the updates of step k
    Sig_bar: np.ndarray  #: (T, 3, 3) predicted covariance
    mu: np.ndarray  #: (T, 3) estimate after the updates of step k
    Sig: np.ndarray  #: (T, 3, 3) its covariance
    error: np.ndarray  #: (T,) distance between the estimated and the true position (m)
    inside: np.ndarray  #: (T,) bool: the true position lies inside the 3-sigma position ellipse
    area: np.ndarray  #: (T,) area of the 1-sigma position ellipse, pi sqrt(det Sig_xy) (m^2)
    nees: np.ndarray  #: (T,) position NEES e^T Sig_xy^-1 e: 2 on average for an honest filter (chapter 6)
    filter: str  #: "ekf", "ukf", or the name of the step function that ran
    dropout: tuple[int, int] | None  #: the sensor is blind for steps t0 <= k < t1
    one_back: bool  #: at step t1 the sensor read only the nearest landmark: sight came back one landmark first
    motion_noise: float  #: scale of the world's odometry noise
    sensor_noise: float  #: scale of the world's reading noise
    filter_motion_noise: float  #: scale of the odometry noise the filter assumes (its R)
    filter_sensor_noise: float  #: scale of the reading noise the filter assumes (its Q)
    kidnap: int | None  #: step at which the true robot was carried half a lap further on
    wrap_bearing: bool  #: whether the bearing innovation was wrapped to (-pi, pi]
    gate: float | None  #: validation gate in standard deviations, or None
    labelled: bool  #: the readings came with the landmark they belong to; if not, nearest-neighbour association
    seed: int

    @property
    def share_inside(self) -> float:
        """Share of the steps with the truth inside the 3-sigma ellipse (0 to 1)."""
        return float(self.inside.mean())

    def honesty(self, k: int | None = None) -> tuple[float, str]:
        """The mean position NEES over steps 0 to ``k`` (by default the whole run) and what it says.

        An honest filter's position NEES is 2 on average (chapter 6).  Its mean over a lap
        stays within :data:`HONEST_NEES`, a band wider than chapter 6's for independent
        draws because one lap's errors are correlated from step to step.  Below it the
        filter is *timid* (its ellipse is larger than its errors), above it *over-confident*.
        """
        k = len(self.t) - 1 if k is None else int(k)
        mean = float(self.nees[: k + 1].mean())
        return mean, verdict(mean)

    def table(self, steps) -> str:
        """One line per step of ``steps``: readings used and rejected, error, 1-sigma area before and after."""
        rows = []
        for k in steps:
            bar = np.pi * np.sqrt(np.linalg.det(self.Sig_bar[k, :2, :2]))
            rows.append(
                [
                    str(k),
                    str(int(self.used[k].sum())),
                    str(int(self.rejected[k].sum())),
                    f"{np.linalg.norm(self.truth[k, :2] - self.mu_bar[k, :2]):.2f}",
                    f"{self.error[k]:.2f}",
                    f"{bar:.3g}",
                    f"{self.area[k]:.3g}",
                    "yes" if self.inside[k] else "no",
                ]
            )
        header = ["step", "used", "rejected", "error before (m)", "after", "1σ area before (m²)", "after", "inside 3σ"]
        return text_table(header, rows)
