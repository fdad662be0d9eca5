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


def text_table(header: list[str], rows: list[list[str]]) -> str:
    """A plain-text table: the header, a rule, then one line per row, each column as wide as its widest cell.

    The cells are strings already formatted by the caller (units and digits are theirs to choose),
    so that a run record's ``table()`` can print itself in a notebook without a loop in the cell.
    The first column is left-aligned, the others right-aligned (numbers).
    """
    lines = [list(header), *[list(row) for row in rows]]
    if any(len(line) != len(header) for line in lines):
        raise ValueError(f"rows must each have {len(header)} cells, one per header")
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]

    def fmt(line):
        cells = zip(line, widths, strict=True)
        return "  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(cells))

    return "\n".join([fmt(lines[0]), "  ".join("-" * w for w in widths), *(fmt(line) for line in lines[1:])])
