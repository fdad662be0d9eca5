"""The hallway demo's two text blocks (its settings, top left; what the last step did, top right)
never cover a belief bar, whatever the controls have done to the belief."""

from __future__ import annotations

import itertools

import kfcourse as kf


def overlaps(demo) -> list[str]:
    """Which text block overlaps which belief bar, in the picture as drawn."""
    fig = demo.renderer.fig
    renderer = fig.canvas.get_renderer()  # the demo has drawn the picture: extents need no new draw
    ax = fig.axes[0]
    texts = [t for t in ax.texts if t.get_text()]
    assert len(texts) == 2  # the settings and the status line
    found = []
    for text, bar in itertools.product(texts, ax.patches):
        if text.get_window_extent(renderer).overlaps(bar.get_window_extent(renderer)):
            found.append(f"{text.get_text().splitlines()[0]!r} over the bar at x = {bar.get_x():.1f}")
    return found


def test_texts_clear_the_bars_through_a_run_of_presses():
    demo = kf.demos.hallway(seed=0)
    c = demo.controls
    assert overlaps(demo) == []  # the first picture: after the first Update, two tall bars at cells 0 and 10
    for motion, sensor in ((1.0, 0.99), (0.5, 0.99), (1.0, 0.5), (0.9, 0.95)):
        c["reset"].click()
        c["motion_reliability"].value, c["sensor_reliability"].value = motion, sensor
        for press in ["update", "predict"] * 8 + ["update"]:
            c[press].click()
            assert overlaps(demo) == [], (motion, sensor, press, demo.model.belief.max())
