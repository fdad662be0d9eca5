"""Checkers for the "Your turn" exercises: ``kf.check.<name>(your_function)``.

Each checker runs your function on a list of cases (the chapter's worked example,
edge cases such as ω = 0, bearings near ±π or n = 1, and seeded random ones) and
compares every answer with the package's own function.  The verdict, shown as
the last line of a cell, is ✔ with what was checked, or ✘ with the first case
that differs (inputs, expected, got) and, when a known wrong version gives the
same answer, the likely mistake and where the chapter has the right equation.

Every checker returns a :class:`CheckResult` with ``passed`` (bool), ``mistake``
(a key of :data:`MISTAKES`, or None) and ``message`` (str).  A function that
still raises ``NotImplementedError`` gets "not yet" (``passed=False``,
``mistake=None``).

Introduced in chapter 1; chapters 1, 3, 4, 5, 7, 8 and 9 end with exercises, and
``notebooks/solutions.ipynb`` has one way to write each.
"""

from ._core import MISTAKES, CheckResult
from .bayes import bayes_predict, bayes_update
from .kalman import fuse, kf_1d_step, kf_step
from .nonlinear import range_bearing, range_bearing_jacobian, unicycle
from .ukf import sigma_points

__all__ = [
    "MISTAKES",
    "CheckResult",
    "bayes_predict",
    "bayes_update",
    "fuse",
    "kf_1d_step",
    "kf_step",
    "range_bearing",
    "range_bearing_jacobian",
    "sigma_points",
    "unicycle",
]
