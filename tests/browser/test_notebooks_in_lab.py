"""Every course notebook, run in JupyterLab in headless Chromium, with every demo driven.

Per notebook: open it, wait for the kernel to be idle, Run All, then check that no cell
wrote to stderr or raised, that every widget really rendered, and, for each ``.kf-demo``
(see ``kfcourse/demos/_base.py`` for the DOM contract): a picture, a caption, every
slider (End / Home / ArrowRight), every button and the Run/Pause animation change the
picture, and after Pause the picture stops within one frame interval.  Slider latency
(key press to new ``src``) is recorded, not asserted.
"""

from __future__ import annotations

import itertools
import os
import time
import urllib.parse

import pytest

from kfcourse.demos._base import FRAME_INTERVAL

try:
    from playwright.sync_api import TimeoutError as PlaywrightTimeoutError
except ImportError:  # the `browser` fixture skips (fails on CI) with the reason
    PlaywrightTimeoutError = TimeoutError

pytestmark = pytest.mark.browser

VIEWPORT = {"width": 1400, "height": 1400}
RUN_ALL_TIMEOUT_MS = int(os.environ.get("KFCOURSE_RUN_ALL_TIMEOUT_S", "240")) * 1000
KERNEL_IDLE_TIMEOUT_MS = 90_000
WIDGETS_RENDER_TIMEOUT_MS = 30_000
CHANGE_TIMEOUT_MS = 10_000  # one control action -> new picture
LATENCY_SAMPLES = 10  # ArrowRight presses per slider
PLAY_MS = 1_500
PAUSE_SLACK_MS = 250  # after Pause: one frame interval, plus the frame already on its way, plus transport
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"

# --------------------------------------------------------------------------- page-side helpers

JS_KERNEL_IDLE = r"""() => Array.from(document.querySelectorAll('.jp-StatusBar-Item'))
    .some(e => !e.classList.contains('lm-mod-hidden') && /\|\s*Idle$/.test(e.textContent.trim()))"""

JS_START_RUN_ALL = """() => {
    window.__kfRunAll = {done: false};
    window.jupyterapp.commands.execute('notebook:run-all-cells').then(
        r => { window.__kfRunAll = {done: true, result: r}; },
        e => { window.__kfRunAll = {done: true, error: String(e)}; });
}"""

JS_RUN_ALL_DONE = """(panelId) => {
    if (!window.__kfRunAll || !window.__kfRunAll.done) return false;
    const panel = document.getElementById(panelId);
    return !Array.from(panel.querySelectorAll('.jp-InputArea-prompt'))
        .some(p => p.textContent.includes('*'));
}"""

# The notebook model after the run: outputs summarised (no image payloads).
JS_CELLS = """() => {
    const panel = window.jupyterapp.shell.currentWidget;
    return panel.content.widgets.map((cell, index) => {
        const m = cell.model;
        const outputs = m.type === 'code' ? m.outputs.toJSON() : [];
        return {
            index, type: m.type, source: m.sharedModel.getSource(),
            count: m.type === 'code' ? (m.executionCount ?? null) : null,
            outputs: outputs.map(o => ({
                output_type: o.output_type, name: o.name || null,
                text: o.output_type === 'stream' ? [].concat(o.text).join('').slice(0, 2000) : null,
                ename: o.ename || null, evalue: o.evalue || null,
                mimes: o.data ? Object.keys(o.data) : [],
            })),
        };
    });
}"""

# Records every src change of the picture (and when the new picture is decoded), and the
# timestamp of the last keydown in the page.
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
    new MutationObserver(records => {
        for (const r of records) {
            if (r.attributeName !== 'src') continue;
            const entry = {t: performance.now(), decoded: null, key: window.__kfKeyT};
            rec.changes.push(entry);
            img.decode().then(() => { entry.decoded = performance.now(); }, () => { entry.decoded = -1; });
        }
    }).observe(img, {attributes: true, attributeFilter: ['src']});
}"""

JS_IMG_READY = """(img) => /^(data|blob):/.test(img.getAttribute('src') || '')
    && img.complete && img.naturalWidth > 0"""

# Resolves once the picture has not changed for `quiet` ms and the kernel is idle.
JS_SETTLE = """async (img, [quiet, max]) => {
    const kernel = () => {
        const s = window.jupyterapp.shell.currentWidget.sessionContext;
        return s && s.session && s.session.kernel ? s.session.kernel.status : 'none';
    };
    const start = performance.now();
    let n = img.__kf.changes.length, since = performance.now();
    while (performance.now() - start < max) {
        await new Promise(r => setTimeout(r, 20));
        if (img.__kf.changes.length !== n || kernel() !== 'idle') {
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


# --------------------------------------------------------------------------- REST helpers


def _xsrf(context, url: str) -> str:
    for cookie in context.cookies(url):
        if cookie["name"] == "_xsrf":
            return cookie["value"]
    context.request.get(url + "lab")  # the page handler sets the cookie
    for cookie in context.cookies(url):
        if cookie["name"] == "_xsrf":
            return cookie["value"]
    raise AssertionError("the server set no _xsrf cookie")


def _shutdown_kernels(context, url: str) -> None:
    """Delete every session and every kernel: kernels outlive the browser."""
    headers = {"X-XSRFToken": _xsrf(context, url)}
    for kind in ("sessions", "kernels"):
        response = context.request.get(f"{url}api/{kind}")
        assert response.ok, f"GET api/{kind}: {response.status}"
        for item in response.json():
            r = context.request.delete(f"{url}api/{kind}/{item['id']}", headers=headers)
            assert r.status in (204, 404), f"DELETE api/{kind}/{item['id']}: {r.status} {r.text()}"


# --------------------------------------------------------------------------- demo driving


class DemoDriver:
    """Drives one ``.kf-demo`` and watches its picture."""

    def __init__(self, page, demo, label: str, problems: list[str], report):
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
        return self.img.evaluate(JS_SETTLE, [quiet_ms, max_ms])

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
        entry = self.img.evaluate("(i) => i.__kf.changes[i.__kf.changes.length - 1] || null")
        state = slider.evaluate(JS_SLIDER_STATE)
        return ok, {"entry": entry if ok else None, "state": state}

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
        self.settle()
        return ok

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


def _check_demo(page, demo, label: str, shot, problems: list[str], report) -> None:
    errors = demo.locator(".jupyter-widgets-error-widget")
    if errors.count():
        problems.append(f"{label}: error widget: {errors.first.inner_text()[:300]}")
        return
    if demo.locator("img.kf-figure").count() == 0:
        problems.append(f"{label}: no img.kf-figure")
        return
    img = demo.locator("img.kf-figure").first
    try:
        page.wait_for_function(JS_IMG_READY, arg=img.element_handle(), timeout=WIDGETS_RENDER_TIMEOUT_MS)
    except PlaywrightTimeoutError:
        problems.append(f"{label}: the picture never loaded (src={str(img.get_attribute('src'))[:40]!r})")
        return
    caption = demo.locator(".kf-caption")
    if caption.count() == 0 or not caption.first.inner_text().strip():
        problems.append(f"{label}: no .kf-caption text")

    driver = DemoDriver(page, demo, label, problems, report)
    demo.scroll_into_view_if_needed()
    driver.settle(quiet_ms=200)
    demo.screenshot(path=shot)

    controls = demo.locator("[class*='kf-control-']")
    all_keys = {DemoDriver.key_of(controls.nth(i)) for i in range(controls.count())}
    tested: set[str] = set()

    sliders = demo.locator(".widget-slider")
    latency: dict[str, list[tuple[float, float | None]]] = {}
    for i in range(sliders.count()):
        slider = sliders.nth(i)
        key = DemoDriver.key_of(slider)
        if key is None:
            problems.append(f"{label}: slider #{i} ({slider.inner_text().strip()!r}) has no kf-control-<key> class")
            key = f"#{i}"
        tested.add(key)
        samples = driver.drive_slider(slider, key)
        if samples:
            latency[key] = samples

    buttons = []
    button_locator = demo.locator(".widget-button")
    for i in range(button_locator.count()):
        button = button_locator.nth(i)
        if button.evaluate("e => e.classList.contains('kf-control-play')"):
            continue
        key = DemoDriver.key_of(button)
        if key is None:
            problems.append(f"{label}: button {button.inner_text().strip()!r} has no kf-control-<key> class")
            key = button.inner_text().strip()
        tested.add(key)
        buttons.append((key, button))
    driver.drive_buttons(buttons)

    choices = demo.locator(
        ".widget-toggle-buttons, .widget-radio-box, .widget-dropdown, .widget-checkbox,"
        " .widget-toggle-button:not(.widget-toggle-buttons .widget-toggle-button):not(.kf-control-play)"
    )
    for i in range(choices.count()):
        choice = choices.nth(i)
        key = DemoDriver.key_of(choice)
        if key is None:
            problems.append(f"{label}: control {choice.inner_text().strip()!r} has no kf-control-<key> class")
            key = f"choice#{i}"
        if driver.drive_choice(choice, key) is not None:
            tested.add(key)

    plays = demo.locator(".kf-control-play")
    for i in range(plays.count()):
        play = plays.nth(i)
        tested.add(DemoDriver.key_of(play) or f"play#{i}")
        frame = demo.locator(".widget-slider.kf-control-frame")
        driver.drive_play(play, frame.first if frame.count() else None)

    untested = sorted(k for k in all_keys - tested if k)
    if untested:
        report.summary.append(f"note {label}: controls not driven by the suite: {', '.join(untested)}")

    if latency:
        samples = [s for v in latency.values() for s in v]
        report.latency[label] = {
            "samples_ms": [round(s[0], 1) for s in samples],
            "decoded_ms": [round(s[1], 1) for s in samples if s[1] is not None],
            "sliders": {k: [round(s[0], 1) for s in v] for k, v in latency.items()},
        }
        ms = sorted(s[0] for s in samples)
        print(f"\n[latency] {label}: median {ms[len(ms) // 2]:.0f} ms over {len(ms)} key presses")


# --------------------------------------------------------------------------- the test


def _full_page_screenshot(page, panel, path) -> None:
    """The whole notebook: scroll it to the top and grow the viewport to its height for one shot."""
    js = """(p) => {
        const outer = p.querySelector('.jp-WindowedPanel-outer');
        const inner = p.querySelector('.jp-WindowedPanel-inner') || outer;
        outer.scrollTop = 0;
        return inner.getBoundingClientRect().height - outer.clientHeight;
    }"""
    extra = panel.evaluate(js)
    page.set_viewport_size({"width": VIEWPORT["width"], "height": int(min(VIEWPORT["height"] + max(extra, 0), 16_000))})
    page.wait_for_timeout(300)
    panel.evaluate(js)
    page.wait_for_timeout(100)
    page.screenshot(path=path)
    page.set_viewport_size(VIEWPORT)
    page.wait_for_timeout(200)


def test_notebook_runs_and_demos_respond(browser, lab_server, report, notebook):
    url = lab_server.url
    context = browser.new_context(viewport=VIEWPORT)
    page_errors: list[str] = []
    timings = {"start": time.monotonic()}
    try:
        _shutdown_kernels(context, url)
        page = context.new_page()
        page.on("pageerror", lambda e: page_errors.append(str(e)))
        page.goto(f"{url}lab/tree/{urllib.parse.quote(notebook.name)}?reset")
        timings["goto"] = time.monotonic()
        page.wait_for_function("() => !!(window.jupyterapp && window.jupyterapp.shell.currentWidget)")
        timings["app"] = time.monotonic()
        page.wait_for_function(
            "(name) => { const w = window.jupyterapp.shell.currentWidget;"
            " return !!(w && w.context && w.context.path === name); }",
            arg=notebook.name,
            timeout=KERNEL_IDLE_TIMEOUT_MS,
        )
        timings["notebook"] = time.monotonic()
        page.evaluate("() => window.jupyterapp.shell.collapseLeft()")
        page.wait_for_function(JS_KERNEL_IDLE, timeout=KERNEL_IDLE_TIMEOUT_MS)
        timings["kernel idle"] = time.monotonic()
        panel_id = page.evaluate("() => window.jupyterapp.shell.currentWidget.id")
        panel = page.locator(f"[id='{panel_id}']")

        page.evaluate(JS_START_RUN_ALL)
        try:
            page.wait_for_function(JS_RUN_ALL_DONE, arg=panel_id, timeout=RUN_ALL_TIMEOUT_MS, polling=100)
            finished = True
        except PlaywrightTimeoutError:
            finished = False
        if not finished:
            pytest.fail(f"{notebook.name}: Run All did not finish in {RUN_ALL_TIMEOUT_MS // 1000} s", pytrace=False)
        timings["run all"] = time.monotonic()

        # -- no cell complained
        problems: list[str] = []
        cells = page.evaluate(JS_CELLS)
        for cell in cells:
            if cell["type"] != "code":
                continue
            head = cell["source"].strip().splitlines()[0][:80] if cell["source"].strip() else ""
            where = f"cell {cell['index']} ({head!r})"
            for out in cell["outputs"]:
                if out["output_type"] == "error":
                    problems.append(f"{where} raised {out['ename']}: {out['evalue']}")
                elif out["output_type"] == "stream" and out["name"] == "stderr":
                    problems.append(f"{where} wrote to stderr: {out['text'][:500]}")
            if cell["source"].strip() and cell["count"] is None and not problems:
                problems.append(f"{where} was not executed by Run All")
        rendered_errors = panel.locator(
            ".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr'],"
            " .jp-OutputArea-output[data-mime-type='application/vnd.jupyter.error'],"
            " .jp-RenderedText[data-mime-type='application/vnd.jupyter.error']"
        )
        if not problems:  # the model said nothing; trust the page
            for i in range(rendered_errors.count()):
                problems.append(f"stderr/error output on the page: {rendered_errors.nth(i).inner_text()[:500]}")
        if problems:
            pytest.fail(f"{notebook.name}:\n  " + "\n  ".join(problems), pytrace=False)

        # -- every widget output really rendered as widgets
        expected = sum(WIDGET_VIEW in out["mimes"] for c in cells for out in c["outputs"])
        try:
            page.wait_for_function(
                "([id, n]) => document.getElementById(id)"
                ".querySelectorAll('.jp-OutputArea-output > .jupyter-widgets').length >= n",
                arg=[panel_id, expected],
                timeout=WIDGETS_RENDER_TIMEOUT_MS,
            )
            rendered = True
        except PlaywrightTimeoutError:
            rendered = False
        if not rendered:
            got = panel.locator(".jp-OutputArea-output > .jupyter-widgets").count()
            pytest.fail(
                f"{notebook.name}: {expected} widget outputs, only {got} rendered as widgets "
                "(a plain-text repr like 'Demo(children=...)' means the widget model is missing)",
                pytrace=False,
            )
        error_widgets = panel.locator(".jupyter-widgets-error-widget")
        if error_widgets.count():
            pytest.fail(f"{notebook.name}: widget failed: {error_widgets.first.inner_text()[:500]}", pytrace=False)

        timings["widgets"] = time.monotonic()
        _full_page_screenshot(page, panel, report.artifacts / f"{notebook.stem}.png")
        timings["screenshot"] = time.monotonic()

        # -- drive every demo
        demos = panel.locator(".kf-demo")
        seen: dict[str, int] = {}
        for i in range(demos.count()):
            demo = demos.nth(i)
            name = demo.evaluate(
                "e => (Array.from(e.classList).find(c => c.startsWith('kf-demo-')) || '').slice(8) || null"
            )
            if name is None:
                problems.append(f"demo #{i} has no kf-demo-<name> class")
                name = f"demo{i}"
            seen[name] = seen.get(name, 0) + 1
            suffix = "" if seen[name] == 1 else f"-{seen[name]}"
            label = f"{notebook.stem}/{name}{suffix}"
            _check_demo(page, demo, label, report.artifacts / f"{notebook.stem}__{name}{suffix}.png", problems, report)
        timings["demos driven"] = time.monotonic()
        steps = list(timings.items())
        phases = ", ".join(f"{name} {b - a:.1f} s" for (_, a), (name, b) in itertools.pairwise(steps))
        print(f"\n[browser] {notebook.name}: {demos.count()} demo(s); {phases}")

        if page_errors:
            report.summary.append(f"note {notebook.stem}: uncaught page errors: {'; '.join(page_errors)[:500]}")
        if problems:
            pytest.fail(f"{notebook.name}:\n  " + "\n  ".join(problems), pytrace=False)
    finally:
        for p in context.pages:
            p.close()
        try:
            _shutdown_kernels(context, url)
        finally:
            context.close()
