"""The package as students meet it: importable from anywhere, light, documented, stable API."""

from __future__ import annotations

import inspect
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kfcourse as kf

REPO = Path(__file__).resolve().parents[1]

# DESIGN.md, "Student-facing API": the documented call of every name (kept stable).
DESIGN_API = """
bayes_predict(belief, kernel, boundary="wall")
bayes_update(belief, likelihood)
kf_1d_step(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1)
steady_state_1d(R, Q, a=1.0, c=1.0)
fuse(mu1, var1, mu2, var2)
kf_predict(mu, Sig, u, F, B, R)
kf_update(mu_bar, Sig_bar, z, H, Q)
kf_step(mu, Sig, u, z, F, B, H, R, Q)
range_bearing(state, landmark)
range_bearing_jacobian(state, landmark)
numeric_jacobian(f, x, eps=1e-6)
unicycle(state, u, dt)
unicycle_jacobian(state, u, dt)
wrap_angle(a)
ekf_predict(mu, Sig, u, g, G, R)
ekf_update(mu_bar, Sig_bar, z, h, H, Q, residual=None)
sigma_points(mu, Sig, lam)
unscented_transform(mu, Sig, f, lam)
unscented_1d(mu, var, f, lam=0.0)
ukf_predict(mu, Sig, u, g, R, lam)
ukf_update(mu_bar, Sig_bar, z, h, Q, lam, residual=None)
mahalanobis(nu, S)
""".strip().splitlines()


def _design_signature(line: str) -> tuple[str, inspect.Signature]:
    name = line.split("(", 1)[0]
    namespace: dict = {}
    exec(f"def {line}: pass", namespace)  # only the literal table above
    return name, inspect.signature(namespace[name])


DESIGN_SIGNATURES = dict(_design_signature(line) for line in DESIGN_API)

# The scalar steps that kf_1d_cycle and kf_1d_step are built from (the demos call them).
STEP_API = """
kf_1d_predict(mu, var, u, a=1.0, b=1.0, R=0.2)
kf_1d_gain(var_bar, c=1.0, Q=0.1)
kf_1d_update(mu_bar, var_bar, z, c=1.0, Q=0.1)
""".strip().splitlines()

API_SIGNATURES = {**DESIGN_SIGNATURES, **dict(_design_signature(line) for line in STEP_API)}


def _public_functions():
    """Every function exported from the top level, plus everything in kfcourse.models.__all__."""
    seen = {}
    for name in kf.__all__:
        obj = getattr(kf, name)
        if inspect.isfunction(obj):
            seen[f"kfcourse.{name}"] = obj
    for name in kf.models.__all__:
        obj = getattr(kf.models, name)
        if inspect.isfunction(obj) and obj not in seen.values():
            seen[f"kfcourse.models.{name}"] = obj
    return seen


PUBLIC = _public_functions()


# ---------------------------------------------------------------- import
def test_import_from_another_folder_is_light(tmp_path):
    code = (
        "import json, sys\n"
        "import kfcourse as kf\n"
        "kf.kf_1d_step(2.0, 0.4, 1.0, 3.6)\n"  # using the math loads nothing heavy either
        "print(json.dumps({'file': kf.__file__,\n"
        "    'loaded': sorted(m for m in sys.modules\n"
        "                     if m.split('.')[0] in ('matplotlib', 'ipywidgets', 'scipy', 'gtsam')\n"
        "                     or m in ('kfcourse.plots', 'kfcourse.demos', 'kfcourse.sim', 'kfcourse.data'))}))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    proc = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120, check=False
    )
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert Path(out["file"]).resolve() == (REPO / "kfcourse" / "__init__.py").resolve()
    assert out["loaded"] == []


def test_the_logs_of_real_robots_are_read_only_when_asked_for():
    """kf.data and kf.sim load without scipy or gtsam; scipy comes with the first log read, and gtsam's compiled
    module only with a factor graph."""
    code = (
        "import json, sys\n"
        "import kfcourse as kf\n"
        "kf.data, kf.sim\n"
        "before = sorted(m for m in ('scipy', 'gtsam') if m in sys.modules)\n"
        "kf.sim.range_localize(kf.data.load_plaza('Plaza2'), steps=3)\n"
        "print(json.dumps({'before': before, 'after': sorted(m for m in ('scipy', 'gtsam') if m in sys.modules)}))\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=False)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout.strip().splitlines()[-1]) == {"before": [], "after": ["scipy"]}


def test_unknown_attribute_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no_such_thing"):
        _ = kf.no_such_thing


# ---------------------------------------------------------------- API table
@pytest.mark.parametrize("name", list(API_SIGNATURES))
def test_design_api_name_is_exported_from_the_top_level(name):
    assert name in kf.__all__
    assert callable(getattr(kf, name))


@pytest.mark.parametrize("name", list(API_SIGNATURES))
def test_design_api_signature_is_kept(name):
    """The documented parameters come first, in order, with the documented defaults;
    anything added after them is an optional keyword."""
    want = list(API_SIGNATURES[name].parameters.values())
    have = list(inspect.signature(getattr(kf, name)).parameters.values())
    assert [p.name for p in have[: len(want)]] == [p.name for p in want]
    for w, h in zip(want, have, strict=False):
        assert h.default == w.default, (w.name, h.default, w.default)
        assert h.kind in (h.POSITIONAL_OR_KEYWORD, h.POSITIONAL_ONLY), w.name
    for extra in have[len(want) :]:
        assert extra.default is not inspect.Parameter.empty, extra.name


def test_every_exported_name_exists():
    missing = [n for n in kf.__all__ if not hasattr(kf, n)]
    assert missing == []


def test_star_import_gives_the_design_api():
    namespace: dict = {}
    exec("from kfcourse import *", namespace)
    assert set(API_SIGNATURES) <= set(namespace)


# ---------------------------------------------------------------- docstrings
RETURNS_SECTION = re.compile(r"^\s*Returns\s*\n\s*-{7,}\s*$", re.MULTILINE)


def test_the_public_function_list_is_not_empty():
    assert len(PUBLIC) >= len(DESIGN_SIGNATURES)


@pytest.mark.parametrize("qualname", list(PUBLIC))
def test_public_function_docstring(qualname):
    doc = inspect.getdoc(PUBLIC[qualname]) or ""
    assert re.search(r"Introduced in chapter \d", doc), qualname
    assert RETURNS_SECTION.search(doc), qualname


def _introductions() -> list[tuple[str, str, int]]:
    """(namespace as a notebook writes it, name, N) for every public callable whose docstring says
    "Introduced in chapter N"."""
    spaces = {"kf": kf, "kf.sim": kf.sim, "kf.plots": kf.plots, "kf.demos": kf.demos, "kf.check": kf.check}
    found, seen = [], set()
    for space, module in spaces.items():
        for name in module.__all__:
            obj = getattr(module, name)
            said = re.search(r"Introduced in chapter (\d+)", inspect.getdoc(obj) or "") if callable(obj) else None
            if said and id(obj) not in seen:
                seen.add(id(obj))
                found.append((space, name, int(said.group(1))))
    return found


def test_introduced_in_names_the_first_chapter_that_uses_it():
    """A docstring's "Introduced in chapter N" is the first chapter whose cells call or name the function
    (``kf.sim.name`` anywhere, or ```name(`` in the prose); a function no chapter names is not checked."""
    chapters = {}
    for path in sorted((REPO / "notebooks").glob("[0-9][0-9]_*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        chapters[int(path.name[:2])] = "\n".join("".join(cell["source"]) for cell in cells)
    introductions = _introductions()
    assert len(introductions) > 100
    wrong = []
    for space, name, said in introductions:
        named = re.compile(rf"{re.escape(space)}\.{name}\b|`{name}\(")
        first = next((number for number, text in chapters.items() if named.search(text)), None)
        if first is not None and first != said:
            wrong.append(f"{space}.{name}: says chapter {said}, first used in chapter {first}")
    assert not wrong, "\n".join(wrong)


def _seeded() -> list:
    """Every public function and demo that takes a ``seed``, with the other arguments it needs."""
    needs = {
        "monte_carlo_drift": {"step_std": 0.05, "n": 10, "n_robots": 10},
        "range_particles": {"log": kf.data.load_plaza("Plaza2")},
        "plaza_family": {"log": kf.data.load_plaza("Plaza2"), "steps": 2, "n_particles": 10},
    }
    found = []
    for space in (kf.sim, kf.demos):
        for name in space.__all__:
            obj = getattr(space, name)
            if inspect.isfunction(obj) and "seed" in inspect.signature(obj).parameters:
                found.append(pytest.param(obj, needs.get(name, {}), id=f"{space.__name__}.{name}"))
    return found


@pytest.mark.parametrize(("function", "needs"), _seeded())
@pytest.mark.parametrize("seed", ["3", 1.5, -3, True, None])
def test_every_seed_is_checked_by_name(function, needs, seed):
    with pytest.raises(ValueError, match=r"^seed must be a whole number >= 0"):
        function(seed=seed, **needs)


# --------------------------------------------------------------------------- one job per module
PACKAGE = REPO / "kfcourse"


def test_no_two_modules_share_a_name():
    """A student told to open a module by its name lands in one file (filters/, sim/, plots/, demos/, check/)."""
    names: dict[str, list[str]] = {}
    for path in PACKAGE.rglob("*.py"):
        if path.name != "__init__.py":
            names.setdefault(path.name, []).append(str(path.relative_to(REPO)))
    assert not {name: where for name, where in names.items() if len(where) > 1}


def test_the_simulations_are_short_modules_of_short_functions():
    """kfcourse/sim: no module over 400 lines, no function (its docstring included) over 80."""
    import ast

    for path in sorted((PACKAGE / "sim").glob("*.py")):
        text = path.read_text()
        assert text.count("\n") <= 400, f"{path.name}: {text.count(chr(10))} lines"
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                first = min([node.lineno, *(d.lineno for d in node.decorator_list)])
                assert node.end_lineno - first + 1 <= 80, (
                    f"{path.name}: {node.name} is {node.end_lineno - first + 1} lines"
                )


def test_the_nees_is_computed_in_one_place():
    """Every NEES of the course is kf.sim.nees (sim/scores.py): no other simulation, demo or plot solves or
    inverts a covariance against an error (the filters' own gains and Mahalanobis distances aside)."""
    found = [
        str(p.relative_to(REPO))
        for part in ("sim", "demos", "plots")
        for p in (PACKAGE / part).glob("*.py")
        if re.search(r"linalg\.(solve|pinv|inv)\(", p.read_text()) and p.name != "scores.py"
    ]
    assert found == ["kfcourse/sim/target.py"] and "K = Sig_bar H^T S^-1" in (PACKAGE / "sim/target.py").read_text()
    for lap in (kf.sim.landmark_loop(0), kf.sim.particle_loop(0, n_particles=200)):
        assert np.array_equal(lap.nees, position_nees(lap))
    ekf = kf.sim.run_ekf(seed=0)  # chapter 7's runs keep only whether the truth is inside the 3σ ellipse
    assert np.array_equal(ekf.inside, position_nees(ekf) <= 9.0)


def position_nees(run) -> np.ndarray:
    """kf.sim.nees of a run's position at every step."""
    return kf.sim.nees(run.truth[:, :2], run.mu[:, :2], run.Sig[:, :2, :2])
