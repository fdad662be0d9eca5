"""The course notebooks are stored clean, and nbval really checks something.

nbval compares a ``# NBVAL_CHECK_OUTPUT`` cell only when the notebook stores its
output *and* execution count; without them it passes silently.  Every other
cell must be stored without outputs or counts so nothing stale ships, and no notebook
stores widget state or a widget view (the course's JupyterLab saves widget state into a
student's own copy, so a notebook saved from a lab session must not be committed as is).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
MARK = "# NBVAL_CHECK_OUTPUT"
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
EXTRA = {"solutions.ipynb", "notation.ipynb"}  # not chapters: the exercises' solutions, the course's symbols
PROSE_ONLY = {"notation.ipynb"}  # no code, so no worked number to check


def cells(path: Path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    return nb, nb["cells"]


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 5
    for path in NOTEBOOKS:
        assert re.fullmatch(r"\d\d_[a-z0-9_]+\.ipynb", path.name) or path.name in EXTRA, path.name


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if p.name not in PROSE_ONLY], ids=lambda p: p.stem)
def test_checked_cells_store_output_and_count(path):
    _, cs = cells(path)
    checked = [c for c in cs if c["cell_type"] == "code" and MARK in "".join(c["source"])]
    assert checked, f"{path.name} has no {MARK} cell: its worked numbers are not checked"
    for c in checked:
        src = "".join(c["source"])
        assert c["execution_count"] is not None, f"no execution count, nbval would skip:\n{src}"
        assert c["outputs"], f"no stored output, nbval would check nothing:\n{src}"
        for out in c["outputs"]:
            assert out.get("name") != "stderr", f"stored stderr output:\n{src}"
            assert out["output_type"] != "error", f"stored error:\n{src}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_widget_state_is_stored(path):
    """Widget state belongs in a student's saved copy (JupyterLab saves it there), never in the course's notebooks."""
    nb, cs = cells(path)
    assert "widgets" not in nb.get("metadata", {}), "widget state stored in metadata.widgets"
    for c in cs:
        for out in c.get("outputs", []):
            assert WIDGET_VIEW not in out.get("data", {}), f"stored widget view:\n{''.join(c['source'])}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_other_cells_are_clean(path):
    _, cs = cells(path)
    for c in cs:
        if c["cell_type"] != "code" or MARK in "".join(c["source"]):
            continue
        src = "".join(c["source"])
        assert c["outputs"] == [], f"unchecked cell stores outputs:\n{src}"
        assert c["execution_count"] is None, f"unchecked cell stores an execution count:\n{src}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_structure(path):
    """Title, what you will learn, links to the neighbours, a recap, no TODO."""
    _, cs = cells(path)
    # The Binder badge cell (tools/badges.py, checked by tests/test_badges.py) comes before the title.
    md = ["".join(c["source"]) for c in cs if c["cell_type"] == "markdown" and c.get("id") != "binder-badges"]
    assert md and md[0].lstrip().startswith("# "), "first cell is not a title"
    text = "\n".join(md)
    assert re.search(r"(?i)you will learn", text), "no 'what you will learn'"
    assert re.search(r"(?i)#+ *recap", text), "no recap section"
    existing = {int(p.name[:2]) for p in NOTEBOOKS if p.name not in EXTRA}
    for neighbour in (int(path.name[:2]) - 1, int(path.name[:2]) + 1) if path.name not in EXTRA else ():
        if neighbour in existing:
            assert re.search(rf"\]\(\s*{neighbour:02d}_[a-z0-9_]+\.ipynb\s*\)", text), f"no link to chapter {neighbour}"
    for target in re.findall(r"\]\(\s*([^)\s]+\.ipynb)", text):
        assert (path.parent / target).exists(), f"broken link to {target}"
    everything = "\n".join("".join(c["source"]) for c in cs)
    assert "TODO" not in everything and "FIXME" not in everything


def test_the_notation_table_is_prose_and_every_chapter_links_it():
    _, cs = cells(ROOT / "notebooks" / "notation.ipynb")
    assert cs and all(c["cell_type"] == "markdown" for c in cs)
    for path in NOTEBOOKS:
        if path.name in EXTRA:
            continue
        _, cs = cells(path)
        text = "\n".join("".join(c["source"]) for c in cs if c["cell_type"] == "markdown")
        assert re.search(r"\]\(\s*notation\.ipynb\s*\)", text), f"{path.name} does not link the notation table"


MAX_CODE_LINES = 15  # a longer answer lets its run record print the table (kfcourse.sim.records.text_table)


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if p.name not in EXTRA], ids=lambda p: p.stem)
def test_no_code_cell_of_a_chapter_is_over_15_lines(path):
    """A chapter shows short calls; a loop that prints a table belongs in the package."""
    _, cs = cells(path)
    too_long = []
    for index, c in enumerate(cs):
        lines = "".join(c["source"]).splitlines()
        if c["cell_type"] == "code" and len(lines) > MAX_CODE_LINES:
            first = next((line for line in lines if line != MARK), "")
            too_long.append(f"cell {index} ({len(lines)} lines): {first!r}")
    assert not too_long, f"{path.name}: code cells over {MAX_CODE_LINES} lines:\n" + "\n".join(too_long)


def test_every_chapter_links_the_chapters_before_and_after_it_at_the_top():
    chapters = [path for path in NOTEBOOKS if path.name not in EXTRA]
    for i, path in enumerate(chapters):
        top = "".join(cells(path)[1][1]["source"])  # the title cell, under the Binder badges
        neighbours = {"Previous": chapters[i - 1] if i else None, "Next": (chapters[i + 1 :] or [None])[0]}
        for word, other in neighbours.items():
            if other is not None:
                link = f"{word}: [Chapter {int(other.name[:2])} ·"
                assert link in top and f"]({other.name})" in top, f"{path.name}: no {link} ...]({other.name})"


# \operatorname{erf}, \mathrm{diag}, \mathbb{E} or \mathbb E; not a unit such as \mathrm{m/s^2}
OPERATOR = re.compile(r"\\(operatorname|mathbb|mathrm)\s*(?:\{([A-Za-z0-9]+)\}|([A-Z])\b)")


def test_every_operator_a_chapter_uses_is_on_the_notation_page():
    """A \\mathbb{E}, \\operatorname{erf} or \\mathrm{diag} in a chapter is one a student can look up."""

    def operators(path: Path) -> set[tuple[str, str]]:
        text = "".join("".join(cell["source"]) for cell in cells(path)[1] if cell["cell_type"] == "markdown")
        return {(kind, braced or bare) for kind, braced, bare in OPERATOR.findall(text)}

    listed = operators(ROOT / "notebooks" / "notation.ipynb")
    used = {op: path.name for path in NOTEBOOKS if path.name not in EXTRA for op in operators(path)}
    assert ("mathbb", "E") in used and ("operatorname", "erf") in used
    missing = sorted(f"\\{kind}{{{name}}} ({used[kind, name]})" for kind, name in used.keys() - listed)
    assert not missing, "not on the notation page: " + ", ".join(missing)
