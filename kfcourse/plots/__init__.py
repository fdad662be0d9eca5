"""Figures for the course: palette, style and artists.

Artists take an ``ax`` and return the artists they made; ``update_*`` functions
move existing artists in place.  Nothing here calls ``plt.show()`` or knows
about widgets.
"""

from . import palette
from .artists import (
    beams,
    belief_bars,
    covariance_ellipse,
    gain_gauge,
    gaussian_curve,
    landmarks,
    robot,
    update_beams,
    update_belief_bars,
    update_covariance_ellipse,
    update_gain_gauge,
    update_gaussian_curve,
    update_robot,
)
from .bayes_cycle import bayes_cycle_chart
from .charts import blend_variance_chart, convergence_chart, drift_chart, ellipse_shadow_chart, samples_chart
from .ekf_figures import jacobian_runs_chart, nonlinear_samples_chart
from .localization_figures import gate_outline, reading_points, update_ellipse_chart, wrap_runs_chart
from .loop import loop_chart, position_errors
from .matrix import predict_update_chart
from .particles import cloud_chart
from .plaza_charts import nees_chart, plaza_chart, ranges_chart
from .runs import kf_run_chart
from .style import FigureRenderer, new_figure
from .ukf_figures import filter_comparison_chart, transform_moments_chart

__all__ = [
    "FigureRenderer",
    "bayes_cycle_chart",
    "beams",
    "belief_bars",
    "blend_variance_chart",
    "cloud_chart",
    "convergence_chart",
    "covariance_ellipse",
    "drift_chart",
    "ellipse_shadow_chart",
    "filter_comparison_chart",
    "gain_gauge",
    "gate_outline",
    "gaussian_curve",
    "jacobian_runs_chart",
    "kf_run_chart",
    "landmarks",
    "loop_chart",
    "nees_chart",
    "new_figure",
    "nonlinear_samples_chart",
    "palette",
    "plaza_chart",
    "position_errors",
    "predict_update_chart",
    "ranges_chart",
    "reading_points",
    "robot",
    "samples_chart",
    "transform_moments_chart",
    "update_beams",
    "update_belief_bars",
    "update_covariance_ellipse",
    "update_ellipse_chart",
    "update_gain_gauge",
    "update_gaussian_curve",
    "update_robot",
    "wrap_runs_chart",
]
