"""Dead-reckoning drift (chapter 0)."""

from __future__ import annotations

import numpy as np

from .. import _validate as v


def _steps(n, name="n"):
    a = v.finite(n, name)
    if (a < 0).any() or (a != np.round(a)).any():
        raise ValueError(f"{name} must hold whole numbers of steps >= 0, got {n!r}")
    return a


def drift_sigma(step_std: float, n):
    r"""Position spread after ``n`` independent steps, each off by ``step_std``.

    Variances add, so :math:`\sigma_n = \sigma_{step}\sqrt{n}`.  Introduced in chapter 0.

    Parameters
    ----------
    step_std : float
        Standard deviation of one step's error (m), >= 0.
    n : int or array_like of int
        Number of steps.

    Returns
    -------
    float or ndarray (m)
    """
    s = v.non_negative(step_std, "step_std", "a standard deviation", "m")
    out = s * np.sqrt(_steps(n))
    return float(out) if out.ndim == 0 else out


def bias_drift(scale_error: float, distance) -> np.ndarray | float:
    """Error from a constant scale bias: it grows linearly, ``scale_error * distance``.

    Introduced in chapter 0 (a 1 % bias is 4 m off after 400 m).
    """
    e = v.scalar(scale_error, "scale_error")
    d = v.finite(distance, "distance")
    out = e * d
    return float(out) if out.ndim == 0 else out


def monte_carlo_drift(step_std: float, n, n_robots: int = 10_000, seed: int = 0) -> np.ndarray | float:
    """Empirical spread of many dead-reckoning robots after ``n`` steps.

    Each robot sums ``max(n)`` independent step errors ``N(0, step_std^2)``; the
    standard deviation across robots of the running sum is read at each ``n``.
    Introduced in chapter 0, beside :func:`drift_sigma`.

    Parameters
    ----------
    step_std : float
        Per-step error standard deviation (m).
    n : int or array_like of int
        Step counts to read the spread at (>= 1).
    n_robots : int
        How many simulated robots.
    seed : int

    Returns
    -------
    float or ndarray (m), same shape as ``n``
    """
    seed = v.whole(seed, "seed", 0)
    s = v.non_negative(step_std, "step_std", "a standard deviation", "m")
    steps = _steps(n).astype(int)
    if (steps < 1).any():
        raise ValueError(f"n must be >= 1, got {n!r}")
    if not isinstance(n_robots, (int, np.integer)) or n_robots < 2:
        raise ValueError(f"n_robots must be a whole number >= 2, got {n_robots!r}")
    rng = np.random.default_rng(seed)
    pos = np.zeros(n_robots)
    spread = {}
    for k in range(1, int(steps.max()) + 1):
        pos += rng.normal(0.0, s, n_robots)  # one more noisy step for every robot
        if k in steps:
            spread[k] = pos.std(ddof=1)
    out = np.array([spread[k] for k in steps.ravel()]).reshape(steps.shape)
    return float(out) if out.ndim == 0 else out
