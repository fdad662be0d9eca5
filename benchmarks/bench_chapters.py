"""Every chapter run top to bottom in a fresh kernel, cell by cell, as Run All runs it.

Run from the repository root (``make bench`` runs it; it is not a pytest test)::

    .venv/bin/python benchmarks/bench_chapters.py [notebooks/NN_*.ipynb ...]   (default: every chapter)

Each notebook runs in its own fresh kernel (the course's own environment, as a student's Run
All), one after another so that no two share the CPU.  Printed: each chapter's time from the
first cell to the last (the kernel's start-up not counted), its slowest cell with its index
(0-based, as in ``nb.cells``) and that cell's time, and a mark where a chapter misses its
target: the whole chapter in at most 60 s and no cell over 10 s (issue 32).  ``--cells``
prints every cell that takes a second or more.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient

if __package__ in (None, ""):  # run as a script: the repository's root on the path, as with -m
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tools.kernels import kernel_config

ROOT = Path(__file__).resolve().parent.parent
CHAPTER_TARGET = 60.0  # s, top to bottom
CELL_TARGET = 10.0  # s, any one cell
SHOWN = 1.0  # s, --cells prints the cells that take this long or longer


def cell_times(path: Path) -> list[tuple[int, float]]:
    """(index, seconds) for every code cell of the notebook at ``path``, run in a fresh kernel."""
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(
        nb,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
        config=kernel_config(),
    )
    times = []
    with client.setup_kernel():
        for index, cell in enumerate(nb.cells):
            if cell.cell_type != "code":
                continue
            t0 = time.perf_counter()
            client.execute_cell(cell, index)
            times.append((index, time.perf_counter() - t0))
    return times


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path)
    parser.add_argument("--cells", action="store_true", help="print every cell of a second or more")
    args = parser.parse_args(argv)
    paths = args.notebooks or sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    print(f"{'chapter':<34}{'total s':>9}{'slowest cell':>14}{'cell s':>8}  met")
    misses = 0
    for path in paths:
        times = cell_times(path)
        total = sum(t for _, t in times)
        index, slowest = max(times, key=lambda it: it[1])
        met = total <= CHAPTER_TARGET and slowest <= CELL_TARGET
        misses += not met
        print(f"{path.stem:<34}{total:9.1f}{index:>14}{slowest:8.1f}  {'yes' if met else 'NO'}", flush=True)
        if args.cells:
            for i, t in times:
                if t >= SHOWN:
                    print(f"{'':<6}cell {i:>3}{t:8.1f} s")
    print(f"targets (chapter <= {CHAPTER_TARGET:.0f} s, cell <= {CELL_TARGET:.0f} s): ", end="")
    print("all met" if not misses else f"NOT met by {misses} chapter(s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
