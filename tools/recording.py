"""A demo's run recorded as an animated WebP: what pressing Run shows, for a page without a kernel.

The static edition (``tools/build_site.py``) loads this file in the kernel that ran a
notebook and calls :func:`record` on each demo with Run/Pause: the recording of its run and the
sentence that says what the run's last picture shows (the recording's alt text ends with it),
in one pass over the run.  :func:`record_run` and :func:`description_at` give each alone.
All go through the demo's public face only: they move the demo's ``step`` slider
(``demo.controls["frame"]``) as a student would, and read each picture from what the demo
drew (its renderer's figure, :func:`frame_pictures`), each description from
``demo.description.text``.  The pictures are as many pixels wide as the demo's own picture and
its still on the page, so the recording, shown in the still's place, looks as sharp.

The page shows a recording only when the reader asks for it, and stops it when asked again
(WCAG 2.2.2: nothing moves by itself); once started, it loops.

A recording of 40 pictures weighs a few hundred kB (170 to 300 kB; the 1900-pixel-wide run of
chapter 0, the widest: about 290 kB).
"""

from __future__ import annotations

import io
import numbers

from PIL import Image

PICTURES = 40  # at most, evenly spaced over the run
PICTURE_MS = 120  # between two pictures: a run plays in about five seconds
HOLD_MS = 1500  # the last picture stays this long before the run starts again
QUALITY = 80  # lossy WebP; text and thin lines stay clean at two device pixels per CSS pixel
WEBP_METHOD = 2  # libwebp's effort, 0 (fastest) to 6


def frames_to_record(first: int, last: int, pictures: int) -> list[int]:
    """At most ``pictures`` frames from ``first`` to ``last``, evenly spaced, both ends included.

    Parameters
    ----------
    first, last : int
        The first and last frame of the run (``last >= first``).
    pictures : int
        At most this many frames (>= 2).

    Returns
    -------
    list of int
        Increasing frame numbers, ``first`` and ``last`` among them.
    """
    if pictures < 2:
        raise ValueError(f"pictures must be at least 2, got {pictures!r}")
    if last < first:
        raise ValueError(f"last must not come before first, got first={first!r}, last={last!r}")
    stride = max(1, -(-(last - first) // (pictures - 1)))  # ceil: never more than `pictures`
    return [*range(first, last, stride), last]


def frame_pictures(demo, frames: list[int]) -> list[Image.Image]:
    """The pictures the demo shows on ``frames``, one per frame, as a student sees them after
    dragging the step slider there.

    Moving the slider makes the demo redraw itself into its figure's canvas at full size (the
    light picture it sends while moving is halved from that canvas), so each picture is read
    off the canvas once it has drawn, not rendered a second time.  A frame the slider is
    already on is rendered afresh (``demo.renderer.image()``), as is any whose canvas is not
    the renderer's full width.

    The demo is left on the last of ``frames``.
    """
    frame, shown = demo.controls["frame"], []
    for k in frames:
        moved = frame.value != k
        frame.value = k  # the demo redraws itself, as when a student drags the slider
        picture = _canvas_picture(demo) if moved else None
        shown.append(picture if picture is not None else demo.renderer.image())
    return shown


def _canvas_picture(demo) -> Image.Image | None:
    """What the demo's canvas holds now, as an RGB image (a copy); None if it is not the full-size picture."""
    canvas = demo.renderer.fig.canvas
    width, height = canvas.get_width_height(physical=True)
    if width != demo.renderer.pixel_width:
        return None
    return Image.frombuffer("RGBA", (width, height), canvas.buffer_rgba(), "raw", "RGBA", 0, 1).convert("RGB")


def record(demo, pictures: int = PICTURES, quality: int = QUALITY) -> tuple[bytes, str]:
    """The demo's run as an animated WebP (:func:`record_run`), and what its description says on
    the run's last frame (:func:`description_at`), in one pass over the run.

    The last frame is read at rest (``demo.refresh()``): its picture and its description are the
    crisp ones a student sees there.  The demo is left on the frame it was on, at rest.

    Returns
    -------
    (bytes, str)
        The WebP file, and the sentence that says what its last picture shows.
    """
    frame = _frames_of(demo, "record its run")
    _check_quality(quality)
    ks = frames_to_record(frame.min, frame.max, pictures)
    start = frame.value
    try:
        shown = frame_pictures(demo, ks[:-1])
        frame.value = ks[-1]
        demo.refresh()  # at rest: the crisp picture and the description of what it shows
        last = demo.description.text
        picture = _canvas_picture(demo)  # refresh() drew it
        shown.append(picture if picture is not None else demo.renderer.image())
    finally:
        frame.value = start
        demo.refresh()
    return _webp(shown, quality), last


def record_run(demo, pictures: int = PICTURES, quality: int = QUALITY) -> bytes:
    """The demo's run, first frame to last, as an animated WebP that loops.

    The demo is left on the frame it was on.

    Parameters
    ----------
    demo : kfcourse.demos.Demo
        A demo with Run/Pause: its controls hold the ``frame`` slider.
    pictures : int
        At most this many pictures, evenly spaced over the run (>= 2).
    quality : int
        WebP quality, 0 to 100.

    Returns
    -------
    bytes
        The WebP file: ``demo.renderer.pixel_width`` pixels wide, as wide as the demo's
        own picture.
    """
    frame = _frames_of(demo, "record its run")
    _check_quality(quality)
    ks = frames_to_record(frame.min, frame.max, pictures)
    start = frame.value
    try:
        shown = frame_pictures(demo, ks)
    finally:
        frame.value = start
    return _webp(shown, quality)


def _frames_of(demo, purpose: str):
    if "frame" not in demo.controls:
        raise ValueError(f"demo must have frames (Run/Pause) to {purpose}")
    return demo.controls["frame"]


def _check_quality(quality: int) -> None:
    if not 0 <= quality <= 100:
        raise ValueError(f"quality must be from 0 to 100, got {quality!r}")


def _webp(shown: list[Image.Image], quality: int) -> bytes:
    """The pictures as an animated WebP that loops, resting on the last one."""
    durations = [PICTURE_MS] * (len(shown) - 1) + [HOLD_MS]
    buf = io.BytesIO()
    # kmax=0: no key frames, each picture stored as its change from the one before (a third fewer bytes than
    # with key frames); method=2: a quarter fewer bytes again than the animation encoder's default (0), at
    # the same fidelity (PSNR within 0.2 dB) and no more time.  minimize_size=True, tried before, made the
    # same file as kmax=0 and took a third longer.
    shown[0].save(
        buf,
        format="webp",
        save_all=True,
        append_images=shown[1:],
        duration=durations,
        loop=0,
        quality=quality,
        method=WEBP_METHOD,
        kmin=0,
        kmax=0,
    )
    return buf.getvalue()


def description_at(demo, k: int) -> str:
    """What the demo's description says on frame ``k``: its ``description.text`` once it rests there.

    The demo is left on the frame it was on, at rest.

    Parameters
    ----------
    demo : kfcourse.demos.Demo
        A demo with Run/Pause: its controls hold the ``frame`` slider.
    k : int
        A frame of the run, from the slider's ``min`` to its ``max``.

    Returns
    -------
    str
        One sentence built from the demo's numbers on that frame.
    """
    frame = _frames_of(demo, "describe one of them")
    if isinstance(k, bool) or not isinstance(k, numbers.Integral) or not frame.min <= k <= frame.max:
        raise ValueError(f"k must be a frame from {frame.min} to {frame.max}, got {k!r}")
    start = frame.value
    try:
        frame.value = int(k)
        demo.refresh()  # at rest: the crisp picture and the description of what it shows
        return demo.description.text
    finally:
        frame.value = start
        demo.refresh()
