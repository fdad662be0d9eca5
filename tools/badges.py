"""Write the Binder badges of every chapter: at the top of each notebook and in the README.

    python tools/badges.py                  # (re)write them; run it again after adding a chapter
    python tools/badges.py --check          # exit 1 if any badge is missing or stale
    python tools/badges.py --print --ref v1.0   # the links at a release tag, e.g. for a class

Each chapter ``notebooks/NN_name.ipynb`` gets two badges: one opens it in JupyterLab on
Binder, the other opens it as an app (Voilà: prose and live demos, no code).  They go into
the notebook's first cell (a markdown cell with the id ``binder-badges``, inserted if
missing; no other cell is touched) and into the "open on Binder" column of the README's
chapter table, whose ``[binder]`` link at the bottom is written too.  The repository is
named once, in ``pyproject.toml`` (``[project.urls] Repository``).  Running this again
changes nothing.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
CELL_ID = "binder-badges"
LAB_BADGE = "https://mybinder.org/badge_logo.svg"
APP_BADGE = "https://img.shields.io/badge/launch-app%20view-E66581"
COLUMN = "open on Binder"
NOTE = "<!-- Binder badges, written by tools/badges.py: run it again after adding a chapter. -->"


def repository(root: Path = ROOT) -> str:
    """``owner/name`` on GitHub, from ``[project.urls] Repository`` in pyproject.toml."""
    text = (root / "pyproject.toml").read_text(encoding="utf-8")
    match = re.search(r'(?m)^Repository\s*=\s*"https://github\.com/([\w.-]+/[\w.-]+?)/?"\s*$', text)
    if match is None:
        raise ValueError('pyproject.toml needs [project.urls] Repository = "https://github.com/OWNER/NAME"')
    return match[1]


def chapters(root: Path = ROOT) -> list[Path]:
    """The chapter notebooks, in order."""
    return sorted((root / "notebooks").glob("[0-9][0-9]_*.ipynb"))


def binder_url(repo: str, ref: str, urlpath: str) -> str:
    return f"https://mybinder.org/v2/gh/{repo}/{ref}?urlpath={urlpath}"


def lab_url(repo: str, ref: str, notebook: str) -> str:
    """Binder opening ``notebook`` (a path from the repository root) in JupyterLab."""
    return binder_url(repo, ref, f"lab/tree/{notebook}")


def app_url(repo: str, ref: str, notebook: str) -> str:
    """Binder opening ``notebook`` as an app (Voilà)."""
    return binder_url(repo, ref, f"voila/render/{notebook}")


def badges(repo: str, ref: str, notebook: Path, root: Path = ROOT) -> str:
    """The two badges of one chapter, as markdown on one line."""
    path = notebook.relative_to(root).as_posix()
    number = int(notebook.name[:2])
    lab = f"[![Open chapter {number} in JupyterLab on Binder]({LAB_BADGE})]({lab_url(repo, ref, path)})"
    app = f"[![Open chapter {number} as an app on Binder]({APP_BADGE})]({app_url(repo, ref, path)})"
    return f"{lab} {app}"


# --------------------------------------------------------------------------- writers


def write_notebook(path: Path, line: str) -> bool:
    """Make the first cell of ``path`` its badge cell; True when the file changed."""
    nb = nbformat.read(path, as_version=4)
    source = f"{NOTE}\n{line}"
    others = [c for c in nb.cells if c.get("id") != CELL_ID]
    first = nb.cells[0] if nb.cells else None
    if first is not None and first.get("id") == CELL_ID and first.source == source and len(others) == len(nb.cells) - 1:
        return False
    cell = nbformat.v4.new_markdown_cell(source, id=CELL_ID)
    nb.cells = [cell, *others]
    nbformat.write(nb, path)
    return True


def table_cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def table_line(cells: list[str]) -> str:
    return "| " + " | ".join(cells) + " |"


def readme_text(text: str, repo: str, ref: str, root: Path = ROOT) -> str:
    """The README with the badge column of the chapter table and the ``[binder]`` link written."""
    lines = text.split("\n")
    header = next((i for i, line in enumerate(lines) if re.match(r"^\|\s*#\s*\|", line)), None)
    if header is None:
        raise ValueError("README.md has no chapter table (a header row starting with '| # |')")
    names = table_cells(lines[header])
    if COLUMN not in names:
        names.insert(2, COLUMN)
        lines[header] = table_line(names)
        lines[header + 1] = table_line(["---"] * len(names)).replace(" ", "")
    column = names.index(COLUMN)
    notebooks = {int(p.name[:2]): p for p in chapters(root)}
    i = header + 2
    while i < len(lines) and lines[i].startswith("|"):
        cells = table_cells(lines[i])
        if len(cells) == len(names) - 1:  # a row written before the column existed
            cells.insert(column, "")
        if cells[0].isdigit():
            notebook = notebooks.get(int(cells[0]))
            cells[column] = badges(repo, ref, notebook, root) if notebook else ""
        lines[i] = table_line(cells)
        i += 1
    text = "\n".join(lines)
    if notebooks:
        first = notebooks[min(notebooks)].relative_to(root).as_posix()
        text = re.sub(r"(?m)^\[binder\]: .*$", f"[binder]: {lab_url(repo, ref, first)}", text)
    return text


def write_all(root: Path = ROOT, ref: str = "HEAD") -> list[Path]:
    """(Re)write every badge under ``root``; returns the files that changed."""
    repo = repository(root)
    changed = [p for p in chapters(root) if write_notebook(p, badges(repo, ref, p, root))]
    readme = root / "README.md"
    old = readme.read_text(encoding="utf-8")
    new = readme_text(old, repo, ref, root)
    if new != old:
        readme.write_text(new, encoding="utf-8")
        changed.append(readme)
    return changed


def stale(root: Path = ROOT, ref: str = "HEAD") -> list[str]:
    """What ``write_all`` would change, without writing: a list of problems, empty when all is well."""
    repo = repository(root)
    problems = []
    for path in chapters(root):
        nb = nbformat.read(path, as_version=4)
        wanted = f"{NOTE}\n{badges(repo, ref, path, root)}"
        if not nb.cells or nb.cells[0].get("id") != CELL_ID or nb.cells[0].source != wanted:
            problems.append(f"{path.relative_to(root)}: the first cell is not its badge cell (or it is stale)")
        elif sum(c.get("id") == CELL_ID for c in nb.cells) != 1:
            problems.append(f"{path.relative_to(root)}: more than one badge cell")
    readme = (root / "README.md").read_text(encoding="utf-8")
    if readme_text(readme, repo, ref, root) != readme:
        problems.append("README.md: the chapter table's badges or the [binder] link are missing or stale")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="only report missing or stale badges")
    parser.add_argument("--print", action="store_true", help="only print each chapter's two links")
    parser.add_argument("--ref", default="HEAD", help="branch or tag Binder builds (default: HEAD)")
    args = parser.parse_args(argv)
    if args.print:
        repo = repository()
        for path in chapters():
            rel = path.relative_to(ROOT).as_posix()
            print(f"{path.stem}\n  lab: {lab_url(repo, args.ref, rel)}\n  app: {app_url(repo, args.ref, rel)}")
        return 0
    if args.check:
        problems = stale(ref=args.ref)
        for problem in problems:
            print(problem)
        if problems:
            print("run: python tools/badges.py")
        return 1 if problems else 0
    for path in write_all(ref=args.ref):
        print(f"wrote {path.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
