"""What the chapters state holds whatever the rounding (see ``tests/rounding.py``).

Another CPU's numpy rounds the last bit of a sine differently, and a diverging filter
magnifies it.  Here each run behind a chart or a demo is repeated with its noise draws
scaled by 1 ± 1e-12, and every text the picture shows (titles, legends, readouts) must
read the same.  ``make test`` also runs the notebooks and the run-fact tests with
``--perturb=±1e-12``; the first test below shows that such a run catches a notebook that
prints a chaotic digit.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import ipywidgets as widgets
import nbformat
import numpy as np
import pytest
from matplotlib.text import Text

import kfcourse as kf
from tests.facts import planted, run_planted
from tests.rounding import perturbed_default_rng

ROOT = Path(__file__).resolve().parents[1]
SIZES = [1e-12, -1e-12]

IMPORTS = "import numpy as np\nimport kfcourse as kf"
# Chapter 7's comparison as it once was: it printed where the diverged filter ends the lap.
CHAOTIC_CELL = """right = kf.sim.run_ekf(flipped=False, seed=0)
wrong = kf.sim.run_ekf(flipped=True, seed=0)
for name, run in (("right H", right), ("flipped bearing row", wrong)):
    print(f"{name}: final position error {run.final_error:5.2f} m, largest {run.error.max():5.2f} m")"""
# The facts it prints now.
FACT_CELL = """wrong = kf.sim.run_ekf(flipped=True, seed=0)
print(f"more than 1 m off from t = {wrong.t[np.argmax(wrong.error > 1.0)]:.1f} s, largest {wrong.error.max():.1f} m")"""


def printed_here(cell: str) -> str:
    """What the cell prints in a plain python with numpy's own generator: its stored output."""
    env = {k: v for k, v in os.environ.items() if k != "IPYTHONDIR"}
    done = subprocess.run(
        [sys.executable, "-c", f"{IMPORTS}\n{cell}"], capture_output=True, text=True, env=env, timeout=120, check=True
    )
    return done.stdout


def probe(cell: str) -> nbformat.NotebookNode:
    nb = nbformat.v4.new_notebook()
    nb.cells.append(nbformat.v4.new_code_cell(IMPORTS))
    checked = nbformat.v4.new_code_cell(f"# NBVAL_CHECK_OUTPUT\n{cell}", execution_count=2)
    checked.outputs = [nbformat.v4.new_output("stream", name="stdout", text=printed_here(cell))]
    nb.cells.append(checked)
    return nb


def test_a_perturbed_notebook_run_catches_a_chaotic_digit():
    notebooks = {
        f"{name}.ipynb": nbformat.writes(probe(cell))
        for name, cell in (("chaotic", CHAOTIC_CELL), ("facts", FACT_CELL))
    }
    printed = run_planted(notebooks, "--nbval-lax", "--nbval-current-env", "--perturb=1e-12")
    found = re.findall(r"^(PASSED|FAILED) \S*/(\w+)\.ipynb::Cell 1", printed, re.M)
    outcome = {name: verdict for verdict, name in found}
    assert outcome == {"chaotic": "FAILED", "facts": "PASSED"}, printed[-3000:]


PLANTED_FACTS = """
import pytest

import kfcourse as kf


@pytest.mark.fact
def test_chaotic_digits():  # where chapter 7's diverged filter ends the lap, to the digits of this machine
    assert f"{{kf.sim.run_ekf(flipped=True, seed=0).final_error:.6f}}" == "{final}"


@pytest.mark.fact
def test_fact():  # what chapter 7 states of the same run
    wrong = kf.sim.run_ekf(flipped=True, seed=0)
    assert (wrong.error > 1.0).any() and wrong.error.max() > 2.0
"""


def test_a_perturbed_repeat_catches_a_planted_chaotic_fact():
    final = printed_here("print(f'{kf.sim.run_ekf(flipped=True, seed=0).final_error:.6f}', end='')")
    source = PLANTED_FACTS.format(final=final)
    (plain, said), (perturbed, said_perturbed) = (planted(source, "-m", "fact", *p) for p in ([], ["--perturb=1e-12"]))
    assert plain == {"test_chaotic_digits": "PASSED", "test_fact": "PASSED"}, said[-3000:]
    assert perturbed == {"test_chaotic_digits": "FAILED", "test_fact": "PASSED"}, said_perturbed[-3000:]


def texts(fig) -> list[str]:
    """Every text the figure shows."""
    return [t.get_text() for t in fig.findobj(Text) if t.get_visible() and t.get_text()]


# The charts the chapters draw from runs that diverge, lose the truth or are kidnapped.
CHARTS = {
    "07 right and flipped H": lambda: kf.plots.jacobian_runs_chart(
        kf.sim.run_ekf(flipped=False, seed=0), kf.sim.run_ekf(flipped=True, seed=0)
    ),
    "08 wrapped and unwrapped": lambda: kf.plots.wrap_runs_chart(
        kf.sim.landmark_loop(0, wrap_bearing=True), kf.sim.landmark_loop(0, wrap_bearing=False)
    ),
    "09 EKF and UKF, noisy motion": lambda: kf.plots.filter_comparison_chart(
        *(kf.sim.landmark_loop(0, filter=name, motion_noise=50.0) for name in ("ekf", "ukf"))
    ),
    "10 kidnapped": lambda: kf.plots.loop_chart(kf.sim.landmark_loop(seed=0, kidnap=60, gate=4.0), k=90),
}


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("chart", CHARTS)
def test_chart_texts_hold_whatever_the_rounding(chart, size, monkeypatch):
    plain = texts(CHARTS[chart]())
    monkeypatch.setattr(np.random, "default_rng", perturbed_default_rng(size))
    assert texts(CHARTS[chart]()) == plain


def demo_texts(demo) -> list[str]:
    """The texts of the demo's picture and of its HTML readouts."""
    shown, todo = texts(demo.renderer.fig), [demo]
    while todo:
        w = todo.pop()
        if isinstance(w, widgets.HTML):
            shown.append(w.value)
        todo.extend(getattr(w, "children", ()))
    return shown


def default_run(name: str) -> list[str]:
    """What a demo says at its first frame and, with Run, at its last."""
    demo = getattr(kf.demos, name)(seed=0)
    said = demo_texts(demo)
    if "frame" in demo.controls:
        demo.controls["frame"].value = demo.controls["frame"].max
        said += demo_texts(demo)
    return said


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("name", kf.demos.__all__)
def test_demo_texts_hold_whatever_the_rounding(name, size, monkeypatch):
    plain = default_run(name)
    monkeypatch.setattr(np.random, "default_rng", perturbed_default_rng(size))
    assert default_run(name) == plain
