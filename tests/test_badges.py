"""Every chapter has its two Binder badges, and every badge opens a notebook that exists.

The badges are written by ``tools/badges.py`` from the repository named once in
pyproject.toml; a chapter notebook added without running it fails here.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

from tools import badges

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = badges.chapters(ROOT)
BINDER = re.compile(
    r"https://mybinder\.org/v2/gh/([\w.-]+/[\w.-]+)/([\w.-]+)\?urlpath=(lab/tree|voila/render)/([^)\s]+)"
)


def binder_links(text: str) -> list[tuple[str, str, str, str]]:
    return BINDER.findall(text)


def test_there_are_chapters():
    assert len(NOTEBOOKS) >= 8


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_every_chapter_opens_with_its_two_badges(path):
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    first = cells[0]
    assert first["cell_type"] == "markdown" and first.get("id") == badges.CELL_ID, (
        f"{path.name} does not start with its Binder badge cell: run python tools/badges.py"
    )
    links = binder_links("".join(first["source"]))
    own = f"notebooks/{path.name}"
    assert sorted((view, target) for _, _, view, target in links) == [("lab/tree", own), ("voila/render", own)]
    assert sum(c.get("id") == badges.CELL_ID for c in cells) == 1


def test_readme_has_both_badges_for_every_chapter():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    found = {(view, target) for _, _, view, target in binder_links(text)}
    for path in NOTEBOOKS:
        for view in ("lab/tree", "voila/render"):
            assert (view, f"notebooks/{path.name}") in found, f"README.md lacks the {view} badge of {path.name}"


def test_every_badge_points_at_an_existing_notebook_of_this_repository():
    repo = badges.repository(ROOT)
    texts = {"README.md": (ROOT / "README.md").read_text(encoding="utf-8")}
    texts |= {p.name: p.read_text(encoding="utf-8") for p in NOTEBOOKS}
    links = [(name, link) for name, text in texts.items() for link in binder_links(text)]
    assert len(links) >= 4 * len(NOTEBOOKS)  # two in each notebook, two per chapter in the README
    for name, (owner_repo, _ref, _view, target) in links:
        assert owner_repo == repo, f"{name}: a Binder link to {owner_repo}, not {repo}"
        assert target.endswith(".ipynb") and (ROOT / target).is_file(), (
            f"{name}: a badge opens {target}, not a notebook"
        )


def test_badges_are_up_to_date():
    assert badges.stale(ROOT) == []


def copy_of_the_course(tmp_path: Path, chapters: list[Path] = NOTEBOOKS[:2]) -> Path:
    root = tmp_path / "course"
    (root / "notebooks").mkdir(parents=True)
    (root / "tools").mkdir()
    for name in ("pyproject.toml", "README.md", "Makefile", "tools/badges.py"):
        shutil.copy(ROOT / name, root / name)
    for path in chapters:
        shutil.copy(path, root / "notebooks")
    return root


def test_the_writer_adds_a_new_chapters_badges_and_touches_nothing_else(tmp_path):
    root = copy_of_the_course(tmp_path)
    new = root / "notebooks" / "08_new_chapter.ipynb"
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Chapter 8 · New", id="title"), nbformat.v4.new_code_cell("1 + 1")]
    nbformat.write(nb, new)
    before = nbformat.read(new, as_version=4)

    assert badges.stale(root) != []
    changed = badges.write_all(root)
    assert new in changed and (root / "README.md") in changed
    assert badges.stale(root) == []

    after = nbformat.read(new, as_version=4)
    assert after.cells[0].id == badges.CELL_ID
    assert after.cells[1:] == before.cells  # nothing else changed
    row = next(
        line for line in (root / "README.md").read_text(encoding="utf-8").splitlines() if line.startswith("| 8 |")
    )
    assert "lab/tree/notebooks/08_new_chapter.ipynb" in row and "voila/render/notebooks/08_new_chapter.ipynb" in row


def test_the_writer_is_idempotent_and_mends_a_stale_badge(tmp_path):
    root = copy_of_the_course(tmp_path)
    files = [root / "README.md", *badges.chapters(root)]
    badges.write_all(root)
    written = {p: p.read_bytes() for p in files}
    assert badges.write_all(root) == []
    assert {p: p.read_bytes() for p in files} == written

    path = badges.chapters(root)[0]
    nb = nbformat.read(path, as_version=4)
    nb.cells[0].source = nb.cells[0].source.replace("/HEAD?", "/some-old-branch?")
    nbformat.write(nb, path)
    assert badges.stale(root) != []
    assert badges.write_all(root) == [path]
    assert path.read_bytes() == written[path]


def test_the_repository_is_named_once():
    """Only pyproject.toml names the repository; everything else is written from it."""
    repo = badges.repository(ROOT)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    outside_links = readme.replace(f"mybinder.org/v2/gh/{repo}/", "")
    assert f"github.com/{repo}" not in outside_links


def test_links_for_a_class_at_a_release_tag(capsys):
    """The README's instructors' recipe: every chapter's two links at a tag, printed, nothing written."""
    before = {p: p.read_bytes() for p in [ROOT / "README.md", *NOTEBOOKS]}
    assert badges.main(["--print", "--ref", "v1.0"]) == 0
    links = binder_links(capsys.readouterr().out)
    assert {ref for _, ref, _, _ in links} == {"v1.0"}
    assert sorted((view, target) for _, _, view, target in links) == sorted(
        (view, f"notebooks/{p.name}") for p in NOTEBOOKS for view in ("lab/tree", "voila/render")
    )
    assert {p: p.read_bytes() for p in before} == before
    teaching = (ROOT / "README.md").read_text(encoding="utf-8").split("## Teaching a class", 1)
    assert len(teaching) == 2, "README.md has no 'Teaching a class' section"
    section = teaching[1].split("\n## ", 1)[0]
    for needed in ("make badges REPO=", "python tools/badges.py --print --ref", "jupyter-repo2docker", "make site"):
        assert needed in section, f"the 'Teaching a class' section does not mention {needed}"


def test_make_badges_points_every_link_at_a_fork_and_a_tag(tmp_path):
    """What an instructor who forks the course runs: no link is left on the original repository."""
    root = copy_of_the_course(tmp_path, NOTEBOOKS)
    old = badges.repository(ROOT)
    venv = Path(sys.prefix)
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
    make = [shutil.which("make") or "make", "--no-print-directory", f"--assume-old={venv / '.kfcourse-installed'}"]
    done = subprocess.run(
        [*make, "badges", f"VENV={venv}", "REPO=a-teacher/kf-course.fork", "REF=v2.1"],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "a-teacher/kf-course.fork at v2.1" in done.stdout
    before, after = ((folder / "pyproject.toml").read_text(encoding="utf-8").splitlines() for folder in (ROOT, root))
    assert len(after) == len(before)  # the two lines change, nothing else
    assert sum(a != b for a, b in zip(before, after, strict=True)) == 2
    files = [root / "README.md", root / "pyproject.toml", *badges.chapters(root)]
    for path in files:
        assert old not in path.read_text(encoding="utf-8"), f"{path.name} still names {old}"
    links = [link for path in files for link in binder_links(path.read_text(encoding="utf-8"))]
    assert len(links) >= 4 * len(NOTEBOOKS)  # each chapter's two badges, in its notebook and in the README
    assert {(repo, ref) for repo, ref, _, _ in links} == {("a-teacher/kf-course.fork", "v2.1")}
    assert badges.stale(root) == []  # the fork's own `make test` finds its badges up to date

    # REF alone moves the links to the next term's tag and keeps the fork.
    assert badges.retarget(root, ref="v3.0") != []
    links = [link for path in files for link in binder_links(path.read_text(encoding="utf-8"))]
    assert {(repo, ref) for repo, ref, _, _ in links} == {("a-teacher/kf-course.fork", "v3.0")}


@pytest.mark.parametrize(("repo", "ref"), [("no-slash", None), ("a/b/c", None), (None, "v1.0 beta"), (None, "../x")])
def test_retarget_refuses_what_is_not_a_repository_or_a_tag(tmp_path, repo, ref):
    root = copy_of_the_course(tmp_path)
    before = {p: p.read_bytes() for p in root.rglob("*") if p.is_file()}
    with pytest.raises(ValueError, match="repo must be OWNER/NAME" if repo else "ref must be a branch or tag"):
        badges.retarget(root, repo, ref)
    assert {p: p.read_bytes() for p in root.rglob("*") if p.is_file()} == before
