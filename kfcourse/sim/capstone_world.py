"""The capstone's world (chapters 10 and 11): the robot's loop through the map, the noise of its odometry and sensor.

:func:`loop_world` drives the default robot round :func:`~kfcourse.sim.loop_controls` with its noise scaled;
the EKF, the UKF and the particle filter of the last chapters all follow this world, draw for draw.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as v
from .records import read_only
from .robot import DEFAULT_LANDMARKS, RobotRun, loop_controls, simulate_robot

V_STD, OMEGA_STD = 0.1, 0.05  # odometry noise at motion_noise = 1: m/s, rad/s
RANGE_STD, BEARING_STD = 0.1, 0.03  # reading noise at sensor_noise = 1: m, rad
SIG0 = read_only(np.diag([0.01, 0.01, 0.001]))  # the start is known to about 10 cm and 2 degrees
NOISE_SCALES = (0.01, 100.0)  # below, a reading so exact the gain's S^-1 loses its digits; above, no robot


def _noise_scale(x, name: str) -> float:
    value = v.scalar(x, name)
    if not NOISE_SCALES[0] <= value <= NOISE_SCALES[1]:
        raise ValueError(f"{name} must be a noise scale from {NOISE_SCALES[0]} to {NOISE_SCALES[1]}, got {value}")
    return value


def loop_world(
    seed: int = 0, motion_noise: float = 1.0, sensor_noise: float = 1.0, landmarks=None, **drive
) -> RobotRun:
    """The capstone's world: the default robot drives :func:`loop_controls` through the map, its noise scaled.

    ``motion_noise`` scales the odometry noise (0.1 m/s, 0.05 rad/s at 1), ``sensor_noise`` the
    reading noise (0.1 m, 0.03 rad at 1), each from 0.01 to 100 (:data:`NOISE_SCALES`); ``drive``
    passes ``sensor_range``, ``laps``, ``kidnap`` and ``dropout`` to :func:`~kfcourse.sim.simulate_robot`.
    Introduced in chapter 11 (chapter 10's :func:`landmark_loop` drives it without naming it).
    """
    seed = v.whole(seed, "seed", 0)
    motion_noise = _noise_scale(motion_noise, "motion_noise")
    sensor_noise = _noise_scale(sensor_noise, "sensor_noise")
    dt = 0.2  # s
    return simulate_robot(
        loop_controls(dt=dt),
        dt,
        landmarks=DEFAULT_LANDMARKS if landmarks is None else landmarks,
        v_std=motion_noise * V_STD,
        omega_std=motion_noise * OMEGA_STD,
        range_std=sensor_noise * RANGE_STD,
        bearing_std=sensor_noise * BEARING_STD,
        seed=seed,
        **drive,
    )


def filter_noise(motion_noise: float, sensor_noise: float) -> tuple[np.ndarray, np.ndarray]:
    """The covariances at these noise scales of the odometry noise ``M`` ([V, omega]) and the reading noise ``Q``
    ([r, phi]), as a filter of the loop assumes them (checked scales, from :func:`_noise_scale`)."""
    M = np.diag([motion_noise * V_STD, motion_noise * OMEGA_STD]) ** 2  # the odometry noise
    Q = np.diag([sensor_noise * RANGE_STD, sensor_noise * BEARING_STD]) ** 2  # the reading noise
    return M, Q
