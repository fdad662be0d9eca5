"""A still figure's alt text is read off the figure: titles, what is plotted against what, legend."""

import pytest

from kfcourse.plots.describe import figure_alt
from kfcourse.plots.style import new_figure


def test_the_alt_text_names_the_title_each_panel_its_axes_and_its_legend():
    fig, (left, right) = new_figure(ncols=2)
    fig.suptitle("Two filters")
    left.plot([0, 1], [0, 1], label="truth")
    left.plot([0, 1], [0, 2], label="estimate")
    left.set(title="KF", xlabel="step", ylabel="position x (m)")
    right.plot([0, 1], [1, 0])
    right.set_xlabel("step")
    alt = figure_alt(fig)
    assert alt.startswith("Figure: Two filters.")
    assert "Panel 1 of 2 'KF': position x (m) against step; shows truth, estimate." in alt
    assert "Panel 2 of 2: step." in alt


def test_empty_panels_and_hidden_legend_entries_are_left_out():
    fig, (drawn, _empty) = new_figure(ncols=2)
    drawn.plot([0, 1], [0, 1], label="_hidden")
    assert figure_alt(fig) == "Figure. Panel: no axis labels."


def test_anything_but_a_figure_is_refused():
    with pytest.raises(ValueError, match="fig"):
        figure_alt("a picture")
