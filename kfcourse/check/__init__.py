"""Checkers for the "Your turn" exercises: ``kf.check.<name>(your_function)``.

Each checker runs your function on a list of cases (the chapter's worked example,
edge cases such as ω = 0, bearings near ±π or n = 1, and seeded random ones) and
compares every answer with the package's own function.  The verdict, shown as
the last line of a cell, is ✔ with what was checked, or ✘ with the first case
that differs (inputs, expected, got) and, when a known wrong version gives the
same answer on every case, the likely mistake and where the chapter has the right
equation (chapters 3 and 5 otherwise say which step and which input are at fault).

Every checker returns a :class:`CheckResult` with ``passed`` (bool), ``mistake``
(a key of :data:`MISTAKES`, or None) and ``message`` (str).  A function that
still raises ``NotImplementedError`` gets "not yet" (``passed=False``,
``mistake=None``).

Introduced in chapter 0; every chapter ends with an exercise (chapter 9 with two, the
sigma points and the unscented transform; chapter 12's first is the range update), and
``notebooks/solutions.ipynb`` has one way to write each.
"""

from ._core import MISTAKES, CheckResult
from .bayes_checks import bayes_predict, bayes_update
from .exercises import affine_gaussian, cv_model, drift_sigma
from .kalman_checks import fuse, kf_1d_step, kf_step
from .localization_checks import localization_step
from .nonlinear import range_bearing, range_bearing_jacobian, unicycle
from .particle_checks import resample_systematic
from .range_checks import range_update
from .ukf_checks import sigma_points, unscented_transform

__all__ = [
    "MISTAKES",
    "CheckResult",
    "affine_gaussian",
    "bayes_predict",
    "bayes_update",
    "cv_model",
    "drift_sigma",
    "fuse",
    "kf_1d_step",
    "kf_step",
    "localization_step",
    "range_bearing",
    "range_bearing_jacobian",
    "range_update",
    "resample_systematic",
    "sigma_points",
    "unicycle",
    "unscented_transform",
]
