"""Write the Binder badges of every chapter: at the top of each notebook and in the README.

    python tools/badges.py                  # (re)write them; run it again after adding a chapter
    python tools/badges.py --repo me/kfcourse --ref v1.0   # point every link at a fork and a tag
    python tools/badges.py --check          # exit 1 if any badge is missing or stale
    python tools/badges.py --print --ref v1.0   # only print the links at a tag, writing nothing

``make badges REPO=OWNER/NAME REF=TAG`` runs the second line in the course's environment.

Each chapter ``notebooks/NN_name.ipynb`` gets two badges: one opens it in JupyterLab on
Binder, the other opens it as an app (Voilà: prose and live demos, no code).  They go into
the notebook's first cell (a markdown cell with the id ``binder-badges``, inserted if
missing; no other cell is touched) and into the "open on Binder" column of the README's
chapter table, whose ``[binder]`` link at the bottom is written too.  The app view (Voilà)
and the static site (``make site``) show each notebook's badge cell, so they follow.  The
repository is named once, in ``pyproject.toml`` (``[project.urls] Repository``), and so is
the branch or tag the links open (``[tool.kfcourse] binder-ref``); ``--repo`` and ``--ref``
change both there, then rewrite every link.  Running this again changes nothing.
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


REPOSITORY = re.compile(r'(?m)^(Repository\s*=\s*)"https://github\.com/([\w.-]+/[\w.-]+?)/?"[ \t]*$')
BINDER_REF = re.compile(r'(?m)^(binder-ref\s*=\s*)"([^"]*)"')
REPO_FORM = re.compile(r"^[\w.-]+/[\w.-]+$")
REF_FORM = re.compile(r"^[\w.-]+$")


def repository(root: Path = ROOT) -> str:
    """``owner/name`` on GitHub, from ``[project.urls] Repository`` in pyproject.toml."""
    match = REPOSITORY.search((root / "pyproject.toml").read_text(encoding="utf-8"))
    if match is None:
        raise ValueError('pyproject.toml needs [project.urls] Repository = "https://github.com/OWNER/NAME"')
    return match[2]


def binder_ref(root: Path = ROOT) -> str:
    """The branch or tag the links open, from ``[tool.kfcourse] binder-ref`` in pyproject.toml."""
    match = BINDER_REF.search((root / "pyproject.toml").read_text(encoding="utf-8"))
    if match is None:
        raise ValueError('pyproject.toml needs [tool.kfcourse] binder-ref = "HEAD" (or a tag)')
    return match[2]


def checked(repo: str | None, ref: str | None) -> None:
    """Raise ValueError unless ``repo`` is ``owner/name`` and ``ref`` a branch or tag name (None: unchanged)."""
    if repo is not None and not REPO_FORM.match(repo):
        raise ValueError(f"repo must be OWNER/NAME on GitHub, e.g. me/kfcourse, got {repo!r}")
    if ref is not None and not REF_FORM.match(ref):
        raise ValueError(f"ref must be a branch or tag name (letters, digits, '.', '_', '-'), e.g. v1.0, got {ref!r}")


def retarget(root: Path = ROOT, repo: str | None = None, ref: str | None = None) -> list[Path]:
    """Name ``repo`` and ``ref`` in pyproject.toml, then rewrite every link; returns the files that changed."""
    checked(repo, ref)
    path = root / "pyproject.toml"
    old = path.read_text(encoding="utf-8")
    repository(root)  # raises unless pyproject.toml names both
    binder_ref(root)
    new = old
    if repo is not None:
        new = REPOSITORY.sub(lambda m: f'{m[1]}"https://github.com/{repo}"', new)
    if ref is not None:
        new = BINDER_REF.sub(lambda m: f'{m[1]}"{ref}"', new)
    changed = []
    if new != old:
        path.write_text(new, encoding="utf-8")
        changed.append(path)
    return changed + write_all(root)


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


def write_all(root: Path = ROOT) -> list[Path]:
    """(Re)write every badge under ``root``; returns the files that changed."""
    repo, ref = repository(root), binder_ref(root)
    changed = [p for p in chapters(root) if write_notebook(p, badges(repo, ref, p, root))]
    readme = root / "README.md"
    old = readme.read_text(encoding="utf-8")
    new = readme_text(old, repo, ref, root)
    if new != old:
        readme.write_text(new, encoding="utf-8")
        changed.append(readme)
    return changed


def stale(root: Path = ROOT) -> list[str]:
    """What ``write_all`` would change, without writing: a list of problems, empty when all is well."""
    repo, ref = repository(root), binder_ref(root)
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
    parser.add_argument("--repo", default=None, help="OWNER/NAME on GitHub: point every link at it (a fork)")
    parser.add_argument("--ref", default=None, help="branch or tag Binder builds, e.g. v1.0 (default: as named)")
    args = parser.parse_args(argv)
    try:
        checked(args.repo, args.ref)
        if args.print:
            repo, ref = args.repo or repository(), args.ref or binder_ref()
            for path in chapters():
                rel = path.relative_to(ROOT).as_posix()
                print(f"{path.stem}\n  lab: {lab_url(repo, ref, rel)}\n  app: {app_url(repo, ref, rel)}")
            return 0
        if args.check:
            problems = stale()
            for problem in problems:
                print(problem)
            if problems:
                print("run: python tools/badges.py")
            return 1 if problems else 0
        changed = retarget(ROOT, args.repo, args.ref)
    except ValueError as error:
        print(f"badges: {error}", file=sys.stderr)
        return 2
    for path in changed:
        print(f"wrote {path.relative_to(ROOT)}")
    print(f"every Binder link opens {repository()} at {binder_ref()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
