"""The static edition (``make site``): built from the notebooks, read in headless Chromium.

The site is built into a temporary folder and served on 127.0.0.1.  Every chapter must
have its page, linked from the index in order; on every page the equations are typeset
by the bundled MathJax, every picture of the site has loaded (above all each demo's first
frame, and the recording of its run where it has one), no cell failed, no script, style or
font comes from outside the site (pictures may: the Binder badges), and every link inside
the site leads to a page (and anchor) that exists.  A demo's caption sits under its
picture; the recording of its run is as sharp as the still (as many pixels, shown as
wide) and light enough for a page; nbval's ``# NBVAL_CHECK_OUTPUT`` markers stay off the pages.
"""

from __future__ import annotations

import functools
import html
import http.server
import json
import os
import re
import subprocess
import sys
import threading
import urllib.parse
from pathlib import Path

import nbformat
import pytest

pytestmark = pytest.mark.browser

REPO_ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = Path(__file__).resolve().parent / "artifacts"
BUILD_TIMEOUT_S = 1800
MATHJAX_TIMEOUT_MS = 60_000
MAX_RECORDING_BYTES = 1_000_000  # a recording of a run: a few hundred kB
NBVAL_MARKER = "# NBVAL_CHECK_OUTPUT"
# A cell that shows a demo ends with the demo's constructor, e.g. ``kf.demos.tracker(seed=0)``.
DEMO_CALL = re.compile(r"^kf\.demos\.\w+\(.*\)\s*;?\s*$")


def notebooks_dir() -> Path:
    override = os.environ.get("KFCOURSE_NOTEBOOKS")
    return Path(override).resolve() if override else REPO_ROOT / "notebooks"


def expected_pages() -> list[Path]:
    """Every NN_*.ipynb in order, then notation.ipynb and solutions.ipynb where there are."""
    folder = notebooks_dir()
    found = sorted(p for p in folder.glob("*.ipynb") if re.fullmatch(r"\d\d_[a-z0-9_]+\.ipynb", p.name))
    return found + [p for p in (folder / "notation.ipynb", folder / "solutions.ipynb") if p.exists()]


def demo_cells(path: Path) -> int:
    nb = nbformat.read(path, as_version=4)
    last_lines = [c.source.strip().splitlines()[-1] for c in nb.cells if c.cell_type == "code" and c.source.strip()]
    return sum(bool(DEMO_CALL.match(line)) for line in last_lines)


def marked_cells(path: Path) -> list[str]:
    """The code under the marker of every cell whose output nbval checks."""
    nb = nbformat.read(path, as_version=4)
    return [c.source.split("\n", 1)[1] for c in nb.cells if c.cell_type == "code" and c.source.startswith(NBVAL_MARKER)]


def has_math(path: Path) -> bool:
    nb = nbformat.read(path, as_version=4)
    return any("$" in c.source for c in nb.cells if c.cell_type == "markdown")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("site")
    command = [sys.executable, str(REPO_ROOT / "tools" / "build_site.py"), "--out", str(out)]
    command += ["--notebooks", str(notebooks_dir())]
    result = subprocess.run(command, capture_output=True, text=True, timeout=BUILD_TIMEOUT_S, cwd=REPO_ROOT)
    if result.returncode != 0:
        pytest.fail(f"the site build failed:\n{result.stdout[-3000:]}\n{result.stderr[-3000:]}", pytrace=False)
    return out


@pytest.fixture(scope="module")
def site_url(site):
    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(site)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=10)


@pytest.fixture(scope="module")
def context(browser):
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    try:
        yield context
    finally:
        context.close()


def test_index_links_every_chapter_in_order(context, site_url, site):
    page = context.new_page()
    try:
        page.goto(site_url + "index.html")
        hrefs = page.eval_on_selector_all("ul.kf-chapters a", "links => links.map(a => a.getAttribute('href'))")
    finally:
        page.close()
    assert hrefs == [p.stem + ".html" for p in expected_pages()]
    assert (site / "index.html").exists() and len(hrefs) >= 8


JS_PAGE_STATE = r"""() => ({
    h1: Array.from(document.querySelectorAll('h1')).map(h => h.textContent.trim()),
    math: document.querySelectorAll('.MathJax, .MathJax_Display').length,
    mathErrors: document.querySelectorAll('.MathJax_Error, .merror, .noError').length,
    rawTex: Array.from(document.querySelectorAll('.jp-MarkdownOutput'))
        .some(e => /\\(frac|hat|mathbf|begin|sigma|Sigma)\b/.test(e.innerText)),
    images: Array.from(document.images).map(i => ({
        cls: i.className, src: i.getAttribute('src').slice(0, 60), ok: i.complete && i.naturalWidth > 0,
        natural: i.naturalWidth, shown: Math.round(i.getBoundingClientRect().width)})),
    errors: document.querySelectorAll(
        '[data-mime-type="application/vnd.jupyter.stderr"], [data-mime-type="application/vnd.jupyter.error"]').length,
    widgetLeftovers: document.querySelectorAll(
        'script[type="application/vnd.jupyter.widget-view+json"], .jupyter-widgets').length
        + (document.body.innerText.includes('Demo(children') ? 1 : 0),
    links: Array.from(document.querySelectorAll('a[href]')).map(a => a.href),
    code: Array.from(document.querySelectorAll('.jp-InputArea-editor')).map(e => e.innerText),
    nbvalShown: document.body.innerText.includes('NBVAL_'),
    demos: Array.from(document.querySelectorAll('.kf-demo-static')).map(d => {
        const box = e => e && e.getBoundingClientRect();
        const follows = (a, b) => !!(a && b) && Boolean(a.compareDocumentPosition(b) & Node.DOCUMENT_POSITION_FOLLOWING)
            && box(b).top >= box(a).bottom - 1;
        const still = d.querySelector('img.kf-demo-picture'), run = d.querySelector('img.kf-demo-animation');
        const size = i => i && {natural: i.naturalWidth, shown: Math.round(box(i).width)};
        return {still: size(still), run: size(run),
            captionUnderPicture: follows(still, d.querySelector('.kf-caption')),
            noteUnderRecording: run ? follows(run, d.querySelector('.kf-demo-run figcaption')) : null};
    }),
})"""


@pytest.mark.parametrize("chapter", expected_pages(), ids=lambda p: p.stem)
def test_chapter_page(context, site_url, site, chapter):
    notebook = chapter
    url = site_url + notebook.stem + ".html"
    page = context.new_page()
    outside, failed = [], []
    page.on(
        "request",
        lambda r: (
            outside.append(f"{r.resource_type} {r.url}")
            if not r.url.startswith((site_url, "data:", "blob:", "about:")) and r.resource_type != "image"
            else None
        ),
    )
    page.on("response", lambda r: failed.append(f"{r.status} {r.url}") if r.status >= 400 and r.url != url else None)
    try:
        response = page.goto(url)
        assert response is not None and response.ok, f"{url}: {response and response.status}"
        page.wait_for_load_state("load")
        page.wait_for_function(
            "() => window.MathJax && MathJax.Hub && MathJax.Hub.queue.pending === 0 && !MathJax.Hub.queue.running",
            timeout=MATHJAX_TIMEOUT_MS,
        )
        state = page.evaluate(JS_PAGE_STATE)
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        figures = page.locator(".kf-demo-static")
        for i in range(figures.count()):
            figures.nth(i).screenshot(path=ARTIFACTS / f"site__{notebook.stem}__demo{i}.png")
        links = state["links"]
    finally:
        page.close()

    assert state["h1"], "no title"
    if has_math(notebook):
        assert state["math"] > 0, "the equations were not typeset"
    assert state["mathErrors"] == 0, "MathJax could not typeset some equations"
    assert not state["rawTex"], "raw TeX left in the text"
    assert state["errors"] == 0, "a cell wrote to stderr or raised"
    assert state["widgetLeftovers"] == 0, "a widget that needs a kernel is on the page"
    # Pictures of the site itself; a badge from the web (Binder) cannot load on this offline machine.
    broken = [i for i in state["images"] if not i["ok"] and not i["src"].startswith(("http:", "https:"))]
    assert not broken, f"pictures that did not load: {broken}"

    pictures = [i for i in state["images"] if "kf-demo-picture" in i["cls"]]
    assert len(pictures) == demo_cells(notebook), "not every demo shows a picture of its first frame"
    for picture in pictures:
        assert picture["src"].startswith("data:image/png")
        assert picture["natural"] >= 1.5 * picture["shown"] > 0  # drawn for a HiDPI screen, shown smaller
    manifest = json.loads((site / "demos.json").read_text(encoding="utf-8"))
    (entry,) = [p for p in manifest["pages"] if p["notebook"] == notebook.name]
    recorded = [d["animation"] for d in entry["demos"] if d["animation"]]
    animations = [i for i in state["images"] if "kf-demo-animation" in i["cls"]]
    assert len(animations) == len(recorded) and len(entry["demos"]) == len(pictures)
    assert len(state["demos"]) == len(pictures)
    for k, demo in enumerate(state["demos"]):
        assert demo["captionUnderPicture"], f"demo {k}: its caption is not under its picture"
        if demo["run"] is not None:
            assert demo["noteUnderRecording"], f"demo {k}: the recording's note is not under it"
            assert demo["run"] == demo["still"], f"demo {k}: the recording is not drawn and shown as the still is"

    assert not state["nbvalShown"], "a page shows an nbval marker"
    for code in marked_cells(notebook):  # the code under the marker is still there
        assert code.strip() in [c.strip() for c in state["code"]], f"a checked cell lost its code: {code[:80]!r}"

    assert not outside, f"the page needs scripts, styles or fonts from outside the site: {outside}"
    site_failures = [f for f in failed if "/_static/mathjax/fonts/" not in f]  # MathJax probes fonts it may lack
    assert not site_failures, f"requests that failed: {site_failures}"
    assert_links_resolve(context, site_url, links)


def assert_links_resolve(context, site_url: str, links: list[str]) -> None:
    """Every link inside the site leads to a page that exists, and to its anchor if it names one."""
    ids: dict[str, set[str]] = {}
    broken = []
    for link in links:
        if not link.startswith(site_url):
            continue
        target, _, fragment = link.partition("#")
        if target not in ids:
            response = context.request.get(target)
            if not response.ok:
                broken.append(f"{link} ({response.status})")
                continue
            body = response.text()
            ids[target] = {html.unescape(m) for m in re.findall(r'\sid="([^"]*)"', body)}
        # As a browser does: the fragment as written, or else percent-decoded, names an id.
        if fragment and not {fragment, urllib.parse.unquote(fragment)} & ids[target]:
            broken.append(f"{link} (no element with that id)")
    assert not broken, f"broken links: {broken}"


def test_every_run_pause_demo_has_a_recording(site):
    """A demo with Run/Pause gets a recording of its run; at least one chapter has such a demo,
    and none weighs down its page."""
    manifest = json.loads((site / "demos.json").read_text(encoding="utf-8"))
    recordings = [d["animation"] for p in manifest["pages"] for d in p["demos"] if d["animation"]]
    assert recordings, "no demo recorded its run"
    for rel in recordings:
        data = (site / rel).read_bytes()
        assert data[:4] == b"RIFF" and data[8:12] == b"WEBP", rel
        assert len(data) <= MAX_RECORDING_BYTES, f"{rel}: {len(data) / 1e6:.2f} MB"
