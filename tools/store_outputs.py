"""Execute course notebooks and store them clean.

Only the cells marked ``# NBVAL_CHECK_OUTPUT`` keep their outputs and execution
counts (nbval compares exactly those); every other cell is stored without
outputs or counts, and widget state is dropped.  A cell that writes to stderr
(a warning) or raises makes this script fail.

    python tools/store_outputs.py notebooks/*.ipynb
"""

from __future__ import annotations

import sys
from pathlib import Path

import nbformat
from nbclient import NotebookClient

if __package__ in (None, ""):  # run as a script: the repository's root on the path, as with -m
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tools.kernels import kernel_config

MARK = "# NBVAL_CHECK_OUTPUT"


def text_outputs(outputs: list) -> list:
    """Keep what nbval compares: text, never images or widget views."""
    kept = []
    for out in outputs:
        if out.get("output_type") in ("execute_result", "display_data"):
            data = {k: v for k, v in out["data"].items() if k.startswith("text/")}
            if not data:
                continue
            out["data"] = data
            out["metadata"] = {}
        kept.append(out)
    return kept


def store(path: Path) -> None:
    nb = nbformat.read(path, as_version=4)
    resources = {"metadata": {"path": str(path.parent)}}
    NotebookClient(nb, timeout=300, kernel_name="python3", resources=resources, config=kernel_config()).execute()
    for cell in nb.cells:
        cell.metadata.pop("execution", None)
        if cell.cell_type != "code":
            continue
        for out in cell.outputs:
            if out.get("output_type") == "stream" and out.get("name") == "stderr":
                raise SystemExit(f"{path}: a cell wrote to stderr:\n{cell.source}\n---\n{out['text']}")
        if MARK in cell.source:
            cell.outputs = text_outputs(cell.outputs)
        else:
            cell.outputs = []
            cell.execution_count = None
    nb.metadata.pop("widgets", None)
    nbformat.write(nb, path)
    print(f"stored {path}")


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        store(Path(arg))
