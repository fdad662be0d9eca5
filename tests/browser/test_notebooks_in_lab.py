"""Every course notebook, run in JupyterLab in headless Chromium, with every demo driven.

Per notebook, in a 1280x800 window beside the file browser (a 13-inch laptop): open it,
wait for the kernel to be idle, Run All, then check that no cell wrote to stderr or raised,
that every widget really rendered, and, for each ``.kf-demo`` (see
``kfcourse/demos/_base.py`` for the DOM contract):

- a picture and a caption; the whole demo (caption, picture, controls, readout and
  description) fits the notebook area at once (at most ``LAYOUT_MAX_PX`` tall), and the
  picture is never shown larger than drawn;
- every slider (End, Home, then ``ARROW_PRESSES`` ArrowRight presses), every button, every
  option of every choice and the Run/Pause animation change the picture;
- after every control the crisp picture comes to rest (two pixels per CSS pixel), while
  something moves the demo sends light pictures, lighter than its crisp ones, and every
  picture holds the format it is sent as;
- Run advances the frame and the picture; after Pause the picture comes to rest, then shows
  no new picture and no new frame, the run did not play on to its last frame, and the button
  is released;
- for assistive technology: the picture's alt text is the description under it, in a polite
  live region; every slider is named by its label and announces the value its readout shows
  (also after it moved); every toggle and choice button exposes whether it is pressed, every
  group of choice buttons has a name; every control reached with Tab shows a focus ring at
  least ``FOCUS_MIN_PX`` wide at ``FOCUS_MIN_CONTRAST`` against the page or better, which no
  box around it clips, and a slider's readout is no Tab stop.

After the demos, axe-core checks the chapter's own content (its rendered Markdown and every
output) against the WCAG 2.1 A and AA rules: no violation.

**Nothing here is timed against a target.**  How fast a control answers and how much its
pictures weigh are figures, measured by ``benchmarks/bench_browser.py`` (``make bench``)
against its targets; other machines are slower than ours.  The bounds that remain are ones a
broken demo misses and a slow machine does not:

- ``ANSWER_MS`` (5 s): an action that brings no new picture within it does not answer, or
  the demo froze.  This machine answers in 100-350 ms at p95 when quiet, and its slowest
  control took 1.8 s at p95 at a load of 25 on its two cores; a passing run never waits for
  the bound, so it can be generous;
- ``PLAY_MS`` (2 s): Run has moved the frame and the picture by then (its first frame comes
  one frame interval, 80 ms, after the click; it skips frames to keep time on a slow machine);
- ``PAUSE_REST_MS`` (10 s): the picture comes to rest after Pause; the checks that Pause
  stopped the run are counts (no new picture or frame once at rest; not played on to the last
  frame for more frames than before Pause), not times;
- the light pictures' weight is compared with the same demo's crisp pictures, not with a
  number of bytes: a demo that sends its crisp picture while moving fails, whatever the machine.

The steps that drive JupyterLab are in ``tests/browser/lab.py``, the ones that drive a
demo's controls in ``tests/browser/demo_driver.py``; this module says what must hold.  One
JupyterLab page serves every chapter; while one chapter is checked, the next one is opened
and run in a background tab (its own kernel), so its kernel start and Run All cost no wait.
"""

from __future__ import annotations

import contextlib
import itertools
import time

import pytest

from tests.browser.axe import format_violations, run_axe
from tests.browser.demo_driver import (
    CRISP,
    JS_IMG_READY,
    DemoDriver,
    demo_labels,
    drive_every_control,
)
from tests.browser.lab import (
    RUN_ALL_TIMEOUT_MS,
    WIDGET_VIEW,
    WIDGETS_RENDER_TIMEOUT_MS,
    PlaywrightTimeoutError,
    element_screenshots,
    full_page_screenshot,
    read_cells,
    wait_for_widgets,
)
from tests.plots.colour_vision import contrast

pytestmark = pytest.mark.browser

LAYOUT_MAX_PX = 680  # a whole demo, caption to description: what a 1280x800 window leaves the notebook
FOCUS_MIN_PX = 2  # the focus ring's width (WCAG 2.4.11/2.4.13: a visible indicator)
FOCUS_MIN_CONTRAST = 3.0  # the focus ring against the page (WCAG 1.4.11, non-text contrast)
MAX_TAB_STOPS = 40  # more in one demo means Tab is caught in it

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

# The focused element's outline, the colour of the page behind it, and the first box around it
# (up to the demo's own) that would clip the ring: one whose overflow is not visible and whose
# inside the ring (the element's box grown by the outline's offset and width) leaves.
JS_FOCUS_RING = """() => {
    const e = document.activeElement;
    const style = getComputedStyle(e);
    const demo = e.closest('.kf-demo');
    const r = e.getBoundingClientRect();
    const reach = Math.max(parseFloat(style.outlineOffset) + parseFloat(style.outlineWidth), 0);
    let clippedBy = null;
    for (let a = e.parentElement; demo && a && demo.contains(a); a = a.parentElement) {
        const s = getComputedStyle(a);
        if (s.overflowX === 'visible' && s.overflowY === 'visible') continue;
        const b = a.getBoundingClientRect();
        const left = b.left + a.clientLeft, top = b.top + a.clientTop;
        if (r.left - reach < left - 0.5 || r.top - reach < top - 0.5
            || r.right + reach > left + a.clientWidth + 0.5 || r.bottom + reach > top + a.clientHeight + 0.5) {
            clippedBy = a.className.toString().slice(0, 60);
            break;
        }
    }
    return {
        what: e.outerHTML.slice(0, 80), style: style.outlineStyle,
        width: parseFloat(style.outlineWidth), color: style.outlineColor,
        inDemo: !!demo, readout: e.classList.contains('widget-readout'), clippedBy,
    };
}"""

# The demo's whole outermost element (caption, picture, controls, readout, description): its
# height and its caption's, the height of the notebook area that shows them, how far any part
# reaches past the output's right edge or overflows its box (a scroll bar), and the picture's
# CSS width against its pixel width.
JS_LAYOUT = """(d) => {
    const img = d.querySelector('img.kf-figure');
    const caption = d.querySelector('.kf-caption');
    const area = d.closest('.jp-WindowedPanel-outer');
    const output = d.closest('.jp-OutputArea-output') || d.parentElement;
    const items = d.querySelectorAll('img, .widget-slider, .widget-button, .widget-toggle-buttons, .widget-html');
    return {
        height: d.getBoundingClientRect().height,
        caption: caption ? caption.getBoundingClientRect().height : 0,
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
    """Every Tab stop of the demo shows a ring of at least FOCUS_MIN_PX at FOCUS_MIN_CONTRAST that no
    box around it clips, and a slider's readout (text the handle announces) is no Tab stop."""
    first = demo.locator(".kf-caption summary, .noUi-handle, button").first
    first.focus()
    page.keyboard.press("Tab")  # to the next stop and back: the focus now comes from the keyboard
    page.keyboard.press("Shift+Tab")
    for _ in range(MAX_TAB_STOPS):
        ring = page.evaluate(JS_FOCUS_RING)
        if not ring["inDemo"]:
            break
        if ring["readout"]:
            problems.append(f"{label}: Tab stops at a slider's readout {ring['what']!r}: it is text, not a control")
        if ring["style"] in ("none", "hidden") or ring["width"] < FOCUS_MIN_PX:
            problems.append(f"{label}: focus on {ring['what']!r} shows a {ring['width']} px {ring['style']} outline")
        elif contrast(css_hex(ring["color"]), "#ffffff") < FOCUS_MIN_CONTRAST:
            problems.append(f"{label}: the focus ring {ring['color']} has too little contrast against the page")
        elif ring["clippedBy"] is not None:
            problems.append(f"{label}: the focus ring of {ring['what']!r} is clipped by {ring['clippedBy']!r}")
        page.keyboard.press("Tab")
    else:
        problems.append(f"{label}: more than {MAX_TAB_STOPS} Tab stops, or Tab never leaves the demo")
    page.keyboard.press("Escape")


def css_hex(css: str) -> str:
    """A computed CSS colour, ``rgb(r, g, b)`` or ``rgba(r, g, b, a)`` (alpha ignored), as ``#rrggbb``."""
    r, g, b = (round(float(v)) for v in css[css.index("(") + 1 : css.index(")")].split(",")[:3])
    return f"#{r:02x}{g:02x}{b:02x}"


def _check_layout(demo, label: str, problems: list[str]) -> None:
    """The whole demo, caption to description, fits the notebook area at once, nothing sticks out on the right,
    and the picture is not enlarged."""
    box = demo.evaluate(JS_LAYOUT)
    room = min(LAYOUT_MAX_PX, box["area"] or LAYOUT_MAX_PX)
    if box["height"] > room:
        problems.append(
            f"{label}: the demo is {box['height']:.0f} px tall (its caption {box['caption']:.0f} px); "
            f"the laptop shows {room} px"
        )
    if box["overflow"] > 1:
        problems.append(f"{label}: the picture or a control sticks out {box['overflow']:.0f} px: a scroll bar")
    if box["shown"] > box["natural"] / 2 + 0.5:
        problems.append(
            f"{label}: the picture is shown {box['shown']:.0f} px wide, larger than it was drawn "
            f"({box['natural']} pixels for 2 per CSS px)"
        )


def _check_pictures(driver: DemoDriver, label: str, problems: list[str], report) -> None:
    """Every picture holds the format it is sent as; light pictures were sent while the controls
    moved, and they weigh less than the demo's crisp ones (median against median)."""
    pictures = driver.pictures()
    for p in pictures:
        if p["holds"] not in (None, p["type"]):
            problems.append(f"{label}: a picture sent as {p['type']} holds {p['holds']} bytes")
            break
    light = sorted(p["bytes"] for p in pictures if p["bytes"] and p["bytes"] > 0 and p["type"] != CRISP)
    crisp = sorted(p["bytes"] for p in pictures if p["bytes"] and p["bytes"] > 0 and p["type"] == CRISP)
    if not light:
        problems.append(f"{label}: no light picture was sent while the controls moved")
    elif crisp and light[len(light) // 2] >= crisp[len(crisp) // 2]:
        problems.append(
            f"{label}: the pictures sent while moving weigh {light[len(light) // 2] / 1e3:.0f} KB (median), "
            f"no lighter than the crisp ones ({crisp[len(crisp) // 2] / 1e3:.0f} KB)"
        )
    report.summary.append(
        f"weight {label}: {len(light)} moving pictures, median {light[len(light) // 2] / 1e3 if light else 0:.0f} KB;"
        f" {len(crisp)} at rest, median {crisp[len(crisp) // 2] / 1e3 if crisp else 0:.0f} KB"
    )


def _check_demo(page, demo, label: str, problems: list[str], report) -> None:
    """A picture and a caption that fit a laptop, then every control drives the picture, with
    light pictures while moving and the crisp one at rest."""
    driver = DemoDriver(page, demo, label, problems, report)
    demo.scroll_into_view_if_needed()
    driver.settle(quiet_ms=200)
    _check_layout(demo, label, problems)

    controls = demo.locator("[class*='kf-control-']")
    all_keys = {DemoDriver.key_of(controls.nth(i)) for i in range(controls.count())}
    _check_accessible(demo, label, problems)
    _check_focus_ring(page, demo, label, problems)
    tested, _ = drive_every_control(demo, driver)
    driver.settle(quiet_ms=200)
    _check_accessible(demo, f"{label} (after its controls moved)", problems)

    untested = sorted(k for k in all_keys - tested if k)
    if untested:
        report.summary.append(f"note {label}: controls not driven by the suite: {', '.join(untested)}")
    _check_pictures(driver, label, problems, report)


def _shown_demos(page, panel, stem: str, problems: list[str], report) -> list[tuple[object, str]]:
    """Every ``.kf-demo`` of the notebook, labelled ``<stem>/<name>`` (``-2``, ... when a name
    repeats), whose picture and caption are shown: (its locator, its label)."""
    demos = panel.locator(".kf-demo")
    shown = []
    for i, label in enumerate(demo_labels(panel, stem)):
        demo = demos.nth(i)
        if demo.evaluate("e => !Array.from(e.classList).some(c => c.startsWith('kf-demo-'))"):
            problems.append(f"demo #{i} has no kf-demo-<name> class")
        if _picture_shown(page, demo, label, problems):
            shown.append((demo, label))
    return shown


# --------------------------------------------------------------------------- the test


def test_notebook_runs_and_demos_respond(lab_app, next_notebook, report, notebook):
    page = lab_app.page
    errors_before = len(lab_app.errors)
    timings = {"start": time.monotonic()}
    panel = None
    try:
        panel_id = lab_app.open(notebook.name, timings)
        if panel_id is None:
            pytest.fail(f"{notebook.name}: Run All did not finish in {RUN_ALL_TIMEOUT_MS // 1000} s", pytrace=False)
        # The next chapter opens and runs in a background tab while this one is checked.
        following = next_notebook(notebook.name)
        if following is not None and following not in lab_app.started:
            lab_app.start(following, activate=False)
        panel = page.locator(f"[id='{panel_id}']")

        # -- no cell complained
        cells = read_cells(page)
        problems = _cell_problems(cells, panel)
        if problems:
            pytest.fail(f"{notebook.name}:\n  " + "\n  ".join(problems), pytrace=False)

        # -- every widget output really rendered as widgets
        _check_widgets_rendered(page, panel_id, panel, cells, notebook.name)
        timings["widgets"] = time.monotonic()
        demos = _shown_demos(page, panel, notebook.stem, problems, report)
        # Each demo with its caption as it opens (the README's pictures come from these).
        shots = [(demo, report.artifacts / f"{label.replace('/', '__')}.png") for demo, label in demos]
        element_screenshots(page, shots)
        timings["screenshots"] = time.monotonic()

        # -- drive every demo
        for demo, label in demos:
            _check_demo(page, demo, label, problems, report)
        n_demos = panel.locator(".kf-demo").count()
        timings["demos driven"] = time.monotonic()

        # -- the chapter's own content against WCAG 2.1 A/AA
        violations = run_axe(page, [f"[id='{panel_id}'] .jp-MarkdownOutput", f"[id='{panel_id}'] .jp-OutputArea"])
        if violations:
            problems.append(f"axe-core: {format_violations(violations)}")
        timings["axe"] = time.monotonic()
        steps = list(timings.items())
        phases = ", ".join(f"{name} {b - a:.1f} s" for (_, a), (name, b) in itertools.pairwise(steps))
        print(f"\n[browser] {notebook.name} ({lab_app.found}): {n_demos} demo(s); {phases}")

        page_errors = lab_app.errors[errors_before:]
        if page_errors:
            report.summary.append(f"note {notebook.stem}: uncaught page errors: {'; '.join(page_errors)[:500]}")
        if problems:
            pytest.fail(f"{notebook.name}:\n  " + "\n  ".join(problems), pytrace=False)
    except BaseException:
        # The whole notebook as the failure left it (about 5 s of rendering: only when it helps).
        if panel is not None:
            with contextlib.suppress(Exception):
                full_page_screenshot(page, panel, report.artifacts / f"{notebook.stem}.png")
        raise
    finally:
        lab_app.close(notebook.name)
