"""A robot on a line with a noisy position sensor (chapter 0's demo)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as v
from ..filters.kalman_1d import kf_1d_cycle
from .records import Record


@dataclass(frozen=True)
class LineRun(Record):
    """One simulated run; every array has one entry per time step."""

    t: np.ndarray  #: step index
    u: np.ndarray  #: commanded move per step (m)
    truth: np.ndarray  #: true position (m)
    z: np.ndarray  #: sensor reading (m); trusting it blindly is the "raw" estimate
    mu: np.ndarray  #: filtered mean (m)
    var: np.ndarray  #: filtered variance (m^2)
    step_std: float
    sensor_std: float
    seed: int
    dead_reckoning: np.ndarray  #: the commands summed from the known start, no sensor (m); drifts away from the truth


def simulate_line(
    n_steps: int = 150, step_std: float = 0.05, sensor_std: float = 0.4, speed: float = 0.25, seed: int = 0
) -> LineRun:
    r"""Drive a robot along a line, read a noisy sensor, and filter with a 1-D KF.

    Truth: :math:`x_t = x_{t-1} + u_t + \varepsilon_t` with :math:`\varepsilon_t \sim N(0, \sigma_{step}^2)`
    (the course's process noise) and a command :math:`u_t = v \sin(2\pi t / T)`: the robot drives out
    along the line and back again.  Sensor: :math:`z_t = x_t + \delta_t` with
    :math:`\delta_t \sim N(0, \sigma_{sensor}^2)`.  The filter runs :func:`kf_1d_step`
    with ``R = step_std**2`` and ``Q = sensor_std**2``, starting from the same known start as
    dead reckoning with variance ``step_std**2`` (one step's disturbance).  Dead reckoning counts the
    commands only, :math:`\hat x_t = \sum_{k \le t} u_k`, so its error is the sum of the
    disturbances and spreads like :math:`\sigma_{step}\sqrt{t}` (chapter 0's drift).

    The standard-normal draws depend only on ``seed`` and ``n_steps``, so changing
    ``sensor_std`` rescales the same noise: the picture changes smoothly.

    Parameters
    ----------
    n_steps : int
        Number of steps (>= 2).
    step_std : float
        Disturbance per step (m), > 0.
    sensor_std : float
        Sensor noise (m), > 0.
    speed : float
        Largest commanded move per step, ``v`` (m).
    seed : int

    Returns
    -------
    LineRun
    """
    seed = v.whole(seed, "seed", 0)
    n_steps = v.whole(n_steps, "n_steps", 2)
    step_std = v.positive(step_std, "step_std", "a standard deviation", "m")
    sensor_std = v.positive(sensor_std, "sensor_std", "a standard deviation", "m")
    speed = v.scalar(speed, "speed")
    rng = np.random.default_rng(seed)
    w = rng.standard_normal(n_steps)
    e = rng.standard_normal(n_steps)
    t = np.arange(n_steps)
    u = speed * np.sin(2 * np.pi * t / n_steps)  # m per step: out and back
    truth = np.cumsum(u + step_std * w * (t > 0))
    z = truth + sensor_std * e
    mu = np.empty(n_steps)
    var = np.empty(n_steps)
    dead_reckoning = np.cumsum(u)  # m: x_t = x_{t-1} + u_t from the known start, never corrected
    m, s2 = dead_reckoning[0], step_std**2  # the same known start, give or take one step's disturbance
    mu[0], var[0] = m, s2
    for k in range(1, n_steps):
        m, s2 = kf_1d_cycle(m, s2, u[k], z[k], R=step_std**2, Q=sensor_std**2)[4:]
        mu[k], var[k] = m, s2
    return LineRun(t.astype(float), u, truth, z, mu, var, step_std, sensor_std, seed, dead_reckoning)
