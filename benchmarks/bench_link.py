"""How every demo feels over a student's link: JupyterLab in headless Chromium behind a slow relay.

Run by hand from the repository's root (not part of the test suite; it needs Chromium)::

    .venv/bin/python -m benchmarks.bench_link [--mbit 10] [--rtt-ms 60] [--no-relay] [chapter ...]

JupyterLab serves a temporary copy of ``notebooks/`` on 127.0.0.1 (autosave off, as in the
browser suite), and Chromium (a 1280x800 window, the file browser open) reaches it only
through :class:`benchmarks.shaping_relay.ShapingRelay`: 10 Mbit/s each way and a 60 ms round
trip by default, for the page's HTTP requests and the kernel's WebSocket alike.  Before the
chapters, a 1 MB download and a few small requests through the relay print the link's
measured rate and round trip.  ``--no-relay`` points Chromium at the server itself: the same
figures on localhost, for comparison.  Arguments like ``03 10`` measure those chapters only.

Each chapter is opened and run (Run All); then every ``.kf-demo`` on the page, labelled
``NN/<name>`` (``-2`` when a name repeats), gives:

- **key to picture**: a slider handle (``.noUi-handle``) is focused and pressed
  (ArrowRight, then ArrowLeft, and so on: the value stays near the demo's default), and the
  time from the keydown to the picture's new ``src`` is taken, p50 and p95 over
  ``PRESSES`` presses per slider.  Between presses the page comes to rest (the crisp picture
  has arrived and the kernel is idle), as when a student looks at the result;
- **Run**: for a demo with Run/Pause, pictures per second while it plays from the first
  frame for ``RUN_MS`` (the pictures that arrived before Pause, over the time from the first
  to the last of them);
- **bytes per picture**: every new ``src`` (a blob URL) is fetched the moment it appears,
  for its size and MIME type.  "moving" is every picture but the last of a key press or a
  run (the demos send a half-size WebP then), "rest" the last, which stays on screen (the
  crisp JPEG, 0.3 s after the last change).  Medians, KB = 1000 bytes.

Targets: key to picture p50 <= 200 ms, Run >= 12 pictures/s, <= 60 KB a picture while
moving; a figure that misses its target is marked ``!``.  The whole course takes about six
minutes over the default link on a 2-core machine.
"""

from __future__ import annotations

import argparse
import contextlib
import http.client
import os
import statistics
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

from playwright.sync_api import Error as PlaywrightError
from playwright.sync_api import sync_playwright

from benchmarks.shaping_relay import ShapingRelay
from tests.browser.conftest import CHROMIUM, CHROMIUM_FLAGS, latency_stats
from tests.browser.demo_driver import JS_IMG_READY, JS_SLIDER_STATE, JS_WATCH_IMG
from tests.browser.lab import (
    WIDGET_VIEW,
    PlaywrightTimeoutError,
    close_context,
    lab_over_copy,
    open_notebook,
    read_cells,
    run_all,
    shutdown_kernels,
    wait_for_widgets,
)
from tools.course import chapters

ROOT = Path(__file__).resolve().parents[1]
WINDOW = {"width": 1280, "height": 800}  # a laptop's browser window
PRESSES = 10  # key presses per slider
RUN_MS = 3_000  # how long Run plays
CHANGE_TIMEOUT_MS = 10_000  # a key press or a click -> the first new picture
REST_QUIET_MS = 150  # at rest: the crisp picture shown, no new one for this long, the kernel idle
REST_FALLBACK_MS = 1_500  # ... or, for a demo that sends no crisp picture, no new one for this long
REST_TIMEOUT_MS = 20_000
CHECK_BYTES = 1_000_000  # the self-check's download

P50_TARGET_MS = 200.0
RUN_TARGET = 12.0  # pictures per second
MOVING_TARGET_KB = 60.0
CRISP = "image/jpeg"

# --------------------------------------------------------------------------- page-side helpers

# Resolves once the page is at rest after change number n: the crisp picture is shown (or no
# picture came for a long while), nothing new for a moment, every blob read, the kernel idle.
JS_AT_REST = """async (img, [n, crisp, quiet, fallback, max]) => {
    const kernel = () => {
        const s = window.jupyterapp.shell.currentWidget.sessionContext;
        return s && s.session && s.session.kernel ? s.session.kernel.status : 'none';
    };
    const changes = img.__kf.changes;
    const start = performance.now();
    let count = changes.length, since = performance.now();
    while (performance.now() - start < max) {
        await new Promise(r => setTimeout(r, 20));
        if (changes.length !== count || kernel() !== 'idle' || changes.some(c => c.bytes === null)) {
            count = changes.length; since = performance.now();
            continue;
        }
        const last = changes.length > n ? changes[changes.length - 1] : null;
        const wait = last && last.type === crisp && last.holds === crisp ? quiet : fallback;
        if (performance.now() - since >= wait) return true;
    }
    return false;
}"""


# --------------------------------------------------------------------------- what one demo gives


@dataclass
class DemoFigures:
    """The figures of one demo, and what went wrong while taking them."""

    label: str
    latency_ms: list[float] = field(default_factory=list)
    run_rate: float | None = None  # pictures per second, for a demo with Run
    moving: list[dict] = field(default_factory=list)  # pictures before the page came to rest
    rest: list[dict] = field(default_factory=list)  # the picture the page came to rest on
    notes: list[str] = field(default_factory=list)

    def add_sequence(self, entries: list[dict]) -> None:
        """The pictures of one key press or run: all but the last were shown while moving."""
        readable = [e for e in entries if e["bytes"] is not None and e["bytes"] >= 0]
        if len(readable) < len(entries):
            self.notes.append(f"{len(entries) - len(readable)} picture(s) whose blob could not be read")
        for e in readable:
            if e["holds"] != e["type"]:
                self.notes.append(f"a picture sent as {e['type']} holds {e['holds']} bytes")
        if entries:
            self.moving += [e for e in readable if e is not entries[-1]]
            self.rest += [e for e in readable if e is entries[-1]]


class Picture:
    """The demo's ``img.kf-figure``, watched: its src changes and the blobs behind them."""

    def __init__(self, page, demo):
        self.page = page
        self.img = demo.locator("img.kf-figure").first.element_handle()
        self.page.wait_for_function(JS_IMG_READY, arg=self.img, timeout=CHANGE_TIMEOUT_MS * 3)
        self.img.evaluate(JS_WATCH_IMG)

    def count(self) -> int:
        return self.img.evaluate("i => i.__kf.changes.length")

    def since(self, n: int) -> list[dict]:
        return self.img.evaluate("(i, n) => i.__kf.changes.slice(n)", n)

    def wait_change(self, n: int) -> bool:
        try:
            self.page.wait_for_function(
                "([i, n]) => i.__kf.changes.length > n", arg=[self.img, n], timeout=CHANGE_TIMEOUT_MS, polling=20
            )
            return True
        except PlaywrightTimeoutError:
            return False

    def wait_rest(self, n: int) -> bool:
        return self.img.evaluate(JS_AT_REST, [n, CRISP, REST_QUIET_MS, REST_FALLBACK_MS, REST_TIMEOUT_MS])


def slider_state(slider) -> dict | None:
    return slider.evaluate(JS_SLIDER_STATE)


def control_key(el) -> str:
    key = el.evaluate("e => (Array.from(e.classList).find(c => c.startsWith('kf-control-')) || '').slice(11)")
    return key or "?"


def press(picture: Picture, handle, key: str) -> list[dict] | None:
    """Press ``key`` on a slider handle and wait for rest; the pictures it brought, or None if none came."""
    n = picture.count()
    handle.focus()
    picture.page.keyboard.press(key)
    if not picture.wait_change(n):
        return None
    picture.wait_rest(n)
    return picture.since(n)


def measure_slider(picture: Picture, slider, figures: DemoFigures) -> None:
    """``PRESSES`` presses, right and left in turn (away from an end), each timed key to picture."""
    name = control_key(slider)
    state = slider_state(slider)
    if state is None or state["min"] == state["max"]:
        figures.notes.append(f"slider {name!r} cannot move")
        return
    handle = slider.locator(".noUi-handle").first
    handle.scroll_into_view_if_needed()
    direction = "ArrowLeft" if state["atMax"] else "ArrowRight"
    for _ in range(PRESSES):
        state = slider_state(slider)
        if state["atMax"] or state["atMin"]:
            direction = "ArrowLeft" if state["atMax"] else "ArrowRight"
        entries = press(picture, handle, direction)
        if entries is None:
            figures.notes.append(f"slider {name!r}: {direction} brought no new picture")
            return
        first = entries[0]
        if first["key"] is not None:
            figures.latency_ms.append(first["t"] - first["key"])
        figures.add_sequence(entries)
        direction = "ArrowLeft" if direction == "ArrowRight" else "ArrowRight"


def measure_run(picture: Picture, demo, figures: DemoFigures) -> None:
    """Run from the first frame for ``RUN_MS``, then Pause; pictures per second while it ran."""
    frame = demo.locator(".widget-slider.kf-control-frame")
    if frame.count():
        state = slider_state(frame.first)
        if state is not None and not state["atMin"]:
            entries = press(picture, frame.first.locator(".noUi-handle").first, "Home")
            if entries is None:
                figures.notes.append("frame slider: Home brought no new picture")
    play = demo.locator(".kf-control-play").first
    play.scroll_into_view_if_needed()
    n = picture.count()
    play.click()  # Run
    picture.page.wait_for_timeout(RUN_MS)
    play.click()  # the same button now reads Pause
    paused_at = picture.page.evaluate("() => window.__kfClickT")
    picture.wait_rest(n)
    entries = picture.since(n)
    running = [e for e in entries if e["t"] < paused_at]
    if len(running) >= 2:
        figures.run_rate = 1000 * (len(running) - 1) / (running[-1]["t"] - running[0]["t"])
    else:
        figures.run_rate = 0.0
        figures.notes.append(f"Run: {len(running)} picture(s) in {RUN_MS} ms")
    figures.add_sequence(entries)


def measure_demo(page, demo, label: str) -> DemoFigures:
    """Every slider of the demo, then Run; what could not be measured goes to the notes."""
    figures = DemoFigures(label)
    demo.scroll_into_view_if_needed()
    try:
        picture = Picture(page, demo)
    except PlaywrightTimeoutError:
        figures.notes.append("the picture never loaded")
        return figures
    try:
        picture.wait_rest(0)
        sliders = demo.locator(".widget-slider")
        for i in range(sliders.count()):
            measure_slider(picture, sliders.nth(i), figures)
        if demo.locator(".kf-control-play").count():
            measure_run(picture, demo, figures)
    except PlaywrightError as error:  # the page changed under the benchmark: report what was measured
        figures.notes.append(f"stopped: {str(error).splitlines()[0]}")
    return figures


def demo_labels(panel, chapter: str) -> list[str]:
    """``NN/<name>`` of every ``.kf-demo`` of the page, in order (``-2``, ... when a name repeats)."""
    names = panel.locator(".kf-demo").evaluate_all(
        "els => els.map(e => (Array.from(e.classList).find(c => c.startsWith('kf-demo-')) || '').slice(8) || '?')"
    )
    seen: dict[str, int] = {}
    labels = []
    for name in names:
        seen[name] = seen.get(name, 0) + 1
        labels.append(f"{chapter}/{name}" + ("" if seen[name] == 1 else f"-{seen[name]}"))
    return labels


def measure_chapter(context, url: str, notebook: Path) -> list[DemoFigures]:
    """Open the chapter, Run All, and measure every demo on the page."""
    chapter = notebook.name[:2]
    shutdown_kernels(context, url)
    page = context.new_page()
    try:
        panel_id = open_notebook(page, url, notebook.name, {})
        page.evaluate("() => window.jupyterapp.shell.expandLeft()")  # the file browser, as a student has it
        if not run_all(page, panel_id):
            return [DemoFigures(f"{chapter}/*", notes=["Run All did not finish"])]
        expected = sum(WIDGET_VIEW in out["mimes"] for cell in read_cells(page) for out in cell["outputs"])
        if not wait_for_widgets(page, panel_id, expected):
            return [DemoFigures(f"{chapter}/*", notes=["the widgets did not render"])]
        panel = page.locator(f"[id='{panel_id}']")
        demos = panel.locator(".kf-demo")
        return [measure_demo(page, demos.nth(i), label) for i, label in enumerate(demo_labels(panel, chapter))]
    except PlaywrightError as error:
        return [DemoFigures(f"{chapter}/*", notes=[f"stopped: {str(error).splitlines()[0]}"])]
    finally:
        page.close()
        shutdown_kernels(context, url)


# --------------------------------------------------------------------------- server, link


@contextlib.contextmanager
def lab_server(source: Path) -> Iterator[tuple[str, Path]]:
    """JupyterLab over a temporary copy of ``source``, as the browser suite starts it
    (:func:`tests.browser.lab.lab_over_copy`: autosave off, no token); yields its address and root."""
    with lab_over_copy(source, prefix="kfcourse-link-") as server:
        yield server.url, server.root


def check_link(url: str, root: Path) -> tuple[float, float]:
    """The link as the browser gets it: (rate in Mbit/s, round trip in ms), from a download of
    ``CHECK_BYTES`` and the median of 5 small requests, over one kept-alive connection."""
    (root / "link-check.bin").write_bytes(os.urandom(CHECK_BYTES))
    address = urlsplit(url)
    connection = http.client.HTTPConnection(address.hostname, address.port, timeout=60)

    def get(path: str) -> tuple[float, bytes]:
        t0 = time.perf_counter()
        connection.request("GET", path, headers={"Referer": url + "lab"})  # /files/ wants a same-site referer
        response = connection.getresponse()
        body = response.read()
        if response.status != 200:
            raise SystemExit(f"the link check got {response.status} for {path}")
        return time.perf_counter() - t0, body

    try:
        get("/api/status")  # opens the connection
        rtt = statistics.median(get("/api/status")[0] for _ in range(5))
        seconds, body = get("/files/link-check.bin")
    finally:
        connection.close()
        (root / "link-check.bin").unlink()
    return 8 * len(body) / 1e6 / max(seconds - rtt, 1e-9), 1000 * rtt


# --------------------------------------------------------------------------- the report

HEADER = ("demo", "p50 ms", "p95 ms", "presses", "Run pics/s", "moving KB", "rest KB")
WIDTHS = (26, 8, 8, 8, 11, 16, 16)


def _cell(text: str, missed: bool = False) -> str:
    """A figure, marked ``!`` when it misses its target."""
    return text + (" !" if missed else "  ")


def _kb(entries: list[dict]) -> tuple[str, float | None]:
    """Median size in KB and the MIME types of some pictures: ("18.0 webp", 18.0)."""
    if not entries:
        return "-", None
    kb = statistics.median(e["bytes"] for e in entries) / 1000
    kinds = "/".join(sorted({e["type"].removeprefix("image/") for e in entries}))
    return f"{kb:.1f} {kinds}", kb


def table_row(row: DemoFigures) -> tuple[list[str], int]:
    """The cells of one demo's row, and how many of its figures miss their target."""
    cells = [row.label, "-  ", "-  ", f"{len(row.latency_ms)}  ", "-  "]
    misses = 0
    if row.latency_ms:
        stats = latency_stats(row.latency_ms)
        missed = stats["median_ms"] > P50_TARGET_MS
        cells[1:3] = [_cell(f"{stats['median_ms']:.0f}", missed), _cell(f"{stats['p95_ms']:.0f}")]
        misses += missed
    if row.run_rate is not None:
        missed = row.run_rate < RUN_TARGET
        cells[4] = _cell(f"{row.run_rate:.1f}", missed)
        misses += missed
    moving, kb = _kb(row.moving)
    missed = kb is not None and kb > MOVING_TARGET_KB
    cells.append(_cell(moving, missed))
    misses += missed
    cells.append(_cell(_kb(row.rest)[0]))
    return cells, misses


def print_table(rows: list[DemoFigures]) -> int:
    """One row per demo; returns how many figures miss their target."""

    def line(cells) -> str:
        return cells[0].ljust(WIDTHS[0]) + "".join(c.rjust(w) for c, w in zip(cells[1:], WIDTHS[1:], strict=True))

    print(line([*HEADER[:1], *(h + "  " for h in HEADER[1:])]))
    misses = 0
    for row in rows:
        cells, missed = table_row(row)
        print(line(cells))
        misses += missed
    return misses


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mbit", type=float, default=10.0, help="link rate each way, Mbit/s (default 10)")
    parser.add_argument("--rtt-ms", type=float, default=60.0, help="link round trip, ms (default 60)")
    parser.add_argument("--no-relay", action="store_true", help="Chromium straight to the server: localhost figures")
    parser.add_argument("chapters", nargs="*", help="chapter numbers to measure, e.g. 03 10 (default: every chapter)")
    args = parser.parse_args(argv)
    if not args.mbit > 0:
        parser.error(f"--mbit must be positive, got {args.mbit}")
    if not args.rtt_ms >= 0:
        parser.error(f"--rtt-ms must be >= 0, got {args.rtt_ms}")
    notebooks = chapters(ROOT / "notebooks")
    if args.chapters:
        wanted = {int(c) for c in args.chapters if c.isdigit()}
        notebooks = [p for p in notebooks if int(p.name[:2]) in wanted]
    if not notebooks:
        parser.error(f"no chapter notebook matches {' '.join(args.chapters)}")
    if not CHROMIUM.exists():
        raise SystemExit(f"{CHROMIUM} is missing (apt-get install chromium)")
    t0 = time.monotonic()
    rows: list[DemoFigures] = []
    with lab_server(ROOT / "notebooks") as (server_url, root), contextlib.ExitStack() as stack:
        if args.no_relay:
            url, link, relay = server_url, "localhost (no relay)", None
        else:
            relay = stack.enter_context(ShapingRelay(urlsplit(server_url).port, args.mbit, args.rtt_ms))
            url = f"http://127.0.0.1:{relay.port}/"
            link = f"{args.mbit:g} Mbit/s each way, {args.rtt_ms:g} ms round trip"
        rate, rtt = check_link(url, root)
        print(f"link: {link}; measured {rate:.1f} Mbit/s down ({CHECK_BYTES / 1e6:g} MB), round trip {rtt:.0f} ms")
        pw = stack.enter_context(sync_playwright())
        browser = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_FLAGS)
        stack.callback(browser.close)
        context = browser.new_context(viewport=WINDOW)
        stack.callback(close_context, context, url)
        for notebook in notebooks:
            start = time.monotonic()
            found = measure_chapter(context, url, notebook)
            print(f"  {notebook.name}: {len(found)} demo(s) in {time.monotonic() - start:.0f} s", file=sys.stderr)
            rows += found
        carried = ""
        if relay is not None:
            carried = f"; over the link {relay.down.bytes / 1e6:.0f} MB down, {relay.up.bytes / 1e6:.1f} MB up"
    print()
    misses = print_table(rows)
    print(
        f"\ntargets: key to picture p50 <= {P50_TARGET_MS:.0f} ms, Run >= {RUN_TARGET:.0f} pictures/s, "
        f"<= {MOVING_TARGET_KB:.0f} KB a picture while moving: " + (f"{misses} figure(s) miss (!)" if misses else "met")
    )
    print(f"{len(rows)} demos in {time.monotonic() - t0:.0f} s{carried}")
    for row in rows:
        for note in dict.fromkeys(row.notes):
            print(f"note {row.label}: {note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
