"""Make the animated picture of chapter 10's landmark loop for the README.

One lap of chapter 10's second prompt, the lesson's recipe: noisy odometry
(process noise 3.2), the sensor blind from step 20 to step 89, then one
landmark back: the ellipse balloons while the robot drives on odometry alone
and collapses at the single reading of step 90.  Drawn from the demo's own model and view (the map and the
error strips), one picture per step as Run plays them, written as an animated GIF
with Pillow.

    python tools/loop_animation.py [docs/screenshots/10_capstone.gif]
"""

from __future__ import annotations

import io
import sys
from pathlib import Path

from PIL import Image

from kfcourse.demos.landmark_loop import LoopModel
from kfcourse.plots.loop import loop_view, update_loop_view
from kfcourse.plots.style import FigureRenderer

OUT = Path("docs/screenshots/10_capstone.gif")
EVERY = 1  # steps per picture
FRAME_MS = 80  # ms per picture: one step of 0.2 s, 2.5 times faster than real time, as the demo plays
HOLD_MS = 1500  # ms the last picture stays before the loop starts again
DPI = 80
MAX_BYTES = 2_000_000
MOTION_NOISE = 3.2  # the process-noise slider of the recipe
BLIND = (20, 90)  # dropout pressed at step 20, and again at step 90


def recipe() -> LoopModel:
    """The demo's model at chapter 10's second prompt, set as a student sets it: process noise, then
    dropout pressed at the blind stretch's first step and again at the step sight comes back."""
    model = LoopModel(seed=0)
    model.set_motion_noise(MOTION_NOISE)
    for model.frame, on in zip(BLIND, (True, False), strict=True):
        model.set_dropout(on)
    return model


def frames(model) -> list[Image.Image]:
    """Every EVERY-th step of the model's run as a picture, the last step always included.

    The model's ``frame`` is left at the last step.
    """
    model.frame = 0
    view = loop_view(model)
    view.fig.set_dpi(DPI)
    renderer = FigureRenderer(view.fig, view.moving)
    T = model.run.t.size
    steps = list(range(0, T, EVERY))
    if steps[-1] != T - 1:
        steps.append(T - 1)
    pictures = []
    for k in steps:
        model.frame = k
        update_loop_view(view, model)
        pictures.append(Image.open(io.BytesIO(renderer.png())).convert("RGB"))
    return pictures


def main(out: Path = OUT) -> None:
    pictures = frames(recipe())
    montage = Image.new("RGB", (pictures[0].width, pictures[0].height * 8))  # one palette from across the lap
    for i, k in enumerate(range(0, len(pictures), -(-len(pictures) // 8))):
        montage.paste(pictures[k], (0, i * pictures[0].height))
    palette_image = montage.quantize(colors=255, method=Image.Quantize.MAXCOVERAGE)
    quantized = [p.quantize(palette=palette_image, dither=Image.Dither.NONE) for p in pictures]
    durations = [FRAME_MS] * (len(quantized) - 1) + [HOLD_MS]
    out.parent.mkdir(parents=True, exist_ok=True)
    quantized[0].save(
        out, save_all=True, append_images=quantized[1:], duration=durations, loop=0, optimize=True, disposal=1
    )
    size = out.stat().st_size
    print(f"{out}: {len(quantized)} pictures, {quantized[0].size[0]}x{quantized[0].size[1]} px, {size / 1e6:.2f} MB")
    if size > MAX_BYTES:
        raise SystemExit(f"{out} is {size / 1e6:.2f} MB, more than {MAX_BYTES / 1e6:.0f} MB")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else OUT)
