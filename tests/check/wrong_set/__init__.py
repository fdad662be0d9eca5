"""A fixed set of wrong (and right) solutions to the course's exercises, to measure the checkers by.

Each was written from an exercise's text in its chapter (``notebooks/NN_*.ipynb``), not from the
checkers' catalogue of known mistakes (``kfcourse/check/``), and says what it gets wrong:

- ``checker``: the name of the checker, ``kf.check.<checker>``;
- ``equation``: the chapter's label of the equation it breaks, as the chapter numbers it ("(4)"),
  or "" where the chapter numbers none;
- ``inputs``: the arguments whose part it gets wrong (those it ignores, misuses or puts in the wrong
  place), possibly none;
- ``what``: the mistake, in a sentence.

``python -m tests.check.wrong_set.report`` runs every one through its checker and reports what each
verdict says; ``tests/check/test_wrong_set.py`` holds the checkers to it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Solution:
    checker: str
    fn: Callable
    right: bool
    equation: str = ""
    inputs: tuple[str, ...] = ()
    what: str = ""


SOLUTIONS: list[Solution] = []


def wrong(checker: str, equation: str, inputs: tuple[str, ...] = (), what: str = ""):
    """Register the decorated function as a wrong solution for ``kf.check.<checker>``."""

    def register(fn: Callable) -> Callable:
        SOLUTIONS.append(Solution(checker, fn, False, equation, tuple(inputs), what))
        return fn

    return register


def right(checker: str, what: str = ""):
    """Register the decorated function as a right solution for ``kf.check.<checker>``, in a style of its own."""

    def register(fn: Callable) -> Callable:
        SOLUTIONS.append(Solution(checker, fn, True, what=what))
        return fn

    return register
