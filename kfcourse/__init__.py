"""kfcourse: the Kalman filter family, from the Bayes filter to the UKF.

``import kfcourse as kf`` gives the whole student-facing API.  Noise letters
follow the course: ``R`` is process (motion) noise, ``Q`` measurement noise.

The sub-packages that draw (``kf.plots``) or build widgets (``kf.demos``), the
simulation engines (``kf.sim``) and the logs of real robots (``kf.data``) load only
when first used, so importing the math never imports matplotlib, ipywidgets or scipy.
"""

from __future__ import annotations

import importlib

from . import models
from .filters import *  # noqa: F403
from .filters import __all__ as _filters_all
from .models import (
    numeric_jacobian,
    range_bearing,
    range_bearing_jacobian,
    unicycle,
    unicycle_control_jacobian,
    unicycle_jacobian,
    wrap_angle,
)

__version__ = "0.1.0"

_LAZY = ("check", "data", "demos", "plots", "sim")

__all__ = [
    *_filters_all,
    "models",
    "numeric_jacobian",
    "range_bearing",
    "range_bearing_jacobian",
    "unicycle",
    "unicycle_control_jacobian",
    "unicycle_jacobian",
    "wrap_angle",
]


def __getattr__(name: str):
    if name in _LAZY:
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'kfcourse' has no attribute {name!r}")


def __dir__():
    return sorted([*globals(), *_LAZY])
