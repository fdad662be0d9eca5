"""Fixtures of the real-browser suite: one JupyterLab server and one Chromium per session.

The server serves a temporary copy of the notebooks with autosave off, so nothing a
test does can reach the course notebooks; their hashes are compared before and after
the session anyway.  ``KFCOURSE_NOTEBOOKS=/some/dir`` runs the suite on another folder
of notebooks (handy while writing a demo: a scratch notebook outside the repo), and
``KFCOURSE_CHROMIUM`` points at another Chromium binary.  Without Chromium the suite is
skipped, or fails when ``CI=true``.

Run with ``pytest -m browser tests/browser`` (add ``-s`` to see per-demo lines as they
happen).  Screenshots and ``latency.json`` land in ``tests/browser/artifacts/``.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import statistics
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from tests.browser.lab import LAB_SETTINGS, running_lab

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


# --------------------------------------------------------------------------- latency report

# demo id -> {"samples_ms": [...], "decoded_ms": [...], ...}; filled by the tests.
LATENCY: dict[str, dict] = {}
# Lines for the end-of-run summary (latency per demo, controls nobody tested, ...).
SUMMARY: list[str] = []


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


class Report:
    """What the tests hand back: where artifacts go, latency samples, summary lines."""

    artifacts = ARTIFACTS
    latency = LATENCY
    summary = SUMMARY


@pytest.fixture(scope="session")
def report():
    """Artifacts folder and collected numbers; latency is written to artifacts/latency.json at the end."""
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    yield Report()
    if not LATENCY:
        return
    report = {"demos": {}}
    everything, decoded_all = [], []
    for demo, rec in LATENCY.items():
        entry = {"key_to_src": latency_stats(rec["samples_ms"]), "sliders": {}}
        if rec["decoded_ms"]:
            entry["key_to_decoded"] = latency_stats(rec["decoded_ms"])
        for key, samples in rec["sliders"].items():
            entry["sliders"][key] = latency_stats(samples)
        report["demos"][demo] = entry
        everything += rec["samples_ms"]
        decoded_all += rec["decoded_ms"]
    report["overall"] = {"key_to_src": latency_stats(everything)}
    if decoded_all:
        report["overall"]["key_to_decoded"] = latency_stats(decoded_all)
    report["note"] = (
        "ms from the keydown event of an ArrowRight on a focused slider handle to the img.kf-figure "
        "src change (key_to_src) and to the new picture decoded (key_to_decoded), measured in the page"
    )
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    (ARTIFACTS / "latency.json").write_text(json.dumps(report, indent=2) + "\n", encoding="utf-8")


def pytest_terminal_summary(terminalreporter):
    if not LATENCY and not SUMMARY:
        return
    terminalreporter.section("kfcourse browser suite")
    for demo, rec in LATENCY.items():
        s = latency_stats(rec["samples_ms"])
        terminalreporter.write_line(
            f"latency {demo}: median {s['median_ms']:.0f} ms, p95 {s['p95_ms']:.0f} ms "
            f"(key press -> new src, n={s['n']}, {len(rec['sliders'])} slider(s))"
        )
    for line in SUMMARY:
        terminalreporter.write_line(line)
    if LATENCY:
        terminalreporter.write_line(f"details: {ARTIFACTS / 'latency.json'}")
