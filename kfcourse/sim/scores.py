"""Scores of a filter's honesty: the NEES and the bands it should lie in (chapters 6, 10 and 11).

Every NEES of the course is :func:`nees`; :func:`nees_band` gives the chi-square band of an
average of independent NEES draws, :data:`HONEST_NEES` the band of one lap's mean position NEES, and
:data:`NEES_BAND` the band of one position NEES (chapter 12).
"""

from __future__ import annotations

import math
from statistics import NormalDist

import numpy as np

from .. import _validate as v

HONEST_NEES = (1.0, 4.0)  # the band of the mean position NEES (2 for an honest filter) read as honest
# The two-sided 95 % band of one position NEES, chi-square with 2 degrees of freedom: -2 ln(1 - p) at
# p = 0.025 and 0.975.  An honest filter's NEES lies inside it at 95 % of its steps.
NEES_BAND = (-2.0 * math.log(1.0 - 0.025), -2.0 * math.log(1.0 - 0.975))  # (0.051, 7.38)
FADE_TIME = 1.0  # s: how long a tracking filter's error takes to fade; the honesty test's draws are this far apart


def nees(truth, mu, Sig) -> np.ndarray:
    r"""Normalised estimation error squared, :math:`\mathrm{NEES} = (x - \mu)^\top \Sigma^{-1} (x - \mu)`.

    If the filter's :math:`\Sigma` is honest (its errors really are
    :math:`N(0, \Sigma)`), the NEES follows a chi-square distribution with
    n degrees of freedom: on average it equals n.  Introduced in chapter 6.

    A flat ellipse (a singular :math:`\Sigma`, which a student's step or a particle cloud
    collapsed onto one pose may give) claims that the error cannot leave its line, or its
    point: an error that does is infinitely unlikely, and its NEES is ``inf``; an error within
    it gets the NEES of the pseudo-inverse.  So is the NEES of an ellipse so small that its
    inverse overflows.  Every NEES of the course (chapters 6, 10 and 11) is this function.

    Parameters
    ----------
    truth, mu : array_like, shape (..., n)
    Sig : array_like, shape (..., n, n)
        Covariances: symmetric, positive semi-definite.

    Returns
    -------
    ndarray, shape (...)
    """
    truth, mu, Sig = v.finite(truth, "truth"), v.finite(mu, "mu"), v.finite(Sig, "Sig")
    if not (truth.ndim and truth.shape == mu.shape and Sig.shape == truth.shape + truth.shape[-1:]):
        raise ValueError(_odd_shape(truth.shape, mu.shape, Sig.shape))
    n = truth.shape[-1]
    v.covariance_stack(Sig.reshape(-1, n, n), "Sig", Sig.size // (n * n) if n else 0, n)
    err = truth - mu  # x - mu
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # an overflow: infinitely unlikely
        try:  # the common case: every Sig positive definite
            d2 = np.einsum("...i,...i->...", err, np.linalg.solve(Sig, err[..., None])[..., 0])
        except np.linalg.LinAlgError:  # a flat ellipse: the pseudo-inverse, and inf for an error that leaves it
            inv = np.linalg.pinv(Sig)
            d2 = np.einsum("...i,...ij,...j->...", err, inv, err)
            off = np.linalg.norm(err - np.einsum("...ij,...jk,...k->...i", Sig, inv, err), axis=-1)
            d2 = np.where(off > 1e-9 * (1.0 + np.linalg.norm(err, axis=-1)), np.inf, d2)
    return np.where(np.isnan(d2), np.inf, d2)


def _odd_shape(truth: tuple, mu: tuple, Sig: tuple) -> str:
    """Which input of :func:`nees` has the odd shape, given that truth and mu must be (..., n) and Sig (..., n, n)."""
    if truth and truth == mu:
        return f"Sig must have shape {truth + truth[-1:]}, as truth and mu have shape {truth}; got {Sig}"
    for name, shape, other, agreed in (("truth", truth, "mu", mu), ("mu", mu, "truth", truth)):
        if agreed and Sig == agreed + agreed[-1:]:
            return f"{name} must have shape {agreed}, as {other} has and Sig has shape {Sig}; got {shape}"
    return f"truth has shape {truth}, mu {mu} and Sig {Sig}: they must be (..., n), (..., n) and (..., n, n)"


def verdict(mean_nees: float, band: tuple[float, float] = HONEST_NEES) -> str:
    """What a mean NEES says of a filter: "honest" inside ``band`` (by default :data:`HONEST_NEES`, that of one
    run's mean position NEES), "timid" below it (its ellipses larger than its errors), "over-confident" above it
    (smaller).  A mean NEES of ``inf`` (a flat ellipse the truth left) is over-confident.  Introduced in chapter
    6; chapters 10 and 12 read a whole run with it."""
    if isinstance(mean_nees, bool) or not isinstance(mean_nees, int | float | np.number) or math.isnan(mean_nees):
        raise ValueError(f"mean_nees must be a number >= 0 (inf for a flat ellipse), got {mean_nees!r}")
    low, high = v.vector(band, "band", 2).tolist()
    if not 0.0 <= low <= high:
        raise ValueError(f"band must be (low, high) with 0 <= low <= high, got {(low, high)}")
    return "timid" if mean_nees < low else "over-confident" if mean_nees > high else "honest"


def nees_band(n_runs: int, dof: int, level: float = 0.95) -> tuple[float, float]:
    r"""The two-sided ``level`` band for the average NEES of ``n_runs`` honest filters.

    The sum of ``n_runs`` independent :math:`\chi^2(\text{dof})` values is
    :math:`\chi^2(\nu)` with :math:`\nu = n_\text{runs}\cdot\text{dof}`, and its
    quantiles follow from the Wilson-Hilferty approximation (a cube root of a
    chi-square is nearly normal):

    .. math:: \chi^2_p(\nu) \approx \nu \left(1 - \frac{2}{9\nu} + \Phi^{-1}(p)\sqrt{\frac{2}{9\nu}}\right)^3

    with :math:`\Phi^{-1}(p)` the standard-normal quantile.  Dividing by ``n_runs`` gives the
    band for the average.  Introduced in chapter 6.

    Returns
    -------
    (low, high) : floats
    """
    n_runs, dof = v.whole(n_runs, "n_runs", 1), v.whole(dof, "dof", 1)
    level = v.scalar(level, "level")
    if not 0 < level < 1:
        raise ValueError(f"level must lie between 0 and 1, got {level}")
    nu = n_runs * dof
    c = 2.0 / (9.0 * nu)
    n_sd = NormalDist().inv_cdf(0.5 + level / 2)  # 1.96 for 95 %
    low = nu * max(1 - c - n_sd * math.sqrt(c), 0.0) ** 3  # chi2 quantile at (1 - level) / 2 (never below 0)
    high = nu * (1 - c + n_sd * math.sqrt(c)) ** 3  # chi2 quantile at (1 + level) / 2
    return low / n_runs, high / n_runs
