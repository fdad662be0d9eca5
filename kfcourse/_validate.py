"""Input checks shared by every public function.

Each check returns a clean ``float`` array (or ``float``) and raises
``ValueError`` whose message starts with the argument's name and says what was
expected.  Every call checks its inputs in full.  A small array (a pose, a reading, a
3x3 covariance) is checked on Python floats, where one numpy call would cost more than
the whole check; a large one with numpy.  Both paths test the same thing.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Mapping

import numpy as np

_SYM_RTOL = 1e-9  # relative asymmetry tolerated in a covariance
_PSD_RTOL = 1e-9  # relative negative eigenvalue tolerated in a covariance
_SUM_ATOL = 1e-6  # how far a probability vector may be from summing to 1
_SMALL = 16  # entries: an array this small is checked on Python floats
_TEXT, _SEQUENCES = (str, bytes), (list, tuple)  # text is never a number; a list or tuple may hold some


def _floats(x, name: str) -> np.ndarray:
    """``x`` as a float array, rejecting non-numbers, a string of digits such as "3.6" too (NaN and inf are
    left to the caller)."""
    if isinstance(x, _TEXT) or (type(x) in _SEQUENCES and any(isinstance(e, _TEXT) for e in x)):
        raise ValueError(f"{name} must be numeric, got {x!r}")
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numeric, got {x!r}") from None


def finite(x, name: str) -> np.ndarray:
    """Return ``x`` as a float array, rejecting NaN, inf and non-numbers."""
    a = _floats(x, name)
    if not (all(map(math.isfinite, a.ravel().tolist())) if a.size <= _SMALL else np.isfinite(a).all()):
        raise ValueError(f"{name} must be finite (no NaN or inf), got {x!r}")
    return a


def scalar(x, name: str) -> float:
    """A finite real number."""
    if isinstance(x, float) and math.isfinite(x):  # already one (a Python or numpy float)
        return float(x)
    a = finite(x, name)
    if a.size != 1:
        raise ValueError(f"{name} must be a scalar, got shape {a.shape}")
    return float(a.reshape(()))


def _units(unit: str) -> str:
    return f" {unit}" if unit else ""


def positive(x, name: str, what: str, unit: str = "") -> float:
    """A finite number ``> 0``; ``what`` says what it is ("a time step", unit "s")."""
    value = scalar(x, name)
    if not value > 0:
        raise ValueError(f"{name} must be {what} > 0{_units(unit)}, got {value}")
    return value


def non_negative(x, name: str, what: str, unit: str = "") -> float:
    """A finite number ``>= 0``; ``what`` says what it is ("a standard deviation", unit "m")."""
    value = scalar(x, name)
    if not value >= 0:
        raise ValueError(f"{name} must be {what} >= 0{_units(unit)}, got {value}")
    return value


def variance(x, name: str) -> float:
    """A finite variance, ``>= 0``."""
    return non_negative(x, name, "a variance")


def probability(x, name: str) -> float:
    """A finite number in ``[0, 1]``."""
    p = scalar(x, name)
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"{name} must be a probability in [0, 1], got {p}")
    return p


def whole(x, name: str, least: int = 0) -> int:
    """A whole number (not a bool) ``>= least``: a count of steps, cells, laps, or a seed."""
    if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or x < least:
        raise ValueError(f"{name} must be a whole number >= {least}, got {x!r}")
    return int(x)


def flag(x, name: str) -> bool:
    """A switch: ``True`` or ``False`` (a numpy bool too), not 0, 1 or a string."""
    if not isinstance(x, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {x!r}")
    return bool(x)


def flags(x, name: str) -> np.ndarray:
    """An array of switches, each True or False (numpy bools, or the numbers 0 and 1), not NaN, 0.5 or text."""
    a = np.asarray(x)
    if a.dtype == bool:
        return a
    f = _floats(x, name)
    if not np.isin(f, (0.0, 1.0)).all():
        raise ValueError(f"{name} must hold True or False values, got {x!r}")
    return f.astype(bool)


def generator(rng, name: str) -> np.random.Generator:
    """A numpy random Generator, the source of a function's draws."""
    if not isinstance(rng, np.random.Generator):
        raise ValueError(f"{name} must be a numpy random Generator, e.g. np.random.default_rng(seed); got {rng!r}")
    return rng


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


def _shaped(a: np.ndarray, name: str, rows: int | None, cols: int | None) -> np.ndarray:
    """The float array ``a`` as a 2-D ``(rows, cols)`` matrix; a scalar becomes 1x1 and a 1-D array one row."""
    if a.ndim < 2:
        a = a.reshape(1, -1)
    if a.ndim != 2:
        raise ValueError(f"{name} must be a 2-D matrix, got shape {a.shape}")
    if (rows is not None and a.shape[0] != rows) or (cols is not None and a.shape[1] != cols):
        want = f"({'n' if rows is None else rows}, {'m' if cols is None else cols})"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    return a


def matrix(x, name: str, rows: int | None = None, cols: int | None = None) -> np.ndarray:
    """A finite 2-D array; a scalar becomes 1x1 and a 1-D array one row."""
    return _shaped(finite(x, name), name, rows, cols)


def _square(a: np.ndarray, name: str, n: int | None) -> np.ndarray:
    """The float array ``a`` as a non-empty, square ``(n, n)`` matrix; a scalar becomes 1x1."""
    a = _shaped(a, name, n, n)
    if a.size == 0:
        raise ValueError(f"{name} must not be empty")
    if a.shape[0] != a.shape[1]:
        raise ValueError(f"{name} must be a square covariance matrix, got shape {a.shape}")
    return a


def covariance(x, name: str, n: int | None = None) -> np.ndarray:
    """A finite, symmetric, positive semi-definite ``(n, n)`` matrix (``n=None``: any size).

    Symmetric and positive semi-definite up to rounding: an asymmetry, or a negative
    eigenvalue, smaller than ``1e-9`` times the matrix's largest entry is allowed.  A
    singular covariance is fine, such as the process noise of a constant-velocity model.
    """
    a = _square(finite(x, name), name, n)
    if a.size <= _SMALL:  # the same tests on Python floats
        entries, mirrored = a.ravel().tolist(), a.T.ravel().tolist()
        scale = max(map(abs, entries))
        asymmetry = max(map(abs, map(operator.sub, entries, mirrored)))
    else:
        scale, asymmetry = np.abs(a).max(), np.abs(a - a.T).max()
    if asymmetry > _SYM_RTOL * scale:
        raise ValueError(f"{name} must be a symmetric covariance matrix, got {a.tolist()}")
    if _positive_definite(a):
        return a  # the common case: every eigenvalue above 0
    lowest = np.linalg.eigvalsh(a)[0]  # semi-definite is fine: look at the smallest eigenvalue
    if lowest < -_PSD_RTOL * scale:
        raise ValueError(f"{name} must be positive semi-definite (a covariance), but has eigenvalue {lowest:.3g}")
    return a


def _positive_definite(a: np.ndarray) -> bool:
    """Whether the Cholesky factorisation of the symmetric matrix ``a`` (from its lower triangle) finds
    every pivot > 0, which holds when ``a`` is positive definite (up to rounding far below the tolerance
    of :func:`covariance`); by hand on Python floats for a small matrix, by numpy for a large one."""
    if a.size > _SMALL:
        try:
            np.linalg.cholesky(a)
        except np.linalg.LinAlgError:
            return False
        return True
    rows = a.tolist()
    L = []  # A = L L^T, row by row
    for i, row in enumerate(rows):
        Li = []
        for j in range(i):  # L_ij = (A_ij - sum_k L_ik L_jk) / L_jj
            Li.append((row[j] - sum(map(operator.mul, Li, L[j]))) / L[j][j])
        pivot = row[i] - sum(map(operator.mul, Li, Li))  # L_ii^2 = A_ii - sum_k L_ik^2
        if not pivot > 0.0:
            return False
        L.append([*Li, math.sqrt(pivot)])
    return True


def covariance_stack(x, name: str, N: int, n: int) -> np.ndarray:
    """A finite (N, n, n) stack of symmetric positive semi-definite matrices (one covariance per
    filter of a batch), checked all at once with the tolerances of :func:`covariance`."""
    a = finite(x, name)
    if a.shape != (N, n, n):
        raise ValueError(f"{name} must have shape ({N}, {n}, {n}), one covariance per filter, got {a.shape}")
    scale = np.abs(a).max(axis=(1, 2))  # (N,)
    asymmetry = np.abs(a - a.transpose(0, 2, 1)).max(axis=(1, 2))
    bad = np.flatnonzero(asymmetry > _SYM_RTOL * scale)
    if bad.size:
        raise ValueError(f"{name}[{bad[0]}] must be a symmetric covariance matrix, got {a[bad[0]].tolist()}")
    try:
        np.linalg.cholesky(a)  # succeeds only if every one is positive definite: the common case
    except np.linalg.LinAlgError:
        lowest = np.linalg.eigvalsh(a)[:, 0]  # semi-definite is fine: look at the smallest eigenvalue of each
        bad = np.flatnonzero(lowest < -_PSD_RTOL * scale)
        if bad.size:
            i = bad[0]
            raise ValueError(
                f"{name}[{i}] must be positive semi-definite (a covariance), but has eigenvalue {lowest[i]:.3g}"
            ) from None
    return a


def update_inputs(mu_bar, Sig_bar, z, Q) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The inputs every measurement update shares: the predicted belief
    ``mu_bar`` (n,), ``Sig_bar`` (n, n), the reading ``z`` (k,) and its noise
    covariance ``Q`` (k, k), each checked on its own; that z and Q agree on k is
    for :func:`reading_size`, with the update's other inputs that carry k."""
    mu_bar = vector(mu_bar, "mu_bar")
    Sig_bar = covariance(Sig_bar, "Sig_bar", mu_bar.size)
    return mu_bar, Sig_bar, vector(z, "z"), covariance(Q, "Q")


LENGTH, ROWS, SQUARE = "length {}", "{} rows", "shape ({0}, {0})"  # how an input carries k, for reading_size


def reading_size(**carriers: tuple[int, str]) -> int:
    """k, the size of one reading, on which every input that carries it agrees.

    ``carriers`` maps each input, in the order of the signature, to the k it carries and how
    (:data:`LENGTH`, :data:`ROWS`, :data:`SQUARE`): ``z=(3, LENGTH), Q=(2, SQUARE)``.  When they
    disagree, the input that disagrees with all the others is named; of two, the second is named
    against the first."""
    items = list(carriers.items())
    sizes = {k for k, _ in carriers.values()}
    if len(sizes) == 1:
        return sizes.pop()
    for i, (name, (k, how)) in enumerate(items):
        rest = items[:i] + items[i + 1 :]
        agreed = {other_k for _, (other_k, _) in rest}
        if len(agreed) == 1 and (len(items) > 2 or i == len(items) - 1):
            want = agreed.pop()
            why = " and ".join(f"{other} has {other_how.format(other_k)}" for other, (other_k, other_how) in rest)
            raise ValueError(f"{name} must have {how.format(want)}, as {why}; got {how.format(k)}")
    said = ", ".join(f"{name} has {how.format(k)}" for name, (k, how) in items)
    raise ValueError(f"{said}: they must agree on the size of one reading")


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


def output(y, name: str, n: int | None = None) -> np.ndarray:
    """The result of a model callable: a finite vector (of length ``n`` if given)."""
    return vector(y, f"the result of {name}", n)


def output_matrix(y, name: str, rows: int, cols: int) -> np.ndarray:
    """The result of a Jacobian callable: a finite ``(rows, cols)`` matrix."""
    return matrix(y, f"the result of {name}", rows, cols)
