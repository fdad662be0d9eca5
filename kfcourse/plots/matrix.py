"""Chapter 5: one matrix Kalman update seen as ellipses in (position, velocity) space.

The predicted belief is a purple ellipse, the posterior a teal one, and a sensor
that reads position only is an orange vertical band: it says where the target is
and nothing about how fast it moves.  The tilt of the purple ellipse is the
position-velocity correlation that lets the update move the velocity anyway.
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate as v
from . import palette
from .artists import covariance_ellipse
from .style import new_figure

__all__ = ["predict_update_chart"]


def _fit_view(ax, beliefs, k: float, band) -> None:
    """Limits: the bounding boxes of the ``k``-sigma ellipses of ``beliefs``, pairs ``(mu, Sig)``
    (half-extent k sqrt(Sig_ii)), and the reading's ``band`` ``(low, high)`` if not None, with a margin;
    one scale on both axes unless their spans differ fourfold or more."""
    lows = [m - k * np.sqrt(np.diag(S)) for m, S in beliefs]
    highs = [m + k * np.sqrt(np.diag(S)) for m, S in beliefs]
    low, high = np.min(lows, axis=0), np.max(highs, axis=0)
    if band is not None:
        low[0], high[0] = min(low[0], band[0]), max(high[0], band[1])
    pad = 0.15 * np.maximum(high - low, 1e-3) + 1e-3  # a margin, and room even for a collapsed belief
    ax.set_xlim(low[0] - pad[0], high[0] + pad[0])
    ax.set_ylim(low[1] - pad[1], high[1] + pad[1])
    span = (high - low) + 2 * pad
    if 0.25 < span[0] / span[1] < 4.0:
        ax.set_aspect("equal", adjustable="box")  # one scale on both axes, so the drawn tilt is the true one


def predict_update_chart(
    mu_bar,
    Sig_bar,
    mu,
    Sig,
    z=None,
    Q=None,
    nsig: float = 1.0,
    labels: tuple[str, str] = ("position p", "velocity v"),
):
    r"""The predicted and the updated belief of a 2-state filter as ``nsig``-sigma ellipses.

    Purple: :math:`\mathcal N(\bar\mu, \bar\Sigma)`, the prediction.  Teal:
    :math:`\mathcal N(\mu, \Sigma)`, the posterior.  Orange: the reading ``z`` of the
    first state component with its band :math:`z \pm k\sqrt{Q}` (``k = nsig``),
    which spans every velocity because the sensor does not see velocity.
    Introduced in chapter 5.

    Parameters
    ----------
    mu_bar, mu : array_like, shape (2,)
        Predicted and updated mean ``[p, v]``.
    Sig_bar, Sig : array_like, shape (2, 2)
        Predicted and updated covariance.
    z : float or array_like of shape (1,), optional
        Position reading; without it no band is drawn.
    Q : float or array_like of shape (1, 1), optional
        Measurement noise variance (>= 0), needed with ``z``.
    nsig : float
        Number of standard deviations of the ellipses and the band (> 0).
    labels : (str, str)
        Axis labels.

    Returns
    -------
    Figure
        Shows itself when it is a notebook cell's last value.
    """
    mu_bar = v.vector(mu_bar, "mu_bar", 2)
    mu = v.vector(mu, "mu", 2)
    Sig_bar = v.covariance(Sig_bar, "Sig_bar", 2)
    Sig = v.covariance(Sig, "Sig", 2)
    k = v.positive(nsig, "nsig", "a number of standard deviations")
    if (z is None) != (Q is None):
        raise ValueError("z and Q must be given together (or both None for no measurement band)")
    if z is not None:
        z = v.scalar(z, "z")
        Q = v.variance(Q, "Q")

    fig, ax = new_figure(5.4, 4.4)
    band = None  # the reading's band z +- k sqrt(Q), if there is a reading
    if z is not None:
        half_width = k * math.sqrt(Q)
        band = (z - half_width, z + half_width)
        ax.axvspan(*band, color=palette.MEASUREMENT, alpha=0.15, lw=0)
        reading = rf"reading $z \pm {k:g}\sigma_Q$"
        ax.axvline(z, color=palette.MEASUREMENT, ls=palette.MEASUREMENT_LINE, lw=1.8, label=reading)
    covariance_ellipse(
        ax,
        mu_bar,
        Sig_bar,
        nsig=k,
        color=palette.PREDICTION,
        label=rf"prediction $\bar\Sigma$ (${k:g}\sigma$)",
        zorder=3,
    )
    covariance_ellipse(
        ax, mu, Sig, nsig=k, color=palette.ESTIMATE, label=rf"posterior $\Sigma$ (${k:g}\sigma$)", zorder=3
    )
    ax.plot(*mu_bar, "o", color=palette.PREDICTION, ms=6, zorder=4)
    ax.plot(*mu, "o", color=palette.ESTIMATE, ms=6, zorder=4)

    _fit_view(ax, [(mu_bar, Sig_bar), (mu, Sig)], k, band)
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    fig.legend(loc="outside lower center", ncols=3, fontsize=8, frameon=False)  # under the axes, inside the figure
    return fig
