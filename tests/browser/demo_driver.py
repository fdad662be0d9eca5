"""Driving one ``.kf-demo`` in the page and watching its picture: every slider (End / Home,
then ArrowRight presses, with the latency of each), every button, every choice and the
Run/Pause animation must change the picture, and after Pause the picture stops within one
frame interval.  See ``kfcourse/demos/_base.py`` for the DOM contract.

Every picture that arrives is weighed (its bytes and MIME type) and measured (its pixel
width against the CSS width it is shown at).  While a control moves, a demo sends a light
WebP; once the student stops, the crisp JPEG, with two pixels per CSS pixel.  The driver
waits for that crisp picture after every action, and says so when it does not come.

What goes wrong is written to the test's list of problems; notes and latency go to its report.
"""

from __future__ import annotations

import itertools
import time

from kfcourse.demos._base import FRAME_INTERVAL
from tests.browser.lab import PlaywrightTimeoutError

CHANGE_TIMEOUT_MS = 10_000  # one control action -> new picture
LATENCY_SAMPLES = 10  # ArrowRight presses per slider
PLAY_MS = 1_500
PAUSE_SLACK_MS = 250  # after Pause: one frame interval, plus the frame already on its way, plus transport
CRISP = "image/jpeg"  # the picture at rest; anything else is a light one, sent while something moves

# --------------------------------------------------------------------------- page-side helpers

# Records every src change of the picture, in the page: when (performance.now()), the time of
# the last keydown and click before it, and what the blob behind the new src holds (its MIME
# type, bytes, the format its first bytes say and its pixel width), read at once because the
# widget revokes the old blob URL when it sets the next one.  Several changes in one observer
# batch are told apart by the mutation's old value (the src each change set is the next
# record's old value, or the current src for the last).  Only the last change of a batch was
# ever on screen: it alone gets the time it was decoded and the CSS width it is shown at.
# The link benchmark (benchmarks/bench_link.py) watches the picture with this same script.
JS_WATCH_IMG = """(img) => {
    if (!window.__kfKeyWatch) {
        window.__kfKeyWatch = true;
        window.__kfKeyT = null;
        window.__kfClickT = null;
        document.addEventListener('keydown', e => { window.__kfKeyT = e.timeStamp; }, true);
        document.addEventListener('click', e => { window.__kfClickT = e.timeStamp; }, true);
    }
    const rec = {changes: []};
    img.__kf = rec;
    const sniff = head => {
        const text = (a, z) => String.fromCharCode(...head.slice(a, z));
        return text(0, 3) === '\\xff\\xd8\\xff' ? 'image/jpeg'
            : text(0, 4) === 'RIFF' && text(8, 12) === 'WEBP' ? 'image/webp'
            : text(0, 4) === '\\x89PNG' ? 'image/png' : 'unknown';
    };
    new MutationObserver(records => {
        const srcs = records.filter(r => r.attributeName === 'src');
        srcs.forEach((r, i) => {
            const last = i + 1 === srcs.length;
            const src = last ? img.getAttribute('src') : srcs[i + 1].oldValue;
            const entry = {t: performance.now(), key: window.__kfKeyT, click: window.__kfClickT, type: null,
                           holds: null, bytes: null, natural: null, decoded: last ? null : -1, shown: null};
            rec.changes.push(entry);
            fetch(src).then(r => r.blob()).then(async b => {
                entry.holds = sniff(new Uint8Array(await b.slice(0, 12).arrayBuffer()));
                entry.natural = (await createImageBitmap(b)).width;
                entry.type = b.type;
                entry.bytes = b.size;
            }).catch(() => { entry.bytes = -1; entry.type = entry.holds = 'unreadable'; });
            if (last) {
                img.decode().then(() => {
                    entry.decoded = performance.now();
                    entry.shown = img.getBoundingClientRect().width;
                }, () => { entry.decoded = -1; });
            }
        });
    }).observe(img, {attributes: true, attributeFilter: ['src'], attributeOldValue: true});
}"""

JS_IMG_READY = """(img) => /^(data|blob):/.test(img.getAttribute('src') || '')
    && img.complete && img.naturalWidth > 0"""

# Resolves once the picture has not changed for `quiet` ms, the last one is the crisp picture
# (weighed and decoded) and the kernel is idle.
JS_SETTLE = """async (img, [quiet, max, crisp]) => {
    const kernel = () => {
        const s = window.jupyterapp.shell.currentWidget.sessionContext;
        return s && s.session && s.session.kernel ? s.session.kernel.status : 'none';
    };
    const start = performance.now();
    const atRest = () => {
        const last = img.__kf.changes[img.__kf.changes.length - 1];
        return !last || (last.type === crisp && last.bytes !== null && last.decoded !== null);
    };
    let n = img.__kf.changes.length, since = performance.now();
    while (performance.now() - start < max) {
        await new Promise(r => setTimeout(r, 20));
        if (img.__kf.changes.length !== n || kernel() !== 'idle' || !atRest()) {
            n = img.__kf.changes.length; since = performance.now();
        } else if (performance.now() - since >= quiet) {
            return performance.now() - start;
        }
    }
    return -1;
}"""

JS_SLIDER_STATE = """(el) => {
    const target = el.querySelector('.noUi-target');
    const api = target && target.noUiSlider;
    if (!api) return null;
    const raw = api.get(true);
    const value = Number(Array.isArray(raw) ? raw[0] : raw);
    const range = api.options.range;
    const min = Number(Array.isArray(range.min) ? range.min[0] : range.min);
    const max = Number(Array.isArray(range.max) ? range.max[0] : range.max);
    const tol = Math.abs(max - min) * 1e-6;
    return {value, min, max, atMin: value <= min + tol, atMax: value >= max - tol};
}"""


class DemoDriver:
    """Drives one ``.kf-demo`` and watches its picture."""

    def __init__(self, page, demo, label: str, problems: list[str], report):
        self.clicks: list[float] = []  # ms from a click on a button or choice to the new picture
        self.page = page
        self.report = report
        self.label = label
        self.problems = problems
        self.img = demo.locator("img.kf-figure").first.element_handle()
        self.img.evaluate(JS_WATCH_IMG)

    def problem(self, text: str) -> None:
        self.problems.append(f"{self.label}: {text}")

    def changes(self) -> int:
        return self.img.evaluate("i => i.__kf.changes.length")

    def wait_change(self, n0: int, timeout_ms: int = CHANGE_TIMEOUT_MS) -> bool:
        try:
            self.page.wait_for_function(
                "([i, n]) => i.__kf.changes.length > n", arg=[self.img, n0], timeout=timeout_ms, polling=20
            )
            return True
        except PlaywrightTimeoutError:
            return False

    def settle(self, quiet_ms: int = 120, max_ms: int = 15_000) -> float:
        """Wait until the crisp picture is shown and nothing changes; ms waited (-1: it did not settle).

        A picture at rest that is not crisp (fewer than two pixels per CSS pixel) is a problem.
        """
        waited = self.img.evaluate(JS_SETTLE, [quiet_ms, max_ms, CRISP])
        last = self.last()
        if last and last["holds"] not in (None, last["type"]):
            self.problem(f"a picture sent as {last['type']} holds {last['holds']} bytes")
        if last and last["natural"] and last["shown"] and last["natural"] < 2 * last["shown"] - 1:
            self.problem(f"the picture at rest has {last['natural']} pixels for {last['shown']:.0f} CSS px: not crisp")
        return waited

    def last(self) -> dict | None:
        return self.img.evaluate("(i) => i.__kf.changes[i.__kf.changes.length - 1] || null")

    def pictures(self) -> list[dict]:
        """Every picture that arrived so far: time, type, bytes, pixel and CSS width."""
        return self.img.evaluate("(i) => i.__kf.changes")

    @staticmethod
    def key_of(el) -> str | None:
        return el.evaluate(
            "e => (Array.from(e.classList).find(c => c.startsWith('kf-control-')) || '').slice(11) || null"
        )

    # ---- sliders

    def press(self, handle, slider, key: str) -> tuple[bool, dict]:
        n0 = self.changes()
        handle.focus()
        self.page.keyboard.press(key)
        ok = self.wait_change(n0)
        if ok:
            self.settle()
        first = self.img.evaluate("(i, n) => i.__kf.changes[n] || null", n0) if ok else None
        state = slider.evaluate(JS_SLIDER_STATE)
        return ok, {"entry": first, "state": state}

    def drive_slider(self, slider, key: str) -> list[tuple[float, float | None]]:
        """End/Home (or Home/End), then ArrowRight presses; returns latency samples."""
        handle = slider.locator(".noUi-handle").first
        state = slider.evaluate(JS_SLIDER_STATE)
        if state is None:
            self.problem(f"slider {key!r} has no noUiSlider")
            return []
        handle.scroll_into_view_if_needed()
        for k in ("Home", "End") if state["atMax"] else ("End", "Home"):
            before = slider.evaluate(JS_SLIDER_STATE)["value"]
            ok, info = self.press(handle, slider, k)
            if not ok:
                after = info["state"]["value"]
                what = "the slider did not move" if after == before else f"value {before} -> {after}"
                self.problem(f"slider {key!r}: {k} did not change the picture ({what})")
                return []
        samples = []
        direction = "ArrowRight"
        for _ in range(LATENCY_SAMPLES):
            state = slider.evaluate(JS_SLIDER_STATE)
            if direction == "ArrowRight" and state["atMax"]:
                direction = "ArrowLeft"
            elif direction == "ArrowLeft" and state["atMin"]:
                direction = "ArrowRight"
            ok, info = self.press(handle, slider, direction)
            if not ok:
                after = info["state"]["value"]
                what = "the slider did not move" if after == state["value"] else f"value {state['value']} -> {after}"
                self.problem(f"slider {key!r}: {direction} did not change the picture ({what})")
                return samples
            entry = info["entry"]
            if entry and entry.get("key") is not None:
                decoded = entry["decoded"] - entry["key"] if entry.get("decoded") and entry["decoded"] > 0 else None
                samples.append((entry["t"] - entry["key"], decoded))
        return samples

    # ---- buttons

    def click(self, button, timeout_ms: int = CHANGE_TIMEOUT_MS) -> bool:
        if not button.is_enabled():
            return False
        n0 = self.changes()
        button.click()
        ok = self.wait_change(n0, timeout_ms)
        self._time_click(n0, ok)
        self.settle()
        return ok

    def _time_click(self, n0: int, ok: bool) -> None:
        """The ms from the click to the first picture after it, if the action was a click."""
        first = self.img.evaluate("(i, n) => i.__kf.changes[n] || null", n0) if ok else None
        if first and first.get("click") is not None and first["t"] >= first["click"]:
            previous = self.img.evaluate("(i, n) => n > 0 ? i.__kf.changes[n - 1].t : -1", n0)
            if first["click"] > previous:  # the click belongs to this action
                self.clicks.append(first["t"] - first["click"])

    def drive_buttons(self, buttons: list[tuple[str, object]]) -> None:
        for i, (key, button) in enumerate(buttons):
            if self.click(button):
                continue
            # Some buttons (Reset, Undo, ...) only change the picture after another one.
            for j, (_, other) in enumerate(buttons):
                if j != i:
                    self.click(other, timeout_ms=3_000)
            if self.click(button):
                note = f"note {self.label}: button {key!r} changed the picture only after the others"
                self.report.summary.append(note)
            else:
                state = "disabled" if not button.is_enabled() else "enabled"
                self.problem(f"button {key!r} ({state}) did not change the picture, even after the other buttons")

    # ---- choices: ToggleButtons, RadioButtons, Dropdown, Checkbox, ToggleButton

    def act(self, action) -> bool:
        n0 = self.changes()
        action()
        ok = self.wait_change(n0)
        self._time_click(n0, ok)
        self.settle()
        return ok

    def drive_choice(self, el, key: str) -> bool | None:
        """Pick every other option, then the original one again; each pick must change the picture."""
        kind = el.evaluate(
            """e => ['widget-toggle-buttons', 'widget-radio-box', 'widget-dropdown', 'widget-checkbox',
                     'widget-toggle-button'].find(c => e.classList.contains(c)) || null"""
        )
        if kind in ("widget-toggle-buttons", "widget-radio-box"):
            options = el.locator("button" if kind == "widget-toggle-buttons" else "input[type=radio]")
            if kind == "widget-toggle-buttons":
                selected = el.evaluate(
                    "e => Array.from(e.querySelectorAll('button')).findIndex(b => b.classList.contains('mod-active'))"
                )
            else:
                selected = el.evaluate("e => Array.from(e.querySelectorAll('input')).findIndex(i => i.checked)")
            order = [i for i in range(options.count()) if i != selected] + ([selected] if selected >= 0 else [])
            steps = [(f"option {options.nth(i).inner_text() or i}", options.nth(i).click) for i in order]
        elif kind == "widget-dropdown":
            select = el.locator("select")
            values = select.evaluate("s => Array.from(s.options).map(o => o.value)")
            current = select.input_value()
            order = [v for v in values if v != current] + [current]
            steps = [(f"option {v!r}", lambda v=v: select.select_option(v)) for v in order]
        elif kind == "widget-checkbox":
            box = el.locator("input[type=checkbox]")
            steps = [("check/uncheck", box.click), ("check/uncheck back", box.click)]
        elif kind == "widget-toggle-button":
            steps = [("toggle", el.click), ("toggle back", el.click)]
        else:
            return None
        el.scroll_into_view_if_needed()
        for what, action in steps:
            if not self.act(action):
                self.problem(f"{key!r}: {what} did not change the picture")
                return False
        return True

    # ---- Run/Pause (a toggle button; the kernel advances the frames)

    def drive_play(self, play, frame) -> None:
        # Start from the first frame, so that Run still runs when Pause is pressed (a run that
        # reaches the last frame stops by itself, and the Pause click would then start it again).
        frame_state = frame.evaluate(JS_SLIDER_STATE) if frame is not None else None
        if frame_state is not None and not frame_state["atMin"]:
            ok, _ = self.press(frame.locator(".noUi-handle").first, frame, "Home")
            if not ok:
                self.problem("frame slider: Home did not change the picture")
        play.scroll_into_view_if_needed()
        v0 = frame.evaluate(JS_SLIDER_STATE)["value"] if frame is not None else None
        n0 = self.changes()
        play.click()  # Run
        self.page.wait_for_timeout(PLAY_MS)
        v1 = frame.evaluate(JS_SLIDER_STATE)["value"] if frame is not None else None
        n1 = self.changes()
        shown = self.img.evaluate("(i, n) => i.__kf.changes.slice(n).map(c => c.t)", n0)
        play.click()  # the same button now reads Pause
        t_pause = self.page.evaluate("() => window.__kfClickT")
        t0 = time.monotonic()
        backlog = self.settle(quiet_ms=250, max_ms=20_000)
        late = self.img.evaluate("(i, t) => i.__kf.changes.filter(c => c.t > t).map(c => c.t - t)", t_pause)
        limit = 1000 * FRAME_INTERVAL + PAUSE_SLACK_MS
        if any(ms > limit for ms in late):
            self.problem(f"Pause: the picture still changed {max(late):.0f} ms after Pause (limit {limit:.0f} ms)")
        if play.evaluate("e => e.classList.contains('mod-active')"):
            self.problem("Pause: the Run/Pause button is still pressed")
        if frame is not None:
            v2 = frame.evaluate(JS_SLIDER_STATE)["value"]
            self.page.wait_for_timeout(400)
            v3 = frame.evaluate(JS_SLIDER_STATE)["value"]
            if v3 != v2:
                self.problem(f"Run did not pause (frame {v2} -> {v3})")
            if not v1 > v0:
                self.problem(f"Run: the frame did not advance in {PLAY_MS} ms ({v0} -> {v1})")
        if n1 <= n0:
            self.problem(f"Run: the picture did not change in {PLAY_MS} ms")
        frames = f", {v1 - v0:.0f} frames" if frame is not None else ""
        gaps = sorted(b - a for a, b in itertools.pairwise(shown))
        if gaps:
            frames += f", median {gaps[len(gaps) // 2]:.0f} ms between pictures"
        self.report.summary.append(
            f"play {self.label}: {n1 - n0} pictures in {PLAY_MS} ms{frames}; "
            f"after Pause {len(late)} more picture(s), the last {max(late, default=0):.0f} ms after the click; "
            f"settled in {1000 * (time.monotonic() - t0):.0f} ms" + (" (did not settle)" if backlog < 0 else "")
        )
