"""Interactive demos, one module each; every demo is a function returning an
ipywidgets widget: ``kf.demos.hallway(seed=0)``."""

from .covariance import covariance_ellipse
from .data_association import data_association
from .hallway import hallway
from .landmark_loop import landmark_loop
from .linearization import linearization
from .nees import nees_panel
from .particle_cloud import particle_cloud
from .particle_hallway import particle_hallway
from .raw_vs_filtered import raw_vs_filtered
from .real_run import real_run
from .sigma_points import sigma_points
from .step_through import step_through
from .tracker import tracker
from .trust import trust_slider

__all__ = [
    "covariance_ellipse",
    "data_association",
    "hallway",
    "landmark_loop",
    "linearization",
    "nees_panel",
    "particle_cloud",
    "particle_hallway",
    "raw_vs_filtered",
    "real_run",
    "sigma_points",
    "step_through",
    "tracker",
    "trust_slider",
]
