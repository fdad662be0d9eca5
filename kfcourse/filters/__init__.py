"""The math of the course: arrays in, arrays out; no plots, no widgets."""

from .association import associate, mahalanobis
from .batch import kf_step_batch
from .bayes import bayes_predict, bayes_update
from .ekf import ekf_predict, ekf_update
from .gaussian import add_gaussians, affine_gaussian, ellipse_axes, fuse, gaussian_pdf, mass_inside, mvn_pdf
from .kalman import kf_gain, kf_predict, kf_step, kf_update
from .kalman_1d import KF1DCycle, kf_1d_cycle, kf_1d_gain, kf_1d_predict, kf_1d_step, kf_1d_update, steady_state_1d
from .localization import ekf_localization_step
from .particle import (
    effective_sample_size,
    inject_random,
    normalise,
    pf_estimate,
    pf_predict,
    pf_weight,
    resample_multinomial,
    resample_stratified,
    resample_systematic,
)
from .ranging import range_update
from .smoother import ekf_rts_smoother, rts_smoother
from .ukf import sigma_points, ukf_predict, ukf_update, unscented_1d, unscented_transform

__all__ = [
    "KF1DCycle",
    "add_gaussians",
    "affine_gaussian",
    "associate",
    "bayes_predict",
    "bayes_update",
    "effective_sample_size",
    "ekf_localization_step",
    "ekf_predict",
    "ekf_rts_smoother",
    "ekf_update",
    "ellipse_axes",
    "fuse",
    "gaussian_pdf",
    "inject_random",
    "kf_1d_cycle",
    "kf_1d_gain",
    "kf_1d_predict",
    "kf_1d_step",
    "kf_1d_update",
    "kf_gain",
    "kf_predict",
    "kf_step",
    "kf_step_batch",
    "kf_update",
    "mahalanobis",
    "mass_inside",
    "mvn_pdf",
    "normalise",
    "pf_estimate",
    "pf_predict",
    "pf_weight",
    "range_update",
    "resample_multinomial",
    "resample_stratified",
    "resample_systematic",
    "rts_smoother",
    "sigma_points",
    "steady_state_1d",
    "ukf_predict",
    "ukf_update",
    "unscented_1d",
    "unscented_transform",
]
