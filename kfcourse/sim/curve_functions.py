"""A Gaussian belief pushed through a nonlinear function (chapters 7 and 9).

The demos of chapters 7 and 9 share this maths: three test functions with their
derivatives (:data:`FUNCTIONS`), and :class:`GaussianThroughCurve`, an input belief
N(m, s²) whose mean and width the sliders set, with a fixed set of seeded
standard-normal draws that become samples of it, those samples pushed through the
function (the true output), and the EKF's answer: the Gaussian that the tangent of
the function at m makes of the input.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v

__all__ = ["FUNCTIONS", "OFFSET", "GaussianThroughCurve", "d_landmark_range", "d_square", "landmark_range", "square"]

OFFSET = 1.0  # m: the landmark sits this far off the robot's line


def square(x):
    """f(x) = x²."""
    return x * x


def d_square(x):
    """f'(x) = 2x."""
    return 2.0 * x


def landmark_range(x):
    """The range r = √(x² + d²) from a robot at x on a line to a landmark ``OFFSET`` = d off it."""
    return np.sqrt(x * x + OFFSET**2)


def d_landmark_range(x):
    """dr/dx = x / r."""
    return x / np.sqrt(x * x + OFFSET**2)


# name: (f, f'); each works on a number or on an array of numbers
FUNCTIONS: dict[str, tuple[Callable, Callable]] = {
    "x²": (square, d_square),
    "sin x": (np.sin, np.cos),
    "range √(x² + 1)": (landmark_range, d_landmark_range),
}


class GaussianThroughCurve:
    """An input N(m, s²), a function f, the sampled output and the EKF's Gaussian.

    The model of chapter 7's linearization demo (and, with sigma points added, of
    chapter 9's).  The input samples are ``m + s e`` for standard-normal draws ``e``
    drawn once from ``seed``: moving m or s moves the same samples, so the picture
    changes smoothly and the same settings always give the same numbers.
    Introduced in chapter 7.

    Parameters
    ----------
    seed : int
    m : float
        Input mean.
    s : float
        Input standard deviation, > 0.
    function : str
        A key of :data:`FUNCTIONS`.
    n_samples : int
        Number of draws, >= 2.

    Attributes
    ----------
    m, s : float
    function : str
    draws : ndarray, shape (n_samples,)
        The standard-normal draws ``e``, fixed.
    """

    def __init__(self, seed: int = 0, m: float = 1.0, s: float = 0.5, function: str = "x²", n_samples: int = 4000):
        self.set_m(m)
        self.set_s(s)
        self.set_function(function)
        n_samples = v.whole(n_samples, "n_samples", 2)
        self.draws = np.random.default_rng(seed).standard_normal(n_samples)  # e ~ N(0, 1), fixed

    def set_m(self, m: float) -> None:
        self.m = v.scalar(m, "m")

    def set_s(self, s: float) -> None:
        self.s = v.positive(s, "s", "a standard deviation")

    def set_function(self, name: str) -> None:
        if name not in FUNCTIONS:
            raise ValueError(f"function must be one of {list(FUNCTIONS)}, got {name!r}")
        self.function = name

    @property
    def f(self) -> Callable:
        """The function f chosen."""
        return FUNCTIONS[self.function][0]

    @property
    def df(self) -> Callable:
        """Its derivative f'."""
        return FUNCTIONS[self.function][1]

    def samples(self) -> np.ndarray:
        """The input samples x = m + s e pushed through f: samples of the true output."""
        return self.f(self.m + self.s * self.draws)

    def sampled(self) -> tuple[float, float]:
        """Mean and variance of the true (sampled) output."""
        y = self.samples()
        return float(y.mean()), float(y.var())

    def ekf(self) -> tuple[float, float]:
        """The EKF's output Gaussian, through the tangent at m: N(f(m), f'(m)² s²)."""
        slope = float(self.df(self.m))
        return float(self.f(self.m)), slope * slope * self.s * self.s  # mean f(m), variance f'(m)^2 s^2
