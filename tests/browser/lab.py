"""Driving JupyterLab for the browser suite: open a notebook, Run All, read its cells back,
wait for its widgets, take a full-page screenshot, and shut every kernel down.

:class:`LabApp` is one JupyterLab page for a whole session: each chapter is opened in it as a
tab beside the file browser (one JupyterLab load, not one per chapter), and the next chapter
can be opened and run in a background tab (its own kernel) while the current one is checked.

The checks on what comes back are in ``tests/browser/test_notebooks_in_lab.py``; driving
one demo's controls is ``tests/browser/demo_driver.py``.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request
from collections.abc import Iterator
from pathlib import Path

from tests.servers import free_port

try:
    from playwright.sync_api import TimeoutError as PlaywrightTimeoutError
except ImportError:  # the `browser` fixture skips (fails on CI) with the reason
    PlaywrightTimeoutError = TimeoutError

# JupyterLab user settings for the test server (a temporary JUPYTERLAB_SETTINGS_DIR).
LAB_SETTINGS = {
    "@jupyterlab/docmanager-extension/plugin": {"autosave": False, "confirmClosingDocument": False},
    "@jupyterlab/notebook-extension/tracker": {
        # Every cell stays in the DOM (the default windowing detaches far-away cells).
        "windowingMode": "none",
        # A notebook without kernelspec metadata starts the default kernel, no dialog.
        "autoStartDefaultKernel": True,
        "kernelShutdown": True,
    },
    "@jupyterlab/apputils-extension/notification": {"checkForUpdates": False, "fetchNews": "false"},
    "@jupyterlab/extensionmanager-extension/plugin": {"enabled": False},
}

SERVER_START_TIMEOUT_S = 60

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


# --------------------------------------------------------------------------- the server


class LabServer:
    """A JupyterLab server started by :func:`running_lab`."""

    def __init__(self, url: str, root: Path, log: Path):
        self.url = url  # ends with "/"
        self.root = root
        self.log = log

    def log_tail(self, n: int = 40) -> str:
        try:
            return "\n".join(self.log.read_text(errors="replace").splitlines()[-n:])
        except OSError:
            return ""


def _status_ok(url: str) -> bool:
    try:
        with urllib.request.urlopen(url + "api/status", timeout=2) as response:
            return response.status == 200
    except (urllib.error.URLError, OSError):
        return False


@contextlib.contextmanager
def running_lab(base: Path, root: Path) -> Iterator[LabServer]:
    """JupyterLab on 127.0.0.1 serving ``root``, no token, with ``LAB_SETTINGS`` (autosave off)
    and its settings, workspaces, runtime and config folders under ``base``; stopped on exit.

    Raises ``RuntimeError`` with the end of its log if it exits or is not up in time.
    """
    settings = base / "user-settings"
    for plugin, values in LAB_SETTINGS.items():
        path = settings / f"{plugin}.jupyterlab-settings"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(values, indent=2), encoding="utf-8")
    for sub in ("workspaces", "runtime", "config"):
        (base / sub).mkdir()
    env = {
        **os.environ,
        "JUPYTERLAB_SETTINGS_DIR": str(settings),
        "JUPYTERLAB_WORKSPACES_DIR": str(base / "workspaces"),
        "JUPYTER_RUNTIME_DIR": str(base / "runtime"),
        "JUPYTER_CONFIG_DIR": str(base / "config"),
        "PYTHONUNBUFFERED": "1",
    }
    env.pop("JUPYTER_TOKEN", None)
    port = free_port()
    url = f"http://127.0.0.1:{port}/"
    sibling = Path(sys.executable).with_name("jupyter")
    cmd = [
        *([str(sibling)] if sibling.exists() else [sys.executable, "-m", "jupyter"]),
        "lab",
        "--no-browser",
        "--ServerApp.ip=127.0.0.1",
        f"--ServerApp.port={port}",
        "--ServerApp.port_retries=0",
        "--IdentityProvider.token=",
        "--PasswordIdentityProvider.hashed_password=",
        "--LabApp.expose_app_in_browser=True",
        f"--ServerApp.root_dir={root}",
    ]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--allow-root")
    log = base / "server.log"
    with open(log, "wb") as log_file:
        proc = subprocess.Popen(cmd, cwd=root, env=env, stdout=log_file, stderr=subprocess.STDOUT)
    server = LabServer(url, root, log)
    try:
        deadline = time.monotonic() + SERVER_START_TIMEOUT_S
        while not _status_ok(url):
            if proc.poll() is not None:
                raise RuntimeError(f"jupyter lab exited with {proc.returncode}:\n{server.log_tail()}")
            if time.monotonic() > deadline:
                raise RuntimeError(f"jupyter lab not up after {SERVER_START_TIMEOUT_S} s:\n{server.log_tail()}")
            time.sleep(0.25)
        yield server
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


@contextlib.contextmanager
def lab_over_copy(source: Path, prefix: str = "kfcourse-lab-") -> Iterator[LabServer]:
    """:func:`running_lab` over a temporary copy of the notebooks in ``source`` (the benchmarks'
    server: what a test or benchmark does never reaches the course's notebooks)."""
    with tempfile.TemporaryDirectory(prefix=prefix) as tmp:
        base = Path(tmp)
        root = base / "notebooks"
        shutil.copytree(source, root, ignore=shutil.ignore_patterns(".ipynb_checkpoints", "__pycache__"))
        with running_lab(base, root) as server:
            yield server


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


def shutdown_sessions(context, url: str, path: str) -> None:
    """Delete the sessions (and so the kernels) of the notebook at ``path``."""
    headers = {"X-XSRFToken": _xsrf(context, url)}
    response = context.request.get(f"{url}api/sessions")
    assert response.ok, f"GET api/sessions: {response.status}"
    for item in response.json():
        if item.get("path") == path:
            r = context.request.delete(f"{url}api/sessions/{item['id']}", headers=headers)
            assert r.status in (204, 404), f"DELETE api/sessions/{item['id']}: {r.status} {r.text()}"


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


def element_screenshots(page, shots, height: int = 1400) -> None:
    """A shot of each ``(locator, path)`` in a window of the same width, ``height`` px tall (so
    that a demo and its caption fit), resized once for all of them."""
    if not shots:
        return
    page.set_viewport_size({"width": VIEWPORT["width"], "height": height})
    try:
        for element, path in shots:
            element.scroll_into_view_if_needed()
            page.wait_for_timeout(50)
            element.screenshot(path=path)
    finally:
        page.set_viewport_size(VIEWPORT)


# --------------------------------------------------------------------------- one page, many chapters

# Opens a notebook in the running app (in front or in a background tab), then, in the page and
# without holding up the caller, waits until its kernel is idle, as the status bar shows it (the
# session's kernelDisplayStatus; a Run All sent earlier is silently dropped), and runs all its
# cells.  window.__kfRuns[path] says how far it got.
JS_OPEN_AND_RUN = """async ([path, activate]) => {
    window.__kfRuns = window.__kfRuns || {};
    const rec = window.__kfRuns[path] = {panel: null, idle: false, done: false, error: null};
    const app = window.jupyterapp;
    const panel = await app.commands.execute('docmanager:open', {path, options: {activate}});
    rec.panel = panel.id;
    (async () => {
        try {
            await panel.context.ready;
            await panel.sessionContext.ready;
            const s = panel.sessionContext;
            while (!(s.session && s.session.kernel && s.kernelDisplayStatus === 'idle')) {
                await new Promise(r => setTimeout(r, 50));
            }
            await s.session.kernel.info;
            rec.idle = true;
            rec.result = await app.commands.execute('notebook:run-all-cells', {widgetId: panel.id, activate: false});
        } catch (e) {
            rec.error = String(e);
        }
        rec.done = true;
    })();
    return panel.id;
}"""

JS_RUN_DONE = """(path) => {
    const rec = window.__kfRuns && window.__kfRuns[path];
    if (!rec || !rec.done) return false;
    const panel = document.getElementById(rec.panel);
    return !panel || !Array.from(panel.querySelectorAll('.jp-InputArea-prompt')).some(p => p.textContent.includes('*'));
}"""

# The notebook as it is closed by a test: no "save changes?" question (it ran, so it is dirty).
JS_DISPOSE = """(path) => {
    const rec = window.__kfRuns && window.__kfRuns[path];
    const w = rec && rec.panel && Array.from(window.jupyterapp.shell.widgets('main')).find(w => w.id === rec.panel);
    if (w) { w.context.model.dirty = false; w.dispose(); }
    if (rec) delete window.__kfRuns[path];
}"""


class LabApp:
    """One JupyterLab page (1280x800, the file browser open) for every chapter of a session.

    :meth:`start` opens a chapter and starts its Run All without waiting (in the background
    when ``activate`` is false); :meth:`open` brings a chapter to the front, starting it if
    nobody did, and waits for its Run All; :meth:`close` disposes of its tab and deletes its
    session.  Uncaught page errors collect in ``errors``.
    """

    def __init__(self, browser, url: str):
        self.url = url
        self.context = browser.new_context(viewport=VIEWPORT)
        self.errors: list[str] = []
        self.started: set[str] = set()
        self.found = ""  # how :meth:`open` found the last chapter: opened now, or started, running, run
        try:
            shutdown_kernels(self.context, url)
            self.page = self.context.new_page()
            self.page.on("pageerror", lambda e: self.errors.append(str(e)))
            self.page.goto(f"{url}lab?reset")
            self.page.wait_for_function("() => !!(window.jupyterapp && window.jupyterapp.shell)")
            self.page.evaluate("() => window.jupyterapp.restored.then(() => true)")
            self.page.evaluate("() => window.jupyterapp.shell.activateById('filebrowser')")
        except BaseException:
            self.shut()
            raise

    def start(self, name: str, activate: bool = False) -> None:
        """Open ``name`` and start its Run All once its kernel is idle; returns at once."""
        self.page.evaluate(JS_OPEN_AND_RUN, [name, activate])
        self.started.add(name)

    def open(self, name: str, timings: dict[str, float]) -> str | None:
        """``name`` in front, its Run All finished; its panel id, or None if Run All did not
        finish in ``RUN_ALL_TIMEOUT_MS`` or failed to start.  Adds each phase's end to ``timings``."""
        if name not in self.started:
            self.start(name, activate=True)
            self.found = "opened now"
        else:
            found = self.page.evaluate("(p) => window.__kfRuns[p]", name)
            self.found = "found " + ("run" if found["done"] else "running" if found["idle"] else "starting")
        panel_id = self.page.evaluate("(p) => window.__kfRuns[p].panel", name)
        self.page.evaluate("(id) => window.jupyterapp.shell.activateById(id)", panel_id)
        self.page.evaluate("() => window.jupyterapp.shell.activateById('filebrowser')")
        timings["opened"] = time.monotonic()
        try:
            self.page.wait_for_function(
                "(p) => window.__kfRuns[p].idle || window.__kfRuns[p].done", arg=name, timeout=KERNEL_IDLE_TIMEOUT_MS
            )
            timings["kernel idle"] = time.monotonic()
            self.page.wait_for_function(JS_RUN_DONE, arg=name, timeout=RUN_ALL_TIMEOUT_MS, polling=100)
        except PlaywrightTimeoutError:
            return None
        timings["run all"] = time.monotonic()
        error = self.page.evaluate("(p) => window.__kfRuns[p].error", name)
        if error:
            raise AssertionError(f"{name}: opening it or Run All failed in the page: {error}")
        return panel_id

    def close(self, name: str) -> None:
        """Dispose of ``name``'s tab (unsaved: the copy on disk stays as it was) and delete its session."""
        try:
            self.page.evaluate(JS_DISPOSE, name)
        finally:
            self.started.discard(name)
            shutdown_sessions(self.context, self.url, name)

    def shut(self) -> None:
        close_context(self.context, self.url)
