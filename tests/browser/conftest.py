"""Fixtures of the real-browser suite: one JupyterLab server and one Chromium per session.

The server serves a temporary copy of the notebooks with autosave off, so nothing a
test does can reach the course notebooks; their hashes are compared before and after
the session anyway.  ``KFCOURSE_NOTEBOOKS=/some/dir`` runs the suite on another folder
of notebooks (handy while writing a demo: a scratch notebook outside the repo), and
``KFCOURSE_CHROMIUM`` points at another Chromium binary.  Without Chromium the suite is
skipped, or fails when ``CI=true``.

Run with ``pytest -m browser tests/browser`` (add ``-s`` to see per-chapter lines as they
happen).  Screenshots land in ``tests/browser/artifacts/``.  The suite times nothing against
a target: ``benchmarks/bench_browser.py`` (``make bench``) measures how fast the demos answer.

The site test's build (``tools/build_site.py``, several minutes of executing notebooks) starts
with the session, at a lower CPU priority, so that it runs while the chapters are checked in
JupyterLab (which mostly wait on the page) instead of after them.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import statistics
import subprocess
import sys
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from tests.browser.lab import LAB_SETTINGS, LabApp, running_lab

REPO_ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = Path(__file__).resolve().parent / "artifacts"
CHROMIUM = Path(os.environ.get("KFCOURSE_CHROMIUM", "/usr/bin/chromium"))
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


# --------------------------------------------------------------------------- notebooks


def notebooks_dir() -> Path:
    """The folder under test: ``$KFCOURSE_NOTEBOOKS`` or the repo's ``notebooks/``."""
    override = os.environ.get("KFCOURSE_NOTEBOOKS")
    return Path(override).resolve() if override else REPO_ROOT / "notebooks"


SITE_TESTS = "test_site.py"


@pytest.fixture(scope="session")
def next_notebook(request):
    """``next_notebook(name)``: the notebook whose lab test runs after ``name``'s, if any (a fixture,
    not a module global: pytest's copy of this conftest is not the one a test module imports)."""
    order = [
        item.callspec.params["notebook"].name
        for item in request.session.items
        if hasattr(item, "callspec") and "notebook" in item.callspec.params and "lab_app" in item.fixturenames
    ]

    def following(name: str) -> str | None:
        if name in order and order.index(name) + 1 < len(order):
            return order[order.index(name) + 1]
        return None

    return following


def pytest_generate_tests(metafunc):
    if "notebook" in metafunc.fixturenames:
        paths = sorted(notebooks_dir().glob("*.ipynb"))
        metafunc.parametrize("notebook", paths, ids=[p.stem for p in paths])


def _hashes(folders) -> dict[str, str]:
    out = {}
    for folder in folders:
        for path in sorted(folder.glob("*.ipynb")):
            out[str(path)] = hashlib.sha256(path.read_bytes()).hexdigest()
    return out


# --------------------------------------------------------------------------- chromium


def _cannot_run(reason: str):
    """Skip the browser suite, but fail on CI, where a skip would hide that nothing ran."""
    if os.environ.get("CI") == "true":
        pytest.fail(reason, pytrace=False)
    pytest.skip(reason)


@pytest.fixture(scope="session")
def chromium_executable() -> Path:
    if not CHROMIUM.exists():
        _cannot_run(f"{CHROMIUM} is missing (apt-get install chromium); the browser suite cannot run")
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        _cannot_run("playwright is not installed (requirements-dev.txt); the browser suite cannot run")
    return CHROMIUM


@pytest.fixture(scope="session")
def browser(chromium_executable):
    from playwright.sync_api import sync_playwright

    pw = sync_playwright().start()
    try:
        browser = pw.chromium.launch(executable_path=str(chromium_executable), args=CHROMIUM_FLAGS)
        try:
            yield browser
        finally:
            browser.close()
    finally:
        pw.stop()


# --------------------------------------------------------------------------- server


def _check_settings_applied(url: str) -> None:
    """The server reads our settings (above all: autosave off), not a user's own."""
    for plugin, values in LAB_SETTINGS.items():
        package, name = plugin.rsplit("/", 1)
        with urllib.request.urlopen(f"{url}lab/api/settings/{package}:{name}", timeout=10) as response:
            applied = json.load(response)["settings"]
        assert applied == values, f"JupyterLab did not take the test settings for {plugin}: {applied}"


@pytest.fixture(scope="session")
def lab_server(tmp_path_factory, chromium_executable):
    source = notebooks_dir()
    watched = {source}
    before = _hashes(watched)

    base = tmp_path_factory.mktemp("lab")
    root = base / "notebooks"
    if source.is_dir():
        shutil.copytree(source, root, ignore=shutil.ignore_patterns(".ipynb_checkpoints", "__pycache__"))
    else:
        root.mkdir()
    try:
        with running_lab(base, root) as server:
            _check_settings_applied(server.url)
            yield server
    except RuntimeError as exc:
        pytest.fail(str(exc), pytrace=False)
    after = _hashes(watched)
    changed = sorted(p for p in before.keys() | after.keys() if before.get(p) != after.get(p))
    if changed:
        pytest.fail(
            "notebooks on disk changed during the browser session (the server only saw a temporary copy "
            "with autosave off, so either that leaked or someone else edited them meanwhile): " + ", ".join(changed),
            pytrace=False,
        )


# --------------------------------------------------------------------------- one page for every chapter


@pytest.fixture(scope="session")
def lab_app(browser, lab_server):
    """One JupyterLab page (:class:`tests.browser.lab.LabApp`) that every chapter opens in."""
    app = LabApp(browser, lab_server.url)
    try:
        yield app
    finally:
        app.shut()


# --------------------------------------------------------------------------- the site, built early


class SiteBuild:
    """``tools/build_site.py --out <out>`` started now, at a lower CPU priority; :meth:`wait` for it."""

    def __init__(self, out: Path, notebooks: Path, log: Path):
        self.out = out
        self.log = log
        command = [sys.executable, str(REPO_ROOT / "tools" / "build_site.py"), "--out", str(out)]
        command += ["--notebooks", str(notebooks)]
        with open(log, "wb") as log_file:
            self.proc = subprocess.Popen(
                command,
                cwd=REPO_ROOT,
                stdout=log_file,
                stderr=subprocess.STDOUT,
                preexec_fn=lambda: os.nice(10),
            )

    def wait(self, timeout_s: float) -> Path:
        try:
            code = self.proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            self.stop()
            pytest.fail(f"the site build took more than {timeout_s:.0f} s", pytrace=False)
        if code != 0:
            tail = self.log.read_text(errors="replace")[-6000:]
            pytest.fail(f"the site build failed ({code}):\n{tail}", pytrace=False)
        return self.out

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


@pytest.fixture(scope="session", autouse=True)
def site_build(request, tmp_path_factory):
    """The site build, started with the session when a site test is selected (else None)."""
    if not any(item.path.name == SITE_TESTS for item in request.session.items):
        yield None
        return
    base = tmp_path_factory.mktemp("site")
    build = SiteBuild(base / "out", notebooks_dir(), base / "build.log")
    try:
        yield build
    finally:
        build.stop()


# --------------------------------------------------------------------------- figures for the benchmarks


def _percentile(values, q: float) -> float:
    xs = sorted(values)
    if len(xs) == 1:
        return xs[0]
    pos = (len(xs) - 1) * q
    lo = int(pos)
    hi = min(lo + 1, len(xs) - 1)
    return xs[lo] + (xs[hi] - xs[lo]) * (pos - lo)


def latency_stats(samples) -> dict:
    return {
        "n": len(samples),
        "median_ms": round(statistics.median(samples), 1),
        "p95_ms": round(_percentile(samples, 0.95), 1),
        "min_ms": round(min(samples), 1),
        "max_ms": round(max(samples), 1),
    }


# --------------------------------------------------------------------------- the report

# Lines for the end-of-run summary (pictures per demo, controls nobody tested, ...).
SUMMARY: list[str] = []


class Report:
    """What the tests hand back: where artifacts go, and summary lines."""

    artifacts = ARTIFACTS
    summary = SUMMARY


@pytest.fixture(scope="session")
def report():
    """The artifacts folder (made) and the summary lines."""
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    return Report()


def pytest_terminal_summary(terminalreporter):
    if not SUMMARY:
        return
    terminalreporter.section("kfcourse browser suite")
    for line in SUMMARY:
        terminalreporter.write_line(line)
