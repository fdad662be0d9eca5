"""Seeded simulation engines, and the course's filters run over them and over a real robot's log
(:mod:`~kfcourse.sim.range_run`).  Each returns an immutable run record (arrays over time), or is a
pure function of its inputs and a seeded generator."""

from .capstone_world import loop_world
from .drift import bias_drift, drift_sigma, monte_carlo_drift
from .ekf_runs import TWO_LANDMARKS, EkfRun, flipped_bearing_jacobian, run_ekf
from .family import FamilyTable, FilterScore, family_table
from .gated_run import OutlierRun, plain_and_gated
from .graph_run import FactorGraphRun, factor_graph
from .hallway_world import (
    HallwayRun,
    door_likelihood,
    hallway_doors,
    motion_kernel,
    move,
    read_door,
    simulate_hallway,
    start_cell,
)
from .landmark_lap import landmark_loop
from .line import LineRun, simulate_line
from .loop_filters import gate_within, localize, loop_filter, process_noise_of_odometry
from .loop_records import LoopRun, Track
from .particle_hallway_run import ParticleHallwayRun, simulate_particle_hallway
from .particle_lap import ParticleRun, localized, particle_loop
from .plaza_family import TUNED, PlazaFamily, PlazaRow, plaza_family
from .range_particles import RangeParticleRun, range_particles
from .range_run import DATA_SHEET, RangeRun, range_localize, smoothed
from .robot import DEFAULT_LANDMARKS, RobotRun, loop_controls, readings, simulate_robot
from .scan import AssociationScan, GatedUpdate, association_scan, gated_update
from .scores import NEES_BAND, nees, nees_band, verdict
from .student_step import localize_with_step
from .target import (
    TargetEstimates,
    TargetRun,
    TrackBatch,
    filter_target,
    filter_tracks,
    process_noise,
    simulate_target,
    simulate_tracks,
)
from .tuning import TuningScore, tuning_score
from .walk import simulate_walk

__all__ = [
    "DATA_SHEET",
    "DEFAULT_LANDMARKS",
    "NEES_BAND",
    "TUNED",
    "TWO_LANDMARKS",
    "AssociationScan",
    "EkfRun",
    "FactorGraphRun",
    "FamilyTable",
    "FilterScore",
    "GatedUpdate",
    "HallwayRun",
    "LineRun",
    "LoopRun",
    "OutlierRun",
    "ParticleHallwayRun",
    "ParticleRun",
    "PlazaFamily",
    "PlazaRow",
    "RangeParticleRun",
    "RangeRun",
    "RobotRun",
    "TargetEstimates",
    "TargetRun",
    "Track",
    "TrackBatch",
    "TuningScore",
    "association_scan",
    "bias_drift",
    "door_likelihood",
    "drift_sigma",
    "factor_graph",
    "family_table",
    "filter_target",
    "filter_tracks",
    "flipped_bearing_jacobian",
    "gate_within",
    "gated_update",
    "hallway_doors",
    "landmark_loop",
    "localize",
    "localize_with_step",
    "localized",
    "loop_controls",
    "loop_filter",
    "loop_world",
    "monte_carlo_drift",
    "motion_kernel",
    "move",
    "nees",
    "nees_band",
    "particle_loop",
    "plain_and_gated",
    "plaza_family",
    "process_noise",
    "process_noise_of_odometry",
    "range_localize",
    "range_particles",
    "read_door",
    "readings",
    "run_ekf",
    "simulate_hallway",
    "simulate_line",
    "simulate_particle_hallway",
    "simulate_robot",
    "simulate_target",
    "simulate_tracks",
    "simulate_walk",
    "smoothed",
    "start_cell",
    "tuning_score",
    "verdict",
]
