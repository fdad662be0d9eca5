"""The notebook checks can fail: a warning in any cell, or a changed worked number."""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]


def run_nbval(cells) -> subprocess.CompletedProcess:
    """Run nbval, as `make test` does, on a notebook made of ``(source, stored_output)`` cells."""
    nb = nbformat.v4.new_notebook()
    for count, (source, stored) in enumerate(cells, start=1):
        cell = nbformat.v4.new_code_cell(source)
        if stored is not None:
            cell.execution_count = count
            cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text=stored)]
        nb.cells.append(cell)
    folder = Path(tempfile.mkdtemp(prefix=".probe-", dir=ROOT / "tests"))  # under the root conftest
    try:
        nbformat.write(nb, folder / "probe.ipynb")
        command = ["pytest", "--nbval-lax", "--nbval-current-env", "-q", "-p", "no:cacheprovider"]
        return subprocess.run(
            [sys.executable, "-m", *command, str(folder / "probe.ipynb")],
            cwd=ROOT,
            capture_output=True,
            text=True,
            timeout=120,
        )
    finally:
        shutil.rmtree(folder)


@pytest.mark.parametrize(
    ("cells", "passes"),
    [
        ([("print(1 + 1)", None)], True),
        ([("import warnings\nwarnings.warn('careful')", None)], False),
        ([("# NBVAL_CHECK_OUTPUT\nprint(f'{6 / 7:.3f}')", "0.857\n")], True),
        ([("# NBVAL_CHECK_OUTPUT\nprint(f'{6 / 7:.3f}')", "0.858\n")], False),
    ],
    ids=["clean", "warning", "number-kept", "number-changed"],
)
def test_nbval_guard(cells, passes):
    result = run_nbval(cells)
    assert (result.returncode == 0) == passes, result.stdout[-2000:]
