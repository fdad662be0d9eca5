"""Shared test configuration.

Notebook cells run by nbval fail when they write to stderr: that is where a
warning (or any other complaint) from a cell ends up.
"""

from __future__ import annotations

import pytest


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item):
    yield
    outputs = getattr(item, "test_outputs", None) or []
    for out in outputs:
        if out.get("output_type") == "stream" and out.get("name") == "stderr":
            pytest.fail(f"notebook cell wrote to stderr (a warning?):\n{out.get('text')}", pytrace=False)
