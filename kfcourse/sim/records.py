"""What every run record is made of: read-only arrays, frozen in one place (:class:`Record`)."""

from __future__ import annotations

import numpy as np


def read_only(a, dtype=float) -> np.ndarray:
    """A read-only copy of ``a`` (as ``dtype``; ``None`` keeps its own), so that a run
    record cannot be changed after the fact, nor through a view somebody else holds."""
    a = np.array(a, dtype=dtype)
    a.flags.writeable = False
    return a


class Record:
    """Base of every run record, a frozen dataclass: its array fields are stored as read-only copies.

    A record cannot be changed after the fact, nor through a view somebody else holds::

        @dataclass(frozen=True)
        class MyRun(Record):
            mu: np.ndarray
    """

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if isinstance(value, np.ndarray):
                object.__setattr__(self, name, read_only(value, dtype=None))
