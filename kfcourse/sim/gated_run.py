"""One wild reading: a plain and a gated 1-D Kalman filter fed the same readings (chapter 4).

The robot stands still (``a = c = 1``, no command).  The plain filter uses every
reading.  The gated one first asks how surprising a reading is, as a Mahalanobis
distance, and skips it when the surprise is beyond the gate: that tick is a
predict without an update.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.association import mahalanobis
from ..filters.kalman_1d import kf_1d_predict, kf_1d_step, kf_1d_update
from .records import Record, text_table


@dataclass(frozen=True)
class OutlierRun(Record):
    """Both filters over the same readings.

    Every array has shape ``(n,)``; entry ``k - 1`` belongs to tick ``k = 1, ..., n``.
    Both filters start from ``N(mu0, var0)``.  Introduced in chapter 4.
    """

    z: np.ndarray  #: the reading of each tick (m)
    mu_plain: np.ndarray  #: the plain filter's estimate after each tick, every reading used (m)
    var_plain: np.ndarray  #: its variance (m^2)
    mu_bar: np.ndarray  #: the gated filter's prediction, chapter 3's equation (1) (m)
    var_bar: np.ndarray  #: its variance, chapter 3's equation (2) (m^2)
    S: np.ndarray  #: innovation variance var_bar + Q (m^2)
    d: np.ndarray  #: Mahalanobis distance |z - mu_bar| / sqrt(S) of each reading
    used: np.ndarray  #: bool: d <= gate, the gated filter updated with the reading
    mu_gated: np.ndarray  #: the gated filter's estimate after each tick (m)
    var_gated: np.ndarray  #: its variance (m^2)
    mu0: float  #: both filters' starting mean (m)
    var0: float  #: their starting variance (m^2)
    R: float  #: process noise variance (m^2)
    Q: float  #: measurement noise variance (m^2)
    gate: float  #: the gate, in standard deviations of surprise

    def table(self) -> str:
        """One line per tick: the reading, the plain estimate, the gate's verdict and the gated estimate."""
        rows = [
            [
                str(k),
                f"{self.z[k - 1]:.2f}",
                f"{self.mu_plain[k - 1]:.3f}",
                f"{self.d[k - 1]:.2f}",
                "used" if self.used[k - 1] else "SKIPPED",
                f"{self.mu_gated[k - 1]:.3f}",
            ]
            for k in range(1, len(self.z) + 1)
        ]
        header = ["tick", "reading (m)", "plain estimate (m)", "gated: d = |ν|/√S", "reading", "estimate (m)"]
        return text_table(header, rows)


def plain_and_gated(z, mu0, var0, R, Q, gate: float = 3.0) -> OutlierRun:
    r"""Run a plain and a gated scalar Kalman filter side by side over the readings ``z``.

    The robot stands still: ``a = c = 1`` and no command (``u = 0``).  The plain filter
    runs :func:`~kfcourse.kf_1d_step` on every reading.  The gated filter predicts with
    :func:`~kfcourse.kf_1d_predict` (chapter 3's equations (1) and (2)), measures the
    surprise of the reading with :func:`~kfcourse.mahalanobis`,

    .. math:: S = \bar\sigma^2 + \sigma_Q^2, \qquad d = \frac{|z - \bar\mu|}{\sqrt S},

    and updates with :func:`~kfcourse.kf_1d_update` (equations (3) to (5)) only if
    :math:`d \le` ``gate``; otherwise it keeps the prediction.  Introduced in chapter 4.

    Parameters
    ----------
    z : array_like, shape (n,)
        The readings, one per tick (m); at least one.
    mu0, var0 : float
        Mean (m) and variance (m², ``>= 0``) both filters start from.
    R : float
        Process noise variance (m², ``>= 0``).
    Q : float
        Measurement noise variance (m², ``> 0``).
    gate : float
        Readings with ``d > gate`` are skipped by the gated filter (standard deviations, ``> 0``).

    Returns
    -------
    OutlierRun
    """
    z = v.vector(z, "z")
    if z.size == 0:
        raise ValueError("z must hold at least one reading, got none")
    mu0 = v.scalar(mu0, "mu0")
    var0 = v.variance(var0, "var0")
    R = v.variance(R, "R")
    Q = v.positive(Q, "Q", "a measurement noise variance", "m²")
    gate = v.positive(gate, "gate", "a gate", "standard deviations")
    n = z.size
    mu_plain, var_plain, mu_bar, var_bar, d, mu_gated, var_gated = (np.empty(n) for _ in range(7))
    used = np.empty(n, dtype=bool)
    plain, gated = (mu0, var0), (mu0, var0)
    for k in range(n):
        plain = kf_1d_step(*plain, u=0.0, z=z[k], b=0.0, R=R, Q=Q)  # every reading used
        mu_bar[k], var_bar[k] = kf_1d_predict(*gated, u=0.0, b=0.0, R=R)  # equations (1), (2)
        d[k] = mahalanobis([z[k] - mu_bar[k]], [[var_bar[k] + Q]])  # d = |nu| / sqrt(S), S = var_bar + Q
        used[k] = d[k] <= gate
        if used[k]:  # an ordinary surprise: update as usual, equations (3) to (5)
            gated = kf_1d_update(mu_bar[k], var_bar[k], z[k], Q=Q)
        else:  # too surprising: keep the prediction, skip the update
            gated = (mu_bar[k], var_bar[k])
        mu_plain[k], var_plain[k] = plain
        mu_gated[k], var_gated[k] = gated
    return OutlierRun(
        z=z,
        mu_plain=mu_plain,
        var_plain=var_plain,
        mu_bar=mu_bar,
        var_bar=var_bar,
        S=var_bar + Q,
        d=d,
        used=used,
        mu_gated=mu_gated,
        var_gated=var_gated,
        mu0=mu0,
        var0=var0,
        R=R,
        Q=Q,
        gate=gate,
    )
