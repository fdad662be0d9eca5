"""The recording of a demo's run for the static edition (``tools/recording.py``).

A demo with Run/Pause is recorded by moving its ``step`` slider and reading its renderer:
an animated WebP as many pixels wide as the demo's still picture, from the run's first
frame to its last, resting there before it loops.
"""

from __future__ import annotations

import base64
import io

import ipywidgets as widgets
import numpy as np
import pytest
from PIL import Image

import kfcourse as kf
from kfcourse.plots.style import PIXEL_DENSITY
from tools.recording import HOLD_MS, description_at, frame_pictures, frames_to_record, record, record_run

DEMOS = kf.demos.__all__
# The demos with a run to play, named here so that collecting the tests builds no demo;
# test_the_demos_with_a_run_are_listed checks the list against every demo.
FRAME_DEMOS = ["landmark_loop", "particle_cloud", "raw_vs_filtered", "real_run", "tracker"]


def picture(data: bytes) -> Image.Image:
    return Image.open(io.BytesIO(bytes(data)))


def pixels(image: Image.Image) -> np.ndarray:
    return np.asarray(image.convert("RGB"), float)


@pytest.mark.parametrize("name", DEMOS)
def test_the_demos_with_a_run_are_listed(name):
    demo = getattr(kf.demos, name)(seed=0)
    assert ("frame" in demo.controls) == (name in FRAME_DEMOS)
    if name in FRAME_DEMOS:
        assert isinstance(demo.controls["play"], widgets.ToggleButton)  # Run/Pause


def frame_picture(demo, k: int) -> np.ndarray:
    """What the demo shows on frame ``k``, as a student sees it after dragging the step slider there."""
    demo.controls["frame"].value = k
    return pixels(picture(demo.image.value))


@pytest.mark.parametrize("name", FRAME_DEMOS)
def test_recording_of_a_run(name):
    demo = getattr(kf.demos, name)(seed=0)
    frame, shown = demo.controls["frame"], bytes(demo.image.value)
    start = frame.value
    still = picture(base64.b64decode(demo._repr_mimebundle_()[0]["image/png"]))

    run = picture(record_run(demo, pictures=8))

    assert frame.value == start and bytes(demo.image.value) == shown  # the demo is left as it was
    assert run.format == "WEBP"
    assert run.size == still.size  # as sharp as the still beside it
    assert run.size[0] == PIXEL_DENSITY * demo.display_width
    assert 2 <= run.n_frames <= 8
    assert run.info.get("loop") == 0  # it plays again and again
    durations = []
    for i in range(run.n_frames):
        run.seek(i)
        run.load()  # the frame's duration is known once it is decoded
        durations.append(run.info["duration"])
    assert durations[-1] == HOLD_MS > max(durations[:-1])  # it rests on the last picture
    run.seek(0)
    first = pixels(run)
    run.seek(run.n_frames - 1)
    last = pixels(run)
    assert np.abs(first - last).mean() > 0.5  # it moves
    assert np.abs(first - frame_picture(demo, frame.min)).mean() < 3.0  # from the run's first frame
    assert np.abs(last - frame_picture(demo, frame.max)).mean() < 3.0  # to its last


@pytest.mark.parametrize(("first", "last", "pictures"), [(0, 149, 40), (0, 159, 8), (3, 12, 40), (0, 1, 2), (7, 7, 5)])
def test_frames_to_record_span_the_run_evenly(first, last, pictures):
    ks = frames_to_record(first, last, pictures)
    assert ks[0] == first and ks[-1] == last
    assert len(ks) <= pictures
    steps = np.diff(ks)
    assert (steps > 0).all()
    assert len(set(steps[:-1].tolist())) <= 1  # evenly spaced; only the step to the last frame may be shorter
    if last - first < pictures:
        assert ks == list(range(first, last + 1))  # a short run: every frame


def test_each_picture_of_a_recording_is_what_the_demo_shows_on_that_frame():
    """The pictures are read off the canvas the demo drew into, not rendered again: they are
    exactly what the renderer gives on that frame, the frame the slider is on included."""
    demo = kf.demos.tracker(seed=0)
    frame = demo.controls["frame"]
    ks = [frame.value, frame.value + 3, frame.max]
    shown = frame_pictures(demo, ks)
    assert frame.value == frame.max
    for k, got in zip(ks, shown, strict=True):
        frame.value = k
        assert got.mode == "RGB" and np.array_equal(np.asarray(got), np.asarray(demo.renderer.image())), k


@pytest.mark.parametrize("name", ["raw_vs_filtered", "tracker"])
def test_record_gives_the_run_and_the_description_of_its_last_frame(name):
    demo = getattr(kf.demos, name)(seed=0)
    frame = demo.controls["frame"]
    start, before, shown = frame.value, demo.description.text, bytes(demo.image.value)

    data, last = record(demo, pictures=6)

    assert frame.value == start and demo.description.text == before  # left as it was, at rest
    assert bytes(demo.image.value) == shown
    assert last == description_at(demo, frame.max)
    run = picture(data)
    assert run.format == "WEBP" and 2 <= run.n_frames <= 6 and run.size[0] == demo.renderer.pixel_width
    assert data == record_run(demo, pictures=6)  # the same file as the recording alone


def test_recording_needs_a_run_and_sensible_settings():
    with pytest.raises(ValueError, match="demo"):
        record_run(kf.demos.covariance_ellipse(seed=0))
    demo = kf.demos.tracker(seed=0)
    with pytest.raises(ValueError, match="pictures"):
        record_run(demo, pictures=1)
    with pytest.raises(ValueError, match="quality"):
        record_run(demo, quality=101)
    with pytest.raises(ValueError, match="demo"):
        record(kf.demos.covariance_ellipse(seed=0))
    with pytest.raises(ValueError, match="quality"):
        record(demo, quality=-1)
    with pytest.raises(ValueError, match="last"):
        frames_to_record(5, 4, 10)


def test_the_description_of_a_frame_is_read_at_rest_and_the_demo_left_where_it_was():
    demo = kf.demos.tracker(seed=0)
    frame = demo.controls["frame"]
    start, before = frame.value, demo.description.text
    last = description_at(demo, frame.max)
    assert last != before and f"step {frame.max}" in last.lower()
    assert frame.value == start and demo.description.text == before
    with pytest.raises(ValueError, match="k must be a frame"):
        description_at(demo, frame.max + 1)
