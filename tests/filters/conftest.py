"""The filter tests' fixtures: defined in ``tests/filters/strategies.py`` with the rest of what
the tests share, and re-exported here so that pytest finds them."""

from tests.filters.strategies import rng  # noqa: F401
