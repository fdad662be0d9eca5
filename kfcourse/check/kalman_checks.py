"""Checkers for chapters 3-5: the scalar Kalman filter, fusion, the matrix Kalman filter.

Noise letters follow the course: ``R`` is process (motion) noise, ``Q`` measurement noise.
"""

from __future__ import annotations

import numpy as np

from .. import filters
from ._core import (
    Case,
    CheckResult,
    Invariant,
    Probe,
    Step,
    Variant,
    is_covariance,
    non_negative,
    random_covariance,
    run_check,
)


# --------------------------------------------------------------------- kf_1d_step
def _kf_1d_with(
    mu,
    var,
    u,
    z,
    a,
    b,
    c,
    R,
    Q,
    *,
    a2=None,
    innovation_sign=1.0,
    bu=True,
    gain_c=True,
    update_c=True,
    gain_from="var_bar",
    innovation_from="mu_bar",
    update_from="var_bar",
):
    """Equations (1)-(5) of chapter 3, with knobs for the mistakes (the defaults are right)."""
    mu_bar = a * mu + (b * u if bu else 0.0)  # (1)
    var_bar = (a * a if a2 is None else a2) * var + R  # (2)
    seen = {"var_bar": var_bar, "var": var, "mu_bar": mu_bar, "mu": mu}
    c_in_gain = c if gain_c else 1.0
    K = c_in_gain * seen[gain_from] / (c_in_gain**2 * seen[gain_from] + Q)  # (3)
    mu_new = mu_bar + K * innovation_sign * (z - c * seen[innovation_from])  # (4)
    return mu_new, (1 - K * (c if update_c else 1.0)) * seen[update_from]  # (5)


# Chapter 3's step, one equation group at a time, and its inputs one at a time (run_check's diagnosis).
KF_1D_STEPS = (
    Step("c = 0", "the prediction (1)-(2) alone", lambda i: {**i, "c": 0.0}),
    Step("a = 1, b = 0 and R = 0", "the update (3)-(5) alone", lambda i: {**i, "a": 1.0, "b": 0.0, "R": 0.0}),
)
KF_1D_PROBES = (
    Probe("mu", lambda x: x + 1.0, "(1), μ̄ = aμ + bu"),
    Probe("var", lambda x: x + 0.5, "(2), σ̄² = a²σ² + R"),
    Probe("u", lambda x: x + 1.0, "(1), μ̄ = aμ + bu"),
    Probe("z", lambda x: x + 1.0, "(4), μ = μ̄ + K(z − cμ̄)"),
    Probe("a", lambda x: x + 0.3, "(1) and (2)"),
    Probe("b", lambda x: x + 0.5, "(1), μ̄ = aμ + bu"),
    Probe("c", lambda x: x + 0.3, "(3), (4) and (5)"),
    Probe("R", lambda x: x + 0.3, "(2), σ̄² = a²σ² + R"),
    Probe("Q", lambda x: x + 0.3, "(3), K = cσ̄² / (c²σ̄² + Q)"),
)


def _kf_1d_cases(rng) -> list[Case]:
    """The cases of :func:`kf_1d_step`: chapter 3's two cycles, the edge cases, then seeded random ones."""
    defaults = {"a": 1.0, "b": 1.0, "c": 1.0, "R": 0.2, "Q": 0.1}
    cyc1 = filters.kf_1d_step(2.0, 0.4, 1.0, 3.6)
    cases = [
        Case("chapter 3's worked example: cycle 1", mu=2.0, var=0.4, u=1.0, z=3.6, **defaults),
        Case("chapter 3's worked example: cycle 2", mu=cyc1[0], var=cyc1[1], u=1.0, z=4.7, **defaults),
        Case("a perfectly known start, var = 0", mu=0.5, var=0.0, u=-1.0, z=0.2, **defaults),
        Case(
            "known exactly, var = 0 and R = 0: σ̄² = 0, K = 0",
            mu=0.5,
            var=0.0,
            u=-1.0,
            z=0.2,
            **{**defaults, "R": 0.0},
        ),
        Case("a ≠ 1, c ≠ 1", mu=1.0, var=0.5, u=0.3, z=2.0, a=0.9, b=2.0, c=1.5, R=0.05, Q=0.3),
    ]
    for _ in range(10):
        R, Q = rng.uniform(0.01, 2.0, 2)
        a, b, c = rng.uniform(-1.5, 1.5, 3)
        mu, u, z = rng.normal(0, 3, 3)
        var = rng.uniform(0, 3)
        cases.append(Case("random a, b, c, R ≠ Q", mu=mu, var=var, u=u, z=z, a=a, b=b, c=c, R=R, Q=Q))
    return cases


KF_1D_WHERE = "chapter 3, equations (1)-(5)"


def _kf_1d_variants() -> list[Variant]:
    """The catalogue of :func:`kf_1d_step`: each known mistake as a wrong version, with its hint."""
    return [
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
        Variant(
            "forgot_R",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, 0.0, Q),
            "the predict step (2) adds the motion noise: σ̄² = a²σ² + R.",
        ),
        Variant(
            "forgot_Q",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, R, 0.0),
            "the gain (3) weighs the prediction against the sensor's noise: K = cσ̄² / (c²σ̄² + Q).",
        ),
        Variant(
            "forgot_control",
            lambda mu, var, u, z, a, b, c, R, Q: _kf_1d_with(mu, var, u, z, a, b, c, R, Q, bu=False),
            "the predicted mean (1) moves with the control: μ̄ = aμ + bu.",
        ),
        Variant(
            "prior_not_predicted",
            lambda *args: _kf_1d_with(*args, gain_from="var"),
            "the gain (3) is built from the predicted variance σ̄², not from σ².",
        ),
        Variant(
            "prior_not_predicted",
            lambda *args: _kf_1d_with(*args, innovation_from="mu"),
            "the innovation (4) compares the reading with the predicted reading: z − c μ̄, not z − c μ.",
        ),
        Variant(
            "prior_not_predicted",
            lambda *args: _kf_1d_with(*args, update_from="var"),
            "the update (5) shrinks the predicted variance: σ² = (1 − Kc) σ̄².",
        ),
        Variant(
            "c_left_out",
            lambda *args: _kf_1d_with(*args, gain_c=False),
            "K = σ̄² / (σ̄² + Q) is the gain for c = 1; in general (3) is K = cσ̄² / (c²σ̄² + Q).",
        ),
        Variant(
            "c_left_out",
            lambda *args: _kf_1d_with(*args, update_c=False),
            "the update (5) is σ² = (1 − Kc) σ̄²; (1 − K) is its c = 1 form.",
        ),
        Variant(
            "c_left_out",
            lambda *args: _kf_1d_with(*args, gain_c=False, update_c=False),
            "K = σ̄² / (σ̄² + Q) and (1 − K) are the c = 1 forms of (3) and (5): keep c in both.",
        ),
    ]


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
    cases = _kf_1d_cases(np.random.default_rng(seed))
    return run_check(
        "kf_1d_step",
        student_fn,
        filters.kf_1d_step,
        cases,
        _kf_1d_variants(),
        ("mu", "var"),
        KF_1D_WHERE,
        steps=KF_1D_STEPS,
        probes=KF_1D_PROBES,
        invariants=(non_negative("var", "a variance"),),
    )


# ---------------------------------------------------------------------------- fuse
def _precision_fusion(mu1, var1, mu2, var2):
    """Inverse-variance fusion of chapter 4: precisions add, each mean weighted by its precision."""
    precision = 1 / var1 + 1 / var2
    return (mu1 / var1 + mu2 / var2) / precision, 1 / precision


# Each input moved alone (run_check's diagnosis): the fused variance follows the variances only.
# Equal variances weigh the means alike; equal means leave only the variance to fuse.
FUSE_STEPS = (
    Step(
        "σ₁² = σ₂²",
        "the plain average of the means, with half the variance",
        lambda i: {**i, "var2": i["var1"]},
    ),
    Step("μ₁ = μ₂", "that same mean, whatever the weights, and the fused variance", lambda i: {**i, "mu2": i["mu1"]}),
)
# Fusing never makes an estimate less sure than the surer of the two, and its mean lies between the two means.
FUSE_INVARIANTS = (
    Invariant(
        lambda i, p: 0 <= p["var"] <= min(i["var1"], i["var2"]) * (1 + 1e-9),
        "your var is not between 0 and the smaller of var1 and var2: fusing two estimates gives one at least as sure "
        "as the surer of them, 1/σ² = 1/σ₁² + 1/σ₂²",
    ),
    Invariant(
        lambda i, p: min(i["mu1"], i["mu2"]) - 1e-9 <= p["mu"] <= max(i["mu1"], i["mu2"]) + 1e-9,
        "your mu is not between mu1 and mu2: the fused mean is a weighted average of the two, with weights that are "
        "positive and sum to 1",
    ),
)
FUSE_PROBES = (
    Probe("mu1", lambda x: x + 1.0, "the fused mean, μ = (μ₁/σ₁² + μ₂/σ₂²) / (1/σ₁² + 1/σ₂²)"),
    Probe("var1", lambda x: 2.0 * x, "the fused variance, 1/σ² = 1/σ₁² + 1/σ₂², and the mean"),
    Probe("mu2", lambda x: x + 1.0, "the fused mean, μ = (μ₁/σ₁² + μ₂/σ₂²) / (1/σ₁² + 1/σ₂²)"),
    Probe("var2", lambda x: 2.0 * x, "the fused variance, 1/σ² = 1/σ₁² + 1/σ₂², and the mean"),
)


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
        Case(
            "chapter 4's worked example: prediction N(3, 0.6), reading N(3.6, 0.1)",
            mu1=3.0,
            var1=0.6,
            mu2=3.6,
            var2=0.1,
        ),
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
            "wrong_weights",
            lambda m1, v1, m2, v2: ((m1 + m2) / 2, 1 / (1 / v1 + 1 / v2)),
            "A plain average ignores how sure each estimate is: weight each mean by its precision 1/σ².",
        ),
        Variant(
            "adds_variances",
            lambda m1, v1, m2, v2: ((v2 * m1 + v1 * m2) / (v1 + v2), v1 + v2),
            "Fusing two estimates adds their precisions, so the fused variance is smaller than both; "
            "adding variances is what a predict step does.",
        ),
    ]
    return run_check(
        "fuse",
        student_fn,
        filters.fuse,
        cases,
        variants,
        ("mu", "var"),
        where,
        steps=FUSE_STEPS,
        probes=FUSE_PROBES,
        invariants=FUSE_INVARIANTS,
    )


# ------------------------------------------------------------------------ kf_step
def _kf_step_with(mu, Sig, u, z, F, B, H, R, Q, **mistake):
    """Equations (1)-(5) of chapter 5; a keyword of :func:`kf_step`'s variants makes one mistake."""
    wrong = mistake.get
    mu_bar = (mu @ F if wrong("row_vector") else F @ mu) + (0.0 if wrong("no_Bu") else B @ u)  # (1)
    if wrong("no_FT"):
        FSF = F @ Sig @ F
    else:
        FSF = F.T @ Sig @ F if wrong("FT_left") else F @ Sig @ F.T
    Sig_bar = FSF + (0.0 if wrong("no_R") else R)  # (2)
    S = H @ (Sig if wrong("S_from") else Sig_bar) @ H.T + (0.0 if wrong("no_Q") else Q)  # (3)
    S_inv = {"none": S, "entries": 1 / S}[wrong("inverse")] if wrong("inverse") else np.linalg.inv(S)
    K = (Sig if wrong("K_from") else Sig_bar) @ (H if wrong("no_HT") else H.T) @ S_inv  # (3)
    innovation = z - H @ (mu if wrong("innovation_from") else mu_bar)
    mu_new = mu_bar + K @ (-innovation if wrong("innovation_sign") else innovation)  # (4)
    I_KH = np.eye(mu.size) + (K @ H if wrong("correction_sign") else -K @ H)
    Sig_from = Sig if wrong("update_from") else Sig_bar
    return mu_new, (Sig_from @ I_KH if wrong("right_side") else I_KH @ Sig_from)  # (5)


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


def _kf_variant(mistake: str, knob: str, hint: str, value=True) -> Variant:
    return Variant(mistake, lambda *args: _kf_step_with(*args, **{knob: value}), hint)


# Chapter 5's step, one equation group at a time, and its inputs one at a time (run_check's diagnosis).
KF_STEPS = (
    Step("H = 0", "the prediction (1)-(2) alone", lambda i: {**i, "H": np.zeros_like(i["H"])}),
    Step(
        "F = I, B = 0 and R = 0",
        "the update (3)-(5) alone",
        lambda i: {**i, "F": np.eye(len(i["mu"])), "B": np.zeros_like(i["B"]), "R": np.zeros_like(i["R"])},
    ),
)
KF_PROBES = (
    Probe("mu", lambda x: x + 1.0, "(1), μ̄ = Fμ + Bu"),
    Probe("Sig", lambda x: x + 0.5 * np.eye(len(x)), "(2), Σ̄ = FΣFᵀ + R"),
    Probe("u", lambda x: x + 1.0, "(1), μ̄ = Fμ + Bu"),
    Probe("z", lambda x: x + 1.0, "(4), μ = μ̄ + K(z − Hμ̄)"),
    Probe("F", lambda x: x + 0.3, "(1) and (2)"),
    Probe("B", lambda x: x + 0.5, "(1), μ̄ = Fμ + Bu"),
    Probe("H", lambda x: x + 0.3, "(3), (4) and (5)"),
    Probe("R", lambda x: x + 0.5 * np.eye(len(x)), "(2), Σ̄ = FΣFᵀ + R"),
    Probe("Q", lambda x: x + 0.5 * np.eye(len(x)), "(3), S = HΣ̄Hᵀ + Q"),
)


def _kf_cases(rng) -> list[Case]:
    """The cases of :func:`kf_step`: chapter 5's worked example, the edge cases, then seeded random ones."""
    cases = [
        Case(
            "chapter 5's worked example: constant velocity, z = 1.2",
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
    ]
    cases += [_kf_case(rng, "n = k = 2, so R and Q have one shape", 2, 2, 1) for _ in range(2)]
    cases.append(_kf_case(rng, "n = 1 (every matrix 1 x 1)", 1, 1, 1))
    for _ in range(8):
        n = int(rng.integers(2, 5))
        k, m = int(rng.integers(1, n + 1)), int(rng.integers(1, 3))
        cases.append(_kf_case(rng, f"random: n = {n}, k = {k}, m = {m}", n, k, m))
    return cases


KF_WHERE = "chapter 5, equations (1)-(5)"


def _kf_variants() -> list[Variant]:
    """The catalogue of :func:`kf_step`: each known mistake as a wrong version, with its hint."""
    return [
        Variant(
            "swapped_R_Q",
            lambda mu, Sig, u, z, F, B, H, R, Q: _kf_step_with(mu, Sig, u, z, F, B, H, Q, R),
            "R, the process noise (n x n), is added in the predict step (2), Σ̄ = FΣFᵀ + R; Q, the "
            "measurement noise (k x k), in the innovation covariance (3), S = HΣ̄Hᵀ + Q.",
        ),
        _kf_variant("missing_transpose", "no_FT", "equation (2) is Σ̄ = F Σ Fᵀ + R, with the transpose on the right."),
        _kf_variant("missing_transpose", "FT_left", "equation (2) is Σ̄ = F Σ Fᵀ + R: the transpose is on the right."),
        _kf_variant("missing_transpose", "no_HT", "the gain (3) is K = Σ̄ Hᵀ S⁻¹, with H transposed."),
        _kf_variant(
            "sign_flip", "innovation_sign", "the innovation in (4) is z − H μ̄ (the reading minus the prediction)."
        ),
        _kf_variant(
            "sign_flip", "correction_sign", "equation (5) is Σ = (I − K H) Σ̄: the update shrinks the covariance."
        ),
        _kf_variant("forgot_R", "no_R", "the predict step (2) adds the process noise: Σ̄ = F Σ Fᵀ + R."),
        _kf_variant("forgot_Q", "no_Q", "the innovation covariance (3) adds the sensor's noise: S = H Σ̄ Hᵀ + Q."),
        _kf_variant("forgot_control", "no_Bu", "the predicted mean (1) moves with the control: μ̄ = F μ + B u."),
        _kf_variant("prior_not_predicted", "K_from", "the gain (3) is built from the predicted Σ̄: K = Σ̄ Hᵀ S⁻¹."),
        Variant(
            "prior_not_predicted",
            lambda *args: _kf_step_with(*args, K_from=True, S_from=True),
            "the gain (3) is built from the predicted Σ̄, in K and in S: K = Σ̄ Hᵀ (H Σ̄ Hᵀ + Q)⁻¹.",
        ),
        _kf_variant("prior_not_predicted", "innovation_from", "the innovation (4) is z − H μ̄, with the predicted μ̄."),
        _kf_variant("prior_not_predicted", "update_from", "the update (5) shrinks the predicted Σ̄: Σ = (I − K H) Σ̄."),
        _kf_variant("no_inverse", "inverse", "the gain (3) divides by S: K = Σ̄ Hᵀ S⁻¹, with np.linalg.inv(S).", "none"),
        _kf_variant(
            "elementwise_inverse",
            "inverse",
            "1 / S inverts each entry, which is S⁻¹ only when S is 1 x 1: use np.linalg.inv(S) in (3).",
            "entries",
        ),
        _kf_variant("wrong_order", "right_side", "equation (5) is Σ = (I − K H) Σ̄, with (I − K H) on the left."),
        _kf_variant("wrong_order", "row_vector", "equation (1) is μ̄ = F μ + B u, with F on the left of μ."),
    ]


def kf_step(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``kf_step(mu, Sig, u, z, F, B, H, R, Q)`` against :func:`kfcourse.kf_step`.

    ``u``, ``B`` and ``z`` are always arrays (no control is ``B`` of zeros).  The first case is
    chapter 5's worked example.  Introduced in chapter 5.

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
    cases = _kf_cases(np.random.default_rng(seed))
    return run_check(
        "kf_step",
        student_fn,
        filters.kf_step,
        cases,
        _kf_variants(),
        ("mu", "Sig"),
        KF_WHERE,
        steps=KF_STEPS,
        probes=KF_PROBES,
        invariants=(is_covariance("Sig"),),
    )
