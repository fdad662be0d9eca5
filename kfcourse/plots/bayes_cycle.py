"""Chapter 1: one cycle of the Bayes filter at a glance."""

from __future__ import annotations

import numpy as np

from . import palette
from .artists import belief_bars
from .style import new_figure


def bayes_cycle_chart(prior, bel_bar, likelihood, posterior, cells=None):
    r"""Four bar panels side by side: prior, prediction, likelihood and posterior of one cycle.

    Colours by role: the beliefs :math:`\mathrm{bel}` in teal (estimate), the prediction
    :math:`\overline{\mathrm{bel}}` in purple, the likelihood :math:`p(z \mid x)` in orange
    (measurement).  Introduced in chapter 1.

    Parameters
    ----------
    prior, bel_bar, likelihood, posterior : array_like, shape (n,)
        ``bel(x_{t-1})``, ``bel_bar(x_t)``, ``p(z_t | x_t)`` and ``bel(x_t)`` over ``n`` cells.
    cells : sequence of str, optional
        Names of the ``n`` cells; ``0, 1, ..., n-1`` if omitted.

    Returns
    -------
    matplotlib.figure.Figure
    """
    stages = [np.asarray(a, float) for a in (prior, bel_bar, likelihood, posterior)]
    n = stages[0].size
    for name, values in zip(("prior", "bel_bar", "likelihood", "posterior"), stages, strict=True):
        if values.shape != (n,) or not np.isfinite(values).all() or (values < 0).any():
            raise ValueError(f"{name} must be {n} finite values >= 0 (one per cell), got {values!r}")
    cells = [str(c) for c in range(n)] if cells is None else [str(c) for c in cells]
    if len(cells) != n:
        raise ValueError(f"cells must name the {n} cells, got {len(cells)} names")
    titles = ["prior bel", r"predicted $\overline{bel}$", "likelihood p(z|x)", "posterior bel"]
    colours = [palette.ESTIMATE, palette.PREDICTION, palette.MEASUREMENT, palette.ESTIMATE]
    top = 1.1 * max(float(values.max()) for values in stages)
    fig, axes = new_figure(9.0, 2.4, ncols=4, sharey=True)
    for ax, values, title, colour in zip(axes, stages, titles, colours, strict=True):
        belief_bars(ax, values, color=colour)
        ax.set(title=title, xticks=range(n), xticklabels=cells, ylim=(0, top))
    return fig
