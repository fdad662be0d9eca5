"""A demo run and saved in the course's JupyterLab still shows its picture when the notebook is reopened.

What a student does with `make lab`: open a chapter, run it, save, shut the kernel down,
and come back later.  Reopened, the notebook gets a new kernel that knows nothing of the
demo's widgets; JupyterLab's widget renderer still wins over the demo's stored PNG, so
without saved widget state the demo shows "Error displaying widget: model not found".
The course's settings (binder/jupyter-config/labconfig/default_setting_overrides.json)
make the widget manager save widget state into the notebook, and the demo then comes back
from that state: the same picture, not live until its cell is run again.

The server is the course's own (tools/course.py lab, as `make lab` runs it) on a free port,
over a temporary working copy, with an empty settings folder: the course's settings only.
The whole chapter is run, as a student runs it: only then are all of its outputs the
student's own, the saved notebook is trusted, and JupyterLab renders widget views in it
when it is reopened (an untrusted notebook shows the stored PNG instead).  Known limits of
ipywidgets 8, not checked here: a notebook opened with "No Kernel" shows "Loading widget...",
and saving the reopened notebook before the demo is run again drops the saved state.
"""

from __future__ import annotations

import json
import os
import re
import sys
from pathlib import Path

import pytest

from tests.servers import Served, free_port, tracked_hashes

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
CHAPTER = "03_kalman_1d.ipynb"  # one light demo (step_through)
VIEWPORT = {"width": 1400, "height": 1000}
SERVER_START_TIMEOUT_S = 120
KERNEL_IDLE_TIMEOUT_MS = 90_000
RUN_ALL_TIMEOUT_MS = 180_000
RENDER_TIMEOUT_MS = 30_000
MIN_PICTURE_WIDTH = 600  # px of the picture itself; the demo's JPEG is 1900 wide

JS_NOTEBOOK_OPEN = """(name) => { const w = window.jupyterapp && window.jupyterapp.shell.currentWidget;
    return !!(w && w.context && w.context.path === name); }"""

JS_KERNEL_IDLE = r"""() => Array.from(document.querySelectorAll('.jp-StatusBar-Item'))
    .some(e => !e.classList.contains('lm-mod-hidden') && /\|\s*Idle$/.test(e.textContent.trim()))"""

JS_KERNEL_ID = """() => { const s = window.jupyterapp.shell.currentWidget.sessionContext;
    return s.session && s.session.kernel ? s.session.kernel.id : null; }"""

JS_START_RUN_ALL = """() => {
    window.__kfRunAll = false;
    window.jupyterapp.commands.execute('notebook:run-all-cells').finally(() => { window.__kfRunAll = true; });
}"""

JS_RUN_ALL_DONE = """() => window.__kfRunAll && !Array.from(window.jupyterapp.shell.currentWidget.node
    .querySelectorAll('.jp-InputArea-prompt')).some(p => p.textContent.includes('*'))"""

JS_NO_KERNEL = """() => !window.jupyterapp.shell.currentWidget.sessionContext.session"""

# Brings the demo's cell into view (a far-away cell may not be rendered) and returns its index.
JS_SHOW_DEMO_CELL = """() => {
    const notebook = window.jupyterapp.shell.currentWidget.content;
    const index = notebook.widgets.findIndex(c => c.model.type === 'code'
        && c.model.sharedModel.getSource().includes('kf.demos.'));
    if (index >= 0) { notebook.activeCellIndex = index; notebook.scrollToItem(index, 'start'); }
    return index;
}"""

# The picture at rest: at least `min` pixels wide, crisp (two pixels per CSS pixel: a demo sends a
# light picture while something moves and the crisp one a moment later), and the same src for
# `quiet` ms, so that the picture compared is the one the student is left looking at.
JS_PICTURE_SHOWN = """async ([min, quiet, max]) => {
    const start = performance.now();
    let src = null, since = performance.now();
    while (performance.now() - start < max) {
        const img = document.querySelector('.kf-demo img.kf-figure');
        const now = img && img.getAttribute('src');
        if (now !== src) { src = now; since = performance.now(); }
        const ready = img && now && img.complete && img.naturalWidth >= min
            && img.naturalWidth >= 2 * img.getBoundingClientRect().width - 1;
        if (ready && performance.now() - since >= quiet) return true;
        await new Promise(r => setTimeout(r, 50));
    }
    return false;
}"""
PICTURE_QUIET_MS = 1_000  # no new picture for this long: at rest

# The picture's size and the SHA-256 of its bytes, to compare the reopened one with the one shown live.
JS_PICTURE = """async () => {
    const img = document.querySelector('.kf-demo img.kf-figure');
    const bytes = await (await fetch(img.src)).arrayBuffer();
    const digest = Array.from(new Uint8Array(await crypto.subtle.digest('SHA-256', bytes)))
        .map(b => b.toString(16).padStart(2, '0')).join('');
    const box = img.getBoundingClientRect();
    return {src: img.getAttribute('src').slice(0, 40), natural: [img.naturalWidth, img.naturalHeight],
            shown: [Math.round(box.width), Math.round(box.height)], bytes: bytes.byteLength, digest};
}"""


# --------------------------------------------------------------------------- the course's server


class CourseLab:
    """``tools/course.py lab`` on a free port over ``base/my-notebooks``; its printed address, with the token."""

    def __init__(self, base: Path):
        self.work = base / "my-notebooks"
        self.port = free_port()
        env = {k: v for k, v in os.environ.items() if k not in ("JUPYTER_TOKEN", "JUPYTER_CONFIG_PATH")}
        for name, sub in [
            ("JUPYTER_RUNTIME_DIR", "runtime"),
            ("JUPYTER_CONFIG_DIR", "config"),
            ("JUPYTERLAB_SETTINGS_DIR", "settings"),  # empty: the course's settings and nothing else
            ("JUPYTERLAB_WORKSPACES_DIR", "workspaces"),
        ]:
            (base / sub).mkdir(parents=True, exist_ok=True)
            env[name] = str(base / sub)
        # Only for the test to drive the page (window.jupyterapp); no setting of the course changes.
        (base / "config" / "jupyter_server_config.json").write_text(
            json.dumps({"LabApp": {"expose_app_in_browser": True}}), encoding="utf-8"
        )
        self.server = Served(
            [sys.executable, str(ROOT / "tools" / "course.py"), "lab", f"--port={self.port}", f"--work={self.work}"],
            ROOT,
            env,
            rf"http://127\.0\.0\.1:{self.port}/\S*\?token=[0-9a-f]+",
        )

    def wait(self) -> tuple[str, str]:
        """The server's base address and its token, once the address is printed."""
        url = self.server.wait_for_url(SERVER_START_TIMEOUT_S)
        return f"http://127.0.0.1:{self.port}/", re.search(r"\?token=([0-9a-f]+)", url)[1]

    def stop(self) -> None:
        self.server.stop()


@pytest.fixture
def course_lab(tmp_path, chromium_executable):
    before = tracked_hashes()
    lab = CourseLab(tmp_path)
    try:
        yield lab
    finally:
        lab.stop()
    assert tracked_hashes() == before, "the tracked notebooks changed while the course was used"


# --------------------------------------------------------------------------- the test


def _open(page, url: str) -> None:
    page.goto(url)
    page.wait_for_function(JS_NOTEBOOK_OPEN, arg=CHAPTER, timeout=KERNEL_IDLE_TIMEOUT_MS)
    page.evaluate("() => window.jupyterapp.shell.collapseLeft()")
    page.wait_for_function(JS_KERNEL_IDLE, timeout=KERNEL_IDLE_TIMEOUT_MS)


def _wait_for_picture(page, when: str) -> None:
    if page.evaluate(JS_SHOW_DEMO_CELL) < 0:
        pytest.fail(f"{CHAPTER} has no demo cell (a cell calling kf.demos.*)", pytrace=False)
    if not page.evaluate(JS_PICTURE_SHOWN, [MIN_PICTURE_WIDTH, PICTURE_QUIET_MS, RENDER_TIMEOUT_MS]):
        shown = page.evaluate(
            "() => Array.from(document.querySelectorAll('.jp-OutputArea-output'))"
            ".map(o => o.innerText.trim()).filter(t => /widget/i.test(t)).join(' | ')"
        )
        pytest.fail(f"{when}: the demo shows no picture; the page says: {shown or 'nothing'}", pytrace=False)


def test_saved_demo_shows_its_picture_when_reopened(browser, course_lab, report):
    url, token = course_lab.wait()
    context = browser.new_context(viewport=VIEWPORT)
    try:
        page = context.new_page()
        _open(page, f"{url}lab/tree/{CHAPTER}?token={token}")
        first_kernel = page.evaluate(JS_KERNEL_ID)

        page.evaluate(JS_START_RUN_ALL)
        page.wait_for_function(JS_RUN_ALL_DONE, timeout=RUN_ALL_TIMEOUT_MS, polling=100)
        _wait_for_picture(page, "after Run All")
        live = page.evaluate(JS_PICTURE)

        # What the student does: File > Save, Kernel > Shut Down Kernel, and later open it again.
        page.evaluate("() => window.jupyterapp.commands.execute('docmanager:save')")
        page.evaluate("() => window.jupyterapp.commands.execute('kernelmenu:shutdown')")
        page.wait_for_function(JS_NO_KERNEL)

        page.reload()
        _open(page, page.url)
        assert page.evaluate(JS_KERNEL_ID) not in (None, first_kernel), "the reopened notebook kept its old kernel"
        _wait_for_picture(page, "reopened with a new kernel")
        assert page.get_by_text("model not found").count() == 0, "a widget of the reopened notebook failed"
        reopened = page.evaluate(JS_PICTURE)
        page.locator(".kf-demo").first.scroll_into_view_if_needed()
        report.artifacts.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=report.artifacts / "saved_notebook_reopened.png")
    finally:
        context.close()

    assert reopened["shown"][0] >= MIN_PICTURE_WIDTH, f"the picture is shown too small: {reopened}"
    assert reopened["digest"] == live["digest"], f"not the picture shown before saving: {live} vs {reopened}"
    saved = course_lab.work / CHAPTER
    state = json.loads(saved.read_text(encoding="utf-8"))["metadata"]["widgets"]
    models = state["application/vnd.jupyter.widget-state+json"]["state"]
    report.summary.append(
        f"saved copy of {CHAPTER} after Run All: {saved.stat().st_size / 1e6:.2f} MB, of which widget state "
        f"{len(json.dumps(state)) / 1e3:.0f} kB ({len(models)} models); picture {reopened['natural']} px"
    )
