"""Every course notebook, run in JupyterLab in headless Chromium, with every demo driven.

Per notebook, in a 1280x800 window beside the file browser (a 13-inch laptop): open it,
wait for the kernel to be idle, Run All, then check that no cell wrote to stderr or raised,
that every widget really rendered, and, for each ``.kf-demo`` (see
``kfcourse/demos/_base.py`` for the DOM contract):

- a picture and a caption; the picture and all of its controls fit the notebook area at
  once (at most ``LAYOUT_MAX_PX`` tall), and the picture is never shown larger than drawn;
- every slider (End / Home / ArrowRight), every button and the Run/Pause animation change
  the picture, and after Pause the picture stops within one frame interval;
- each control answers with a new picture within ``CONTROL_P95_MS`` at the 95th percentile
  (key press or click to new ``src``), the pictures sent while something moves weigh at most
  ``LIGHT_MAX_BYTES`` (median), and after every action the crisp picture comes to rest;
- for assistive technology: the picture's alt text is the description under it, in a polite
  live region; every slider is named by its label and announces the value its readout shows
  (also after it moved); every toggle and choice button exposes whether it is pressed, every
  group of choice buttons has a name; a control reached with Tab shows a focus ring at least
  ``FOCUS_MIN_PX`` wide at ``FOCUS_MIN_CONTRAST`` against the page or better.

After the demos, axe-core checks the chapter's own content (its rendered Markdown and every
output) against the WCAG 2.1 A and AA rules: no violation.

The steps that drive JupyterLab are in ``tests/browser/lab.py``, the ones that drive a
demo's controls in ``tests/browser/demo_driver.py``; this module says what must hold.
"""

from __future__ import annotations

import itertools
import time

import pytest

from tests.browser.axe import format_violations, run_axe
from tests.browser.conftest import latency_stats
from tests.browser.demo_driver import CRISP, JS_IMG_READY, DemoDriver
from tests.browser.lab import (
    RUN_ALL_TIMEOUT_MS,
    VIEWPORT,
    WIDGET_VIEW,
    WIDGETS_RENDER_TIMEOUT_MS,
    PlaywrightTimeoutError,
    close_context,
    full_page_screenshot,
    open_notebook,
    read_cells,
    run_all,
    shutdown_kernels,
    wait_for_widgets,
)
from tests.plots.colour_vision import contrast

pytestmark = pytest.mark.browser

Latency = dict[str, list[tuple[float, float | None]]]  # slider key -> (key to src, key to decoded) in ms

LAYOUT_MAX_PX = 680  # the picture and its controls, caption aside: what a 1280x800 window leaves the notebook
CONTROL_P95_MS = 250  # key press or click to the new picture, 95th percentile per demo
LIGHT_MAX_BYTES = 60_000  # median weight of the pictures sent while a control moves or Run plays
FOCUS_MIN_PX = 2  # the focus ring's width (WCAG 2.4.11/2.4.13: a visible indicator)
FOCUS_MIN_CONTRAST = 3.0  # the focus ring against the page (WCAG 1.4.11, non-text contrast)

# What a screen reader is told of a demo: the picture's alt text and the description under it,
# each slider's name and spoken value against its label and readout, each toggle's pressed
# state against the class that shows it, each group of choice buttons' name.
JS_ACCESSIBLE = """(d) => ({
    alt: d.querySelector('img.kf-figure')?.getAttribute('alt') ?? null,
    description: d.querySelector('.kf-description [aria-live]')?.textContent ?? null,
    live: d.querySelector('.kf-description [aria-live]')?.getAttribute('aria-live') ?? null,
    sliders: Array.from(d.querySelectorAll('.widget-slider')).map(s => ({
        label: s.querySelector('.widget-label')?.textContent.trim() ?? '',
        name: s.querySelector('.noUi-handle')?.getAttribute('aria-label') ?? null,
        spoken: s.querySelector('.noUi-handle')?.getAttribute('aria-valuetext') ?? null,
        shown: s.querySelector('.widget-readout')?.textContent.trim() ?? null,
    })),
    toggles: Array.from(d.querySelectorAll('button.widget-toggle-button')).map(b => ({
        text: b.textContent.trim(), active: b.classList.contains('mod-active'), pressed: b.getAttribute('aria-pressed'),
    })),
    groups: Array.from(d.querySelectorAll('.widget-toggle-buttons')).map(g => ({
        role: g.getAttribute('role'), name: g.getAttribute('aria-label'),
    })),
})"""

# The focused element's outline, and the colour of the page behind it.
JS_FOCUS_RING = """() => {
    const e = document.activeElement;
    const style = getComputedStyle(e);
    return {
        what: e.outerHTML.slice(0, 80), style: style.outlineStyle,
        width: parseFloat(style.outlineWidth), color: style.outlineColor,
        inDemo: !!e.closest('.kf-demo'),
    };
}"""

# The demo's picture and controls (every child but the caption): their height, the height of the
# notebook area that shows them, how far any of them reaches past the output's right edge or
# overflows its box (a scroll bar), and the picture's CSS width against its pixel width.
JS_LAYOUT = """(d) => {
    const parts = Array.from(d.children).filter(c => !c.classList.contains('kf-caption'));
    const rects = parts.map(c => c.getBoundingClientRect()).filter(r => r.height > 0);
    const img = d.querySelector('img.kf-figure');
    const area = d.closest('.jp-WindowedPanel-outer');
    const output = d.closest('.jp-OutputArea-output') || d.parentElement;
    const items = d.querySelectorAll('img, .widget-slider, .widget-button, .widget-toggle-buttons, .widget-html');
    return {
        height: Math.max(...rects.map(r => r.bottom)) - Math.min(...rects.map(r => r.top)),
        area: area ? area.clientHeight : null,
        overflow: Math.max(
            ...Array.from(items).map(e => e.getBoundingClientRect().right - output.getBoundingClientRect().right),
            ...[d, ...d.querySelectorAll('.widget-box')].map(b => b.scrollWidth - b.clientWidth),  // a scroll bar
        ),
        shown: img.getBoundingClientRect().width,
        natural: img.naturalWidth,
    };
}"""


# --------------------------------------------------------------------------- the notebook


def _cell_problems(cells: list[dict], panel) -> list[str]:
    """Errors and stderr of the cells after Run All, and code cells it did not run; the page's
    rendered stderr/error outputs when the model shows none."""
    problems: list[str] = []
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
    return problems


def _check_widgets_rendered(page, panel_id: str, panel, cells: list[dict], name: str) -> None:
    """Every widget output of the cells really rendered as a widget, and none as an error widget."""
    expected = sum(WIDGET_VIEW in out["mimes"] for c in cells for out in c["outputs"])
    if not wait_for_widgets(page, panel_id, expected):
        got = panel.locator(".jp-OutputArea-output > .jupyter-widgets").count()
        pytest.fail(
            f"{name}: {expected} widget outputs, only {got} rendered as widgets "
            "(a plain-text repr like 'Demo(children=...)' means the widget model is missing)",
            pytrace=False,
        )
    error_widgets = panel.locator(".jupyter-widgets-error-widget")
    if error_widgets.count():
        pytest.fail(f"{name}: widget failed: {error_widgets.first.inner_text()[:500]}", pytrace=False)


# --------------------------------------------------------------------------- one demo


def _picture_shown(page, demo, label: str, problems: list[str]) -> bool:
    """No error widget, a picture that loads, and a caption (its absence is a problem, not a stop)."""
    errors = demo.locator(".jupyter-widgets-error-widget")
    if errors.count():
        problems.append(f"{label}: error widget: {errors.first.inner_text()[:300]}")
        return False
    if demo.locator("img.kf-figure").count() == 0:
        problems.append(f"{label}: no img.kf-figure")
        return False
    img = demo.locator("img.kf-figure").first
    try:
        page.wait_for_function(JS_IMG_READY, arg=img.element_handle(), timeout=WIDGETS_RENDER_TIMEOUT_MS)
    except PlaywrightTimeoutError:
        problems.append(f"{label}: the picture never loaded (src={str(img.get_attribute('src'))[:40]!r})")
        return False
    caption = demo.locator(".kf-caption")
    if caption.count() == 0 or not caption.first.inner_text().strip():
        problems.append(f"{label}: no .kf-caption text")
    return True


def _drive_sliders(demo, driver: DemoDriver, latency: Latency) -> set[str]:
    """Every slider moves the picture; their latency samples go to ``latency``.  Returns their keys."""
    tested: set[str] = set()
    sliders = demo.locator(".widget-slider")
    for i in range(sliders.count()):
        slider = sliders.nth(i)
        key = DemoDriver.key_of(slider)
        if key is None:
            driver.problem(f"slider #{i} ({slider.inner_text().strip()!r}) has no kf-control-<key> class")
            key = f"#{i}"
        tested.add(key)
        samples = driver.drive_slider(slider, key)
        if samples:
            latency[key] = samples
    return tested


def _drive_buttons(demo, driver: DemoDriver) -> set[str]:
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


def _drive_choices(demo, driver: DemoDriver) -> set[str]:
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


def _drive_plays(demo, driver: DemoDriver) -> set[str]:
    """Run animates the picture (and the frame slider) and Pause stops it.  Returns their keys."""
    tested: set[str] = set()
    plays = demo.locator(".kf-control-play")
    for i in range(plays.count()):
        play = plays.nth(i)
        tested.add(DemoDriver.key_of(play) or f"play#{i}")
        frame = demo.locator(".widget-slider.kf-control-frame")
        driver.drive_play(play, frame.first if frame.count() else None)
    return tested


def _check_accessible(demo, label: str, problems: list[str]) -> None:
    """What assistive technology is told of the demo matches what the page shows."""
    state = demo.evaluate(JS_ACCESSIBLE)
    if not state["description"] or not state["description"].strip():
        problems.append(f"{label}: no description under the picture")
    elif state["alt"] != state["description"]:
        problems.append(f"{label}: the picture's alt text {state['alt']!r} is not its description")
    if state["live"] != "polite":
        problems.append(f"{label}: the description is not a polite live region (aria-live={state['live']!r})")
    for s in state["sliders"]:
        if not s["name"] or s["name"] != s["label"]:
            problems.append(f"{label}: slider {s['label']!r} is named {s['name']!r} for a screen reader")
        if s["spoken"] != s["shown"]:
            problems.append(f"{label}: slider {s['label']!r} shows {s['shown']!r} but announces {s['spoken']!r}")
    for t in state["toggles"]:
        if t["pressed"] != str(t["active"]).lower():
            look = "on" if t["active"] else "off"
            problems.append(f"{label}: button {t['text']!r} looks {look}, aria-pressed={t['pressed']!r}")
    for g in state["groups"]:
        if g["role"] != "group" or not g["name"]:
            problems.append(f"{label}: a group of choice buttons has role {g['role']!r} and name {g['name']!r}")


def _check_focus_ring(page, demo, label: str, problems: list[str]) -> None:
    """A control reached with the keyboard shows a ring of at least FOCUS_MIN_PX at FOCUS_MIN_CONTRAST."""
    first = demo.locator(".noUi-handle, button").first
    first.focus()
    page.keyboard.press("Tab")
    ring = page.evaluate(JS_FOCUS_RING)
    if not ring["inDemo"]:
        first.focus()
        page.keyboard.press("Shift+Tab")
        ring = page.evaluate(JS_FOCUS_RING)
    page.keyboard.press("Escape")
    if ring["style"] in ("none", "hidden") or ring["width"] < FOCUS_MIN_PX:
        problems.append(f"{label}: focus on {ring['what']!r} shows a {ring['width']} px {ring['style']} outline")
        return
    ratio = contrast(css_hex(ring["color"]), "#ffffff")
    if ratio < FOCUS_MIN_CONTRAST:
        problems.append(f"{label}: the focus ring {ring['color']} has {ratio:.2f}:1 against the page")


def css_hex(css: str) -> str:
    """A computed CSS colour, ``rgb(r, g, b)`` or ``rgba(r, g, b, a)`` (alpha ignored), as ``#rrggbb``."""
    r, g, b = (round(float(v)) for v in css[css.index("(") + 1 : css.index(")")].split(",")[:3])
    return f"#{r:02x}{g:02x}{b:02x}"


def _record_latency(label: str, latency: Latency, report) -> None:
    samples = [s for v in latency.values() for s in v]
    report.latency[label] = {
        "samples_ms": [round(s[0], 1) for s in samples],
        "decoded_ms": [round(s[1], 1) for s in samples if s[1] is not None],
        "sliders": {k: [round(s[0], 1) for s in v] for k, v in latency.items()},
    }
    ms = sorted(s[0] for s in samples)
    print(f"\n[latency] {label}: median {ms[len(ms) // 2]:.0f} ms over {len(ms)} key presses")


def _check_layout(demo, label: str, problems: list[str]) -> None:
    """The picture and its controls fit the notebook area at once, nothing sticks out on the right,
    and the picture is not enlarged."""
    box = demo.evaluate(JS_LAYOUT)
    room = min(LAYOUT_MAX_PX, box["area"] or LAYOUT_MAX_PX)
    if box["height"] > room:
        problems.append(f"{label}: picture and controls are {box['height']:.0f} px tall; the laptop shows {room} px")
    if box["overflow"] > 1:
        problems.append(f"{label}: the picture or a control sticks out {box['overflow']:.0f} px: a scroll bar")
    if box["shown"] > box["natural"] / 2 + 0.5:
        problems.append(
            f"{label}: the picture is shown {box['shown']:.0f} px wide, larger than it was drawn "
            f"({box['natural']} pixels for 2 per CSS px)"
        )


def _check_speed_and_weight(driver: DemoDriver, latency: Latency, label: str, problems: list[str], report) -> None:
    """Each control's new picture within CONTROL_P95_MS (p95); light pictures while moving."""
    ms = sorted([s[0] for samples in latency.values() for s in samples] + driver.clicks)
    if ms:
        p95 = latency_stats(ms)["p95_ms"]
        if p95 > CONTROL_P95_MS:
            problems.append(f"{label}: a control takes {p95:.0f} ms to a new picture at p95 (limit {CONTROL_P95_MS})")
    pictures = driver.pictures()
    light = sorted(p["bytes"] for p in pictures if p["bytes"] and p["type"] != CRISP)
    crisp = sorted(p["bytes"] for p in pictures if p["bytes"] and p["type"] == CRISP)
    if light and light[len(light) // 2] > LIGHT_MAX_BYTES:
        problems.append(f"{label}: pictures sent while moving weigh {light[len(light) // 2] / 1e3:.0f} KB (median)")
    if not light:
        problems.append(f"{label}: no light picture was sent while the controls moved")
    report.summary.append(
        f"weight {label}: {len(light)} moving pictures, median {light[len(light) // 2] / 1e3 if light else 0:.0f} KB;"
        f" {len(crisp)} at rest, median {crisp[len(crisp) // 2] / 1e3 if crisp else 0:.0f} KB;"
        f" {len(ms)} control actions, p95 {latency_stats(ms)['p95_ms'] if ms else 0:.0f} ms"
    )


def _check_demo(page, demo, label: str, shot, problems: list[str], report) -> None:
    """A picture and a caption that fit a laptop, a screenshot to ``shot``, then every control
    drives the picture, quickly and with light pictures."""
    if not _picture_shown(page, demo, label, problems):
        return
    driver = DemoDriver(page, demo, label, problems, report)
    demo.scroll_into_view_if_needed()
    driver.settle(quiet_ms=200)
    _check_layout(demo, label, problems)
    # The screenshot with its caption: a taller window of the same width, so nothing is cut off.
    page.set_viewport_size({"width": VIEWPORT["width"], "height": 1400})
    demo.scroll_into_view_if_needed()
    page.wait_for_timeout(200)
    demo.screenshot(path=shot)
    page.set_viewport_size(VIEWPORT)
    demo.scroll_into_view_if_needed()

    controls = demo.locator("[class*='kf-control-']")
    all_keys = {DemoDriver.key_of(controls.nth(i)) for i in range(controls.count())}
    _check_accessible(demo, label, problems)
    _check_focus_ring(page, demo, label, problems)
    latency: Latency = {}
    tested = _drive_sliders(demo, driver, latency)
    tested |= _drive_buttons(demo, driver)
    tested |= _drive_choices(demo, driver)
    tested |= _drive_plays(demo, driver)
    driver.settle(quiet_ms=200)
    _check_accessible(demo, f"{label} (after its controls moved)", problems)

    untested = sorted(k for k in all_keys - tested if k)
    if untested:
        report.summary.append(f"note {label}: controls not driven by the suite: {', '.join(untested)}")
    if latency:
        _record_latency(label, latency, report)
    _check_speed_and_weight(driver, latency, label, problems, report)


def _check_demos(page, panel, stem: str, problems: list[str], report) -> int:
    """Check every ``.kf-demo`` of the notebook, labelled ``<stem>/<name>`` (``-2``, ... when a
    name repeats), with a screenshot each; returns how many there are."""
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
        label = f"{stem}/{name}{suffix}"
        _check_demo(page, demo, label, report.artifacts / f"{stem}__{name}{suffix}.png", problems, report)
    return demos.count()


# --------------------------------------------------------------------------- the test


def test_notebook_runs_and_demos_respond(browser, lab_server, report, notebook):
    url = lab_server.url
    context = browser.new_context(viewport=VIEWPORT)
    page_errors: list[str] = []
    timings = {"start": time.monotonic()}
    try:
        shutdown_kernels(context, url)
        page = context.new_page()
        page.on("pageerror", lambda e: page_errors.append(str(e)))
        panel_id = open_notebook(page, url, notebook.name, timings)
        panel = page.locator(f"[id='{panel_id}']")

        if not run_all(page, panel_id):
            pytest.fail(f"{notebook.name}: Run All did not finish in {RUN_ALL_TIMEOUT_MS // 1000} s", pytrace=False)
        timings["run all"] = time.monotonic()

        # -- no cell complained
        cells = read_cells(page)
        problems = _cell_problems(cells, panel)
        if problems:
            pytest.fail(f"{notebook.name}:\n  " + "\n  ".join(problems), pytrace=False)

        # -- every widget output really rendered as widgets
        _check_widgets_rendered(page, panel_id, panel, cells, notebook.name)
        timings["widgets"] = time.monotonic()
        full_page_screenshot(page, panel, report.artifacts / f"{notebook.stem}.png")
        timings["screenshot"] = time.monotonic()

        # -- drive every demo
        n_demos = _check_demos(page, panel, notebook.stem, problems, report)
        timings["demos driven"] = time.monotonic()

        # -- the chapter's own content against WCAG 2.1 A/AA
        violations = run_axe(page, [f"[id='{panel_id}'] .jp-MarkdownOutput", f"[id='{panel_id}'] .jp-OutputArea"])
        if violations:
            problems.append(f"axe-core: {format_violations(violations)}")
        timings["axe"] = time.monotonic()
        steps = list(timings.items())
        phases = ", ".join(f"{name} {b - a:.1f} s" for (_, a), (name, b) in itertools.pairwise(steps))
        print(f"\n[browser] {notebook.name}: {n_demos} demo(s); {phases}")

        if page_errors:
            report.summary.append(f"note {notebook.stem}: uncaught page errors: {'; '.join(page_errors)[:500]}")
        if problems:
            pytest.fail(f"{notebook.name}:\n  " + "\n  ".join(problems), pytrace=False)
    finally:
        close_context(context, url)
