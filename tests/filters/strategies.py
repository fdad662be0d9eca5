"""What the filter tests share, in one place: the Hypothesis strategies, the checks and
tolerances, the ``rng`` fixture, the lesson's worked-example numbers that more than one
subject uses, and the small valid inputs that the bad-input tables spoil one at a time,
with the runner of those tables.

Import from here: ``from tests.filters.strategies import spd, assert_close``.  The fixture
reaches the tests through ``tests/filters/conftest.py``, which only re-exports it.

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from functools import partial

import numpy as np
import pytest
from hypothesis import assume, settings
from hypothesis import strategies as st

import kfcourse as kf

TWO_PI = 2.0 * math.pi

# ---------------------------------------------------------------- Hypothesis strategies
FAST = settings(max_examples=60, deadline=None)


def reals(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


@st.composite
def matrices(draw, rows: int, cols: int, bound: float = 2.0) -> np.ndarray:
    vals = draw(st.lists(reals(-bound, bound), min_size=rows * cols, max_size=rows * cols))
    return np.array(vals).reshape(rows, cols)


@st.composite
def vectors(draw, n: int, bound: float = 10.0) -> np.ndarray:
    return np.array(draw(st.lists(reals(-bound, bound), min_size=n, max_size=n)))


@st.composite
def spd(draw, n: int) -> np.ndarray:
    """A well-conditioned symmetric positive definite (n, n) matrix."""
    A = draw(matrices(n, n))
    ridge = draw(reals(0.05, 2.0))
    return A @ A.T + ridge * np.eye(n)


@st.composite
def linear_models(draw):
    """A linear model of 1-4 states, 1-2 controls and 1-3 readings, with a belief to start from."""
    n = draw(st.integers(1, 4))
    m = draw(st.integers(1, 2))
    k = draw(st.integers(1, 3))
    return {
        "n": n,
        "mu": draw(vectors(n)),
        "Sig": draw(spd(n)),
        "u": draw(vectors(m)),
        "F": draw(matrices(n, n)),
        "B": draw(matrices(n, m)),
        "R": draw(spd(n)),
        "z": draw(vectors(k)),
        "H": draw(matrices(k, n)),
        "Q": draw(spd(k)),
    }


@st.composite
def probability_vectors(draw, min_size=1, max_size=20):
    w = np.array(draw(st.lists(reals(0.0, 1.0), min_size=min_size, max_size=max_size)))
    assume(w.sum() > 1e-3)
    return w / w.sum()


@st.composite
def kernels(draw):
    """A motion kernel {cell offset: probability} of 1-6 offsets within 25 cells."""
    offsets = draw(st.lists(st.integers(-25, 25), min_size=1, max_size=6, unique=True))
    p = draw(probability_vectors(len(offsets), len(offsets)))
    return dict(zip(offsets, p.tolist(), strict=True))


poses = st.tuples(reals(-50, 50), reals(-50, 50), reals(-10, 10)).map(np.array)

omegas = st.one_of(
    st.just(0.0),
    st.just(-0.0),
    reals(1e-300, 1e-8),  # tiny
    reals(-1e-8, -1e-300),
    reals(-5.0, 5.0),
    reals(50.0, 1e3),  # large
    reals(-1e3, -50.0),
)

seam_cases = st.tuples(
    reals(2.0, 10.0),  # landmark distance
    reals(-0.05, 0.05),  # landmark direction off straight behind
    reals(-0.05, 0.05),  # reading bearing error
    reals(-math.pi, math.pi),  # robot heading
)


# ---------------------------------------------------------------- checks, tolerances, the fixture
Z_TOL = 5.0  # standard errors allowed in a sampled check
N_SAMPLES = 400_000


def assert_close(actual, desired, rtol=1e-8, scale=1.0):
    np.testing.assert_allclose(actual, desired, rtol=rtol, atol=rtol * scale)


def angle_gap(a, b) -> float:
    """Distance between two angles on the circle, computed without kfcourse."""
    return abs(math.remainder(float(a) - float(b), TWO_PI))


def r3(x) -> float:
    """Round as the lesson prints: 3 decimal places."""
    return round(float(x), 3)


def square(x):
    return x**2


@pytest.fixture
def rng() -> np.random.Generator:
    """A seeded generator: the sampled checks are deterministic."""
    return np.random.default_rng(20240611)


# ---------------------------------------------------------------- the lesson's worked example, chapters 7-8
POSE = np.array([1.0, 2.0, 0.0])
LANDMARK = np.array([4.0, 6.0])
Z_CH8 = np.array([4.6, 0.95])
SIG_BAR_CH8 = np.diag([0.3, 0.3, 0.1])
Q_CH8 = np.diag([0.04, 0.01])


# ---------------------------------------------------------------- a bearing across the +-pi seam
LM_BEHIND = np.array([-5.0, 0.1])  # straight behind a robot at the origin facing +x: bearing pi - 0.02
POSE0 = np.array([0.0, 0.0, 0.0])
SIG_BAR = np.diag([0.2, 0.2, 0.05])
Q_SEAM = np.diag([0.04, 0.01])
h_behind = partial(kf.range_bearing, landmark=LM_BEHIND)
H_behind = partial(kf.range_bearing_jacobian, landmark=LM_BEHIND)


def textbook_update(mu_bar, Sig_bar, y, H, Q):
    """The lesson's update with a given (already wrapped) innovation, in plain numpy."""
    S = H @ Sig_bar @ H.T + Q
    K = Sig_bar @ H.T @ np.linalg.inv(S)
    return mu_bar + K @ y, (np.eye(mu_bar.size) - K @ H) @ Sig_bar


# ---------------------------------------------------------------- bad input
# Bad input gets a ValueError that names the offending argument.  Each subject file has a table of
# (id, call, argument) cases, one per (function, argument, kind of badness).  The message must *start*
# by naming the argument as a whole word ("Sig_bar must be ...", "the result of g must ...",
# "kernel[1] must ..."), so "Sig" does not pass for "Sig_bar" and the "a" of "must be a scalar" does
# not pass for the coefficient ``a``.
NAN, INF = float("nan"), float("inf")

# small valid inputs to spoil one at a time
MU2 = np.array([0.0, 1.0])
I2 = np.eye(2)
I3 = np.eye(3)
F2 = np.array([[1.0, 1.0], [0.0, 1.0]])
B2 = np.zeros((2, 1))
H12 = np.array([[1.0, 0.0]])
Q11 = np.array([[0.5]])
NONSYM = np.array([[1.0, 0.5], [0.0, 1.0]])
INDEFINITE = np.array([[1.0, 2.0], [2.0, 1.0]])  # eigenvalues 3 and -1
NEGVAR = np.diag([-1.0, 1.0])


def g_ok(x, u):
    return np.asarray(x, dtype=float)


def G_ok(x, u):
    return np.eye(np.size(x))


def h_rb(x):
    return kf.range_bearing(x, LANDMARK)


def H_rb(x):
    return kf.range_bearing_jacobian(x, LANDMARK)


def lin(x):
    return np.asarray(x, dtype=float)


BadInput = Sequence[tuple[str, Callable[[], object], str]]

# a message starts with the argument; a model's output, or a helper's argument, is named after it
NAMES_ARG = r"^(?:the result of |pose_residual |range_bearing_residual )?"


def bad_input_cases(cases: BadInput) -> list:
    """A table of (id, call, argument) cases as pytest parameters (call, argument), with their ids."""
    return [pytest.param(c, a, id=i) for i, c, a in cases]


def assert_raises_naming(call: Callable[[], object], arg: str) -> None:
    """call() raises a ValueError whose message starts by naming ``arg`` as a whole word."""
    with pytest.raises(ValueError, match=NAMES_ARG + re.escape(arg) + r"(?!\w)"):
        call()


def assert_unique_ids(cases: BadInput) -> None:
    """pytest would make repeated ids unique silently; a repeated id is a copied case."""
    ids = [i for i, _, _ in cases]
    assert len(ids) == len(set(ids))


def assert_raises_saying(call: Callable[[], object], message: str) -> None:
    """call() raises a ValueError that says ``message`` (what the argument is: a step, a variance, ...)."""
    with pytest.raises(ValueError, match=re.escape(message)):
        call()
