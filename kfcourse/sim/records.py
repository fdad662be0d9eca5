"""What every run record is made of: read-only arrays."""

from __future__ import annotations

import numpy as np


def read_only(a, dtype=float) -> np.ndarray:
    """A read-only copy of ``a`` (as ``dtype``; ``None`` keeps its own), so that a run
    record cannot be changed after the fact, nor through a view somebody else holds."""
    a = np.array(a, dtype=dtype)
    a.flags.writeable = False
    return a
