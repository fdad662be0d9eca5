"""How fast every demo answers in the browser: JupyterLab in headless Chromium, on localhost.

Run by hand from the repository's root (``make bench`` runs it; it needs Chromium)::

    .venv/bin/python -m benchmarks.bench_browser [chapter ...]

The figures the browser suite used to assert, measured here instead (the suite only checks
that every control answers at all): JupyterLab serves a temporary copy of ``notebooks/``
(autosave off, as in the suite), and each chapter is opened in one 1280x800 Chromium page
beside the file browser and run (Run All), alone: nothing else runs in the page meanwhile.
Every ``.kf-demo``, labelled ``NN/<name>``, is driven as the suite drives it
(:func:`tests.browser.demo_driver.drive_every_control`), with more presses: End and Home,
then ``LATENCY_PRESSES`` ArrowRight presses per slider, each from rest (the crisp picture
shown, the kernel idle), every button, every option of every choice, then Run and Pause.

Per demo:

- **ms**: from the keydown or click (the page's event time) to the picture's new ``src``:
  the median and the p95 over every timed action of the demo, and the worst control's p95
  (its key in brackets).  Target: ``P95_TARGET_MS`` at p95 for every control;
- **light KB**: the median weight of the pictures sent while something moves (the half-size
  WebP), and **crisp KB**, of the picture at rest.  Target: ``LIGHT_TARGET_KB``;
- **Run pics/s**: pictures per second while Run plays (a figure; Run asks for 12.5).

A figure that misses its target is marked ``!``.  Arguments like ``03 10`` measure those
chapters only.  The whole course takes about seven minutes on a 2-core machine.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

if __package__ in (None, ""):  # run as a script: the repository's root on the path, as with -m
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from playwright.sync_api import Error as PlaywrightError
from playwright.sync_api import sync_playwright

from tests.browser.conftest import CHROMIUM, CHROMIUM_FLAGS, latency_stats
from tests.browser.demo_driver import (
    CRISP,
    JS_IMG_READY,
    LATENCY_PRESSES,
    DemoDriver,
    demo_labels,
    drive_every_control,
)
from tests.browser.lab import WIDGET_VIEW, LabApp, lab_over_copy, read_cells, wait_for_widgets
from tools.course import chapters

ROOT = Path(__file__).resolve().parents[1]
P95_TARGET_MS = 150.0  # key press or click to the new picture, p95, for every control
LIGHT_TARGET_KB = 60.0  # median weight of a picture sent while something moves (KB = 1000 bytes)
ANSWER_MS = 10_000  # an action that brings nothing in this long is noted, not timed


@dataclass
class DemoFigures:
    """What one demo gave, and what went wrong while measuring it."""

    label: str
    by_control: dict[str, list[float]] = field(default_factory=dict)  # key -> ms, key press or click to picture
    light: list[int] = field(default_factory=list)  # bytes
    crisp: list[int] = field(default_factory=list)
    run_rate: float | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def samples(self) -> list[float]:
        return [ms for values in self.by_control.values() for ms in values]


class Summary:
    """Where the driver writes its notes (the suite's report has the same attribute)."""

    def __init__(self):
        self.summary: list[str] = []


def measure_demo(page, demo, label: str) -> DemoFigures:
    figures = DemoFigures(label)
    demo.scroll_into_view_if_needed()
    img = demo.locator("img.kf-figure").first
    if img.count() == 0:
        figures.notes.append("no img.kf-figure")
        return figures
    page.wait_for_function(JS_IMG_READY, arg=img.element_handle(), timeout=30_000)
    summary = Summary()
    driver = DemoDriver(
        page, demo, label, figures.notes, summary, answer_ms=ANSWER_MS, arrow_presses=LATENCY_PRESSES, rest_each=True
    )
    try:
        driver.settle(quiet_ms=200)
        _, runs = drive_every_control(demo, driver)
    except PlaywrightError as error:  # the page changed under the benchmark: report what was measured
        figures.notes.append(f"stopped: {str(error).splitlines()[0]}")
        runs = []
    for key, samples in driver.latency.items():
        figures.by_control.setdefault(key, []).extend(ms for ms, _ in samples)
    for key, samples in driver.clicks.items():
        figures.by_control.setdefault(key, []).extend(samples)
    for p in driver.pictures():
        if p["bytes"] and p["bytes"] > 0:
            (figures.crisp if p["type"] == CRISP else figures.light).append(p["bytes"])
    for run in runs:
        running = [c["t"] for c in run["shown"] if run["t_pause"] is None or c["t"] < run["t_pause"]]
        if len(running) >= 2:
            figures.run_rate = 1000 * (len(running) - 1) / (running[-1] - running[0])
    figures.notes = [n.removeprefix(f"{label}: ") for n in figures.notes]
    return figures


def measure_chapter(app: LabApp, notebook: Path) -> list[DemoFigures]:
    """Open the chapter, Run All, and measure every demo on the page."""
    chapter = notebook.name[:2]
    try:
        panel_id = app.open(notebook.name, {})
        if panel_id is None:
            return [DemoFigures(f"{chapter}/*", notes=["Run All did not finish"])]
        page = app.page
        expected = sum(WIDGET_VIEW in out["mimes"] for cell in read_cells(page) for out in cell["outputs"])
        if not wait_for_widgets(page, panel_id, expected):
            return [DemoFigures(f"{chapter}/*", notes=["the widgets did not render"])]
        panel = page.locator(f"[id='{panel_id}']")
        demos = panel.locator(".kf-demo")
        return [measure_demo(page, demos.nth(i), label) for i, label in enumerate(demo_labels(panel, chapter))]
    except (PlaywrightError, AssertionError) as error:
        return [DemoFigures(f"{chapter}/*", notes=[f"stopped: {str(error).splitlines()[0]}"])]
    finally:
        app.close(notebook.name)


# --------------------------------------------------------------------------- the report

HEADER = ("demo", "actions", "median ms", "p95 ms", "worst control p95", "light KB", "crisp KB", "Run pics/s")
WIDTHS = (26, 8, 11, 9, 26, 11, 10, 12)


def _mark(text: str, missed: bool) -> str:
    return text + (" !" if missed else "  ")


def table_row(row: DemoFigures) -> tuple[list[str], int]:
    """The cells of one demo's row, and how many of its figures miss their target."""
    cells = [row.label, f"{len(row.samples)}  ", "-  ", "-  ", "-  ", "-  ", "-  ", "-  "]
    misses = 0
    if row.samples:
        stats = latency_stats(row.samples)
        cells[2] = _mark(f"{stats['median_ms']:.0f}", False)
        cells[3] = _mark(f"{stats['p95_ms']:.0f}", stats["p95_ms"] > P95_TARGET_MS)
        worst_key, worst = max(
            ((key, latency_stats(ms)["p95_ms"]) for key, ms in row.by_control.items() if ms), key=lambda kv: kv[1]
        )
        missed = sum(latency_stats(ms)["p95_ms"] > P95_TARGET_MS for ms in row.by_control.values() if ms)
        cells[4] = _mark(f"{worst:.0f} ({worst_key})", missed > 0)
        misses += missed
    if row.light:
        kb = statistics.median(row.light) / 1000
        cells[5] = _mark(f"{kb:.1f}", kb > LIGHT_TARGET_KB)
        misses += kb > LIGHT_TARGET_KB
    if row.crisp:
        cells[6] = _mark(f"{statistics.median(row.crisp) / 1000:.1f}", False)
    if row.run_rate is not None:
        cells[7] = _mark(f"{row.run_rate:.1f}", False)
    return cells, misses


def print_table(rows: list[DemoFigures]) -> int:
    """One row per demo; returns how many figures miss their target (a control's p95, a demo's light KB)."""

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
    parser.add_argument("chapters", nargs="*", help="chapter numbers to measure, e.g. 03 10 (default: every chapter)")
    args = parser.parse_args(argv)
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
    with lab_over_copy(ROOT / "notebooks", prefix="kfcourse-bench-") as server, sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_FLAGS)
        try:
            app = LabApp(browser, server.url)
            try:
                for notebook in notebooks:
                    start = time.monotonic()
                    found = measure_chapter(app, notebook)
                    print(
                        f"  {notebook.name}: {len(found)} demo(s) in {time.monotonic() - start:.0f} s", file=sys.stderr
                    )
                    rows += found
            finally:
                app.shut()
        finally:
            browser.close()
    print("\nkey press or click -> new picture in the page (ms); pictures sent while moving and at rest (KB)")
    misses = print_table(rows)
    print(
        f"\ntargets: every control <= {P95_TARGET_MS:.0f} ms at p95, light pictures <= {LIGHT_TARGET_KB:.0f} KB "
        "(median): " + (f"{misses} miss (!)" if misses else "met")
    )
    print(f"{len(rows)} demos in {time.monotonic() - t0:.0f} s")
    for row in rows:
        for note in dict.fromkeys(row.notes):
            print(f"note {row.label}: {note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
