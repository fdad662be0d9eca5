"""Each demo is a model, a view in ``kfcourse/plots/`` and a short wiring function.

A student who opens a demo's module finds what its controls do, in a few lines: the
model's methods and the view's update function live elsewhere, named.  No demo module
imports another demo module (what two demos share lives in plots/ or in a model module),
and the view modules know nothing of widgets.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import kfcourse as kf

DEMOS_DIR = Path(kf.__file__).parent / "demos"
PLOTS_DIR = Path(kf.__file__).parent / "plots"
DEMO_MODULES = sorted(p for p in DEMOS_DIR.glob("*.py") if not p.name.startswith("_"))
WIRING_LINES = 40  # "about 30 lines": the controls, the view, the renderer and Demo(...)


def tree(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"))


def relative_imports(module: ast.Module) -> set[str]:
    """The modules a file imports relative to its own package: ``._base``, ``.hallway``, ``..plots``."""
    found = set()
    for node in ast.walk(module):
        if isinstance(node, ast.ImportFrom) and node.level:
            found.add("." * node.level + (node.module or ""))
    return found


@pytest.mark.parametrize("path", DEMO_MODULES, ids=lambda p: p.stem)
def test_no_demo_imports_another_demo(path):
    siblings = {f".{p.stem}" for p in DEMO_MODULES}
    assert not relative_imports(tree(path)) & siblings


@pytest.mark.parametrize("name", kf.demos.__all__)
def test_the_demo_function_is_short_wiring(name):
    function = getattr(kf.demos, name)
    path = Path(function.__code__.co_filename)
    node = next(n for n in tree(path).body if isinstance(n, ast.FunctionDef) and n.name == name)
    body = node.body[1:] if ast.get_docstring(node) else node.body  # the code, without its docstring
    lines = body[-1].end_lineno - body[0].lineno + 1
    assert lines <= WIRING_LINES, f"{name} wires its demo in {lines} lines"


@pytest.mark.parametrize("path", sorted(PLOTS_DIR.glob("*.py")), ids=lambda p: p.stem)
def test_plots_know_nothing_of_widgets_or_demos(path):
    module = tree(path)
    imported = {alias.name for n in ast.walk(module) if isinstance(n, ast.Import) for alias in n.names}
    imported |= {n.module or "" for n in ast.walk(module) if isinstance(n, ast.ImportFrom)}
    assert not any(name.startswith(("ipywidgets", "demos")) or ".demos" in name for name in imported)
    assert "..demos" not in relative_imports(module)
