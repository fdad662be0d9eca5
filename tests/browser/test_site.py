"""The static edition (``make site``): built from the notebooks, read in headless Chromium.

The site is built into a temporary folder and served on 127.0.0.1.  Every chapter must
have its page, linked from the index in order; on every page the equations are typeset
by the bundled MathJax, every picture of the site has loaded (above all each demo's first
frame, and the recording of its run once asked for), no cell failed, no script, style or
font comes from outside the site (pictures may: the Binder badges) and no script names an
outside address, no request fails (not even one of MathJax's for a font), and every link
inside the site leads to a page (and anchor) that exists.

Every page, the index too, passes axe-core's WCAG 2.1 A and AA rules with no violation
(``tests/browser/axe.py``: contrast of code and prompts, links told apart from text, alt
texts, ...); it has ``lang="en"``, a title, and a ``<main>`` landmark with the navigation
outside it.  No picture's alt text is a stock phrase (nbconvert's "No description has been
provided for this image"); a demo's picture has the demo's own description as its alt text,
the same sentence is printed under the picture, and the caption under that.  Nothing moves by
itself: a recording is not even fetched until its "Play the run" button (a real
``<button>`` with ``aria-pressed``) is pressed from the keyboard; then it shows in the
still's place, as sharp as the still (as many pixels, shown as wide), and pressed again
the still comes back and the recording stops.  Recordings are light enough for a page;
nbval's ``# NBVAL_CHECK_OUTPUT`` markers stay off the pages.
"""

from __future__ import annotations

import functools
import html
import http.server
import json
import os
import re
import threading
import urllib.parse
from pathlib import Path

import nbformat
import pytest

from tests.browser.axe import format_violations, run_axe

pytestmark = pytest.mark.browser

REPO_ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = Path(__file__).resolve().parent / "artifacts"
BUILD_TIMEOUT_S = 1800
MATHJAX_TIMEOUT_MS = 60_000
MAX_RECORDING_BYTES = 1_000_000  # a recording of a run: a few hundred kB
NBVAL_MARKER = "# NBVAL_CHECK_OUTPUT"
# A cell that shows a demo ends with the demo's constructor, e.g. ``kf.demos.tracker(seed=0)``.
DEMO_CALL = re.compile(r"^kf\.demos\.\w+\(.*\)\s*;?\s*$")
# Alt texts that say nothing about the picture: nbconvert's default and the site's old ones.
STOCK_ALT = {"no description has been provided for this image", "the demo as it opens", "the demo, its run", ""}
RECORDING_ALT = "Recording of the demo's run"
PLAY = "Play the run"


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
def site(site_build) -> Path:
    """The site, built by ``tools/build_site.py`` from the session's start (``conftest.site_build``)."""
    assert site_build is not None, "the site build was not started with the session"
    return site_build.wait(BUILD_TIMEOUT_S)


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


JS_LANDMARKS = r"""() => ({
    lang: document.documentElement.getAttribute('lang'),
    title: document.title.trim(),
    main: document.querySelectorAll('main').length,
    navInMain: document.querySelectorAll('main nav').length,
    navs: document.querySelectorAll('nav').length,
})"""


def assert_page_structure(page) -> None:
    """``lang="en"``, a title, one ``<main>``, the navigation outside it."""
    found = page.evaluate(JS_LANDMARKS)
    assert found["lang"] == "en", f"the page's language: {found['lang']!r}"
    assert found["title"], "the page has no title"
    assert found["main"] == 1, f"{found['main']} <main> landmark(s), not one"
    assert found["navInMain"] == 0, "the navigation is inside <main>"


def assert_no_axe_violations(page, include: list[str], when: str) -> None:
    violations = run_axe(page, include)
    assert not violations, f"{when}: {format_violations(violations)}"


def test_index_links_every_chapter_in_order(context, site_url, site):
    page = context.new_page()
    try:
        page.goto(site_url + "index.html")
        hrefs = page.eval_on_selector_all("ul.kf-chapters a", "links => links.map(a => a.getAttribute('href'))")
        assert_page_structure(page)
        assert_no_axe_violations(page, ["html"], "index.html")
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
        cls: i.className, src: (i.getAttribute('src') || '').slice(0, 60), ok: i.complete && i.naturalWidth > 0,
        alt: i.getAttribute('alt'), hidden: i.hidden,
        natural: i.naturalWidth, shown: Math.round(i.getBoundingClientRect().width)})),
    errors: document.querySelectorAll(
        '[data-mime-type="application/vnd.jupyter.stderr"], [data-mime-type="application/vnd.jupyter.error"]').length,
    widgetLeftovers: document.querySelectorAll(
        'script[type="application/vnd.jupyter.widget-view+json"], .jupyter-widgets').length
        + (document.body.innerText.includes('Demo(children') ? 1 : 0),
    links: Array.from(document.querySelectorAll('a[href]')).map(a => a.href),
    scripts: Array.from(document.scripts).map(s => s.src || s.textContent),
    code: Array.from(document.querySelectorAll('.jp-InputArea-editor')).map(e => e.innerText),
    nbvalShown: document.body.innerText.includes('NBVAL_'),
    demos: Array.from(document.querySelectorAll('.kf-demo-static')).map(d => {
        const box = e => e && e.getBoundingClientRect();
        const follows = (a, b) => !!(a && b) && Boolean(a.compareDocumentPosition(b) & Node.DOCUMENT_POSITION_FOLLOWING)
            && box(b).top >= box(a).bottom - 1;
        const still = d.querySelector('img.kf-demo-picture'), run = d.querySelector('img.kf-demo-animation');
        const description = d.querySelector('.kf-description'), caption = d.querySelector('.kf-caption');
        const button = d.querySelector('button.kf-play');
        return {
            alt: still && still.getAttribute('alt'),
            description: description && description.textContent,
            descriptionUnderPicture: follows(still, description),
            captionUnderDescription: follows(description, caption),
            run: run && {src: run.getAttribute('src'), hidden: run.hidden, alt: run.getAttribute('alt')},
            button: button && {tag: button.tagName, type: button.type, pressed: button.getAttribute('aria-pressed')},
        };
    }),
})"""

# One demo figure after its button was pressed: what shows, and the recording's size.
JS_FIGURE = r"""figure => {
    const still = figure.querySelector('img.kf-demo-picture'), run = figure.querySelector('img.kf-demo-animation');
    const visible = e => !e.hidden && e.getBoundingClientRect().width > 0;
    return {
        pressed: figure.querySelector('button.kf-play').getAttribute('aria-pressed'),
        stillShown: visible(still), runShown: visible(run), runSrc: run.getAttribute('src'),
        runLoaded: run.complete && run.naturalWidth > 0,
        run: {natural: run.naturalWidth, shown: Math.round(run.getBoundingClientRect().width)},
    };
}"""


@pytest.mark.parametrize("chapter", expected_pages(), ids=lambda p: p.stem)
def test_chapter_page(context, site_url, site, chapter):
    notebook = chapter
    url = site_url + notebook.stem + ".html"
    manifest = json.loads((site / "demos.json").read_text(encoding="utf-8"))
    (entry,) = [p for p in manifest["pages"] if p["notebook"] == notebook.name]
    page = context.new_page()
    outside, failed, media = [], [], []
    page.on(
        "request",
        lambda r: (
            outside.append(f"{r.resource_type} {r.url}")
            if not r.url.startswith((site_url, "data:", "blob:", "about:")) and r.resource_type != "image"
            else None
        ),
    )
    page.on(
        "request", lambda r: media.append(r.url[len(site_url) :]) if r.url.startswith(site_url + "media/") else None
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
        fetched_before_play = list(media)
        assert_page_structure(page)
        assert_no_axe_violations(page, ["html"], notebook.stem)
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        figures = page.locator(".kf-demo-static")
        for i in range(figures.count()):
            figures.nth(i).screenshot(path=ARTIFACTS / f"site__{notebook.stem}__demo{i}.png")
        played = play_and_stop_every_recording(page, figures, notebook.stem)
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
    # A recording has no src until it is asked for.
    shown = [i for i in state["images"] if not i["hidden"]]
    broken = [i for i in shown if not i["ok"] and not i["src"].startswith(("http:", "https:"))]
    assert not broken, f"pictures that did not load: {broken}"
    stock = [i for i in state["images"] if (i["alt"] or "").strip().lower() in STOCK_ALT]
    assert not stock, f"pictures whose alt text says nothing about them: {[(i['cls'], i['alt']) for i in stock]}"

    pictures = [i for i in state["images"] if "kf-demo-picture" in i["cls"]]
    assert len(pictures) == demo_cells(notebook), "not every demo shows a picture of its first frame"
    for picture in pictures:
        assert picture["src"].startswith("data:image/png")
        assert picture["natural"] >= 1.5 * picture["shown"] > 0  # drawn for a HiDPI screen, shown smaller
    recorded = [d["animation"] for d in entry["demos"] if d["animation"]]
    animations = [i for i in state["images"] if "kf-demo-animation" in i["cls"]]
    assert len(animations) == len(recorded) and len(entry["demos"]) == len(pictures)
    assert len(state["demos"]) == len(pictures)
    for k, (demo, listed) in enumerate(zip(state["demos"], entry["demos"], strict=True)):
        assert demo["alt"] == listed["description"], f"demo {k}: its alt text is not its description"
        assert demo["description"] == listed["description"], f"demo {k}: its description is not printed"
        assert demo["descriptionUnderPicture"], f"demo {k}: its description is not under its picture"
        assert demo["captionUnderDescription"], f"demo {k}: its caption is not under its description"
        if listed["animation"] is None:
            assert demo["run"] is None and demo["button"] is None
            continue
        assert demo["run"] == {"src": None, "hidden": True, "alt": listed["animation_alt"]}, f"demo {k}: {demo['run']}"
        assert demo["run"]["alt"].startswith(RECORDING_ALT) and len(demo["run"]["alt"]) > len(RECORDING_ALT) + 20
        assert demo["button"] == {"tag": "BUTTON", "type": "button", "pressed": "false"}, f"demo {k}: {demo['button']}"
    assert not fetched_before_play, f"recordings fetched (and played) before anyone asked: {fetched_before_play}"
    assert sorted(set(media)) == sorted(recorded), "pressing Play did not fetch each recording"
    for k, (still, run) in played.items():
        assert run == still, f"demo {k}: the recording is not drawn and shown as the still is"

    assert not state["nbvalShown"], "a page shows an nbval marker"
    for code in marked_cells(notebook):  # the code under the marker is still there
        assert code.strip() in [c.strip() for c in state["code"]], f"a checked cell lost its code: {code[:80]!r}"

    assert not outside, f"the page needs scripts, styles or fonts from outside the site: {outside}"
    # Not even a script that would fetch one only in some case (nbconvert's loader of mermaid diagrams).
    for script in state["scripts"]:
        assert script.startswith(site_url) or not re.search(r"https?://", script), f"an outside script: {script[:200]}"
    assert not failed, f"requests that failed (a MathJax font too): {failed}"
    assert_links_resolve(context, site_url, links)


def play_and_stop_every_recording(page, figures, stem: str) -> dict[int, tuple[dict, dict]]:
    """Press each demo's "Play the run" from the keyboard, check the recording replaces the still,
    then press it again and check the still is back.  Returns, per demo with a recording, the
    still's and the recording's size in pixels: drawn (natural) and shown."""
    sizes = {}
    for k in range(figures.count()):
        figure = figures.nth(k)
        button = figure.get_by_role("button", name=PLAY, exact=True)
        if figure.locator("button.kf-play").count() == 0:
            continue
        assert button.count() == 1, f"demo {k}: its button is not named {PLAY!r}"
        still = figure.locator("img.kf-demo-picture").evaluate(
            "i => ({natural: i.naturalWidth, shown: Math.round(i.getBoundingClientRect().width)})"
        )
        button.focus()
        page.keyboard.press("Enter")
        figure.locator("img.kf-demo-animation").wait_for(state="visible")
        page.wait_for_function(
            "f => { const r = f.querySelector('img.kf-demo-animation'); return r.complete && r.naturalWidth > 0; }",
            arg=figure.element_handle(),
        )
        playing = figure.evaluate(JS_FIGURE)
        assert playing["pressed"] == "true", f"demo {k}: the button is not pressed while the run plays"
        assert playing["runShown"] and not playing["stillShown"], f"demo {k}: the recording is not in the still's place"
        assert playing["runSrc"] and playing["runSrc"].startswith("media/") and playing["runLoaded"], playing
        if k == 0:
            figure.screenshot(path=ARTIFACTS / f"site__{stem}__demo{k}__playing.png")
        assert_no_axe_violations(page, [".kf-demo-static"], f"{stem}, demo {k} playing")
        sizes[k] = (still, playing["run"])

        page.keyboard.press("Space")  # the same button, still focused: stop
        stopped = figure.evaluate(JS_FIGURE)
        assert stopped["pressed"] == "false", f"demo {k}: pressed again, the button stays pressed"
        assert stopped["stillShown"] and not stopped["runShown"], f"demo {k}: pressed again, the still is not back"
        assert stopped["runSrc"] is None, f"demo {k}: the recording keeps playing out of sight"
    return sizes


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
