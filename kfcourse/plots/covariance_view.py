r"""Chapter 2's picture: samples of a 2-D Gaussian and its 1, 2, 3-sigma ellipses.

On the left, samples of :math:`\mathcal N(0, \Sigma)` (grey dots), the contours at
:math:`k = 1, 2, 3` standard deviations (teal, each labelled at the right end of its
major axis) and the dashed box :math:`\pm\sigma_x, \pm\sigma_y` that the 1-sigma contour
fits in, its shadow on the axes.  On the right, the matrix :math:`\Sigma` and a table:
the share of the samples inside each contour beside the theory
:math:`1 - e^{-k^2/2}` (in 2-D).

:func:`covariance_view` builds the figure; :func:`update_covariance` shows a model's
:math:`\Sigma` and samples on it.  Introduced in chapter 2.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PathCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse
from matplotlib.text import Text

from ..filters.gaussian import mass_inside
from . import palette
from .artists import covariance_ellipse, update_covariance_ellipse
from .style import new_figure

LIMIT = 7.5  # half-width of the view, both ways: the 3σ contour (at most ±6) and its label fit at every slider position


@dataclass(frozen=True)
class CovarianceView:
    """What :func:`covariance_view` drew; :func:`update_covariance` moves it."""

    fig: Figure
    ax: Axes  #: the samples and the contours
    ax_text: Axes  #: the matrix and the table, beside the plot
    sigmas: tuple[int, ...]  #: k of each contour
    dots: PathCollection  #: the samples
    rings: tuple[Ellipse, ...]  #: the k-sigma contours, one per ``sigmas``
    labels: tuple[Text, ...]  #: "kσ" at each contour's right end
    shadow: Line2D  #: the dashed box, plus or minus sigma_x by plus or minus sigma_y
    info: Text  #: the matrix and the table

    @property
    def moving(self) -> list:
        """Every artist that changes with the covariance."""
        return [self.dots, *self.rings, *self.labels, self.shadow, self.info]


def covariance_view(sigmas=(1, 2, 3)) -> CovarianceView:
    """The plot and the table beside it, for contours at ``sigmas`` standard deviations.

    Parameters
    ----------
    sigmas : sequence of int
        k of each contour, from 1 to 3 (the view holds the 3-sigma contour of the largest
        variance the chapter's sliders reach, 4).

    Returns
    -------
    CovarianceView
    """
    sigmas = tuple(sigmas)
    if not sigmas or any(isinstance(k, bool) or k not in (1, 2, 3) for k in sigmas):
        raise ValueError(f"sigmas must be contours among 1, 2, 3 standard deviations, got {sigmas!r}")
    fig, (ax, ax_text) = new_figure(7.6, 4.4, ncols=2, gridspec_kw={"width_ratios": [3, 1.1]})
    ax_text.set_axis_off()
    ax.set_xlim(-LIMIT, LIMIT)
    ax.set_ylim(-LIMIT, LIMIT)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    dots = ax.scatter([], [], s=5, color=palette.INK, alpha=0.35, lw=0)
    eye = np.eye(2)
    rings = tuple(
        covariance_ellipse(ax, (0, 0), eye, k, palette.ESTIMATE, lw=2.4 - 0.6 * i, alpha=1.0 - 0.25 * i)
        for i, k in enumerate(sigmas)
    )
    labels = tuple(ax.text(0, 0, f"{k}σ", color=palette.ESTIMATE_TEXT, fontsize=9, weight="bold") for k in sigmas)
    (shadow,) = ax.plot([], [], "--", color=palette.INK, lw=1.0, label="1σ shadow: ±σx, ±σy")
    ax_text.legend(handles=[shadow], loc="lower left", fontsize=8)  # beside the plot: never over a contour
    info = ax_text.text(
        0.0, 0.95, "", transform=ax_text.transAxes, ha="left", va="top", fontsize=10, family="monospace"
    )
    return CovarianceView(fig, ax, ax_text, sigmas, dots, rings, labels, shadow, info)


def update_covariance(view: CovarianceView, model) -> None:
    r"""Show the model's :math:`\Sigma`, its samples and the shares inside each contour.

    Parameters
    ----------
    view : CovarianceView
    model
        Anything with ``Sig`` (2x2), ``samples()`` (an (N, 2) array drawn from
        :math:`\mathcal N(0, \Sigma)`) and ``fractions()`` (the share of them inside each of
        the view's contours), such as :class:`kfcourse.demos.covariance.CovarianceModel`.
    """
    Sig = model.Sig
    view.dots.set_offsets(model.samples())
    w, V = np.linalg.eigh(Sig)  # eigenvalues in ascending order: the major axis is the last
    major = V[:, 1] if V[0, 1] >= 0 else -V[:, 1]  # pointing right
    for ring, label, k in zip(view.rings, view.labels, view.sigmas, strict=True):
        update_covariance_ellipse(ring, (0, 0), Sig)
        label.set_position(k * np.sqrt(w[1]) * major * 1.03)  # just past the contour's right end
    sx, sy = np.sqrt(Sig[0, 0]), np.sqrt(Sig[1, 1])  # the 1σ contour's shadow: ±sigma_x, ±sigma_y
    view.shadow.set_data([-sx, sx, sx, -sx, -sx], [-sy, -sy, sy, sy, -sy])
    inside = model.fractions()
    theory = mass_inside(np.array(view.sigmas), dim=2)  # 1 - exp(-k^2 / 2)
    rows = "\n".join(
        f" {k}σ   {100 * f:5.1f}% {100 * t:5.1f}%" for k, f, t in zip(view.sigmas, inside, theory, strict=True)
    )
    view.info.set_text(
        "Σ =\n"
        f" [{Sig[0, 0]:5.2f} {Sig[0, 1]:5.2f}]\n"
        f" [{Sig[1, 0]:5.2f} {Sig[1, 1]:5.2f}]\n\n"
        f"inside samples theory\n{rows}"
    )
