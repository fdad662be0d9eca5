"""The machinery every checker shares: run cases, compare, find the first failure, name the mistake.

A checker is a list of :class:`Case` (inputs, each with a label saying what it
tests), the package's own function (the reference) and a list of :class:`Variant`
(known wrong versions, each with the mistake it makes and a hint).  :func:`run_check`
runs the student's function on every case and stops at the first one whose answer
differs from the reference.  It then runs each wrong variant on that same case:
a variant that gives the student's (wrong) answer names the likely mistake.  No
guessing: a mistake is named only when a known wrong version reproduces it.
"""

from __future__ import annotations

import contextlib
import copy
import html
import io
import traceback
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

RTOL = 1e-6  # relative tolerance of every comparison
ATOL = 1e-8  # absolute tolerance (for values near zero)

#: The mistakes a checker can recognise: catalogue key -> what went wrong, in general.
#: Each checker's variants add a hint that points at the equation of its chapter.
MISTAKES = {
    "not_normalised": "the result is not normalised",
    "shift_wrong_way": "the belief moves the wrong way",
    "ignores_boundary": "the boundary (wall or ring) is ignored",
    "leaks_at_wall": "probability leaks out at a wall",
    "swapped_R_Q": "R and Q are swapped",
    "std_not_var": "a standard deviation is used where a variance belongs (or the other way round)",
    "a_not_squared": "the variance is scaled by a instead of a²",
    "adds_variances": "the variances are added instead of fused",
    "missing_transpose": "a transpose is missing",
    "sign_flip": "a sign is flipped",
    "q_not_sqrt_q": "q and √q are mixed up",
    "atan_not_atan2": "atan is used instead of atan2",
    "divides_by_omega": "divides by ω, with no straight-line limit at ω = 0",
    "euler_step": "the pose moves in a straight line even while turning",
    "unwrapped_angle": "an angle is not wrapped into (−π, π]",
    "wrong_weights": "the weights are wrong",
    "points_as_columns": "the points are columns instead of rows",
    "not_cholesky": "a square root other than the lower Cholesky factor is used",
}


class Case:
    """One test case: named inputs (passed in this order) and a label saying what it tests."""

    def __init__(self, label: str, **inputs):
        self.label = label
        self.inputs = inputs

    def call(self, fn: Callable):
        """``fn`` on a fresh copy of the inputs (so a function that changes its inputs changes no other call)."""
        return fn(*copy.deepcopy(list(self.inputs.values())))


@dataclass(frozen=True)
class Variant:
    """A known wrong version of the function: the mistake it makes and a hint to fix it."""

    mistake: str  #: a key of MISTAKES
    fn: Callable  #: same signature as the reference, with that one mistake
    hint: str  #: where the right version is, in the chapter


@dataclass(frozen=True, repr=False)
class CheckResult:
    """The verdict of a checker.  Shown as the last line of a notebook cell, it prints itself.

    Attributes
    ----------
    passed : bool
        Whether the function matched the package on every case.
    mistake : str or None
        The key of :data:`MISTAKES` of the recognised mistake, or None (passed, not
        written yet, or a failure no known mistake explains).
    message : str
        The whole verdict as plain text.
    """

    passed: bool
    mistake: str | None
    message: str
    headline: str = field(default="", repr=False)  #: first line of the verdict
    details: str = field(default="", repr=False)  #: the failing case: inputs, expected, got
    hint: str = field(default="", repr=False)  #: the likely mistake and where to look

    def __repr__(self) -> str:
        return self.message

    def _repr_html_(self) -> str:
        colour = "#1b7f5f" if self.passed else ("#b35900" if self.details else "#555555")  # pass, fail, not yet
        parts = [f'<p style="color:{colour}"><b>{html.escape(self.headline)}</b></p>']
        if self.details:
            parts.append(f"<pre>{html.escape(self.details)}</pre>")
        if self.hint:
            parts.append(f"<p>{html.escape(self.hint)}</p>")
        return "<div>" + "".join(parts) + "</div>"


def _quietly(fn: Callable, case: Case):
    """Run ``fn`` on ``case`` without letting it print or warn: ("returned", value) or ("raised", error)."""
    try:
        with warnings.catch_warnings(), np.errstate(all="ignore"), contextlib.redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            return "returned", case.call(fn)
    except Exception as error:  # the student's code may raise anything; it becomes the verdict
        return "raised", error


def _parts(value, returns: tuple[str, ...]):
    """The values named in ``returns``, as a list, or None when ``value`` does not have that many."""
    if len(returns) == 1:
        return [value]
    if isinstance(value, (tuple, list)) and len(value) == len(returns):
        return list(value)
    return None


def _as_array(x):
    """``x`` as a float array, or None if it is not numbers."""
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        return None


def problem(expected, got, returns: tuple[str, ...]) -> str | None:
    """What is wrong with ``got`` in a few words, or None when it matches ``expected``."""
    parts = _parts(got, returns)
    if parts is None:
        return f"it returned {_kind(got)}; expected {len(returns)} values ({', '.join(returns)})"
    for name, e, g in zip(returns, _parts(expected, returns), parts, strict=True):
        e, a = np.asarray(e, dtype=float), _as_array(g)
        if a is None:
            return f"{name} is not a number or an array of numbers"
        if a.shape != e.shape and not (e.ndim == 0 and a.size == 1):
            return f"{name} has shape {a.shape}; expected {e.shape if e.ndim else 'a single number'}"
        if np.isnan(a).any():
            return f"{name} contains NaN"
        if np.isinf(a).any():
            return f"{name} contains inf"
        if not np.allclose(a.reshape(e.shape), e, rtol=RTOL, atol=ATOL):
            return f"{name} has the wrong value"
    return None


def _same_outcome(mine, theirs, returns: tuple[str, ...]) -> bool:
    """Whether two outcomes of :func:`_quietly` agree: equal values (NaN where NaN), or the same error."""
    if mine[0] != theirs[0]:
        return False
    if mine[0] == "raised":
        return type(mine[1]) is type(theirs[1]) and str(mine[1]) == str(theirs[1])
    a, b = _parts(mine[1], returns), _parts(theirs[1], returns)
    if a is None or b is None:
        return False
    for x, y in zip(a, b, strict=True):
        x, y = _as_array(x), _as_array(y)
        if x is None or y is None or x.shape != y.shape:
            return False
        if not np.allclose(x, y, rtol=RTOL, atol=ATOL, equal_nan=True):
            return False
    return True


def _kind(x) -> str:
    if isinstance(x, (tuple, list)):
        return f"a {type(x).__name__} of {len(x)}"
    if x is None:
        return "None"
    return f"one {type(x).__name__}"


def show(x) -> str:
    """A short, readable text for an input or output value."""
    if isinstance(x, Mapping):
        return "{" + ", ".join(f"{k!r}: {show(p)}" for k, p in x.items()) + "}"
    if x is None or isinstance(x, str):
        return repr(x)
    a = _as_array(x)
    if a is None or a.dtype == object:
        text = repr(x)
        return text if len(text) < 300 else text[:300] + " ..."
    if a.ndim == 0:
        return f"{float(a):.6g}"
    return np.array2string(a, precision=6, suppress_small=True, separator=", ", max_line_width=100)


def _block(named: list[tuple[str, object]]) -> str:
    """``name = value`` lines, continuation lines of a matrix lined up under its first row."""
    width = max(len(name) for name, _ in named)
    lines = []
    for name, value in named:
        text = show(value).replace("\n", "\n" + " " * (width + 7))
        lines.append(f"    {name:<{width}} = {text}")
    return "\n".join(lines)


def _named(value, returns):
    parts = _parts(value, returns)
    return list(zip(returns, parts, strict=True)) if parts is not None else [("returned", value)]


def _where(error: Exception, fn: Callable) -> str:
    """The line of ``fn``'s own code that raised ``error`` (the deepest one, if it calls itself)."""
    frames = traceback.extract_tb(error.__traceback__)
    own = getattr(getattr(fn, "__code__", None), "co_filename", None)
    frames = [f for f in frames if f.filename == own] or frames[-1:]
    if not frames:
        return ""
    last = frames[-1]
    return f"\n    raised in {last.name}, line {last.lineno}: {last.line}"


def random_covariance(rng: np.random.Generator, n: int, scale: float = 1.0) -> np.ndarray:
    """A random symmetric positive definite n x n matrix, correlated (not diagonal)."""
    A = rng.normal(size=(n, n))
    return scale * (A @ A.T / n + 0.2 * np.eye(n))


def run_check(
    name: str,
    student_fn: Callable,
    reference: Callable,
    cases: list[Case],
    variants: list[Variant],
    returns: tuple[str, ...],
    where: str,
) -> CheckResult:
    """Run ``student_fn`` on every case and compare with ``reference``; name the likely mistake.

    Parameters
    ----------
    name : str
        The package function checked, e.g. ``"kf_step"``.
    student_fn : callable
        The student's function, with the same signature as the reference.
    reference : callable
        The package's function.
    cases : list of Case
    variants : list of Variant
        Known wrong versions; the first that reproduces the student's answer on
        the first failing case names the mistake.
    returns : tuple of str
        Names of the returned values (one name: a single value, not a tuple).
    where : str
        The chapter's equation to compare with, e.g. ``"chapter 5, equations (1)-(5)"``.

    Returns
    -------
    CheckResult
    """
    if not callable(student_fn):
        raise ValueError(
            f"student_fn must be your function itself, e.g. kf.check.{name}(my_{name}); got {student_fn!r}"
        )
    who = getattr(student_fn, "__name__", "your function")
    for number, case in enumerate(cases, start=1):
        outcome = _quietly(student_fn, case)
        if outcome[0] == "raised" and isinstance(outcome[1], NotImplementedError):
            headline = f"✎ Not yet: {who} raises NotImplementedError. Write its body, then run this cell again."
            return CheckResult(False, None, headline, headline)
        expected = case.call(reference)
        if outcome[0] == "raised":
            error = outcome[1]
            what = f"it raised {type(error).__name__}: {str(error).rstrip('.')}"
        else:
            what = problem(expected, outcome[1], returns)
            if what is None:
                continue
        headline = f"✘ {who} is not right yet: on case {number} of {len(cases)} ({case.label}), {what}."
        details = "inputs:\n" + _block(list(case.inputs.items()))
        details += "\nexpected:\n" + _block(_named(expected, returns))
        if outcome[0] == "raised":
            details += _where(outcome[1], student_fn)
        else:
            details += "\ngot:\n" + _block(_named(outcome[1], returns))
        mistake, hint = None, f"No known mistake gives this answer. Compare your code with {where}."
        for variant in variants:
            if _same_outcome(_quietly(variant.fn, case), outcome, returns):
                mistake = variant.mistake
                hint = f"Likely mistake: {MISTAKES[mistake]}. {variant.hint} See {where}."
                break
        message = "\n".join([headline, details, hint])
        return CheckResult(False, mistake, message, headline, details, hint)
    labels = list(dict.fromkeys(case.label.split(":")[0] for case in cases))  # each kind of case once, in order
    headline = f"✔ {who} matches kf.{name} on all {len(cases)} cases: {'; '.join(labels)}."
    return CheckResult(True, None, headline, headline)
