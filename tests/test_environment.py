"""The pinned environment is fully pinned and is the one the tests run in.

``make test`` builds its virtualenv from ``requirements-dev.txt`` (which includes
``binder/requirements.txt``, the set Binder builds), so on a fresh clone this
checks that the pinned set installs and that kfcourse works in it.
"""

from __future__ import annotations

import re
from importlib import metadata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PIN = re.compile(r"^([A-Za-z0-9_.\-]+)==([A-Za-z0-9_.+\-!]+)$")


def pins(path: Path) -> dict[str, str]:
    found = {}
    for line in path.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#") or line == "-r binder/requirements.txt":
            continue
        match = PIN.match(line)
        assert match, f"{path.name}: not pinned to one version: {line!r}"
        found[match[1].lower().replace("_", "-")] = match[2]
    return found


def test_binder_files():
    assert re.fullmatch(r"python-3\.1[0-9]", (ROOT / "binder" / "runtime.txt").read_text().strip())
    post = (ROOT / "binder" / "postBuild").read_text()
    assert "set -e" in post and "--no-deps" in post


@pytest.mark.parametrize("name", ["binder/requirements.txt", "requirements-dev.txt"])
def test_every_requirement_is_pinned_and_installed(name):
    wanted = pins(ROOT / name)
    assert len(wanted) > 10
    for package in ("numpy", "matplotlib", "ipywidgets", "jupyterlab") if name.startswith("binder") else ("nbval",):
        assert package in wanted
    wrong = {p: (v, metadata.version(p)) for p, v in wanted.items() if metadata.version(p) != v}
    assert not wrong, f"installed versions differ from {name} (pinned, installed): {wrong}"
