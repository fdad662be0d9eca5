"""The scalar Kalman filter of chapters 3 and 4: five equations on numbers.

Noise letters follow the course: ``R`` is the process (motion) noise variance,
``Q`` the measurement (sensor) noise variance.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from .. import _validate as v

__all__ = ["KF1DCycle", "kf_1d_cycle", "kf_1d_gain", "kf_1d_predict", "kf_1d_step", "kf_1d_update", "steady_state_1d"]


class KF1DCycle(NamedTuple):
    """Every intermediate quantity of one scalar predict/update cycle."""

    mu_bar: float  #: predicted mean
    var_bar: float  #: predicted variance
    innovation: float  #: z - c mu_bar
    K: float  #: Kalman gain
    mu: float  #: updated mean
    var: float  #: updated variance


def kf_1d_predict(mu, var, u, a=1.0, b=1.0, R=0.2) -> tuple[float, float]:
    r"""Scalar Kalman predict step: move the belief and grow its variance.

    .. math:: \bar\mu = a\mu + bu, \qquad \bar\sigma^2 = a^2\sigma^2 + \sigma_R^2

    Introduced in chapter 3.

    Parameters
    ----------
    mu, var : float
        Prior mean and variance (``var >= 0``).
    u : float
        Control (commanded move).
    a, b : float
        Motion and control coefficients.
    R : float
        Process (motion) noise variance, ``>= 0``.

    Returns
    -------
    (mu_bar, var_bar) : floats
        Predicted mean and variance.
    """
    mu = v.scalar(mu, "mu")
    var = v.variance(var, "var")
    u = v.scalar(u, "u")
    a, b = v.scalar(a, "a"), v.scalar(b, "b")
    R = v.variance(R, "R")
    mu_bar = a * mu + b * u  # predict mean: mu_bar = a mu + b u
    var_bar = a * a * var + R  # predict variance: var_bar = a^2 var + R
    return mu_bar, var_bar


def kf_1d_gain(var_bar, c=1.0, Q=0.1) -> float:
    r"""Scalar Kalman gain: how far the update moves toward the measurement.

    .. math:: K = \frac{c\,\bar\sigma^2}{c^2\bar\sigma^2 + \sigma_Q^2}

    With ``c = 1``, ``K`` is near 1 when the prediction is much less certain than
    the sensor and near 0 when it is much more certain.  Introduced in chapter 3.

    Parameters
    ----------
    var_bar : float
        Predicted variance, ``>= 0``.
    c : float
        Measurement coefficient.
    Q : float
        Measurement noise variance, ``>= 0`` (``> 0`` when ``c^2 var_bar`` is 0).

    Returns
    -------
    K : float
    """
    var_bar = v.variance(var_bar, "var_bar")
    c = v.scalar(c, "c")
    Q = v.variance(Q, "Q")
    denom = c * c * var_bar + Q  # c^2 var_bar + Q
    if denom <= 0:
        raise ValueError("Q must be > 0 when the predicted variance c^2 var_bar is 0")
    return c * var_bar / denom  # gain: K = c var_bar / (c^2 var_bar + Q)


def kf_1d_update(mu_bar, var_bar, z, c=1.0, Q=0.1) -> tuple[float, float]:
    r"""Scalar Kalman update step: blend the prediction with a measurement.

    .. math:: \mu = \bar\mu + K(z - c\bar\mu), \qquad \sigma^2 = (1 - Kc)\,\bar\sigma^2

    with ``K`` from :func:`kf_1d_gain`.  Introduced in chapter 3.

    Parameters
    ----------
    mu_bar, var_bar : float
        Predicted mean and variance (``var_bar >= 0``).
    z : float
        Measurement.
    c : float
        Measurement coefficient.
    Q : float
        Measurement noise variance, ``>= 0``.

    Returns
    -------
    (mu, var) : floats
        Updated mean and variance.
    """
    mu_bar = v.scalar(mu_bar, "mu_bar")
    var_bar = v.variance(var_bar, "var_bar")
    z = v.scalar(z, "z")
    c = v.scalar(c, "c")
    K = kf_1d_gain(var_bar, c, Q)  # gain: K = c var_bar / (c^2 var_bar + Q)
    innovation = z - c * mu_bar  # innovation: the surprise z - c mu_bar
    mu = mu_bar + K * innovation  # update mean
    var = (1.0 - K * c) * var_bar  # update variance
    return mu, max(var, 0.0)


def kf_1d_cycle(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1) -> KF1DCycle:
    r"""One scalar Kalman cycle, returning every intermediate quantity.

    .. math::
        \bar\mu = a\mu + bu,\quad \bar\sigma^2 = a^2\sigma^2 + \sigma_R^2,\quad
        K = \frac{c\,\bar\sigma^2}{c^2\bar\sigma^2 + \sigma_Q^2},\quad
        \mu' = \bar\mu + K(z - c\bar\mu),\quad \sigma'^2 = (1 - Kc)\,\bar\sigma^2

    Built from :func:`kf_1d_predict`, :func:`kf_1d_gain` and :func:`kf_1d_update`.
    Introduced in chapter 3.

    Parameters
    ----------
    mu, var : float
        Prior mean and variance (``var >= 0``).
    u : float
        Control (commanded move).
    z : float or None
        Measurement; ``None`` skips the update (a predict-only tick, ``K = 0``).
    a, b, c : float
        Motion, control and measurement coefficients.
    R : float
        Process (motion) noise variance, ``>= 0``.
    Q : float
        Measurement noise variance, ``>= 0``.

    Returns
    -------
    KF1DCycle
    """
    mu_bar, var_bar = kf_1d_predict(mu, var, u, a, b, R)
    c, Q = v.scalar(c, "c"), v.variance(Q, "Q")  # checked even on a predict-only tick
    if z is None:
        return KF1DCycle(mu_bar, var_bar, 0.0, 0.0, mu_bar, var_bar)
    z = v.scalar(z, "z")
    K = kf_1d_gain(var_bar, c, Q)
    mu_new, var_new = kf_1d_update(mu_bar, var_bar, z, c, Q)
    return KF1DCycle(mu_bar, var_bar, z - c * mu_bar, K, mu_new, var_new)


def kf_1d_step(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1) -> tuple[float, float]:
    """One scalar Kalman predict/update cycle, as in the lesson.

    :func:`kf_1d_predict` then :func:`kf_1d_update`.  Introduced in chapter 3.
    See :func:`kf_1d_cycle` for the equations and the parameters; this returns
    only the posterior.

    Returns
    -------
    (mu, var) : floats
    """
    mu_bar, var_bar = kf_1d_predict(mu, var, u, a, b, R)
    c, Q = v.scalar(c, "c"), v.variance(Q, "Q")  # checked even on a predict-only tick
    if z is None:
        return mu_bar, var_bar
    return kf_1d_update(mu_bar, var_bar, z, c, Q)


def steady_state_1d(R, Q, a=1.0, c=1.0) -> tuple[float, float, float]:
    r"""Steady-state gain and variances of the scalar filter (scalar Riccati equation).

    At the fixed point the prior variance :math:`P` satisfies

    .. math:: P = a^2\,\frac{P\,Q}{c^2 P + Q} + R
        \;\Longleftrightarrow\;
        c^2 P^2 + \left(Q(1 - a^2) - R c^2\right) P - R Q = 0,

    whose non-negative root is taken; then :math:`K = cP/(c^2P+Q)` and the
    posterior variance is :math:`(1 - Kc)P`.  Introduced in chapter 3; chapter 4 derives it.

    Parameters
    ----------
    R : float
        Process noise variance, >= 0.
    Q : float
        Measurement noise variance, >= 0 (not both zero).
    a, c : float
        Motion and measurement coefficients.

    Returns
    -------
    (K, var_prior, var_post) : floats
    """
    R = v.variance(R, "R")
    Q = v.variance(Q, "Q")
    a, c = v.scalar(a, "a"), v.scalar(c, "c")
    if R == 0 and Q == 0:
        raise ValueError("R and Q must not both be 0 (the gain is undefined)")
    if c == 0:
        if abs(a) >= 1:
            raise ValueError("c must be non-zero unless |a| < 1: with no measurement the variance grows forever")
        P = R / (1.0 - a * a)
        return 0.0, P, P
    beta = Q * (1.0 - a * a) - R * c * c  # linear coefficient of the quadratic
    root = math.sqrt(beta * beta + 4.0 * c * c * R * Q)
    P = (root - beta) / (2 * c * c) if beta <= 0 else 2 * R * Q / (root + beta)  # stable root
    K = c * P / (c * c * P + Q)  # steady-state gain
    return K, P, (1.0 - K * c) * P
