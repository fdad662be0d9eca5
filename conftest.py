"""Shared test configuration (at the root, so it also governs the notebooks).

A notebook cell run by nbval fails when it writes to stderr: that is where a
warning (or any other complaint) from a cell ends up, and nbval alone would let
it pass in a cell whose output is not compared.

``--perturb=SIZE`` scales every normal draw by ``1 + SIZE``, in the tests and in the
notebook kernels (``tests/rounding.py``): a run whose stated facts change under a
perturbation of 1e-12 states digits of this machine's rounding, not facts.

The frozen runs the tests share are built once per process (``tests/frozen_runs.py``).

In a repeat (``--perturb``) the demos and charts draw no pixels: ``FigureRenderer`` hands out a
blank picture, since what a repeat checks is a run's numbers and the words and artists made of them,
and drawing is most of a demo test's time.  A test that reads what is drawn (the picture changing,
a label's extent, which artists redraw) is marked ``pixels``, and its pictures are drawn.

Every notebook cell is marked ``fact``: a chapter states facts of its seeded runs.  In a run without
``--perturb``, a test that runs a seeded simulation without the ``fact`` marker fails
(``tests/facts.py``): the repeats select by that marker.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import pytest


def pytest_addoption(parser):
    parser.addoption(
        "--perturb",
        type=float,
        default=None,
        metavar="SIZE",
        help="scale every normal draw by 1 + SIZE, in the tests and the notebook kernels (tests/rounding.py)",
    )


def pytest_configure(config):
    from tests import facts, frozen_runs

    frozen_runs.install(facts.count_one)  # each frozen run built once per process (tests/frozen_runs.py)
    size = config.getoption("--perturb")
    if size is None:
        facts.install()
        return
    from tests import rounding

    rounding.perturb_noise(size)
    ipython_dir = Path(tempfile.mkdtemp(prefix="kfcourse-ipython-"))
    config.add_cleanup(lambda: shutil.rmtree(ipython_dir, ignore_errors=True))
    startup = ipython_dir / "profile_default" / "startup"
    startup.mkdir(parents=True)
    (startup / "00-perturb.py").write_text(rounding.startup_script(size))
    os.environ["IPYTHONDIR"] = str(ipython_dir)  # the notebook kernels nbval starts read it


def pytest_collection_modifyitems(config, items):
    for item in items:
        if item.path.suffix == ".ipynb":
            item.add_marker(pytest.mark.fact)


@pytest.fixture(autouse=True)
def _no_pixels_in_a_repeat(request, monkeypatch):
    """In a repeat, a test not marked ``pixels`` gets blank pictures (see the module's text)."""
    if request.config.getoption("--perturb") is None or request.node.get_closest_marker("pixels"):
        return
    from PIL import Image

    from kfcourse.plots.style import FigureRenderer

    monkeypatch.setattr(FigureRenderer, "_render", lambda self, mode: Image.new(mode, (2, 2)))


@pytest.hookimpl(wrapper=True)
def pytest_fixture_setup(fixturedef, request):
    from tests import facts

    before = facts.made()
    result = yield
    if facts.made() > before:  # the fixture runs a seeded simulation: so does every test that uses it
        facts.seeded_fixtures.add(fixturedef)
    return result


@pytest.hookimpl(wrapper=True)
def pytest_runtest_setup(item):
    from tests import facts

    item.generators_before = facts.made()
    return (yield)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    from tests import facts

    result = yield
    if item.config.getoption("--perturb") is None and item.path.suffix != ".ipynb":
        complaint = facts.complaint(item)
        if complaint:
            pytest.fail(complaint, pytrace=False)
    for out in getattr(item, "test_outputs", None) or []:
        if out.get("output_type") == "stream" and out.get("name") == "stderr":
            pytest.fail(f"notebook cell wrote to stderr (a warning?):\n{out.get('text')}", pytrace=False)
    return result
