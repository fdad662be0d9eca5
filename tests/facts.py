"""Which tests state facts of seeded runs: the ``fact`` marker, its guard, and a runner for planted tests.

A test marked ``fact`` states something about a run built on seeded random draws (a count, a
bound, a verdict).  ``make test`` runs every such test, and every notebook, again as
another CPU's rounding (``tests/repeats.py``: numpy's lower SIMD levels) with every normal draw
scaled by ``1 ± 1e-12`` (``tests/rounding.py``): what it states must hold in every repeat.  The
repeats select by the marker (``-m fact``), not by folder.

**The guard.** In a run without ``--perturb``, every test that makes a seeded generator
(``np.random.default_rng``, which every simulation, demo model and particle filter of the
course calls), or uses a fixture that did, must be marked ``fact`` or listed in
:data:`UNMARKED` with the reason it needs no repeat; otherwise the test fails, naming the
marker.  So a new test that states a seeded run's number cannot leave the repeats unseen.
"""

from __future__ import annotations

import functools
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

MARKER = "fact"
ROOT = Path(__file__).resolve().parents[1]

# Tests that make seeded generators but state no fact of a seeded run that rounding could move,
# by node id (a file, or a file and a test): the reason each needs no repeat.
UNMARKED = {
    "tests/test_rounding.py": "it perturbs its runs itself and compares them with the plain run: one pass is the check",
    "tests/filters/": "random inputs to identities and properties checked to a tolerance (any draw must pass), "
    "or statistical checks of the filters' own draws with margins of many standard errors",
    "tests/check/": "the checkers run a student's function and the course's on the same draws and compare them "
    "to a tolerance: a verdict, not a number of a noisy run",
    "tests/test_package.py::test_the_nees_is_computed_in_one_place": "a run's NEES against kf.sim.nees of the same "
    "run: one computation both ways, whatever the rounding",
    "tests/test_recording.py": "the frames of a recording against the demo's own pictures: the same run both ways",
    "tests/test_charts.py": "what each chart draws (titles, axes, artists), not the run's numbers",
    "tests/test_bad_arguments.py": "that a bad argument is refused by name, and that a valid call runs: "
    "no number of a noisy run",
    "tests/demos/test_stale.py": "which artists a control redraws and when the picture is drawn in full, not a number",
    "tests/demos/test_light_and_crisp.py": "the light picture against the crisp one of one state",
    "tests/demos/test_hallway_layout.py": "where the two text blocks stand, not what the run did",
    "tests/plots/test_density.py": "the same picture at more pixels: one run drawn twice",
    "tests/plots/test_loop_animation.py": "the README's animation draws the demo's own frames, not the run's numbers",
    "tests/plots/test_role_styles.py": "the line style of each role in every figure, not the run's numbers",
}

_made = [0]  # seeded generators made in this process
seeded_fixtures: set = set()  # the fixture definitions whose set-up made a seeded generator


def _counting(default_rng):
    """``np.random.default_rng`` that also counts the generators it makes."""

    @functools.wraps(default_rng)
    def counted(*args, **kwargs):
        _made[0] += 1
        return default_rng(*args, **kwargs)

    return counted


def install() -> None:
    """Count every generator made from now on (the guard's eyes)."""
    np.random.default_rng = _counting(np.random.default_rng)


def made() -> int:
    """How many seeded generators were made so far."""
    return _made[0]


def seeded(item) -> bool:
    """Whether the test made a seeded generator (in its set-up or its call) or uses a fixture that did."""
    if made() > getattr(item, "generators_before", made()):
        return True
    definitions = getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {})
    return any(d in seeded_fixtures for name in item.fixturenames for d in definitions.get(name, ()))


def listed(nodeid: str) -> str | None:
    """The reason a test may make seeded generators without the marker, or None."""
    for where, reason in UNMARKED.items():
        if where.endswith(("/", ".py")):  # a folder or a whole file
            hit = nodeid.startswith(where)
        else:  # one test, with all its parameters
            hit = nodeid == where or nodeid.startswith(where + "[")
        if hit:
            return reason
    return None


def complaint(item) -> str | None:
    """What is wrong with the test's marker, or None: a seeded run neither marked nor listed."""
    marked = item.get_closest_marker(MARKER) is not None
    if seeded(item) and not marked and listed(item.nodeid) is None:
        return (
            f"{item.nodeid} runs a seeded simulation (it made a seeded generator or uses a fixture "
            f"that did) but is not marked '{MARKER}': mark it (@pytest.mark.{MARKER}, or pytestmark in its module) "
            "so that make test repeats it under other rounding, or list it in tests/facts.py UNMARKED with the "
            "reason it needs no repeat"
        )
    return None


def run_planted(files: dict[str, str], *options: str) -> str:
    """Run pytest, with ``options``, on ``files`` (name: text) written to a folder under tests/ (so the
    root conftest governs them), in a fresh process; what pytest printed (``-rA``: every verdict)."""
    folder = Path(tempfile.mkdtemp(prefix=".probe-", dir=ROOT / "tests"))
    try:
        for name, text in files.items():
            (folder / name).write_text(text)
        result = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-rA", "-p", "no:cacheprovider", *options, str(folder)],
            cwd=ROOT,
            capture_output=True,
            text=True,
            timeout=300,
        )
    finally:
        shutil.rmtree(folder)
    return result.stdout


def planted(source: str, *options: str) -> tuple[dict[str, str], str]:
    """:func:`run_planted` on ``source`` as one test file: each test's verdict by name, and what pytest printed."""
    printed = run_planted({"test_planted.py": source}, *options)
    found = re.findall(r"^(PASSED|FAILED) \S*::(\w+)", printed, re.M)
    return {name: verdict for verdict, name in found}, printed
