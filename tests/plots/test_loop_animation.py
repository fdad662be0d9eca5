"""The README's animated landmark loop (``tools/loop_animation.py``) is drawn from the demo's
model and view at chapter 10's second prompt (the lesson's recipe), one picture per step shown."""

from __future__ import annotations

import numpy as np

from tools import loop_animation


def test_the_animation_plays_the_recipe_with_the_demo_view(monkeypatch, tmp_path):
    model = loop_animation.recipe()
    assert model.blind == (20, 90) and model.motion_noise == loop_animation.MOTION_NOISE == 3.2  # prompt 2
    assert np.count_nonzero(model.run.used[90]) == 1  # sight comes back one landmark first
    monkeypatch.setattr(loop_animation, "EVERY", 40)  # steps 0, 40, 80, 120 and the last, 121
    pictures = loop_animation.frames(model)
    assert len(pictures) == 5 and model.frame == model.run.t.size - 1
    assert len({p.size for p in pictures}) == 1
    first, blind = (np.asarray(p, float) for p in pictures[:2])
    assert np.abs(first - blind).mean() > 0.5  # the robot moved on
    out = tmp_path / "loop.gif"
    loop_animation.main(out)
    assert out.read_bytes()[:6] == b"GIF89a" and out.stat().st_size <= loop_animation.MAX_BYTES
