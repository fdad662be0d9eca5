"""Shared test configuration (at the root, so it also governs the notebooks).

A notebook cell run by nbval fails when it writes to stderr: that is where a
warning (or any other complaint) from a cell ends up, and nbval alone would let
it pass in a cell whose output is not compared.

``--perturb=SIZE`` scales every normal draw by ``1 + SIZE``, in the tests and in the
notebook kernels (``tests/rounding.py``): a run whose stated facts change under a
perturbation of 1e-12 states digits of this machine's rounding, not facts.
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
    size = config.getoption("--perturb")
    if size is None:
        return
    from tests import rounding

    rounding.perturb_noise(size)
    ipython_dir = Path(tempfile.mkdtemp(prefix="kfcourse-ipython-"))
    config.add_cleanup(lambda: shutil.rmtree(ipython_dir, ignore_errors=True))
    startup = ipython_dir / "profile_default" / "startup"
    startup.mkdir(parents=True)
    (startup / "00-perturb.py").write_text(rounding.startup_script(size))
    os.environ["IPYTHONDIR"] = str(ipython_dir)  # the notebook kernels nbval starts read it


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    result = yield
    for out in getattr(item, "test_outputs", None) or []:
        if out.get("output_type") == "stream" and out.get("name") == "stderr":
            pytest.fail(f"notebook cell wrote to stderr (a warning?):\n{out.get('text')}", pytrace=False)
    return result
