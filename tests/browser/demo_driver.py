"""Driving one ``.kf-demo`` in the page and watching its picture: every slider (End / Home,
then ArrowRight presses), every button, every choice and the Run/Pause animation must change
the picture, and Pause must stop it.  See ``kfcourse/demos/_base.py`` for the DOM contract.

Every picture that arrives is weighed (its bytes and MIME type) and measured (its pixel
width against the CSS width it is shown at).  While a control moves, a demo sends a light
WebP; once the student stops, the crisp JPEG, with two pixels per CSS pixel.  Every action
must bring a light picture (a crisp one still on its way from the previous action is no
answer); the driver waits for the crisp picture after each control's last action
(``rest_each``: after every single action) and says so when it does not come.

Two users: the browser suite (``tests/browser/test_notebooks_in_lab.py``: few presses, no
rest between the presses of one slider, nothing timed but "an answer within ``ANSWER_MS``")
and the browser benchmark (``benchmarks/bench_browser.py``: ``LATENCY_PRESSES`` presses per
slider, each from rest, timed from the key press or click to the new picture).

What goes wrong is written to the list of problems; notes go to the report's summary.
"""

from __future__ import annotations

import itertools
import time

from tests.browser.lab import PlaywrightTimeoutError

# A new picture within ANSWER_MS of a key press or click: a demo that misses it does not answer
# (or froze).  This machine answers in 100-350 ms at p95 when quiet; at a load of 25 on its two
# cores the benchmark saw a worst control at 1.8 s p95.  Waiting costs nothing in a passing run.
ANSWER_MS = 5_000
ARROW_PRESSES = 2  # the suite: ArrowRight/Left presses per slider after End and Home
LATENCY_PRESSES = 10  # the benchmark: ArrowRight/Left presses per slider, each timed from rest
PLAY_MS = 2_000  # Run plays this long: the frame and the picture must have moved
PAUSE_REST_MS = 10_000  # after Pause the picture comes to rest (crisp, nothing new) within this
STOPPED_MS = 500  # ... and then shows no new picture and no new frame for this long
SETTLE_MAX_MS = 15_000
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
    const shown = el.querySelector('.widget-readout')?.textContent.trim() ?? null;
    return {value, shown, min, max, atMin: value <= min + tol, atMax: value >= max - tol};
}"""


# Resolves once a light picture (anything but the crisp type) arrived after change number n: the
# answer to a key press when the presses of a slider follow each other without waiting for rest
# (a crisp picture still on its way from the previous press is not an answer).
JS_LIGHT_SINCE = """([img, n, crisp]) => img.__kf.changes.slice(n).some(c => c.type !== null && c.type !== crisp)"""


class DemoDriver:
    """Drives one ``.kf-demo`` and watches its picture.

    ``answer_ms``: how long an action may take to bring a new picture before it counts as not
    answering.  ``rest_each``: wait for the crisp picture after every slider press (the
    benchmark, which times each press from rest) instead of after each slider's last press.
    """

    def __init__(
        self,
        page,
        demo,
        label: str,
        problems: list[str],
        report,
        *,
        answer_ms: int = ANSWER_MS,
        arrow_presses: int = ARROW_PRESSES,
        rest_each: bool = False,
    ):
        self.clicks: dict[str, list[float]] = {}  # control key -> ms from a click on it to the new picture
        self.latency: dict[str, list[tuple[float, float | None]]] = {}  # slider key -> (to src, to decoded) ms
        self.page = page
        self.report = report
        self.label = label
        self.problems = problems
        self.answer_ms = answer_ms
        self.arrow_presses = arrow_presses
        self.rest_each = rest_each
        self.img = demo.locator("img.kf-figure").first.element_handle()
        self.img.evaluate(JS_WATCH_IMG)

    def problem(self, text: str) -> None:
        self.problems.append(f"{self.label}: {text}")

    def note(self, text: str) -> None:
        summary = getattr(self.report, "summary", None)
        if summary is not None:
            summary.append(text)

    def changes(self) -> int:
        return self.img.evaluate("i => i.__kf.changes.length")

    def wait_change(self, n0: int, timeout_ms: int | None = None) -> bool:
        try:
            self.page.wait_for_function(
                "([i, n]) => i.__kf.changes.length > n",
                arg=[self.img, n0],
                timeout=timeout_ms or self.answer_ms,
                polling=20,
            )
            return True
        except PlaywrightTimeoutError:
            return False

    def wait_light(self, n0: int) -> bool:
        try:
            self.page.wait_for_function(JS_LIGHT_SINCE, arg=[self.img, n0, CRISP], timeout=self.answer_ms, polling=20)
            return True
        except PlaywrightTimeoutError:
            return False

    def settle(self, quiet_ms: int = 60, max_ms: int = SETTLE_MAX_MS) -> float:
        """Wait until the crisp picture is shown and nothing changes; ms waited (-1: it did not settle).

        A picture at rest that is not crisp (fewer than two pixels per CSS pixel) is a problem.
        """
        waited = self.img.evaluate(JS_SETTLE, [quiet_ms, max_ms, CRISP])
        last = self.last()
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

    def press(self, handle, slider, key: str, rest: bool = True) -> tuple[bool, dict]:
        """Press ``key`` on the focused handle; whether a new picture came within ``answer_ms``
        (with ``rest``: any picture, then the page comes to rest; without: a light one)."""
        n0 = self.changes()
        handle.focus()
        self.page.keyboard.press(key)
        if rest:
            ok = self.wait_change(n0)
            if ok:
                self.settle()
        else:
            ok = self.wait_light(n0)
        first = self.img.evaluate("(i, n) => i.__kf.changes[n] || null", n0) if ok else None
        state = slider.evaluate(JS_SLIDER_STATE)
        return ok, {"entry": first, "state": state}

    def drive_slider(self, slider, key: str) -> list[tuple[float, float | None]]:
        """End/Home (or Home/End), then ``arrow_presses`` ArrowRight presses (ArrowLeft back from
        the top), each answered by a new picture, then rest; returns the (key to src, key to
        decoded) ms of the arrow presses made from rest (``rest_each``), else none."""
        handle = slider.locator(".noUi-handle").first
        state = slider.evaluate(JS_SLIDER_STATE)
        if state is None:
            self.problem(f"slider {key!r} has no noUiSlider")
            return []
        handle.scroll_into_view_if_needed()
        for k in ("Home", "End") if state["atMax"] else ("End", "Home"):
            before = slider.evaluate(JS_SLIDER_STATE)["value"]
            ok, info = self.press(handle, slider, k, rest=self.rest_each)
            if not ok:
                after = info["state"]["value"]
                what = "the slider did not move" if after == before else f"value {before} -> {after}"
                self.problem(f"slider {key!r}: {k} brought no new picture within {self.answer_ms} ms ({what})")
                self.settle()
                return []
        samples = []
        direction = "ArrowRight"
        for _ in range(self.arrow_presses):
            state = slider.evaluate(JS_SLIDER_STATE)
            if direction == "ArrowRight" and state["atMax"]:
                direction = "ArrowLeft"
            elif direction == "ArrowLeft" and state["atMin"]:
                direction = "ArrowRight"
            ok, info = self.press(handle, slider, direction, rest=self.rest_each)
            if not ok and info["state"]["shown"] == state["shown"]:
                continue  # a step too small to change the value shown (N = 1 to 1.02, say): nothing to redraw
            if not ok:
                after = info["state"]["value"]
                what = "the slider did not move" if after == state["value"] else f"value {state['value']} -> {after}"
                self.problem(f"slider {key!r}: {direction} brought no new picture within {self.answer_ms} ms ({what})")
                break
            entry = info["entry"]
            if self.rest_each and entry and entry.get("key") is not None:
                decoded = entry["decoded"] - entry["key"] if entry.get("decoded") and entry["decoded"] > 0 else None
                samples.append((entry["t"] - entry["key"], decoded))
        if not self.rest_each:
            self.settle()  # the crisp picture after the slider's last press
        if samples:
            self.latency[key] = samples
        return samples

    # ---- buttons

    def _answered(self, n0: int, key: str) -> bool:
        """After a click: whether it brought a new picture within ``answer_ms`` (with ``rest_each``
        any picture, then rest; without, a light one: every control sends one, and a crisp one
        still on its way from the previous action is no answer)."""
        ok = self.wait_change(n0) if self.rest_each else self.wait_light(n0)
        self._time_click(n0, ok, key)
        if self.rest_each:
            self.settle()
        return ok

    def click(self, button, key: str) -> bool:
        if not button.is_enabled():
            return False
        n0 = self.changes()
        button.click()
        return self._answered(n0, key)

    def _time_click(self, n0: int, ok: bool, key: str) -> None:
        """The ms from the click to the first picture after it, if the action was a click."""
        first = self.img.evaluate("(i, n) => i.__kf.changes[n] || null", n0) if ok else None
        if first and first.get("click") is not None and first["t"] >= first["click"]:
            previous = self.img.evaluate("(i, n) => n > 0 ? i.__kf.changes[n - 1].t : -1", n0)
            if first["click"] > previous:  # the click belongs to this action
                self.clicks.setdefault(key, []).append(first["t"] - first["click"])

    def drive_buttons(self, buttons: list[tuple[str, object]]) -> None:
        for i, (key, button) in enumerate(buttons):
            if self.click(button, key):
                continue
            # Some buttons (Reset, Undo, ...) only change the picture after another one.
            for j, (other_key, other) in enumerate(buttons):
                if j != i:
                    self.click(other, other_key)
            if self.click(button, key):
                self.note(f"note {self.label}: button {key!r} changed the picture only after the others")
            else:
                state = "disabled" if not button.is_enabled() else "enabled"
                self.problem(
                    f"button {key!r} ({state}) brought no new picture within {self.answer_ms} ms, "
                    "even after the other buttons"
                )
        self.settle()  # the crisp picture after the last button

    # ---- choices: ToggleButtons, RadioButtons, Dropdown, Checkbox, ToggleButton

    def act(self, action, key: str) -> bool:
        n0 = self.changes()
        action()
        return self._answered(n0, key)

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
            if not self.act(action, key):
                self.problem(f"{key!r}: {what} brought no new picture within {self.answer_ms} ms")
                self.settle()
                return False
        self.settle()  # the crisp picture after the last option
        return True

    # ---- Run/Pause (a toggle button; the kernel advances the frames)

    def drive_play(self, play, frame) -> dict:
        """Run from the first frame for ``PLAY_MS``, then Pause.  Run must advance the frame and
        the picture; after Pause the picture comes to rest within ``PAUSE_REST_MS`` and then shows
        no new picture and no new frame for ``STOPPED_MS``, the run did not play on to its last
        frame for more frames than it played before Pause (as a demo that ignores Pause does),
        and the button is released.  Returns the pictures shown while it ran (for the benchmark)."""
        # Start from the first frame, so that Run still runs when Pause is pressed (a run that
        # reaches the last frame stops by itself, and the Pause click would then start it again).
        frame_state = frame.evaluate(JS_SLIDER_STATE) if frame is not None else None
        if frame_state is not None and not frame_state["atMin"]:
            ok, _ = self.press(frame.locator(".noUi-handle").first, frame, "Home")
            if not ok:
                self.problem(f"frame slider: Home brought no new picture within {self.answer_ms} ms")
        play.scroll_into_view_if_needed()
        v0 = frame.evaluate(JS_SLIDER_STATE)["value"] if frame is not None else None
        n0 = self.changes()
        play.click()  # Run
        self.page.wait_for_timeout(PLAY_MS)
        v1 = frame.evaluate(JS_SLIDER_STATE)["value"] if frame is not None else None
        n1 = self.changes()
        shown = self.img.evaluate("(i, n) => i.__kf.changes.slice(n)", n0)
        play.click()  # the same button now reads Pause
        t_pause = self.page.evaluate("() => window.__kfClickT")
        t0 = time.monotonic()
        rested = self.settle(quiet_ms=250, max_ms=PAUSE_REST_MS)
        if rested < 0:
            self.problem(f"Pause: the picture did not come to rest within {PAUSE_REST_MS} ms")
        if play.evaluate("e => e.classList.contains('mod-active')"):
            self.problem("Pause: the Run/Pause button is still pressed")
        n2 = self.changes()
        at_rest = frame.evaluate(JS_SLIDER_STATE) if frame is not None else None
        self.page.wait_for_timeout(STOPPED_MS)
        n3 = self.changes()
        if n3 != n2:
            self.problem(f"Pause: {n3 - n2} new picture(s) after the picture had come to rest")
        if frame is not None:
            v2 = at_rest["value"]
            v3 = frame.evaluate(JS_SLIDER_STATE)["value"]
            if v3 != v2:
                self.problem(f"Run did not pause (frame {v2} -> {v3})")
            if not v1 > v0:
                self.problem(f"Run: the frame did not advance in {PLAY_MS} ms ({v0} -> {v1})")
            elif at_rest["atMax"] and v2 - v1 > v1 - v0:
                self.problem(
                    f"Pause: the run played on to its last frame, {v2 - v1:.0f} frames after Pause, more "
                    f"than the {v1 - v0:.0f} it played before it"
                )
        if n1 <= n0:
            self.problem(f"Run: the picture did not change in {PLAY_MS} ms")
        late = self.img.evaluate("(i, t) => i.__kf.changes.filter(c => c.t > t).map(c => c.t - t)", t_pause)
        frames = f", {v1 - v0:.0f} frames" if frame is not None else ""
        gaps = sorted(b["t"] - a["t"] for a, b in itertools.pairwise(shown))
        if gaps:
            frames += f", median {gaps[len(gaps) // 2]:.0f} ms between pictures"
        self.note(
            f"play {self.label}: {n1 - n0} pictures in {PLAY_MS} ms{frames}; "
            f"after Pause {len(late)} more picture(s), the last {max(late, default=0):.0f} ms after the click; "
            f"settled in {1000 * (time.monotonic() - t0):.0f} ms" + (" (did not settle)" if rested < 0 else "")
        )
        return {"shown": shown, "t_pause": t_pause}


# --------------------------------------------------------------------------- every control of a demo


def demo_labels(panel, stem: str) -> list[str]:
    """``<stem>/<name>`` of every ``.kf-demo`` of the panel, in order (``-2``, ... when a name repeats;
    ``demo<i>`` for a demo without a ``kf-demo-<name>`` class)."""
    names = panel.locator(".kf-demo").evaluate_all(
        "els => els.map(e => (Array.from(e.classList).find(c => c.startsWith('kf-demo-')) || '').slice(8) || null)"
    )
    seen: dict[str, int] = {}
    labels = []
    for i, name in enumerate(names):
        name = name or f"demo{i}"
        seen[name] = seen.get(name, 0) + 1
        labels.append(f"{stem}/{name}" + ("" if seen[name] == 1 else f"-{seen[name]}"))
    return labels


def drive_sliders(demo, driver: DemoDriver) -> set[str]:
    """Every slider moves the picture.  Returns their keys."""
    tested: set[str] = set()
    sliders = demo.locator(".widget-slider")
    for i in range(sliders.count()):
        slider = sliders.nth(i)
        key = DemoDriver.key_of(slider)
        if key is None:
            driver.problem(f"slider #{i} ({slider.inner_text().strip()!r}) has no kf-control-<key> class")
            key = f"#{i}"
        tested.add(key)
        driver.drive_slider(slider, key)
    return tested


def drive_buttons(demo, driver: DemoDriver) -> set[str]:
    """Every button but Run/Pause changes the picture.  Returns their keys."""
    tested: set[str] = set()
    buttons = []
    button_locator = demo.locator(".widget-button")
    for i in range(button_locator.count()):
        button = button_locator.nth(i)
        if button.evaluate("e => e.classList.contains('kf-control-play')"):
            continue
        key = DemoDriver.key_of(button)
        if key is None:
            driver.problem(f"button {button.inner_text().strip()!r} has no kf-control-<key> class")
            key = button.inner_text().strip()
        tested.add(key)
        buttons.append((key, button))
    driver.drive_buttons(buttons)
    return tested


def drive_choices(demo, driver: DemoDriver) -> set[str]:
    """Every option of every choice changes the picture.  Returns the keys of the choices driven."""
    tested: set[str] = set()
    choices = demo.locator(
        ".widget-toggle-buttons, .widget-radio-box, .widget-dropdown, .widget-checkbox,"
        " .widget-toggle-button:not(.widget-toggle-buttons .widget-toggle-button):not(.kf-control-play)"
    )
    for i in range(choices.count()):
        choice = choices.nth(i)
        key = DemoDriver.key_of(choice)
        if key is None:
            driver.problem(f"control {choice.inner_text().strip()!r} has no kf-control-<key> class")
            key = f"choice#{i}"
        if driver.drive_choice(choice, key) is not None:
            tested.add(key)
    return tested


def drive_plays(demo, driver: DemoDriver) -> tuple[set[str], list[dict]]:
    """Run animates the picture (and the frame slider) and Pause stops it.  Returns their keys
    and what each run showed."""
    tested: set[str] = set()
    runs = []
    plays = demo.locator(".kf-control-play")
    for i in range(plays.count()):
        play = plays.nth(i)
        tested.add(DemoDriver.key_of(play) or f"play#{i}")
        frame = demo.locator(".widget-slider.kf-control-frame")
        runs.append(driver.drive_play(play, frame.first if frame.count() else None))
    return tested, runs


def drive_every_control(demo, driver: DemoDriver) -> tuple[set[str], list[dict]]:
    """Sliders, buttons, choices, then Run/Pause, as a student might; the keys of the controls
    driven and what each run showed."""
    tested = drive_sliders(demo, driver)
    tested |= drive_buttons(demo, driver)
    tested |= drive_choices(demo, driver)
    played, runs = drive_plays(demo, driver)
    return tested | played, runs
