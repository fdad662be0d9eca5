"""Checkers for chapters 3-5: the scalar Kalman filter, fusion, the matrix Kalman filter.

Noise letters follow the course: ``R`` is process (motion) noise, ``Q`` measurement noise.
"""

from __future__ import annotations

import numpy as np

from .. import filters
from ._core import Case, CheckResult, Variant, random_covariance, run_check


# --------------------------------------------------------------------- kf_1d_step
def _kf_1d_with(mu, var, u, z, a, b, c, R, Q, *, a2=None, innovation_sign=1.0):
    """Equations (1)-(5) of chapter 3, with knobs for the mistakes."""
    mu_bar = a * mu + b * u  # (1)
    var_bar = (a * a if a2 is None else a2) * var + R  # (2)
    K = c * var_bar / (c * c * var_bar + Q)  # (3)
    mu_new = mu_bar + K * innovation_sign * (z - c * mu_bar)  # (4)
    return mu_new, (1 - K * c) * var_bar  # (5)


def kf_1d_step(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``kf_1d_step(mu, var, u, z, a, b, c, R, Q)`` against :func:`kfcourse.kf_1d_step`.

    Every argument is passed, in that order (``z`` is always a number).
    Introduced in chapter 3.

    Parameters
    ----------
    student_fn : callable ``(mu, var, u, z, a, b, c, R, Q) -> (mu, var)``, all floats
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    defaults = {"a": 1.0, "b": 1.0, "c": 1.0, "R": 0.2, "Q": 0.1}
    cyc1 = filters.kf_1d_step(2.0, 0.4, 1.0, 3.6)
    cases = [
        Case("the chapter's cycle 1", mu=2.0, var=0.4, u=1.0, z=3.6, **defaults),
        Case("the chapter's cycle 2", mu=cyc1[0], var=cyc1[1], u=1.0, z=4.7, **defaults),
        Case("a perfectly known start, var = 0", mu=0.5, var=0.0, u=-1.0, z=0.2, **defaults),
        Case("a ≠ 1, c ≠ 1", mu=1.0, var=0.5, u=0.3, z=2.0, a=0.9, b=2.0, c=1.5, R=0.05, Q=0.3),
    ]
    for _ in range(10):
        R, Q = rng.uniform(0.01, 2.0, 2)
        a, b, c = rng.uniform(-1.5, 1.5, 3)
        mu, u, z = rng.normal(0, 3, 3)
        var = rng.uniform(0, 3)
        cases.append(Case("random a, b, c, R ≠ Q", mu=mu, var=var, u=u, z=z, a=a, b=b, c=c, R=R, Q=Q))
    ch3 = "chapter 3, equations (1)-(5)"
    variants = [
        Variant(
            "swapped_R_Q",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, Q, R),
            "R is the motion noise, added in the predict step (2), σ̄² = a²σ² + R; Q is the sensor's noise, "
            "in the gain (3), K = cσ̄² / (c²σ̄² + Q).",
        ),
        Variant(
            "std_not_var",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, R**2, Q**2),
            "R and Q are already variances (σ_R², σ_Q²); add them as they are, do not square them.",
        ),
        Variant(
            "std_not_var",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, np.sqrt(R), np.sqrt(Q)),
            "R and Q are variances (σ_R², σ_Q²) and go into (2) and (3) as they are, without a square root.",
        ),
        Variant(
            "sign_flip",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, R, Q, innovation_sign=-1.0),
            "the innovation in (4) is z − c μ̄ (the reading minus what was predicted), not c μ̄ − z.",
        ),
        Variant(
            "a_not_squared",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, R, Q, a2=a),
            "equation (2) scales the variance by a², σ̄² = a²σ² + R (a variance scales by the square).",
        ),
    ]
    return run_check("kf_1d_step", student_fn, filters.kf_1d_step, cases, variants, ("mu", "var"), ch3)


# ---------------------------------------------------------------------------- fuse
def _precision_fusion(mu1, var1, mu2, var2):
    """Inverse-variance fusion of chapter 4: precisions add, each mean weighted by its precision."""
    precision = 1 / var1 + 1 / var2
    return (mu1 / var1 + mu2 / var2) / precision, 1 / precision


def fuse(student_fn, seed: int = 0) -> CheckResult:
    """Check your scalar ``fuse(mu1, var1, mu2, var2)`` against :func:`kfcourse.fuse`.

    Introduced in chapter 4 (inverse-variance fusion).

    Parameters
    ----------
    student_fn : callable ``(mu1, var1, mu2, var2) -> (mu, var)``, all floats
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    cases = [
        Case("chapter 3's cycle 1: prediction and reading", mu1=3.0, var1=0.6, mu2=3.6, var2=0.1),
        Case("equal variances", mu1=0.0, var1=0.3, mu2=1.0, var2=0.3),
        Case("a very sure and a very unsure estimate", mu1=-2.0, var1=1e-4, mu2=5.0, var2=50.0),
    ]
    for _ in range(10):
        mu1, mu2 = rng.normal(0, 5, 2)
        var1, var2 = rng.uniform(0.01, 4.0, 2)
        cases.append(Case("random", mu1=mu1, var1=var1, mu2=mu2, var2=var2))
    where = "chapter 4, inverse-variance fusion: μ = (μ₁/σ₁² + μ₂/σ₂²) / (1/σ₁² + 1/σ₂²), 1/σ² = 1/σ₁² + 1/σ₂²"
    variants = [
        Variant(
            "wrong_weights",
            lambda m1, v1, m2, v2: ((v1 * m1 + v2 * m2) / (v1 + v2), v1 * v2 / (v1 + v2)),
            "Each estimate is weighted by the other's variance (by its own precision), so the surer one "
            "pulls harder: μ = (σ₂² μ₁ + σ₁² μ₂) / (σ₁² + σ₂²).",
        ),
        Variant(
            "std_not_var",
            lambda m1, v1, m2, v2: _precision_fusion(m1, v1**2, m2, v2**2),
            "var1 and var2 are already variances: the precisions are 1/var1 and 1/var2, not 1/var1².",
        ),
        Variant(
            "adds_variances",
            lambda m1, v1, m2, v2: ((v2 * m1 + v1 * m2) / (v1 + v2), v1 + v2),
            "Fusing two estimates adds their precisions, so the fused variance is smaller than both; "
            "adding variances is what a predict step does.",
        ),
    ]
    return run_check("fuse", student_fn, filters.fuse, cases, variants, ("mu", "var"), where)


# ------------------------------------------------------------------------ kf_step
def _kf_step_with(mu, Sig, u, z, F, B, H, R, Q, *, transpose=True, innovation_sign=1.0, correction_sign=-1.0):
    """Equations (1)-(5) of chapter 5, with knobs for the mistakes."""
    mu_bar = F @ mu + B @ u  # (1)
    Sig_bar = F @ Sig @ (F.T if transpose else F) + R  # (2)
    S = H @ Sig_bar @ H.T + Q  # (3)
    K = Sig_bar @ H.T @ np.linalg.inv(S)  # (3)
    mu_new = mu_bar + K @ (innovation_sign * (z - H @ mu_bar))  # (4)
    return mu_new, (np.eye(mu.size) + correction_sign * K @ H) @ Sig_bar  # (5)


def _kf_case(rng, label: str, n: int, k: int, m: int) -> Case:
    return Case(
        label,
        mu=rng.normal(size=n),
        Sig=random_covariance(rng, n),
        u=rng.normal(size=m),
        z=rng.normal(size=k),
        F=np.eye(n) + 0.5 * rng.normal(size=(n, n)),  # not symmetric: a missing transpose shows
        B=rng.normal(size=(n, m)),
        H=rng.normal(size=(k, n)),
        R=random_covariance(rng, n, 0.1),
        Q=random_covariance(rng, k, 0.5),
    )


def kf_step(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``kf_step(mu, Sig, u, z, F, B, H, R, Q)`` against :func:`kfcourse.kf_step`.

    ``u``, ``B`` and ``z`` are always arrays (no control is ``B`` of zeros).
    Introduced in chapter 5.

    Parameters
    ----------
    student_fn : callable ``(mu (n,), Sig (n, n), u (m,), z (k,), F (n, n), B (n, m), H (k, n), R (n, n), Q (k, k))
        -> (mu (n,), Sig (n, n))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    cases = [_kf_case(rng, "n = k = 2, so R and Q have one shape", 2, 2, 1) for _ in range(2)]
    cases.append(
        Case(
            "the chapter's constant-velocity example",
            mu=np.array([0.0, 1.0]),
            Sig=np.eye(2),
            u=np.zeros(1),
            z=np.array([1.2]),
            F=np.array([[1.0, 1.0], [0.0, 1.0]]),
            B=np.zeros((2, 1)),
            H=np.array([[1.0, 0.0]]),
            R=0.01 * np.eye(2),
            Q=np.array([[0.5]]),
        )
    )
    cases.append(_kf_case(rng, "n = 1 (every matrix 1 x 1)", 1, 1, 1))
    for _ in range(8):
        n = int(rng.integers(2, 5))
        k, m = int(rng.integers(1, n + 1)), int(rng.integers(1, 3))
        cases.append(_kf_case(rng, f"random: n = {n}, k = {k}, m = {m}", n, k, m))
    ch5 = "chapter 5, equations (1)-(5)"
    variants = [
        Variant(
            "swapped_R_Q",
            lambda mu, Sig, u, z, F, B, H, R, Q: _kf_step_with(mu, Sig, u, z, F, B, H, Q, R),
            "R, the process noise (n x n), is added in the predict step (2), Σ̄ = FΣFᵀ + R; Q, the "
            "measurement noise (k x k), in the innovation covariance (3), S = HΣ̄Hᵀ + Q.",
        ),
        Variant(
            "missing_transpose",
            lambda *args: _kf_step_with(*args, transpose=False),
            "equation (2) is Σ̄ = F Σ Fᵀ + R, with F on both sides and the transpose on the right.",
        ),
        Variant(
            "sign_flip",
            lambda *args: _kf_step_with(*args, innovation_sign=-1.0),
            "the innovation in (4) is z − H μ̄ (the reading minus the predicted reading).",
        ),
        Variant(
            "sign_flip",
            lambda *args: _kf_step_with(*args, correction_sign=1.0),
            "equation (5) is Σ = (I − K H) Σ̄: the update shrinks the covariance.",
        ),
    ]
    return run_check("kf_step", student_fn, filters.kf_step, cases, variants, ("mu", "Sig"), ch5)
