"""Driving JupyterLab for the browser suite: open a notebook, Run All, read its cells back,
wait for its widgets, take a full-page screenshot, and shut every kernel down.

The checks on what comes back are in ``tests/browser/test_notebooks_in_lab.py``; driving
one demo's controls is ``tests/browser/demo_driver.py``.
"""

from __future__ import annotations

import os
import time
import urllib.parse

try:
    from playwright.sync_api import TimeoutError as PlaywrightTimeoutError
except ImportError:  # the `browser` fixture skips (fails on CI) with the reason
    PlaywrightTimeoutError = TimeoutError

VIEWPORT = {"width": 1280, "height": 800}  # a 13-inch laptop; the notebook opens beside the file browser
RUN_ALL_TIMEOUT_MS = int(os.environ.get("KFCOURSE_RUN_ALL_TIMEOUT_S", "240")) * 1000
KERNEL_IDLE_TIMEOUT_MS = 90_000
WIDGETS_RENDER_TIMEOUT_MS = 30_000
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


def shutdown_kernels(context, url: str) -> None:
    """Delete every session and every kernel: kernels outlive the browser."""
    headers = {"X-XSRFToken": _xsrf(context, url)}
    for kind in ("sessions", "kernels"):
        response = context.request.get(f"{url}api/{kind}")
        assert response.ok, f"GET api/{kind}: {response.status}"
        for item in response.json():
            r = context.request.delete(f"{url}api/{kind}/{item['id']}", headers=headers)
            assert r.status in (204, 404), f"DELETE api/{kind}/{item['id']}: {r.status} {r.text()}"


def close_context(context, url: str) -> None:
    """Close every page, shut the kernels down and close the browser context, whatever fails."""
    for p in context.pages:
        p.close()
    try:
        shutdown_kernels(context, url)
    finally:
        context.close()


# --------------------------------------------------------------------------- the notebook


def open_notebook(page, url: str, name: str, timings: dict[str, float]) -> str:
    """Open the notebook ``name`` with a fresh workspace, the file browser open beside it (as a
    student has it), and wait until its kernel is idle; returns the id of its panel.  Adds each
    phase's end to ``timings``."""
    page.goto(f"{url}lab/tree/{urllib.parse.quote(name)}?reset")
    timings["goto"] = time.monotonic()
    page.wait_for_function("() => !!(window.jupyterapp && window.jupyterapp.shell.currentWidget)")
    timings["app"] = time.monotonic()
    page.wait_for_function(
        "(name) => { const w = window.jupyterapp.shell.currentWidget;"
        " return !!(w && w.context && w.context.path === name); }",
        arg=name,
        timeout=KERNEL_IDLE_TIMEOUT_MS,
    )
    timings["notebook"] = time.monotonic()
    page.evaluate("() => window.jupyterapp.shell.activateById('filebrowser')")
    page.wait_for_function(JS_KERNEL_IDLE, timeout=KERNEL_IDLE_TIMEOUT_MS)
    timings["kernel idle"] = time.monotonic()
    return page.evaluate("() => window.jupyterapp.shell.currentWidget.id")


def run_all(page, panel_id: str) -> bool:
    """Run All, and wait until it has returned and no cell of the panel is still queued or running."""
    page.evaluate(JS_START_RUN_ALL)
    try:
        page.wait_for_function(JS_RUN_ALL_DONE, arg=panel_id, timeout=RUN_ALL_TIMEOUT_MS, polling=100)
        return True
    except PlaywrightTimeoutError:
        return False


def read_cells(page) -> list[dict]:
    """The current notebook's cells: index, type, source, execution count and summarised outputs."""
    return page.evaluate(JS_CELLS)


def wait_for_widgets(page, panel_id: str, expected: int) -> bool:
    """Whether at least ``expected`` outputs of the panel render as widgets in time."""
    try:
        page.wait_for_function(
            "([id, n]) => document.getElementById(id)"
            ".querySelectorAll('.jp-OutputArea-output > .jupyter-widgets').length >= n",
            arg=[panel_id, expected],
            timeout=WIDGETS_RENDER_TIMEOUT_MS,
        )
        return True
    except PlaywrightTimeoutError:
        return False


def full_page_screenshot(page, panel, path) -> None:
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
