"""Checkers for chapters 0, 2 and 6: drift after n steps, a Gaussian through an affine map, the 2-D
constant-velocity model.

Noise letters follow the course: ``R`` is process (motion) noise.
"""

from __future__ import annotations

import math

import numpy as np

from .. import filters, models, sim
from ._core import Case, CheckResult, Probe, Step, Variant, is_covariance, non_negative, random_covariance, run_check


def _function(student_fn, name: str) -> None:
    """Refuse anything but a function, naming this checker (its reference has another name)."""
    if not callable(student_fn):
        raise ValueError(
            f"student_fn must be your function itself, e.g. kf.check.{name}(my_{name}); got {student_fn!r}"
        )


# ------------------------------------------------------------------ drift_sigma
# One step alone is one step's spread; each input moved alone (run_check's diagnosis).
DRIFT_STEPS = (
    Step(
        "n = 1",
        "one step's spread, σ₁ = σ, step_std itself",
        lambda i: {**i, "n": 1 if np.ndim(i["n"]) == 0 else np.ones_like(i["n"])},
    ),
)
DRIFT_PROBES = (
    Probe("step_std", lambda s: 2.0 * s + 0.01, "σ_n = σ √n"),
    Probe("n", lambda n: 4 * np.asarray(n), "σ_n = σ √n, as its square root"),
)


def _drift_cases(rng) -> list[Case]:
    """The cases of :func:`drift_sigma`: chapter 0's drift table, the edge cases, then seeded random ones."""
    cases = [
        Case("chapter 0's drift table: 2 cm steps", step_std=0.02, n=np.array([1, 25, 100, 400])),
        Case("one number of steps", step_std=0.02, n=2500),
        Case("a 5 cm step, 149 steps", step_std=0.05, n=149),
        Case("a perfect step, step_std = 0", step_std=0.0, n=np.array([4, 9])),
        Case("no step yet, n = 0", step_std=0.03, n=np.array([0, 1, 16])),
    ]
    for _ in range(6):
        n = rng.integers(2, 1000, size=int(rng.integers(1, 5)))
        cases.append(Case("random", step_std=float(rng.uniform(0.001, 0.5)), n=n))
    return cases


DRIFT_WHERE = "chapter 0: variances add, n σ² after n steps, so σ_n = σ √n"


def _drift_variants() -> list[Variant]:
    """The catalogue of :func:`drift_sigma`: each known mistake as a wrong version, with its hint."""
    return [
        Variant(
            "std_not_var",
            lambda s, n: s**2 * np.asarray(n),
            "The variance after n steps is n σ²; its square root, σ √n, is the spread asked for.",
        ),
        Variant(
            "n_not_sqrt_n",
            lambda s, n: s * np.asarray(n),
            "Standard deviations do not add up, variances do: σ_n² = n σ², so σ_n grows as √n, not n.",
        ),
        Variant(
            "divides_by_sqrt_n",
            lambda s, n: s / np.sqrt(n),
            "Dividing by √n is the spread of an average of n readings; the sum of n step errors spreads as σ √n.",
        ),
        Variant(
            "root_of_sigma_n",
            lambda s, n: np.sqrt(s * np.asarray(n)),
            "The root is of the summed variances, n σ², not of σ n: σ_n = √(n σ²) = σ √n.",
        ),
        Variant(
            "off_by_one",
            lambda s, n: s * np.sqrt(np.asarray(n) + 1),
            "After n steps n step errors have added up, not n + 1: σ √n.",
        ),
        Variant(
            "off_by_one",
            lambda s, n: s * np.sqrt(np.maximum(np.asarray(n) - 1, 0)),  # a loop from 1 to n: none at n = 0
            "After n steps n step errors have added up, not n − 1: σ √n.",
        ),
        Variant(
            "scalar_only",
            lambda s, n: s * math.sqrt(n),
            "The step counts may come as an array: np.sqrt takes the root of each, math.sqrt only of one number.",
        ),
    ]


def drift_sigma(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``drift_sigma(step_std, n)`` against :func:`kfcourse.sim.drift_sigma`.

    ``n`` is a whole number of steps, or an array of them.  Introduced in chapter 0.

    Parameters
    ----------
    student_fn : callable ``(step_std, n) -> sigma``, a number for a number ``n``, an array for an array
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    _function(student_fn, "drift_sigma")
    cases = _drift_cases(np.random.default_rng(seed))
    return run_check(
        "sim.drift_sigma",
        student_fn,
        sim.drift_sigma,
        cases,
        _drift_variants(),
        ("sigma",),
        DRIFT_WHERE,
        steps=DRIFT_STEPS,
        probes=DRIFT_PROBES,
        invariants=(non_negative("sigma", "a spread"),),
    )


# --------------------------------------------------------------- affine_gaussian
# Each input moved alone (run_check's diagnosis): the covariance A Σ Aᵀ follows neither μ nor b.
AFFINE_PROBES = (
    Probe("mu", lambda x: x + 1.0, "the mean, A μ + b"),
    Probe("Sig", lambda x: 2.0 * x, "the covariance, A Σ Aᵀ"),
    Probe("A", lambda x: x + 0.5, "the mean A μ + b and the covariance A Σ Aᵀ"),
    Probe("b", lambda x: x + 1.0, "the mean, A μ + b"),
)


def _affine_cases(rng) -> list[Case]:
    """The cases of :func:`affine_gaussian`: the lesson's examples, then seeded random ones."""

    def one_d(label, A, b):  # X ~ N(2, 0.5), the lesson's example, as 1-element arrays
        return Case(label, mu=np.array([2.0]), Sig=np.array([[0.5]]), A=np.array([[A]]), b=np.array([b]))

    cases = [
        one_d("the lesson's Z = 2X, X ~ N(2, 0.5)", 2.0, 0.0),
        one_d("the lesson's Y = X + 3", 1.0, 3.0),
        one_d("Y = −0.5 X + 1", -0.5, 1.0),
        Case(
            "chapter 2's F: p + v Δt, v",
            mu=np.array([2.0, 1.0]),
            Sig=np.diag([0.5, 0.1]),
            A=np.array([[1.0, 1.0], [0.0, 1.0]]),
            b=np.zeros(2),
        ),
        Case(
            "a correlated Σ, a shift b",
            mu=np.array([1.0, -1.0]),
            Sig=np.array([[1.0, 0.6], [0.6, 2.0]]),
            A=np.array([[2.0, 1.0], [-1.0, 0.5]]),
            b=np.array([0.5, -2.0]),
        ),
        Case(
            "A with one row: a 2-D Gaussian seen along one direction",
            mu=np.array([1.0, 2.0]),
            Sig=np.array([[1.0, 0.3], [0.3, 0.5]]),
            A=np.array([[1.0, -1.0]]),
            b=np.array([0.5]),
        ),
    ]
    for _ in range(6):
        n, m = int(rng.integers(1, 4)), int(rng.integers(1, 4))
        cases.append(
            Case(
                f"random: n = {n}, m = {m}",
                mu=rng.normal(size=n),
                Sig=random_covariance(rng, n),
                A=rng.normal(size=(m, n)),
                b=rng.normal(size=m),
            )
        )
    return cases


AFFINE_WHERE = "chapter 2, closure property 1: Y = A X + b ~ N(A μ + b, A Σ Aᵀ)"


def _affine_variants() -> list[Variant]:
    """The catalogue of :func:`affine_gaussian`: each known mistake as a wrong version, with its hint."""
    sandwich = "The covariance gets A on both sides, A Σ Aᵀ; in one dimension that is A² σ², not A σ²."
    return [
        Variant(
            "elementwise_not_matmul",
            lambda mu, S, A, b: (A @ mu + b, A * S * A.T),
            "* multiplies entry by entry, which agrees with the sandwich only for 1 x 1 arrays: write A @ Sig @ A.T.",
        ),
        Variant("a_not_squared", lambda mu, S, A, b: (A @ mu + b, A @ S), sandwich),
        Variant("a_not_squared", lambda mu, S, A, b: (A @ mu + b, A * S), sandwich),
        Variant(
            "missing_transpose",
            lambda mu, S, A, b: (A @ mu + b, A @ S @ A),
            "The right-hand A of the sandwich is transposed: A Σ Aᵀ (A Σ A is not even symmetric).",
        ),
        Variant(
            "transpose_on_left",
            lambda mu, S, A, b: (A @ mu + b, A.T @ S @ A),
            "The transpose belongs on the right: A Σ Aᵀ, with A first (A is m x n, Σ n x n).",
        ),
        Variant(
            "b_in_covariance",
            lambda mu, S, A, b: (A @ mu + b, A @ S @ A.T + b),
            "A shift b moves the mean and leaves the spread alone: Σ_y = A Σ Aᵀ, with no b.",
        ),
        Variant(
            "b_forgotten",
            lambda mu, S, A, b: (A @ mu, A @ S @ A.T),
            "The mean is shifted by b: μ_y = A μ + b.",
        ),
    ]


def affine_gaussian(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``affine_gaussian(mu, Sig, A, b)`` against :func:`kfcourse.affine_gaussian`.

    Every input is an array: ``mu`` (n,), ``Sig`` (n, n), ``A`` (m, n), ``b`` (m,); the
    lesson's one-dimensional example comes as 1-element arrays.  Introduced in chapter 2.

    Parameters
    ----------
    student_fn : callable ``(mu (n,), Sig (n, n), A (m, n), b (m,)) -> (mu_y (m,), Sig_y (m, m))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _affine_cases(np.random.default_rng(seed))
    return run_check(
        "affine_gaussian",
        student_fn,
        filters.affine_gaussian,
        cases,
        _affine_variants(),
        ("mu", "Sig"),
        AFFINE_WHERE,
        probes=AFFINE_PROBES,
        invariants=(is_covariance("Sig"),),
    )


# ---------------------------------------------------------------------- cv_model
def _cv_reference(dt, accel_var):
    """Chapter 6's F (constant velocity, two axes) and R (white-noise acceleration)."""
    return models.constant_velocity(dt, 2)[0], sim.process_noise(dt, accel_var)


def _cv_with(dt, accel_var, *, pos=None, var=None, diagonal=False, interleaved=False, transposed=False):
    """F and R of chapter 6, with a knob for each mistake: ``pos`` replaces ½Δt² in Γ, ``var`` σa²."""
    I, Z = np.eye(2), np.zeros((2, 2))
    F = np.block([[I, dt * I], [Z, I]])
    Gamma = np.vstack([(0.5 * dt**2 if pos is None else pos) * I, dt * I])
    R = (accel_var if var is None else var) * Gamma @ Gamma.T
    if diagonal:
        R = np.diag(np.diag(R))
    if transposed:
        F = F.T
    if interleaved:  # state [px, vx, py, vy]
        order = [0, 2, 1, 3]
        F, R = F[np.ix_(order, order)], R[np.ix_(order, order)]
    return F, R


# With no acceleration noise R is 0, so the answer is F alone; each input moved alone (run_check's diagnosis).
CV_STEPS = (Step("σa² = 0", "F = [[I, Δt I], [0, I]] with R = 0", lambda i: {**i, "accel_var": 0.0}),)
CV_PROBES = (
    Probe("accel_var", lambda q: 2.0 * q + 1.0, "R = σa² Γ Γᵀ alone, not F"),
    Probe("dt", lambda dt: 1.5 * dt, "F's Δt I and every entry of R, through Γ = [½Δt² I; Δt I]"),
)


def cv_model(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``cv_model(dt, accel_var)`` against chapter 6's ``F`` and ``R``.

    The state is ``[px, py, vx, vy]``; ``F`` is ``kf.models.constant_velocity(dt, 2)[0]`` and
    ``R`` the white-noise-acceleration process noise ``kf.sim.process_noise(dt, accel_var)``.
    Introduced in chapter 6.

    Parameters
    ----------
    student_fn : callable ``(dt, accel_var) -> (F (4, 4), R (4, 4))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    cases = [
        Case("chapter 6's tracker: Δt = 0.1 s, σa² = 10", dt=0.1, accel_var=10.0),
        Case("Δt = 0.5 s, σa² = 2", dt=0.5, accel_var=2.0),
        Case("Δt = 1 s, σa² = 1", dt=1.0, accel_var=1.0),
        Case("no acceleration noise, σa² = 0", dt=0.1, accel_var=0.0),
    ]
    for _ in range(6):
        cases.append(Case("random", dt=float(rng.uniform(0.05, 3.0)), accel_var=float(rng.uniform(0.1, 50.0))))
    where = (
        "chapter 6: F = [[I, Δt I], [0, I]] for the state [px, py, vx, vy], and R = σa² Γ Γᵀ with Γ = [½Δt² I; Δt I]"
    )
    position = "An acceleration a held for Δt moves the position by ½ a Δt² (and the velocity by a Δt)"
    variants = [
        Variant(
            "state_order",
            lambda dt, q: _cv_with(dt, q, interleaved=True),
            "The state is ordered [px, py, vx, vy]: both positions first, then both velocities; F and R "
            "follow that order.",
        ),
        Variant(
            "F_transposed",
            lambda dt, q: _cv_with(dt, q, transposed=True),
            "Row i of F says what the new i-th entry is made of: p_x' = p_x + Δt v_x puts Δt in row 0, column 2 "
            "(above the diagonal), not below.",
        ),
        Variant("missing_half", lambda dt, q: _cv_with(dt, q, pos=dt**2), position + ": the ½ is missing."),
        Variant("dt_not_dt2", lambda dt, q: _cv_with(dt, q, pos=0.5 * dt), position + ": Δt², not Δt."),
        Variant("dt_not_dt2", lambda dt, q: _cv_with(dt, q, pos=dt), position + ": ½ Δt², not Δt."),
        Variant(
            "R_diagonal",
            lambda dt, q: _cv_with(dt, q, diagonal=True),
            "One acceleration moves position and velocity together, so R = σa² Γ Γᵀ has the cross terms "
            "σa² Δt³/2 between p_x and v_x (and p_y and v_y).",
        ),
        Variant(
            "std_not_var",
            lambda dt, q: _cv_with(dt, q, var=np.sqrt(q)),
            "accel_var is already the variance σa²: R = σa² Γ Γᵀ takes it as it is, no square root.",
        ),
        Variant(
            "std_not_var",
            lambda dt, q: _cv_with(dt, q, var=q**2),
            "accel_var is already the variance σa²: R = σa² Γ Γᵀ takes it as it is, not squared.",
        ),
    ]
    _function(student_fn, "cv_model")
    reference = "models.constant_velocity(dt, 2)[0] and kf.sim.process_noise"
    return run_check(
        reference,
        student_fn,
        _cv_reference,
        cases,
        variants,
        ("F", "R"),
        where,
        steps=CV_STEPS,
        probes=CV_PROBES,
        invariants=(is_covariance("R"),),
    )
