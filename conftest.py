"""Shared test configuration (at the root, so it also governs the notebooks).

A notebook cell run by nbval fails when it writes to stderr: that is where a
warning (or any other complaint) from a cell ends up, and nbval alone would let
it pass in a cell whose output is not compared.
"""

from __future__ import annotations

import pytest


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    result = yield
    for out in getattr(item, "test_outputs", None) or []:
        if out.get("output_type") == "stream" and out.get("name") == "stderr":
            pytest.fail(f"notebook cell wrote to stderr (a warning?):\n{out.get('text')}", pytrace=False)
    return result
