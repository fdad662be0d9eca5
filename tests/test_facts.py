"""The ``fact`` marker's guard finds a test that runs a seeded simulation unmarked (``tests/facts.py``).

Each test here plants a small test file under ``tests/`` and runs pytest on it in a fresh process
(``tests.facts.planted``), as ``make test``'s passes run, and reads the verdicts.
"""

from __future__ import annotations

import os
import subprocess
import sys

from tests.facts import ROOT, planted
from tests.repeats import SIZE, repeats

PLANTED = """
import pytest

import kfcourse as kf


def test_unmarked_run():
    assert kf.sim.simulate_walk(seed=0).truth.size > 0


@pytest.mark.fact
def test_marked_run():
    assert kf.sim.simulate_walk(seed=0).truth.size > 0


@pytest.fixture(scope="module")
def walk():
    return kf.sim.simulate_walk(seed=1)


@pytest.mark.fact
def test_marked_first_user_of_a_seeded_fixture(walk):
    assert walk.truth.size > 0


def test_unmarked_later_user_of_a_seeded_fixture(walk):
    assert walk.truth.size > 0


@pytest.mark.fact
def test_marked_without_a_run():
    assert sum([1, 2]) == 3


def test_unmarked_without_a_run():
    assert sum([1, 2]) == 3


def picture_width():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from kfcourse.plots.style import FigureRenderer

    fig = Figure(figsize=(2, 1), dpi=50)
    FigureCanvasAgg(fig)
    return FigureRenderer(fig).image().width


@pytest.mark.fact
def test_marked_picture_is_drawn():
    assert picture_width() == 100


@pytest.mark.fact
@pytest.mark.pixels
def test_marked_picture_read_by_its_pixels_is_drawn():
    assert picture_width() == 100
"""


def test_the_guard_fails_an_unmarked_test_that_runs_a_seeded_simulation():
    outcome, output = planted(PLANTED)
    assert outcome == {
        "test_unmarked_run": "FAILED",
        "test_marked_run": "PASSED",
        "test_marked_first_user_of_a_seeded_fixture": "PASSED",
        "test_unmarked_later_user_of_a_seeded_fixture": "FAILED",
        "test_marked_without_a_run": "PASSED",
        "test_unmarked_without_a_run": "PASSED",
        "test_marked_picture_is_drawn": "PASSED",
        "test_marked_picture_read_by_its_pixels_is_drawn": "PASSED",
    }, output[-3000:]
    assert "is not marked 'fact'" in output, output[-3000:]


def test_the_repeats_select_only_the_marked_tests_and_draw_only_for_those_reading_pixels():
    outcome, output = planted(PLANTED, "-m", "fact", "--perturb=1e-12")
    assert set(outcome) == {
        "test_marked_run",
        "test_marked_first_user_of_a_seeded_fixture",
        "test_marked_without_a_run",
        "test_marked_picture_is_drawn",
        "test_marked_picture_read_by_its_pixels_is_drawn",
    }
    assert outcome["test_marked_run"] == "PASSED", output[-3000:]
    assert outcome["test_marked_picture_is_drawn"] == "FAILED", output[-3000:]  # a blank picture in a repeat
    assert outcome["test_marked_picture_read_by_its_pixels_is_drawn"] == "PASSED", output[-3000:]


def test_each_repeat_is_a_level_below_this_cpus_perturbed_with_signs_alternating():
    avx512 = {"X86_V2": True, "X86_V3": True, "X86_V4": True, "AVX512_ICL": True, "AVX512_SPR": False}
    assert repeats(avx512) == [  # as AVX2, then as the baseline
        ("X86_V3", "X86_V4 AVX512_ICL", SIZE),
        ("x86-64-v2", "X86_V3 X86_V4 AVX512_ICL", -SIZE),
    ]
    assert repeats({"X86_V2": True, "X86_V3": True, "X86_V4": False}) == [("x86-64-v2", "X86_V3", SIZE)]
    assert repeats({"X86_V2": True, "X86_V3": False}) == [("this-cpu", "", SIZE)]  # nothing lower: perturbed only
    assert repeats({"ASIMD": True}) == [("this-cpu", "", SIZE)]  # another architecture


def test_a_cpu_standing_in_for_a_slower_one_keeps_its_levels_off_in_every_repeat():
    as_avx2 = {"X86_V2": True, "X86_V3": True, "X86_V4": False, "AVX512_ICL": False}  # numpy, AVX-512 turned off
    assert repeats(as_avx2, disabled="X86_V4 AVX512_ICL") == [("x86-64-v2", "X86_V4 AVX512_ICL X86_V3", SIZE)]
    baseline = {"X86_V2": True, "X86_V3": False, "X86_V4": False}
    assert repeats(baseline, disabled=" X86_V3  X86_V4 ") == [("this-cpu", "X86_V3 X86_V4", SIZE)]


def test_the_repeats_read_what_the_environment_turns_off():
    env = {**os.environ, "NPY_DISABLE_CPU_FEATURES": "X86_V4 AVX512_ICL"}
    lines = subprocess.run(
        [sys.executable, "-m", "tests.repeats"], env=env, capture_output=True, text=True, check=True, cwd=ROOT
    ).stdout.splitlines()
    assert lines and all(line.split(";")[1].split()[:2] == ["X86_V4", "AVX512_ICL"] for line in lines)
    assert not any(name == "X86_V3" for name, *_ in (line.split(";") for line in lines))  # no repeat as AVX2 itself


# A stand-in for pytest: says how it was called and with which features off; fails when asked to.
FAKE_PYTEST = (
    "import os, sys; print('ran', os.environ['NPY_DISABLE_CPU_FEATURES'], os.nice(0), *sys.argv[1:]);"
    " sys.exit(3 if 'fail' in sys.argv else 0)"
)


def test_run_makes_each_repeat_in_turn_at_a_lower_priority_and_stops_at_a_failure(tmp_path):
    def run(*args: str) -> subprocess.CompletedProcess:
        command = [sys.executable, "-m", "tests.repeats", "run", str(tmp_path), sys.executable, "-c", FAKE_PYTEST]
        return subprocess.run([*command, *args], capture_output=True, text=True, cwd=ROOT)

    planned = subprocess.run(
        [sys.executable, "-m", "tests.repeats"], capture_output=True, text=True, check=True, cwd=ROOT
    ).stdout.splitlines()
    done = run("-m", "fact")
    ran = [line.split() for line in done.stdout.splitlines() if line.startswith("ran ")]
    assert done.returncode == 0 and len(ran) == len(planned), done.stdout + done.stderr
    for said, line in zip(ran, planned, strict=True):
        name, off, size = line.split(";")
        assert said[1 : 1 + len(off.split())] == off.split()  # as that level
        lower = str(min(os.nice(0) + 10, 19))  # nice 10 from here
        tail = ["-m", "fact", f"--perturb={size}", f"--junitxml={tmp_path}/2-repeat-{name}.xml"]
        assert said[1 + len(off.split()) :] == [lower, *tail]
    failed = run("fail")
    assert failed.returncode == 3 and failed.stdout.count("ran ") == 1  # the first failure ends the repeats
