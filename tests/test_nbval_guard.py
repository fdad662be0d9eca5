"""The notebook checks can fail: a warning in any cell, or a changed worked number."""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

from tests.facts import run_planted

ROOT = Path(__file__).resolve().parents[1]

# Each case is a notebook of ``(source, stored_output)`` cells and whether nbval passes it.
CASES = {
    "clean": ([("print(1 + 1)", None)], True),
    "warning": ([("import warnings\nwarnings.warn('careful')", None)], False),
    "number-kept": ([("# NBVAL_CHECK_OUTPUT\nprint(f'{6 / 7:.3f}')", "0.857\n")], True),
    "number-changed": ([("# NBVAL_CHECK_OUTPUT\nprint(f'{6 / 7:.3f}')", "0.858\n")], False),
}


def notebook(cells) -> nbformat.NotebookNode:
    nb = nbformat.v4.new_notebook()
    for count, (source, stored) in enumerate(cells, start=1):
        cell = nbformat.v4.new_code_cell(source)
        if stored is not None:
            cell.execution_count = count
            cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text=stored)]
        nb.cells.append(cell)
    return nb


@pytest.fixture(scope="module")
def nbval_run() -> tuple[dict[str, list[str]], str]:
    """Run nbval once, as `make test` does, on one notebook per case: each case's cell outcomes,
    and what nbval printed."""
    notebooks = {f"{case}.ipynb": nbformat.writes(notebook(cells)) for case, (cells, _) in CASES.items()}
    printed = run_planted(notebooks, "--nbval-lax", "--nbval-current-env")
    found: dict[str, list[str]] = {}
    for outcome, case in re.findall(r"^(PASSED|FAILED|ERROR) \S*/([\w-]+)\.ipynb::Cell \d+", printed, re.M):
        found.setdefault(case, []).append(outcome)
    return found, printed


@pytest.mark.parametrize("case", CASES)
def test_nbval_guard(nbval_run, case):
    (found, printed), (cells, passes) = nbval_run, CASES[case]
    seen = found.get(case, [])
    assert len(seen) == len(cells), printed[-2000:]  # every cell was run and reported
    assert all(o == "PASSED" for o in seen) == passes, printed[-2000:]
