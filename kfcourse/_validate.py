"""Input checks shared by every public function.

Each check returns a clean ``float`` array and raises ``ValueError`` naming the
argument and what was expected.  They are deliberately cheap: the filters call
them on every step.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Callable, Mapping

import numpy as np

_SYM_RTOL = 1e-9  # relative asymmetry tolerated in a covariance
_PSD_RTOL = 1e-9  # relative negative eigenvalue tolerated in a covariance
_SUM_ATOL = 1e-6  # how far a probability vector may be from summing to 1

_FLOAT = np.dtype(float)
_SMALL = 64  # arrays up to this many elements are summed in Python to test finiteness (faster)
_SMALL_CHOLESKY = 4  # rows up to which the positive-definiteness test runs in Python (faster)
_CONSTANT_MAX_SIZE = 1024  # elements; larger constant matrices are not remembered
_CONSTANT_MAX_COUNT = 64  # constant matrices remembered before the memory is cleared
_valid_constants: dict[tuple, None] = {}  # (kind, shape, bytes) of constant matrices that passed


_PRODUCED_MAX_COUNT = 64  # covariances remembered before the memory is cleared
_produced: dict[int, tuple[weakref.ref, bytes]] = {}  # covariances a filter step returned, by id


def produced(a: np.ndarray) -> np.ndarray:
    """Remember a covariance that a filter step computed (symmetric and positive
    semi-definite by construction) so that passing it straight back into the next
    step skips the symmetry and definiteness checks.  Its bytes are remembered
    too: an array changed in place since is checked in full again."""
    if _all_finite(a):
        if len(_produced) >= _PRODUCED_MAX_COUNT:
            _produced.clear()
        _produced[id(a)] = (weakref.ref(a), a.tobytes())
    return a


def _was_produced(x) -> bool:
    entry = _produced.get(id(x))
    return entry is not None and entry[0]() is x and x.tobytes() == entry[1]


def _all_finite(a: np.ndarray) -> bool:
    """Whether every element of a float array is finite.

    For a small array a Python sum is the cheapest test: it is finite only if
    every term is, and a non-finite sum may be an overflow, so then look properly.
    """
    if a.size <= _SMALL and math.isfinite(sum(a.ravel().tolist())):
        return True
    return bool(np.isfinite(a).all())


def finite(x, name: str) -> np.ndarray:
    """Return ``x`` as a float array, rejecting NaN, inf and non-numbers."""
    if type(x) is np.ndarray and x.dtype == _FLOAT:
        a = x  # already a float array: what np.asarray would return
    else:
        try:
            a = np.asarray(x, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be numeric, got {x!r}") from None
    if not _all_finite(a):
        raise ValueError(f"{name} must be finite (no NaN or inf), got {x!r}")
    return a


def scalar(x, name: str) -> float:
    """A finite real number."""
    if type(x) is float and math.isfinite(x):
        return x
    a = finite(x, name)
    if a.size != 1:
        raise ValueError(f"{name} must be a scalar, got shape {a.shape}")
    return float(a.reshape(()))


def variance(x, name: str, *, positive: bool = False) -> float:
    """A finite variance, ``>= 0`` (or ``> 0`` with ``positive``)."""
    v = scalar(x, name)
    if v < 0 or (positive and v == 0):
        need = "> 0" if positive else ">= 0"
        raise ValueError(f"{name} is a variance and must be {need}, got {v}")
    return v


def vector(x, name: str, n: int | None = None) -> np.ndarray:
    """A finite 1-D array (a scalar becomes length 1), of length ``n`` if given."""
    a = finite(x, name)
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise ValueError(f"{name} must be a 1-D vector, got shape {a.shape}")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name} must have length {n}, got length {a.shape[0]}")
    return a


def matrix(x, name: str, rows: int | None = None, cols: int | None = None) -> np.ndarray:
    """A finite 2-D array; a scalar becomes 1x1 and a 1-D array one row."""
    a = finite(x, name)
    if a.ndim < 2:
        a = a.reshape(1, -1)
    if a.ndim != 2:
        raise ValueError(f"{name} must be a 2-D matrix, got shape {a.shape}")
    if (rows is not None and a.shape[0] != rows) or (cols is not None and a.shape[1] != cols):
        want = f"({'n' if rows is None else rows}, {'m' if cols is None else cols})"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    return a


def _constant_key(x, kind: str):
    """Key under which a small float matrix that passed a check is remembered."""
    if type(x) is np.ndarray and x.dtype == _FLOAT and x.ndim == 2 and x.size <= _CONSTANT_MAX_SIZE:
        return (kind, x.shape, x.tobytes())
    return None


def _remember(key) -> None:
    if key is not None:
        if len(_valid_constants) >= _CONSTANT_MAX_COUNT:
            _valid_constants.clear()
        _valid_constants[key] = None


def constant_matrix(x, name: str, rows: int | None = None, cols: int | None = None) -> np.ndarray:
    """:func:`matrix` for a model matrix passed unchanged on every step (F, B, H):
    a float array that already passed is remembered by its shape and bytes."""
    key = _constant_key(x, "matrix")
    if key in _valid_constants and (rows is None or x.shape[0] == rows) and (cols is None or x.shape[1] == cols):
        return x
    a = matrix(x, name, rows, cols)
    _remember(key)
    return a


def covariance(x, name: str, n: int | None = None, *, constant: bool = False) -> np.ndarray:
    """A finite, symmetric, positive semi-definite ``(n, n)`` matrix.

    With ``constant`` (for a model's noise covariance, passed unchanged on every
    step) a float array that already passed is remembered by its shape and
    bytes, so the same matrix is not checked again.  A covariance that a filter
    step returned (see :func:`produced`) is not checked again either.
    """
    if type(x) is np.ndarray and _was_produced(x) and (n is None or x.shape == (n, n)):
        return x
    key = _constant_key(x, "covariance") if constant else None
    if key in _valid_constants and (n is None or x.shape == (n, n)):
        return x
    a = matrix(x, name, n, n)
    if a.size == 0:
        raise ValueError(f"{name} must not be empty")
    if a.shape[0] != a.shape[1]:
        raise ValueError(f"{name} must be a square covariance matrix, got shape {a.shape}")
    _check_symmetric_psd(a, name)
    _remember(key)
    return a


def _check_symmetric_psd(a: np.ndarray, name: str) -> None:
    """Raise unless the finite square ``a`` is symmetric and positive semi-definite."""
    exactly_symmetric = a.tobytes() == a.T.tobytes()
    if exactly_symmetric and a.shape[0] > 1 and _cholesky_succeeds(a):
        return  # positive definite; otherwise maybe semi-definite: look at the eigenvalues
    scale = float(np.abs(a).max()) if a.size else 0.0
    if not exactly_symmetric and np.abs(a - a.T).max(initial=0.0) > _SYM_RTOL * scale:
        raise ValueError(f"{name} must be a symmetric covariance matrix, got {a.tolist()}")
    if a.shape[0] == 1:
        lowest = a[0, 0]
    else:
        lowest = np.linalg.eigvalsh(a)[0]
    if lowest < -_PSD_RTOL * scale:
        raise ValueError(f"{name} must be positive semi-definite (a covariance), but has eigenvalue {lowest:.3g}")


def _cholesky_succeeds(a: np.ndarray) -> bool:
    """Whether the lower Cholesky factorisation of the finite symmetric ``a`` succeeds.

    Success proves ``a`` positive definite (up to rounding far below the PSD
    tolerance).  Up to _SMALL_CHOLESKY rows it runs in Python floats, which costs
    less than a LAPACK call's overhead; any non-finite pivot counts as failure.
    """
    if a.shape[0] > _SMALL_CHOLESKY:
        try:
            np.linalg.cholesky(a)
        except np.linalg.LinAlgError:
            return False
        return True
    rows = a.tolist()
    L: list[list[float]] = []
    for j, row in enumerate(rows):
        Lj = []
        for i in range(j):  # L[j][i] = (a[j][i] - sum_k L[j][k] L[i][k]) / L[i][i]
            Li = L[i]
            s = row[i]
            for k in range(i):
                s -= Lj[k] * Li[k]
            Lj.append(s / Li[i])
        d = row[j]  # pivot: a[j][j] - sum_k L[j][k]^2
        for x in Lj:
            d -= x * x
        if not 0.0 < d < math.inf:
            return False
        Lj.append(math.sqrt(d))
        L.append(Lj)
    return True


def probabilities(x, name: str) -> np.ndarray:
    """A 1-D array of non-negative numbers that sums to 1."""
    p = vector(x, name)
    if p.size == 0:
        raise ValueError(f"{name} must not be empty")
    if (p < 0).any():
        raise ValueError(f"{name} holds probabilities and must be >= 0, got {p.tolist()}")
    total = float(p.sum())
    if abs(total - 1.0) > _SUM_ATOL:
        raise ValueError(f"{name} must sum to 1, but sums to {total:.6g}")
    return p


def kernel(k, name: str) -> dict[int, float]:
    """A mapping ``offset -> probability`` whose probabilities sum to 1."""
    if not isinstance(k, Mapping) or not k:
        raise ValueError(f"{name} must be a non-empty mapping offset -> probability, got {k!r}")
    out: dict[int, float] = {}
    for off, p in k.items():
        try:
            whole = not isinstance(off, bool) and float(off).is_integer()
        except (TypeError, ValueError):
            whole = False
        if not whole:
            raise ValueError(f"{name} offsets must be whole numbers of cells, got {off!r}")
        prob = scalar(p, f"{name}[{off}]")
        if prob < 0:
            raise ValueError(f"{name}[{off}] is a probability and must be >= 0, got {prob}")
        out[int(off)] = prob
    total = math.fsum(out.values())
    if abs(total - 1.0) > _SUM_ATOL:
        raise ValueError(f"{name} probabilities must sum to 1, but sum to {total:.6g}")
    return out


def function(f, name: str) -> Callable:
    """A callable."""
    if not callable(f):
        raise ValueError(f"{name} must be callable, got {f!r}")
    return f


def optional_function(f, name: str) -> Callable | None:
    """A callable or None (an optional hook such as ``residual``)."""
    return None if f is None else function(f, name)


def output(y, name: str, n: int) -> np.ndarray:
    """The result of a model callable: a finite vector of length ``n``."""
    return vector(y, f"the result of {name}", n)


def output_matrix(y, name: str, rows: int, cols: int) -> np.ndarray:
    """The result of a Jacobian callable: a finite ``(rows, cols)`` matrix."""
    return matrix(y, f"the result of {name}", rows, cols)
