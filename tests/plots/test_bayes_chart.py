"""The chapter 1 cycle chart draws the four stages it is given, in their roles' colours."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.colors import to_hex

import kfcourse as kf
from kfcourse.plots import palette

PRIOR = np.array([0.5, 0.3, 0.2])
BEL_BAR = np.array([0.10, 0.46, 0.44])
DOOR = np.array([0.1, 0.6, 0.3])
POSTERIOR = np.array([0.024, 0.660, 0.316])


def test_chart_draws_each_stage_as_bars_in_its_colour():
    fig = kf.plots.bayes_cycle_chart(PRIOR, BEL_BAR, DOOR, POSTERIOR, cells="ABC")
    assert len(fig.axes) == 4
    colours = [palette.ESTIMATE, palette.PREDICTION, palette.MEASUREMENT, palette.ESTIMATE]
    for ax, values, colour in zip(fig.axes, (PRIOR, BEL_BAR, DOOR, POSTERIOR), colours, strict=True):
        heights = [bar.get_height() for bar in ax.patches]
        np.testing.assert_allclose(heights, values)
        assert {to_hex(bar.get_facecolor()) for bar in ax.patches} == {to_hex(colour)}
        assert [t.get_text() for t in ax.get_xticklabels()] == ["A", "B", "C"]
        assert ax.get_ylim()[1] >= values.max()  # nothing cut off at the top
    assert "predicted" in fig.axes[1].get_title() and "likelihood" in fig.axes[2].get_title()
    png = fig._repr_png_()
    assert png[:4] == b"\x89PNG"


def test_cells_are_numbered_when_not_named():
    fig = kf.plots.bayes_cycle_chart(PRIOR, BEL_BAR, DOOR, POSTERIOR)
    assert [t.get_text() for t in fig.axes[0].get_xticklabels()] == ["0", "1", "2"]


@pytest.mark.parametrize(
    "args, word",
    [
        ((PRIOR, BEL_BAR[:2], DOOR, POSTERIOR), "bel_bar"),
        ((PRIOR, BEL_BAR, -DOOR, POSTERIOR), "likelihood"),
        ((PRIOR, BEL_BAR, DOOR, [0.1, np.nan, 0.2]), "posterior"),
    ],
)
def test_bad_stages_are_named(args, word):
    with pytest.raises(ValueError, match=word):
        kf.plots.bayes_cycle_chart(*args)


def test_wrong_number_of_cell_names():
    with pytest.raises(ValueError, match="cells"):
        kf.plots.bayes_cycle_chart(PRIOR, BEL_BAR, DOOR, POSTERIOR, cells="AB")
