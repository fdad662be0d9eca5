"""The discrete (histogram) Bayes filter over a 1-D row of cells.

Introduced in chapter 1.  A belief is a probability vector ``bel`` of shape
``(n,)``; ``bel[i]`` is the probability that the robot is in cell ``i``.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from .. import _validate as v

BOUNDARIES = ("wall", "wrap")


def bayes_predict(belief, kernel: Mapping[int, float], boundary: str = "wall") -> np.ndarray:
    r"""Predict step: push the belief through a motion kernel.

    .. math:: \overline{bel}(x_t) = \sum_{x_{t-1}} p(x_t \mid u_t, x_{t-1})\, bel(x_{t-1})

    Introduced in chapter 1.

    Parameters
    ----------
    belief : array_like, shape (n,)
        Current belief; non-negative, sums to 1.
    kernel : mapping int -> float
        Probability of moving by each offset (in cells), e.g. ``{1: 0.8, 0: 0.2}``
        for "one cell right, or stall".  Sums to 1.
    boundary : {"wall", "wrap"}
        ``"wall"``: the hallway ends in walls, mass that would leave stops in the
        end cell.  ``"wrap"``: the hallway is a ring, mass leaving one end enters
        the other.

    Returns
    -------
    ndarray, shape (n,)
        Predicted belief; sums to 1.
    """
    bel = v.probabilities(belief, "belief")
    k = v.kernel(kernel, "kernel")
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}, got {boundary!r}")
    n = bel.size
    src = np.arange(n)
    bel_bar = np.zeros(n)
    for offset, p in k.items():
        dst = src + offset
        dst = dst % n if boundary == "wrap" else np.clip(dst, 0, n - 1)
        np.add.at(bel_bar, dst, p * bel)  # sum over every source cell
    return bel_bar


def bayes_update(belief, likelihood, *, return_eta: bool = False):
    r"""Update step: Bayes' rule with a measurement likelihood.

    .. math:: bel(x_t) = \eta\, p(z_t \mid x_t)\, \overline{bel}(x_t),
              \qquad \eta = 1 / \sum_x p(z_t \mid x)\, \overline{bel}(x)

    Introduced in chapter 1.

    Parameters
    ----------
    belief : array_like, shape (n,)
        Predicted belief; non-negative, sums to 1.
    likelihood : array_like, shape (n,)
        ``p(z | x)`` for each cell; non-negative, need not sum to 1.
    return_eta : bool
        Also return the normaliser ``eta``.

    Returns
    -------
    ndarray, shape (n,)
        Posterior belief; sums to 1.  With ``return_eta``, the pair ``(bel, eta)``.
    """
    bel_bar = v.probabilities(belief, "belief")
    lik = v.vector(likelihood, "likelihood", bel_bar.size)
    if (lik < 0).any():
        raise ValueError(f"likelihood must be >= 0, got {lik.tolist()}")
    return_eta = v.flag(return_eta, "return_eta")
    unnormalised = lik * bel_bar  # p(z|x) * bel_bar(x)
    total = unnormalised.sum()
    if total <= 0:
        raise ValueError("likelihood is zero wherever belief is non-zero: the reading is impossible")
    eta = float(1.0 / total)  # the normaliser of Bayes' rule
    bel = eta * unnormalised
    return (bel, eta) if return_eta else bel
