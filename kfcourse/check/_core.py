"""The machinery every checker shares: run cases, compare, find the first failure, name the mistake.

A checker is a list of :class:`Case` (inputs, each with a label saying what it
tests), the package's own function (the reference) and a list of :class:`Variant`
(known wrong versions, each with the mistake it makes and a hint).  :func:`run_check`
runs the student's function on every case and stops at the first one whose answer
differs from the reference.  It then runs each wrong variant on every case: a variant
that gives the student's answer on all of them names the likely mistake, unless
another mistake does too (then both are said and neither is named).  No guessing:
a mistake is named only when a known wrong version reproduces it everywhere.
Without a name, a checker that declares its steps (:class:`Step`) and inputs
(:class:`Probe`) says which step is wrong on its own and which input an output
ignores or follows where the right one does not.
"""

from __future__ import annotations

import contextlib
import copy
import html
import io
import itertools
import math
import re
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
    "wall_sends_back": "a move that would pass a wall leaves the robot where it started",
    "overwrites_not_adds": "a contribution overwrites a cell instead of adding to it",
    "adds_not_multiplies": "the likelihood is added to the belief instead of multiplied",
    "swapped_R_Q": "R and Q are swapped",
    "std_not_var": "a standard deviation is used where a variance belongs (or the other way round)",
    "a_not_squared": "the variance is scaled by a instead of a²",
    "adds_variances": "the variances are added instead of fused",
    "forgot_R": "the process noise R is never added",
    "forgot_Q": "the measurement noise Q is left out",
    "forgot_control": "the control term (bu, Bu) is left out",
    "c_left_out": "c is left out of the update (its c = 1 form is used)",
    "prior_not_predicted": "the previous belief (μ, Σ) is used where the predicted one (μ̄, Σ̄) belongs",
    "no_inverse": "S is multiplied where its inverse S⁻¹ belongs",
    "elementwise_inverse": "1/S, entry by entry, is used where the matrix inverse S⁻¹ belongs",
    "wrong_order": "a matrix product is taken in the wrong order",
    "missing_transpose": "a transpose is missing",
    "sign_flip": "a sign is flipped",
    "q_not_sqrt_q": "q and √q are mixed up",
    "atan_not_atan2": "atan is used instead of atan2",
    "atan2_arguments_swapped": "atan2's arguments are swapped: it takes (Δy, Δx)",
    "robot_minus_landmark": "Δx and Δy point from the landmark to the robot (robot minus landmark)",
    "position_entries_flipped": (
        "every position entry of H has the wrong sign: Δx and Δy taken from the landmark to the robot, or H "
        "differentiated with respect to the landmark's position instead of the robot's"
    ),
    "wrap_shifted_by_pi": "the angle is wrapped by (φ mod 2π) − π, which also turns it by π",
    "heading_sign": "the heading θ enters with the wrong sign",
    "degrees": "an angle is in degrees where radians belong",
    "outputs_swapped": "the outputs are returned in the wrong order",
    "bearing_row_sign": "the bearing row of H has the wrong sign",
    "range_row_sign": "the range row of H has the wrong sign",
    "dx_dy_swapped": "Δx and Δy are swapped",
    "missing_theta": "the bearing's dependence on θ (∂φ/∂θ = −1) is left out",
    "numeric_not_derived": "the Jacobian is approximated by finite differences instead of derived",
    "divides_by_omega": "divides by ω, with no straight-line limit at ω = 0",
    "euler_step": "the pose moves in a straight line even while turning",
    "exact_zero_test": "ω is compared with exactly 0, so a tiny ω still goes through V/ω",
    "straight_too_wide": "the straight-line branch is taken where V/ω is still exact",
    "sin_cos_swapped": "sin and cos are swapped",
    "heading_without_dt": "the heading turns by ω instead of ωΔt",
    "speed_not_distance": "the speed V is used where the distance VΔt belongs",
    "unwrapped_angle": "an angle is not wrapped into (−π, π]",
    "wrong_weights": "the weights are wrong",
    "missing_scale": "the points are not spread by √(n + λ) times a square root of Σ",
    "f_not_applied": "the sigma points are not passed through f",
    "f_of_mean": "the mean is f(μ) instead of the weighted mean of the transformed points",
    "mean_not_subtracted": "the covariance is taken without subtracting the mean",
    "outer_product_order": "yᵀy (a number) is used where the outer product y yᵀ (a matrix) belongs",
    "points_as_columns": "the points are columns instead of rows",
    "not_cholesky": "a square root other than the lower Cholesky factor is used",
    # chapters 0, 2, 6 and 10
    "n_not_sqrt_n": "the spread grows with n instead of √n",
    "divides_by_sqrt_n": "σ is divided by √n instead of multiplied by it",
    "off_by_one": "the number of steps is off by one",
    "root_of_sigma_n": "the square root is taken of σ n instead of the summed variances n σ²",
    "elementwise_not_matmul": "* (entry by entry) is used where the matrix product @ belongs",
    "scalar_only": "it works for one number but not for an array of them",
    "transpose_on_left": "the transpose is on the left-hand A: Aᵀ Σ A instead of A Σ Aᵀ",
    "b_in_covariance": "the shift b is added to the covariance",
    "b_forgotten": "the shift b is left out of the mean",
    "missing_half": "the ½ of ½Δt² is missing",
    "dt_not_dt2": "Δt is used where Δt² belongs",
    "R_diagonal": "R keeps only its diagonal: the position-velocity cross terms are missing",
    "state_order": "the state is ordered [px, vx, py, vy] instead of [px, py, vx, vy]",
    "F_transposed": "F is transposed: its Δt entries are below the diagonal",
    "R_not_mapped": "the odometry noise M is used as the process noise, not mapped through W (R = W M Wᵀ)",
    "stale_mean": "every reading is linearized at the predicted mean μ̄ instead of the current one",
    "bearing_not_wrapped": "the bearing innovation is not wrapped into (−π, π]",
    "heading_not_wrapped": "the heading is not wrapped into (−π, π] after an update",
    "gate_on_d_not_d2": "the gate mixes d and d²: d² compared with the gate, or d with gate²",
    "no_gate": "readings the gate refuses are used",
    "used_wrong": "the used flags do not say which readings were used",
    "no_predict_when_blind": "the prediction is skipped when no reading is in view",
    "deviations_from_f_mu": "the covariance takes deviations from f(μ) instead of from the mean μ_y",
    # chapter 11
    "offset_not_divided": "the offset U ~ U[0, 1) is not divided by N, so the positions run past 1",
    "no_offset": "the positions have no random offset (or one too small to matter): i/N instead of (i + U)/N",
    "fixed_offset": "the offset is fixed at ½ instead of drawn: positions (i + ½)/N",
    "multinomial": "N independent positions are drawn (multinomial resampling), not N evenly spaced ones",
    "unnormalised_weights": "the weights are taken as normalised: the cumulative sum ends at their sum, not at 1",
    "cumsum_not_one": "the cumulative sum does not end at exactly 1, so an index runs past the end",
    "shortfall_to_last": "the cumulative sum is not divided by its last entry, so what the weights lack of 1 goes "
    "to the last particle, even one of weight 0",
    "boundary_side": "a position exactly on a slice boundary c_i goes to particle i instead of i + 1",
    "weights_not_indices": "weights are returned where the indices of the particles drawn belong",
    "counts_not_indices": "how often each particle is drawn is returned where the indices belong",
    "weights_not_reset": "the particles drawn keep their old weights instead of 1/N",
    "weights_returned_too": "the new weights are returned beside the indices",
    "float_indices": "the indices are floats, and particles[indices] needs integers",
    "ignores_rng": "the random draws do not come from the rng given, so the same rng gives other particles",
    "changes_input": "the function changes an array it was handed, in place",
    "stratified_not_systematic": "this is stratified resampling (one offset per slot), a right scheme, but the "
    "exercise asks for systematic resampling (one offset for all)",
    # chapter 12
    "H_not_unit": "H's position entries are the offset (x − bx, y − by) not divided by r: not the unit vector",
    "heading_in_H": "H has a heading entry, and a range does not change when the robot turns: ∂r/∂θ = 0",
    "no_Sig_bar": "Σ̄ is left out of the covariance update: I − KH instead of (I − KH)Σ̄",
    "Sig_not_updated": "the covariance is returned as it came, Σ̄: the reading leaves the belief no surer",
    "heading_held": "the heading is held fixed, and a range moves it through Σ̄'s correlation of θ with x and y",
    "dot_not_outer": "K·H, the dot product of two 1-D arrays (a number), is used where the outer product KH (a "
    "matrix) belongs",
    "r_zero_not_refused": "a robot exactly at the beacon (r = 0) is not refused: the range has no direction there, "
    "so H is undefined",
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


@dataclass(frozen=True)
class Step:
    """One step of a chapter's equations, isolated: inputs under which the right answer is that step's alone.

    With c = 0 the update of chapter 3 hands the prediction back unchanged, so the answer is (1)-(2) alone;
    with a = 1, b = 0 and R = 0 the prediction is the prior, so it is the update (3)-(5) alone.
    """

    inputs: str  #: the isolating inputs, as the verdict says them: "c = 0"
    equations: str  #: what alone gives the answer there: "the prediction (1)-(2)"
    isolate: Callable  #: the inputs of a case (a dict) -> the same with the isolating values put in


@dataclass(frozen=True)
class Probe:
    """One input moved alone, to see which outputs follow it: the right ones do as the equations say."""

    name: str  #: the input, as the function names it
    move: Callable  #: its value -> another value
    enters: str  #: where it enters, by the chapter's numbers: "(2), σ̄² = a²σ² + R"
    label: str = ""  #: what moves, when it is a part of the input: "θ" of the state (default: the input's name)

    @property
    def what(self) -> str:
        return self.label or self.name


@dataclass(frozen=True)
class Invariant:
    """What every right answer holds, whatever the numbers: a covariance symmetric, a belief that sums to 1."""

    holds: Callable  #: (a case's inputs, the answer's parts by name) -> whether it holds
    says: str  #: what an answer that breaks it does, as the verdict says it: "your bel does not sum to 1"


def moved(index: int, by: float) -> Callable:
    """A probe's move: the array with entry ``index`` moved by ``by``."""

    def move(a):
        a = np.array(a, dtype=float)
        a[index] += by
        return a

    return move


def sums_to_one(name: str, why: str) -> Invariant:
    """``name`` sums to 1 (``why``: what makes it)."""
    return Invariant(
        lambda inputs, parts: abs(float(np.sum(parts[name])) - 1.0) <= 1e-9, f"your {name} does not sum to 1: {why}"
    )


def non_negative(name: str, what: str, index: int | None = None, label: str = "") -> Invariant:
    """``name`` (its entry ``index``, when given; ``label``: what the verdict calls it) is not negative, as ``what``
    ("a variance") never is."""

    def holds(inputs, parts) -> bool:
        a = np.asarray(parts[name], dtype=float)
        return bool(np.all((a if index is None else a.reshape(-1)[index]) >= 0))

    return Invariant(holds, f"your {label or name} is negative, and {what} never is")


def is_covariance(name: str, psd: bool = True) -> Invariant:
    """``name`` is symmetric and, unless ``psd`` is False, positive semi-definite, up to rounding.  (An unscented
    transform with λ < 0 has a negative weight w₀, and its covariance can lose semi-definiteness.)"""

    def holds(inputs, parts) -> bool:
        a = np.asarray(parts[name], dtype=float)
        scale = max(float(np.abs(a).max()), 1e-300)
        if a.ndim != 2 or a.shape[0] != a.shape[1] or np.abs(a - a.T).max() > 1e-9 * scale:
            return False
        return not psd or bool(np.linalg.eigvalsh((a + a.T) / 2)[0] >= -1e-9 * scale)

    broken = "it is not symmetric, or has a negative eigenvalue" if psd else "it is not symmetric"
    return Invariant(holds, f"your {name} is not a covariance: {broken}")


def angle_in_range(name: str, index: int, what: str) -> Invariant:
    """Entry ``index`` of ``name`` (``what``: "the heading θ'") lies in (−π, π]."""

    def holds(inputs, parts) -> bool:
        a = float(np.asarray(parts[name], dtype=float).reshape(-1)[index])
        return -math.pi - 1e-12 < a <= math.pi + 1e-12

    return Invariant(holds, f"your {what} lies outside (−π, π]: wrap it (kf.wrap_angle)")


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


@contextlib.contextmanager
def _silenced():
    """Run the student's code without letting it print or warn."""
    with warnings.catch_warnings(), np.errstate(all="ignore"), contextlib.redirect_stdout(io.StringIO()):
        warnings.simplefilter("ignore")
        yield


def _quietly(fn: Callable, case: Case, handed: dict | None = None):
    """Run ``fn`` on ``case`` without letting it print or warn: ("returned", value) or ("raised", error).

    ``handed``: the copy of the case's inputs to call it on, to look at afterwards (default: a fresh copy)."""
    try:
        with _silenced():
            return "returned", (case.call(fn) if handed is None else fn(*handed.values()))
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
    if x is None:
        return None
    try:
        return np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        return None


def _wrong_entries(a: np.ndarray, e: np.ndarray) -> str:
    """Where ``a`` differs from ``e``, when only a few of many entries do: " at [1, 0] and [1, 1]"."""
    bad = np.argwhere(~np.isclose(a, e, rtol=RTOL, atol=ATOL))
    if e.size == 1 or len(bad) == e.size or len(bad) > 4:
        return ""
    where = [f"[{', '.join(str(int(i)) for i in index)}]" for index in bad]
    return " at " + (where[0] if len(where) == 1 else ", ".join(where[:-1]) + " and " + where[-1])


def problem(expected, got, returns: tuple[str, ...]) -> str | None:
    """What is wrong with ``got`` in a few words, or None when it matches ``expected``.

    Every output is judged: the wrong ones are named (with the entries that differ, when
    only a few do) and, beside them, the outputs that are right.
    """
    if got is None:
        return "it returned None: is its return statement missing?"
    parts = _parts(got, returns)
    if parts is None:
        return f"it returned {_kind(got)}; expected {len(returns)} values ({', '.join(returns)})"
    broken, wrong, right = [], [], []
    for name, e, g in zip(returns, _parts(expected, returns), parts, strict=True):
        e, a = np.asarray(e, dtype=float), _as_array(g)
        if a is None:
            broken.append(f"{name} is not a number or an array of numbers")
        elif a.shape != e.shape and not (e.ndim == 0 and a.size == 1):
            broken.append(f"{name} has shape {a.shape}; expected {e.shape if e.ndim else 'a single number'}")
        elif np.isnan(a).any():
            broken.append(f"{name} contains NaN")
        elif np.isinf(a).any():
            broken.append(f"{name} contains inf")
        elif not np.allclose(a.reshape(e.shape), e, rtol=RTOL, atol=ATOL):
            wrong.append((name, _wrong_entries(a.reshape(e.shape), e)))
        else:
            right.append(name)
    if len(wrong) > 1 and not any(where for _, where in wrong):
        broken.append(" and ".join(name for name, _ in wrong) + " have wrong values")
    else:
        broken += [f"{name} has the wrong value{where}" for name, where in wrong]
    if not broken:
        return None
    text = "; ".join(broken)
    if right and len(returns) > 1:
        text += f" ({' and '.join(right)} {'is' if len(right) == 1 else 'are'} right)"
    return text


def _same_outcome(mine, theirs, returns: tuple[str, ...]) -> bool:
    """Whether two outcomes of :func:`_quietly` agree: equal values (NaN where NaN), or the same error."""
    if mine[0] != theirs[0]:
        return False
    if mine[0] == "raised":
        return type(mine[1]) is type(theirs[1]) and str(mine[1]) == str(theirs[1])
    a, b = _parts(mine[1], returns), _parts(theirs[1], returns)
    return a is not None and b is not None and all(_close(x, y) for x, y in zip(a, b, strict=True))


def _kind(x) -> str:
    if isinstance(x, (tuple, list)):
        return f"a {type(x).__name__} of {len(x)}"
    if x is None:
        return "None"
    return f"one {type(x).__name__}"


def show(x, suppress_small: bool = True) -> str:
    """A short, readable text for an input or output value (inputs: ``suppress_small=False``, so
    that a tiny input such as ω = 1e-15 does not print as 0).  Integers (indices) and booleans
    (flags) print as they are, not as floats."""
    if isinstance(x, Mapping):
        return "{" + ", ".join(f"{k!r}: {show(p, suppress_small)}" for k, p in x.items()) + "}"
    if x is None or isinstance(x, str):
        return repr(x)
    a = _as_array(x)
    if a is None or a.dtype == object:
        text = repr(x)
        return text if len(text) < 300 else text[:300] + " ..."
    exact = np.asarray(x).dtype.kind in "biu"  # booleans, integers
    if exact:
        a = np.asarray(x)
    if a.ndim == 0:
        return str(a.item()) if exact else f"{float(a):.6g}"
    return np.array2string(a, precision=6, suppress_small=suppress_small, separator=", ", max_line_width=100)


def _block(named: list[tuple[str, object]], suppress_small: bool = True) -> str:
    """``name = value`` lines, continuation lines of a matrix lined up under its first row."""
    width = max(len(name) for name, _ in named)
    lines = []
    for name, value in named:
        text = show(value, suppress_small).replace("\n", "\n" + " " * (width + 7))
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


def _paired(outcome, expected, pair: Callable | None):
    """The outcome with its value put into the reference's order by ``pair`` (when there is one)."""
    if pair is None or outcome[0] == "raised":
        return outcome
    try:
        return "returned", pair(expected, outcome[1])
    except Exception:  # an answer ``pair`` cannot read is compared as it is
        return outcome


def _likely_mistakes(student_fn, variants, cases, expected, number, returns, pair) -> list[Variant]:
    """The known wrong versions that give the student's outcome on every case, the first of each mistake.

    Two mistakes can agree on one case (where c mu equals mu_bar, z - mu_bar and z - c mu are the same
    number), so a wrong version counts only when it agrees with the student's function on all the
    cases, those it passes and those it fails: a wrong name is worse than none.  They agree on a case
    when they give the same values there, or both raise the same kind of error (the student's in words
    of its own, say, where the variant divides by zero).  Case ``number``, the first that fails, is tried
    first: it tells most variants apart at once.  Two different mistakes that agree on every case
    cannot be told apart by any answer: both are returned, and the verdict names neither.
    """

    def run(fn, i):
        return _paired(_quietly(fn, cases[i]), expected[i], pair)

    student = {}

    def agrees(variant, i) -> bool:
        if i not in student:
            student[i] = run(student_fn, i)
        mine, theirs = student[i], run(variant.fn, i)
        if mine[0] == theirs[0] == "raised":
            return type(mine[1]) is type(theirs[1])
        return _same_outcome(theirs, mine, returns)

    order = [number, *(i for i in range(len(cases)) if i != number)]
    found = {}
    for variant in variants:
        if variant.mistake not in found and all(agrees(variant, i) for i in order):
            found[variant.mistake] = variant
    return list(found.values())


def _answers(fn, inputs: dict, expected, pair):
    """``fn`` on a fresh copy of ``inputs``, put into the reference's order: the outcome of :func:`_quietly`."""
    return _paired(_quietly(fn, Case("", **inputs)), expected, pair)


def _diagnosis(check: _Check, number: int) -> list[str]:
    """What the student's function does step by step and input by input: sentences that hold of it.

    First what its answers break: an invariant of every right answer (:class:`Invariant`) on some case, and
    the right numbers in other places.  Then each step is run alone on every case (:class:`Step`): said
    when the steps are right on their own, or some are and some are not; when every one is wrong, they tell
    nothing apart and nothing is said.  Then each input of the failing cases is moved alone
    (:class:`Probe`), and an output that follows an input the right one ignores, or ignores one the right
    one follows, is named with the equation where that input enters.  No sentence guesses at a mistake:
    each says what the function did.  An answer that is not finite (NaN, inf) tells nothing of the kind.
    The answers on the cases are computed once and shared; the exchanges, the steps and the probes run the
    functions on inputs of their own.
    """
    answers = [_outcomes(check, case.inputs) for case in check.cases]  # (the right outcome, the student's)
    said = _exchanged(check) + _broken(check, number, answers)
    steps = []  # each step with the outputs wrong on its inputs ([] when right on every case)
    for step in check.steps:
        wrong = [_wrong_parts(_outcomes(check, step.isolate(dict(case.inputs))), check.returns) for case in check.cases]
        wrong = [w for w in wrong if w is not None]  # None: the right function refuses those inputs
        if wrong:
            steps.append((step, [name for name in (*check.returns, "raises") if any(name in w for w in wrong)]))
    if len(steps) < 2 or not all(outputs for _, outputs in steps):  # every one of several wrong tells nothing apart
        for step, outputs in steps:
            there = (
                ", and yours is right there"
                if not outputs
                else ", and yours is wrong there "
                + ("(it raises an error)" if "raises" in outputs else f"(its {' and '.join(outputs)})")
            )
            said.append(f"with {step.inputs} the answer is {step.equations}{there}")
    if check.probes:
        failing = [number] + [k for k in range(number + 1, len(answers)) if _wrong_parts(answers[k], check.returns)]
        said += _probe_sentences(check, [(check.cases[k], answers[k]) for k in failing[:3]])
    return said


def _outcomes(check: _Check, inputs: dict):
    """The right function's outcome on ``inputs`` and the student's (put into the right one's order; None when the
    right function refuses the inputs): outcomes of :func:`_quietly`, each function on a fresh copy."""
    right = _quietly(check.reference, Case("", **inputs))
    return right, None if right[0] == "raised" else _answers(check.student_fn, inputs, right[1], check.pair)


def _exchanged(check: _Check) -> list[str]:
    """Each pair of inputs of one shape that, exchanged, turns the right function into the student's: on every case
    where the two differ (two cases at least), the right answer with them exchanged is the student's."""
    said = []
    for a, b in itertools.combinations(check.cases[0].inputs, 2):
        agreed = 0
        for case in check.cases:
            x, y = _as_array(case.inputs[a]), _as_array(case.inputs[b])
            if x is None or y is None or x.shape != y.shape or _close(x, y):
                continue  # not one kind of number, or equal: exchanging them tells nothing
            right = _quietly(check.reference, Case("", **{**case.inputs, a: case.inputs[b], b: case.inputs[a]}))
            mine = _answers(check.student_fn, dict(case.inputs), right[1], check.pair)
            if right[0] == "raised" or not _same_outcome(mine, right, check.returns):
                break
            agreed += 1
        else:
            if agreed >= 2:
                said.append(
                    f"your answers are the right ones with {a} and {b} exchanged, on every case where they differ: "
                    f"each is used where the other belongs"
                )
    return said


def _broken(check: _Check, number: int, answers: list) -> list[str]:
    """The invariants the student's answers (``answers``: each case's outcomes) break, each on the first case where
    it does; and each output that, on every case where it is wrong, holds the right numbers in other places (said
    with case ``number``'s)."""
    returns, said, parts = check.returns, [], []  # parts: each case's right parts and the student's (None: none)
    for right, mine in answers:
        mine = _parts(mine[1], returns) if mine[0] == "returned" else None
        parts.append(
            (_parts(right[1], returns), None if mine is None or any(_as_array(p) is None for p in mine) else mine)
        )
    for invariant in check.invariants:
        for k, (case, (_, mine)) in enumerate(zip(check.cases, parts, strict=True)):
            try:
                broken = (
                    mine is not None
                    and _finite(mine)
                    and not invariant.holds(case.inputs, dict(zip(returns, mine, strict=True)))
                )
            except Exception:  # an answer of another shape: the invariant cannot be read
                broken = False
            if broken:
                said.append(f"on case {k + 1} ({case.label}) {invariant.says}")
                break
    for index, name in enumerate(returns):
        wrong = [(_as_array(right[index]), _as_array(mine[index])) for right, mine in parts if mine is not None]
        wrong = [(e, m) for e, m in wrong if not _close(e, m)]
        if wrong and all(
            e.shape == m.shape
            and e.size > 1
            and np.allclose(np.sort(e, axis=None), np.sort(m, axis=None), rtol=RTOL, atol=ATOL)
            for e, m in wrong
        ):
            right, mine = parts[number]
            where = _wrong_entries(_as_array(mine[index]), _as_array(right[index])) if mine is not None else ""
            said.append(f"your {name} holds the right numbers, some in the wrong places{where}")
    return said


def _wrong_parts(outcomes, returns) -> list[str] | None:
    """The outputs of the student's function that differ from the right one's (``outcomes``, from
    :func:`_outcomes`): ["raises"] when it raises and the right one does not, [] when it agrees, None when the
    right function refuses the inputs."""
    right, mine = outcomes
    if mine is None:
        return None
    if mine[0] == "raised":
        return ["raises"]
    parts = _parts(mine[1], returns)
    if parts is None:
        return list(returns)
    return [name for name, m, e in zip(returns, parts, _parts(right[1], returns), strict=True) if not _close(m, e)]


def _finite(parts) -> bool:
    """Whether every part of an answer is numbers, none NaN or inf."""
    arrays = [_as_array(p) for p in parts]
    return all(a is not None and bool(np.isfinite(a).all()) for a in arrays)


def _probe_sentences(check: _Check, failing: list) -> list[str]:
    """For each input moved alone on the first failing case: the outputs whose following of it differs from the
    right ones'; then, when what is wrong changes with a few inputs only, the same on every failing case, those.
    ``failing``: each failing case with its outcomes (:func:`_outcomes`).

    An answer that is the right one plus an error moves, when an input moves, by the right one's change
    plus the error's: the same amount exactly when the error does not depend on that input.  So the inputs
    under which the two answers move by different amounts are the ones what is wrong depends on."""
    probes, out, depends = check.probes, [], []
    for number, (case, base) in enumerate(failing):
        moves = [_moved_alone(check, case, base, probe) for probe in probes]
        if number == 0:
            for probe, parts in zip(probes, moves, strict=True):
                if parts is None:
                    continue
                for name, r0, r1, m0, m1 in zip(check.returns, *parts, strict=True):
                    follows, yours = not _close(r0, r1), not _close(m0, m1)
                    if follows and not yours:
                        out.append(
                            f"your {name} does not change when {probe.what} changes, and the right one does: "
                            f"{probe.what} enters {probe.enters}"
                        )
                    elif yours and not follows:
                        out.append(f"your {name} changes when {probe.what} changes, and the right one does not")
        moved = [(probe, parts) for probe, parts in zip(probes, moves, strict=True) if parts is not None]
        depends.append({probe.what for probe, parts in moved if not _same_moves(*parts)} if len(moved) > 1 else set())
        depends[-1] = depends[-1] if len(depends[-1]) <= len(moved) // 2 else set()  # naming most of them tells nothing
    same = len(depends) >= 2 and all(d == depends[0] for d in depends)  # seen on one case only, it may be chance
    traced = [probe for probe in probes if same and probe.what in depends[0]]
    if out or not traced:
        return out
    names = " and ".join(probe.what for probe in traced)
    where = "; ".join(f"{probe.what} enters {probe.enters}" for probe in traced)
    alone = "alone" if len(traced) == 1 else "only"
    return [
        f"what is wrong in your answer depends on {names} {alone}: moved by itself, "
        f"{'it changes' if len(traced) == 1 else 'each changes'} your answer by another amount than the right "
        f"one, and every other input by the same amount, on every case that fails. {where}"
    ]


def _moved_alone(check: _Check, case: Case, base, probe: Probe):
    """The right answer and the student's on ``case`` (``base``: their outcomes there) and after ``probe`` moves its
    input: four lists of parts, or None when a function raises, an answer has another number of parts, or one is
    not finite."""
    (right0, mine0), moved = base, {**case.inputs, probe.name: probe.move(copy.deepcopy(case.inputs[probe.name]))}
    right1, mine1 = _outcomes(check, moved)
    if mine1 is None or mine0[0] == "raised" or mine1[0] == "raised":
        return None
    parts = [_parts(x[1], check.returns) for x in (right0, right1, mine0, mine1)]
    if any(p is None or not _finite(p) for p in parts):
        return None
    return parts


def _same_moves(r0, r1, m0, m1) -> bool:
    """Whether the student's answer moved by the same amount as the right one, in every part."""
    deltas = [(_delta(a0, a1), _delta(b0, b1)) for a0, a1, b0, b1 in zip(m0, m1, r0, r1, strict=True)]
    return any(d is None for pair in deltas for d in pair) or all(_close(a, b) for a, b in deltas)


def _delta(a, b):
    """``b - a`` for two parts of an answer of one shape, or None."""
    a, b = _as_array(a), _as_array(b)
    return None if a is None or b is None or a.shape != b.shape else b - a


def _close(a, b) -> bool:
    """Whether two parts of an answer are equal within the checkers' tolerance (other things than numbers: equal)."""
    x, y = _as_array(a), _as_array(b)
    if x is None or y is None:
        try:
            return bool(a == b)
        except Exception:  # an array against something else: not equal
            return False
    return x.shape == y.shape and bool(np.allclose(x, y, rtol=RTOL, atol=ATOL, equal_nan=True))


def _gap(expected, got, returns: tuple[str, ...]) -> float:
    """The largest absolute difference between two answers that :func:`problem` finds equal."""
    pairs = zip(_parts(expected, returns), _parts(got, returns), strict=True)
    return max(float(np.max(np.abs(np.asarray(g, dtype=float).reshape(np.shape(e)) - e))) for e, g in pairs)


def _sentence(hint: str) -> str:
    """The hint with a capital first letter when it starts with a word; a symbol (x, n, θ) stays as it is."""
    return hint[:1].upper() + hint[1:] if re.match(r"[a-z]{2,}\b(?![.(])", hint) else hint  # not accel_var, np.sqrt


@dataclass(frozen=True)
class _Check:
    """One checker's run: the verdicts of a function that fails, in one of three ways."""

    name: str
    student_fn: Callable
    reference: Callable
    cases: list
    variants: list
    returns: tuple
    where: str
    pair: Callable | None
    steps: tuple
    probes: tuple
    invariants: tuple

    @property
    def who(self) -> str:
        return getattr(self.student_fn, "__name__", "your function")

    def _details(self, number: int, expected, outcome) -> str:
        details = "inputs:\n" + _block(list(self.cases[number].inputs.items()), suppress_small=False)
        details += "\nexpected:\n" + _block(_named(expected, self.returns))
        if outcome[0] == "raised":
            return details + _where(outcome[1], self.student_fn)
        return details + "\ngot:\n" + _block(_named(outcome[1], self.returns))

    def failed(self, number: int, outcome, expected: list, what: str) -> CheckResult:
        """Case ``number`` fails (``what``): the case, then a mistake named when exactly one known wrong version
        gives the student's answer on every case (both said when two do), else what the diagnosis finds."""
        cases, returns, where = self.cases, self.returns, self.where
        headline = (
            f"✘ {self.who} is not right yet: on case {number + 1} of {len(cases)} ({cases[number].label}), {what}."
        )
        details = self._details(number, expected[number], outcome)
        found = _likely_mistakes(self.student_fn, self.variants, cases, expected, number, returns, self.pair)
        mistake = found[0].mistake if len(found) == 1 else None
        if mistake:
            hint = f"Likely mistake: {MISTAKES[mistake]}. {_sentence(found[0].hint)} See {where}."
        elif found:  # no answer tells these apart: name neither, say both
            either = "; or ".join(MISTAKES[variant.mistake] for variant in found)
            hint = f"Each of these mistakes gives your answer on every case, and no case tells them apart: {either}. "
            hint += f"See {where}."
        else:
            said = _diagnosis(self, number)
            hint = "No known mistake gives this answer. " + "".join(f"{_sentence(sentence)}. " for sentence in said)
            hint += f"Compare your code with {where}."
        return CheckResult(False, mistake, "\n".join([headline, details, hint]), headline, details, hint)

    def approximate(self, expected, answers, exact_to: float, mistake: str, advice: str) -> CheckResult | None:
        """Every answer within the tolerance, but one farther than ``exact_to`` from the reference: an
        approximation of the formula asked for (``mistake``), or None."""
        gaps = [_gap(e, a, self.returns) for e, a in zip(expected, answers, strict=True)]
        number = int(np.argmax(gaps))
        if gaps[number] <= exact_to:
            return None
        headline = (
            f"✘ {self.who} is not right yet: it agrees with kf.{self.name} only to {gaps[number]:.0e}, where the exact "
            f"formula agrees to rounding (about 1e-15); the largest difference is on case {number + 1} of "
            f"{len(self.cases)} ({self.cases[number].label})."
        )
        details = self._details(number, expected[number], ("returned", answers[number]))
        hint = f"Likely mistake: {MISTAKES[mistake]}. {advice} See {self.where}."
        return CheckResult(False, mistake, "\n".join([headline, details, hint]), headline, details, hint)

    def in_place(self, number: int, argument: str) -> CheckResult:
        """Right answers from a function that changes its argument ``argument`` in place on case ``number``."""
        headline = (
            f"✘ {self.who} is not right yet: its answers are right, but on case {number + 1} of {len(self.cases)} "
            f"({self.cases[number].label}) it changes its argument {argument} in place."
        )
        hint = (
            f"Likely mistake: {MISTAKES['changes_input']}. The caller's {argument} is the belief it still holds: "
            f"build a new array (x = x + ..., or start from x.copy()) instead of x += ... or x[i] = .... "
            f"See {self.where}."
        )
        return CheckResult(False, "changes_input", f"{headline}\n{hint}", headline, "", hint)


def run_check(
    name: str,
    student_fn: Callable,
    reference: Callable,
    cases: list[Case],
    variants: list[Variant],
    returns: tuple[str, ...],
    where: str,
    *,
    pair: Callable | None = None,
    approximation: tuple[float, str, str] | None = None,
    steps: tuple[Step, ...] = (),
    probes: tuple[Probe, ...] = (),
    invariants: tuple[Invariant, ...] = (),
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
        The first is the chapter's worked example, where the chapter has one.
    variants : list of Variant
        Known wrong versions; one that gives the student's answer on every case
        names the mistake, when no other mistake does (:func:`_likely_mistakes`).
    returns : tuple of str
        Names of the returned values (one name: a single value, not a tuple).
    where : str
        The chapter's equation to compare with, e.g. ``"chapter 5, equations (1)-(5)"``.
    pair : callable ``pair(expected, got) -> got``, optional
        Puts an answer whose parts may come in any order (sigma points) into the
        reference's order before it is compared.
    approximation : (float, str, str), optional
        ``(exact_to, mistake, hint)``: an answer that matches on every case within the
        tolerance but differs from the reference by more than ``exact_to`` somewhere is
        an approximation (a numerically differentiated Jacobian), not the formula asked
        for; it fails with the key ``mistake`` of :data:`MISTAKES` and ``hint``.
    steps, probes : tuple of Step, tuple of Probe
        The chapter's steps, each with the inputs that isolate it, and the inputs to move one at a time:
        when no known mistake gives the student's answer, the verdict says which steps are right on their
        own and which outputs follow the wrong inputs (:func:`_diagnosis`).
    invariants : tuple of Invariant
        What every right answer holds (a covariance symmetric, a belief summing to 1): an answer that breaks
        one is told so first.

    Returns
    -------
    CheckResult
    """
    if not callable(student_fn):
        raise ValueError(
            f"student_fn must be your function itself, e.g. kf.check.{name}(my_{name}); got {student_fn!r}"
        )
    if len(returns) > 1:  # every checker of several outputs knows this mistake
        order = f"Return {', '.join(returns)}, in this order."
        variants = [*variants, Variant("outputs_swapped", lambda *a: tuple(reversed(reference(*a))), order)]
    expected = [case.call(reference) for case in cases]
    for invariant in invariants:  # what the verdict may say of an answer must hold of the right ones
        for case, right in zip(cases, expected, strict=True):
            if not invariant.holds(case.inputs, dict(zip(returns, _parts(right, returns), strict=True))):
                raise AssertionError(f"kf.check.{name}: the right answer breaks '{invariant.says}' on {case.label}")
    check = _Check(name, student_fn, reference, cases, variants, returns, where, pair, steps, probes, invariants)
    answers, changed = [], None
    for number, case in enumerate(cases):
        handed = copy.deepcopy(case.inputs)
        outcome = _quietly(student_fn, case, handed)
        changed = changed or _changed_in_place(number, case.inputs, handed)
        if outcome[0] == "raised" and isinstance(outcome[1], NotImplementedError):
            headline = f"✎ Not yet: {check.who} raises NotImplementedError. Write its body, then run this cell again."
            return CheckResult(False, None, headline, headline)
        outcome = _paired(outcome, expected[number], pair)
        if outcome[0] == "raised":
            error = outcome[1]
            what = f"it raised {type(error).__name__}: {str(error).rstrip('.')}"
        else:
            what = problem(expected[number], outcome[1], returns)
            if what is None:
                answers.append(outcome[1])
                continue
        return check.failed(number, outcome, expected, what)
    if approximation is not None and (verdict := check.approximate(expected, answers, *approximation)):
        return verdict
    if changed is not None:
        return check.in_place(*changed)
    labels = list(dict.fromkeys(case.label.split(":")[0] for case in cases))  # each kind of case once, in order
    headline = f"✔ {check.who} matches kf.{name} on all {len(cases)} cases: {'; '.join(labels)}."
    return CheckResult(True, None, headline, headline)


def _changed_in_place(number: int, inputs: dict, handed: dict) -> tuple[int, str] | None:
    """``(number, argument)`` for the first array argument the student's function changed in place (the copy
    ``handed`` to it of the case's ``inputs`` came back different), or None."""
    for argument, value in inputs.items():
        if isinstance(value, np.ndarray) and not _same_array(handed[argument], value):
            return number, argument
    return None


def _same_array(a, b) -> bool:
    """Whether two arrays hold the same entries (NaN where NaN)."""
    if not isinstance(a, np.ndarray) or a.shape != b.shape:
        return False
    return bool(np.array_equal(a, b) or (a.dtype.kind == "f" and np.array_equal(a, b, equal_nan=True)))
