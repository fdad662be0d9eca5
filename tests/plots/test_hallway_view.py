"""Chapter 1's view: the bars, the map and the likelihood show the model they are given,
the belief axis keeps room for the texts, and only a new top redraws the background."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.colors import to_hex

from kfcourse.plots import palette
from kfcourse.plots.hallway_view import BARS_SHARE, TOP_STEP, hallway_view, update_hallway
from kfcourse.plots.style import FigureRenderer
from kfcourse.sim.hallway_world import hallway_doors

DOORS = hallway_doors()
N = DOORS.shape[1]


def model(belief, phase="updated", boundary="wrap", **kwargs):
    """Everything :func:`update_hallway` reads, and nothing else."""
    belief = np.asarray(belief, float)
    likelihood = kwargs.pop("likelihood", np.linspace(0.1, 0.9, N))
    return SimpleNamespace(
        belief=belief,
        likelihood=likelihood,
        true_cell=kwargs.pop("true_cell", 4),
        phase=phase,
        boundary=boundary,
        motion_reliability=0.8,
        sensor_reliability=0.9,
        steps=kwargs.pop("steps", 3),
        saw_door=np.array([True, False]),
        eta=0.25,
        likelihood_is_stale=lambda: kwargs.get("stale", False),
    )


def peaked(height: float, at: int = 5) -> np.ndarray:
    """A belief with one bar of ``height`` and the rest spread evenly."""
    belief = np.full(N, (1.0 - height) / (N - 1))
    belief[at] = height
    return belief


def test_the_update_shows_the_model():
    view = hallway_view(DOORS)
    m = model(peaked(0.4), phase="predicted", boundary="wall", true_cell=7, steps=1)
    update_hallway(view, m)
    assert [bar.get_height() for bar in view.bars] == pytest.approx(m.belief)
    assert {to_hex(bar.get_facecolor()) for bar in view.bars} == {palette.PREDICTION}
    assert [bar.get_height() for bar in view.likelihood] == pytest.approx(m.likelihood)
    assert {bar.get_alpha() for bar in view.likelihood} == {0.35}  # a prediction does not use the reading
    assert view.robot.get_xdata()[0] == 7
    assert all(wall.get_visible() for wall in view.end_walls)
    assert "1 move since Reset" in view.status.get_text()
    assert "one cell right 0.80, stall 0.20" in view.setup.get_text() and "walls" in view.setup.get_text()
    m.phase, m.boundary = "updated", "wrap"
    update_hallway(view, m)
    assert {to_hex(bar.get_facecolor()) for bar in view.bars} == {palette.ESTIMATE}
    assert {bar.get_alpha() for bar in view.likelihood} == {1.0}
    assert not any(wall.get_visible() for wall in view.end_walls)
    assert "left “door”, right “no door”, η = 0.25" in view.status.get_text()
    assert "loop (wrap)" in view.setup.get_text()


def test_the_map_draws_every_door():
    view = hallway_view(DOORS)
    doors = view.ax_map.patches  # a rectangle per door
    assert len(doors) == DOORS.sum()
    upper = sorted(round(p.get_x() + p.get_width() / 2) for p in doors if p.get_y() > 0.5)
    assert upper == list(np.flatnonzero(DOORS[0]))  # the left wall is the upper one


@pytest.mark.parametrize("height", [1 / N, 0.2, 0.4, 0.6, 0.9, 1.0])
def test_the_belief_axis_leaves_room_for_the_texts(height):
    view = hallway_view(DOORS)
    update_hallway(view, model(peaked(height)))
    top = view.ax.get_ylim()[1]
    assert height <= BARS_SHARE * top + 1e-12  # the tallest bar stays under the texts
    assert top / TOP_STEP == round(top / TOP_STEP)  # in coarse steps
    assert top - TOP_STEP < height / BARS_SHARE  # the next step down would not do
    assert max(view.ax.get_yticks()) <= 1.0  # a probability's ticks stop at 1


def test_only_a_new_top_redraws_the_background():
    view = hallway_view(DOORS)
    m = model(peaked(0.3))
    update_hallway(view, m)
    renderer = FigureRenderer(view.fig, view.moving)
    renderer.image()
    for height, at in ((0.32, 6), (0.28, 2)):  # the same top: bars, robot, texts move
        m.belief, m.true_cell = peaked(height, at), at
        update_hallway(view, m)
        renderer.image()
    assert renderer.full_draws == 1
    m.belief = peaked(0.8)
    update_hallway(view, m)
    renderer.image()
    assert renderer.full_draws == 2


@pytest.mark.parametrize("doors", [np.ones(12, bool), np.zeros((3, 12), bool), np.ones((2, 12))])
def test_doors_must_be_a_two_wall_map(doors):
    with pytest.raises(ValueError, match="doors"):
        hallway_view(doors)
