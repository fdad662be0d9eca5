"""A figure's alt text: what a reader who cannot see the picture needs to know is there.

A still figure in a chapter is shown as a picture; a screen reader announces its alt text.
The sentence is read off the figure itself: its title, and for each panel its title, what is
plotted against what, and the names in its legend.
"""

from __future__ import annotations

from matplotlib.axes import Axes
from matplotlib.figure import Figure


def figure_alt(fig: Figure) -> str:
    """Alt text for ``fig``, built from its titles, axis labels and legend entries.

    Returns
    -------
    str
        E.g. ``"Figure: Two filters. Left panel 'KF': position x (m) against step;
        truth, estimate."``
    """
    if not isinstance(fig, Figure):
        raise ValueError(f"fig: expected a matplotlib Figure, got {type(fig).__name__}")
    panels = [ax for ax in fig.get_axes() if ax.get_visible() and _has_content(ax)]
    title = fig.get_suptitle().strip()
    parts = [f"Figure: {title}." if title else "Figure."]
    for i, ax in enumerate(panels):
        name = "Panel" if len(panels) == 1 else f"Panel {i + 1} of {len(panels)}"
        parts.append(_panel(ax, name))
    return " ".join(parts)


def _has_content(ax: Axes) -> bool:
    return bool(ax.lines or ax.collections or ax.patches or ax.images or ax.texts)


def _panel(ax: Axes, name: str) -> str:
    title = " ".join(t for t in (ax.get_title(loc) for loc in ("left", "center", "right")) if t.strip())
    head = f"{name} '{title}'" if title else name
    x, y = ax.get_xlabel().strip(), ax.get_ylabel().strip()
    if x and y:
        axes = f"{y} against {x}"
    else:
        axes = x or y or "no axis labels"
    _, labels = ax.get_legend_handles_labels()
    shown = [label for label in dict.fromkeys(labels) if label and not label.startswith("_")]
    return f"{head}: {axes}" + (f"; shows {', '.join(shown)}." if shown else ".")
