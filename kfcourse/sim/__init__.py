"""Seeded simulation engines.  Each returns an immutable run record (arrays over
time), or is a pure function of its inputs and a seeded generator."""

from .drift import bias_drift, drift_sigma, monte_carlo_drift
from .hallway import door_likelihood, motion_kernel, move, read_door
from .line import LineRun, simulate_line
from .robot import DEFAULT_LANDMARKS, RobotRun, loop_controls, simulate_robot
from .walk import simulate_walk

__all__ = [
    "DEFAULT_LANDMARKS",
    "LineRun",
    "RobotRun",
    "bias_drift",
    "door_likelihood",
    "drift_sigma",
    "loop_controls",
    "monte_carlo_drift",
    "motion_kernel",
    "move",
    "read_door",
    "simulate_line",
    "simulate_robot",
    "simulate_walk",
]
