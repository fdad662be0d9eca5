"""A robot walking down a rail, filtered by the 1-D Kalman filter (chapter 3).

The world and the filter are described separately, so a run can show what goes
wrong when the filter's model does not match the world: a bad initial guess,
mistuned noise levels, or a velocity the motion model does not know about.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.kalman_1d import kf_1d_cycle
from .records import Record


@dataclass(frozen=True)
class WalkRun(Record):
    """One simulated run of the 1-D Kalman filter.

    Every array has shape ``(n_steps,)``; entry ``k - 1`` belongs to time step
    ``k = 1, ..., n_steps`` (``t``).  The belief before step 1 is
    ``N(mu0, var0)`` and the robot starts at ``x0``.  Introduced in chapter 3.
    """

    t: np.ndarray  #: time step k = 1 .. n_steps
    u: np.ndarray  #: commanded move of each step (m), what the filter's model knows
    truth: np.ndarray  #: true position after each step (m)
    z: np.ndarray  #: sensor reading at each step (m)
    mu_bar: np.ndarray  #: predicted mean, equation (1) (m)
    var_bar: np.ndarray  #: predicted variance, equation (2) (m^2)
    innovation: np.ndarray  #: z - mu_bar (m)
    S: np.ndarray  #: innovation variance var_bar + Q (m^2): the spread the filter expects of the innovation
    K: np.ndarray  #: Kalman gain, equation (3)
    mu: np.ndarray  #: updated mean, equation (4) (m)
    var: np.ndarray  #: updated variance, equation (5) (m^2)
    x0: float  #: true start position (m)
    mu0: float  #: initial guess (m)
    var0: float  #: initial variance (m^2)
    R: float  #: process noise variance the filter assumes (m^2)
    Q: float  #: measurement noise variance the filter assumes (m^2)
    R_true: float  #: process noise variance of the world (m^2)
    Q_true: float  #: measurement noise variance of the world (m^2)
    velocity: float  #: extra move per step the model does not know (m)
    seed: int

    def error(self) -> np.ndarray:
        """Estimation error ``mu - truth`` (m), shape ``(n_steps,)``; negative means behind the robot."""
        return self.mu - self.truth

    def rms_error(self, start: int = 0) -> float:
        """Root-mean-square estimation error (m) over the steps from index ``start`` on."""
        return float(np.sqrt(np.mean(self.error()[start:] ** 2)))

    def rms_reading_error(self, start: int = 0) -> float:
        """Root-mean-square error (m) of trusting each reading blindly, from index ``start`` on."""
        return float(np.sqrt(np.mean((self.z[start:] - self.truth[start:]) ** 2)))

    def mean_innovation(self, start: int = 0) -> float:
        """Average innovation (m) from index ``start`` on; about 0 when the model is right."""
        return float(np.mean(self.innovation[start:]))

    def innovations_inside(self, start: int = 0) -> float:
        """Fraction of innovations inside ``±sqrt(S)`` from index ``start`` on; about 0.68 when the
        filter's noise levels match the world's."""
        return float(np.mean(np.abs(self.innovation[start:]) <= np.sqrt(self.S[start:])))

    def truth_inside(self, start: int = 0) -> float:
        """Fraction of steps from index ``start`` on whose true position lies inside ``mu ± sigma``;
        about 0.68 when the filter's variance is honest."""
        return float(np.mean(np.abs(self.error()[start:]) <= np.sqrt(self.var[start:])))

    def innovation_correlation(self, start: int = 0) -> float:
        """Correlation of each innovation with the next (lag 1) from index ``start`` on; about 0
        when the filter is healthy: one surprise does not predict the next.  Needs at least
        three innovations from ``start`` on."""
        nu = self.innovation[start:]
        if nu.size < 3:
            raise ValueError(f"start must leave at least 3 innovations, got start={start} of {self.innovation.size}")
        return float(np.corrcoef(nu[:-1], nu[1:])[0, 1])  # does one innovation predict the next?

    def health(self, start: int = 0) -> str:
        """One line of health numbers from index ``start`` on (time step ``start + 1``): the final
        gain, the RMS error, the share of true positions inside ``±sigma``, the mean innovation,
        the share of innovations inside ``±sqrt(S)`` and their lag-1 correlation.  Introduced in
        chapter 3."""
        estimate = f"RMS error {self.rms_error(start):.3f} m  truth in ±σ {self.truth_inside(start):4.0%}"
        innovations = f"mean ν {self.mean_innovation(start):+.3f} m  ν in ±√S {self.innovations_inside(start):4.0%}"
        return f"K {self.K[-1]:.3f}  {estimate}  {innovations}  corr {self.innovation_correlation(start):+.2f}"


def simulate_walk(
    n_steps: int = 100,
    *,
    u: float = 1.0,
    R_true: float = 0.01,
    Q_true: float = 0.25,
    R: float | None = None,
    Q: float | None = None,
    velocity: float = 0.0,
    x0: float = 0.0,
    mu0: float | None = None,
    var0: float = 0.25,
    seed: int = 0,
) -> WalkRun:
    r"""Drive a robot ``u`` metres a step along a rail and filter its noisy readings.

    World: :math:`x_k = x_{k-1} + u + v + w_k`, :math:`w_k \sim N(0, R_{true})`, and
    :math:`z_k = x_k + \delta_k`, :math:`\delta_k \sim N(0, Q_{true})`, from
    :math:`x_0`.  Filter: :func:`kf_1d_cycle` with ``a = b = c = 1``, the
    command ``u``, and its own ``R`` and ``Q``, from ``N(mu0, var0)``; it does
    not know the extra speed :math:`v` (``velocity``).

    The standard-normal draws depend only on ``seed``: runs with the same seed
    share the same disturbances and sensor errors (a shorter run is the start of
    a longer one), so changing a setting changes nothing else.  Introduced in
    chapter 3.

    Parameters
    ----------
    n_steps : int
        Number of time steps, >= 1.
    u : float
        Commanded move per step (m).
    R_true, Q_true : float
        The world's process and measurement noise variances (m^2), >= 0: by default a
        10 cm wobble on each 1 m step and a 50 cm sensor.
    R, Q : float, optional
        The variances the filter assumes; by default the true ones.
        ``Q`` must be > 0 if ``var0`` and ``R`` are both 0.
    velocity : float
        Extra move per step (m) the filter's motion model does not know.
    x0 : float
        True start position (m).
    mu0 : float, optional
        The filter's initial guess (m); by default ``x0``.
    var0 : float
        The filter's initial variance (m^2), >= 0.
    seed : int

    Returns
    -------
    WalkRun
    """
    seed = v.whole(seed, "seed", 0)
    n_steps = v.whole(n_steps, "n_steps", 1)
    u = v.scalar(u, "u")
    R_true, Q_true = v.variance(R_true, "R_true"), v.variance(Q_true, "Q_true")
    velocity = v.scalar(velocity, "velocity")
    x0 = v.scalar(x0, "x0")
    R, Q, mu0, var0 = _filter_settings(R, Q, mu0, var0, R_true=R_true, Q_true=Q_true, x0=x0)
    w, e = np.random.default_rng(seed).standard_normal((n_steps, 2)).T  # one pair of draws per step
    truth = x0 + np.cumsum(u + velocity + math.sqrt(R_true) * w)  # x_k = x_{k-1} + u + v + w_k,  w ~ N(0, R_true)
    z = truth + math.sqrt(Q_true) * e  # z_k = x_k + delta_k,  delta ~ N(0, Q_true)
    return WalkRun(
        t=np.arange(1, n_steps + 1, dtype=float),
        u=np.full(n_steps, u),
        truth=truth,
        z=z,
        **_filter_readings(z, u, mu0, var0, R=R, Q=Q),
        x0=x0,
        mu0=mu0,
        var0=var0,
        R=R,
        Q=Q,
        R_true=R_true,
        Q_true=Q_true,
        velocity=velocity,
        seed=seed,
    )


def _filter_settings(R, Q, mu0, var0, *, R_true: float, Q_true: float, x0: float) -> tuple[float, float, float, float]:
    """The filter's ``R``, ``Q``, ``mu0`` and ``var0``, checked; ``None`` takes the world's value."""
    R = R_true if R is None else v.variance(R, "R")
    Q = Q_true if Q is None else v.variance(Q, "Q")
    mu0 = x0 if mu0 is None else v.scalar(mu0, "mu0")
    var0 = v.variance(var0, "var0")
    if Q == 0 and R == 0 and var0 == 0:
        raise ValueError("Q must be > 0 when R and var0 are both 0 (the gain would be 0/0)")
    return R, Q, mu0, var0


def _filter_readings(z: np.ndarray, u: float, mu0: float, var0: float, *, R: float, Q: float) -> dict[str, np.ndarray]:
    """One :func:`kf_1d_cycle` per reading of ``z`` (command ``u`` each step), from ``N(mu0, var0)``.

    Returns the filter's arrays of a :class:`WalkRun` by field name: ``mu_bar``, ``var_bar``,
    ``innovation``, ``S``, ``K``, ``mu`` and ``var``, each of shape ``(len(z),)``.
    """
    rows = []
    mu, var = mu0, var0
    for z_k in z:
        cyc = kf_1d_cycle(mu, var, u, float(z_k), R=R, Q=Q)
        rows.append((cyc.mu_bar, cyc.var_bar, cyc.innovation, cyc.var_bar + Q, cyc.K, cyc.mu, cyc.var))
        mu, var = cyc.mu, cyc.var
    names = ("mu_bar", "var_bar", "innovation", "S", "K", "mu", "var")
    return dict(zip(names, np.array(rows, dtype=float).T, strict=True))
