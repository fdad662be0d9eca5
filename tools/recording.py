"""A demo's run recorded as an animated WebP: what pressing Run shows, for a page without a kernel.

The static edition (``tools/build_site.py``) loads this file in the kernel that ran a
notebook and calls :func:`record_run` on each demo with Run/Pause, and :func:`description_at`
for the sentence that says what the run's last picture shows (the recording's alt text ends
with it).  Both go through the demo's public face only: they move the demo's ``step`` slider
(``demo.controls["frame"]``) as a student would, and read each picture from the demo's
renderer (``demo.renderer.image()``), each description from ``demo.description.text``.
The pictures are as many pixels wide as the demo's own picture and its still on the page,
so the recording, shown in the still's place, looks as sharp.

The page shows a recording only when the reader asks for it, and stops it when asked again
(WCAG 2.2.2: nothing moves by itself); once started, it loops.

A recording of 40 pictures weighs a few hundred kB (a 1900-pixel-wide run: 250 to 600 kB).
"""

from __future__ import annotations

import io
import numbers

PICTURES = 40  # at most, evenly spaced over the run
PICTURE_MS = 120  # between two pictures: a run plays in about five seconds
HOLD_MS = 1500  # the last picture stays this long before the run starts again
QUALITY = 80  # lossy WebP; text and thin lines stay clean at two device pixels per CSS pixel


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
    if "frame" not in demo.controls:
        raise ValueError("demo must have frames (Run/Pause) to record its run")
    if not 0 <= quality <= 100:
        raise ValueError(f"quality must be from 0 to 100, got {quality!r}")
    frame = demo.controls["frame"]
    start, shown = frame.value, []
    try:
        for k in frames_to_record(frame.min, frame.max, pictures):
            frame.value = k  # the demo redraws itself, as when a student drags the slider
            shown.append(demo.renderer.image())
    finally:
        frame.value = start
    durations = [PICTURE_MS] * (len(shown) - 1) + [HOLD_MS]
    buf = io.BytesIO()
    # minimize_size: no key frames, each picture stored as its change from the one before (a third fewer bytes)
    shown[0].save(
        buf,
        format="webp",
        save_all=True,
        append_images=shown[1:],
        duration=durations,
        loop=0,
        quality=quality,
        minimize_size=True,
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
    if "frame" not in demo.controls:
        raise ValueError("demo must have frames (Run/Pause) to describe one of them")
    frame = demo.controls["frame"]
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
