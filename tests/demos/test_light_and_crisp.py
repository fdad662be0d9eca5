"""What a demo sends in the kernel: a light picture while something moves, the crisp one at rest.

In the kernel a demo lives on an event loop.  A control change shows a half-size WebP at
once and the full JPEG ``REST_AFTER`` seconds after the last change; Run sends light
pictures and Pause the crisp one.  JupyterLab may deliver widget messages on a kernel
subshell, in another thread: such a change is drawn on the demo's own loop all the same.
"""

from __future__ import annotations

import asyncio
import io
import threading

from PIL import Image

import kfcourse as kf
from kfcourse.demos._base import FRAME_INTERVAL, REST_AFTER, running_sentence


def watch(demo) -> list[tuple[str, int, int]]:
    """Every picture the demo sends: (format, pixel width, thread)."""
    sent = []

    def record(change) -> None:
        width = Image.open(io.BytesIO(bytes(change["new"]))).size[0]
        sent.append((demo.image.format, width, threading.get_ident()))

    demo.image.observe(record, "value")
    return sent


def in_kernel(scenario):
    """Run ``scenario(demo, sent)`` on an event loop with a tracker built on it, as in a notebook cell."""

    async def main():
        demo = kf.demos.tracker(seed=0)
        sent = watch(demo)
        await scenario(demo, sent)
        return demo, sent

    return asyncio.run(main())


def from_another_thread(action) -> None:
    thread = threading.Thread(target=action)
    thread.start()
    thread.join()


def test_a_change_sends_a_light_picture_then_the_crisp_one():
    async def scenario(demo, sent):
        demo.controls["R"].value = demo.controls["R"].max
        assert [fmt for fmt, *_ in sent] == ["webp"]  # at once: the light picture only
        await asyncio.sleep(REST_AFTER + 0.2)

    demo, sent = in_kernel(scenario)
    (light, light_width, _), (crisp, crisp_width, _) = sent
    assert (light, crisp) == ("webp", "jpeg")
    assert light_width == crisp_width // 2 and crisp_width == demo.renderer.pixel_width


def test_changes_in_quick_succession_send_one_crisp_picture_at_the_end():
    async def scenario(demo, sent):
        for k in range(1, 6):
            demo.controls["frame"].value = k
            await asyncio.sleep(REST_AFTER / 5)
        await asyncio.sleep(REST_AFTER + 0.2)

    _, sent = in_kernel(scenario)
    assert [fmt for fmt, *_ in sent] == ["webp"] * 5 + ["jpeg"]


def test_a_change_from_another_thread_is_drawn_on_the_demo_loop():
    async def scenario(demo, sent):
        from_another_thread(lambda: setattr(demo.controls["frame"], "value", 5))
        await asyncio.sleep(REST_AFTER + 0.2)

    demo, sent = in_kernel(scenario)
    assert demo.model.frame == 5
    assert [fmt for fmt, *_ in sent] == ["webp", "jpeg"]
    assert {thread for *_, thread in sent} == {threading.get_ident()}


def test_run_and_pause_from_another_thread():
    async def scenario(demo, sent):
        from_another_thread(lambda: setattr(demo.controls["play"], "value", True))
        await asyncio.sleep(12 * FRAME_INTERVAL)
        from_another_thread(lambda: setattr(demo.controls["play"], "value", False))
        await asyncio.sleep(0.05)
        paused_at, pictures = demo.controls["frame"].value, len(sent)
        await asyncio.sleep(REST_AFTER + 0.2)
        assert demo.controls["frame"].value == paused_at and len(sent) == pictures  # nothing after Pause

    demo, sent = in_kernel(scenario)
    formats = [fmt for fmt, *_ in sent]
    assert formats[-1] == "jpeg" and set(formats[:-1]) == {"webp"} and len(formats) >= 6
    assert {thread for *_, thread in sent} == {threading.get_ident()}
    assert demo.controls["play"].description == "Run"


def test_while_run_plays_the_sentence_says_so_and_pause_brings_back_the_step_shown():
    seen = {}

    async def scenario(demo, sent):
        demo.controls["frame"].value = 7
        await asyncio.sleep(REST_AFTER + 0.2)
        seen["at rest"] = demo.description.text
        demo.controls["play"].value = True
        await asyncio.sleep(6 * FRAME_INTERVAL)
        seen["running"] = demo.description.text
        seen["moved"] = demo.controls["frame"].value > 7
        demo.controls["play"].value = False
        await asyncio.sleep(0.05)
        seen["paused"] = demo.description.text

    demo, _ = in_kernel(scenario)
    assert seen["moved"] and seen["running"] == running_sentence(7)
    assert seen["at rest"] != seen["running"]
    assert seen["paused"] == demo.model.describe() != seen["at rest"]  # the step Pause stopped at
