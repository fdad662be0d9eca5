"""Checkers for chapter 9: the sigma points and their weights, and the unscented transform."""

from __future__ import annotations

import numpy as np

from .. import filters
from ._core import (
    ATOL,
    RTOL,
    Case,
    CheckResult,
    Probe,
    Step,
    Variant,
    is_covariance,
    random_covariance,
    run_check,
    sums_to_one,
)

CH9_WEIGHTS = "w₀ = λ/(n + λ), wᵢ = 1/(2(n + λ))"


def _sigma_points_with(mu, Sig, lam, *, root="cholesky", columns=True, weights="julier", as_rows=True, scale="in"):
    """The sigma points of chapter 9, with knobs for the mistakes (the defaults are right)."""
    n = mu.size
    A = {"in": (n + lam) * Sig, "none": Sig, "out": Sig}[scale]  # L L^T = (n + lam) Sig
    if root == "cholesky":
        L = np.linalg.cholesky(A)
    elif root == "symmetric":
        w, V = np.linalg.eigh(A)
        L = V @ np.diag(np.sqrt(w)) @ V.T
    elif root == "entries":  # np.sqrt of each entry (NaN where an entry is negative)
        L = np.sqrt(A)
    else:  # no square root at all
        L = A
    L = (n + lam) * L if scale == "out" else L
    D = L.T if columns else L  # one row per column of L
    chi = np.vstack([mu, mu + D, mu - D])
    wm = np.full(2 * n + 1, 0.5 / (n + lam))  # w_i = 1 / (2 (n + lam))
    wm[0] = lam / (n + lam)  # w_0 = lam / (n + lam)
    if weights == "no_half":
        wm[1:] = 1.0 / (n + lam)
    elif weights == "one_over_2n":
        wm[1:] = 0.5 / n
    elif weights == "equal":
        wm[:] = 1.0 / (2 * n + 1)
    wc = wm.copy()
    if weights == "beta":
        wc[0] += 2.0
    return (chi if as_rows else chi.T), wm, wc


def _pair_points(expected, got):
    """``got`` = (chi, wm, wc) in ``expected``'s order when it is the same points in another order.

    A valid set of sigma points may come in any order: each of the reference's points (a row
    of chi with its two weights) is paired with the nearest of the student's not yet paired.
    When every pair matches, the reordered answer is returned; any other answer as it is.
    """
    chi, wm, wc = (np.asarray(x, dtype=float) for x in got)
    mine = np.column_stack([chi, wm, wc])
    theirs = np.column_stack([np.asarray(x, dtype=float) for x in expected])
    if mine.shape != theirs.shape:
        return got
    order = []
    for point in theirs:
        distance = np.linalg.norm(mine - point, axis=1)
        distance[order] = np.inf  # each of the student's points is paired once
        order.append(int(np.argmin(distance)))
    return (chi[order], wm[order], wc[order]) if np.allclose(mine[order], theirs, rtol=RTOL, atol=ATOL) else got


# One coordinate alone (n = 1, no correlation to follow) and a diagonal Σ (its root the standard deviations).
SIGMA_STEPS = (
    Step(
        "n = 1 (the first coordinate of μ and Σ alone)",
        "the points μ and μ ± √((1 + λ)σ²), with w₀ = λ/(1 + λ)",
        lambda i: {**i, "mu": np.asarray(i["mu"])[:1], "Sig": np.asarray(i["Sig"])[:1, :1]},
    ),
    Step(
        "Σ diagonal (its off-diagonal entries 0)",
        "the points μ ± √(n + λ) σⱼ along each axis, with the same weights",
        lambda i: {**i, "Sig": np.diag(np.diag(i["Sig"]))},
    ),
)
# Each input moved alone (run_check's diagnosis): μ moves every point and no weight; Σ spreads the points and
# leaves the weights; λ changes both.
SIGMA_PROBES = (
    Probe("mu", lambda x: x + 1.0, "every point, χ₀ = μ and χᵢ = μ ± Lᵢ, and no weight"),
    Probe("Sig", lambda x: 2.0 * x, "the spread L of the points (L Lᵀ = (n + λ)Σ), and no weight"),
    Probe("lam", lambda x: x + 0.5, "the spread L (through n + λ) and every weight"),
)


def _sigma_cases(rng) -> list[Case]:
    """The cases of :func:`sigma_points`: chapter 9's worked example, the edge cases, then seeded random ones."""
    cases = [
        Case(
            "chapter 9's worked example: n = 1, μ = 2, σ² = 1, λ = 0, weights 0, ½, ½",
            mu=np.array([2.0]),
            Sig=np.array([[1.0]]),
            lam=0.0,
        ),
        Case("n = 1, λ = 2", mu=np.array([-1.0]), Sig=np.array([[0.25]]), lam=2.0),
        Case("n = 2, correlated", mu=np.array([1.0, 2.0]), Sig=np.array([[2.0, 0.6], [0.6, 1.0]]), lam=1.0),
        Case("n = 3, λ = 3 − n = 0", mu=np.array([1.0, 2.0, 0.1]), Sig=random_covariance(rng, 3), lam=0.0),
    ]
    for _ in range(8):
        n = int(rng.integers(1, 5))
        lam = float(rng.uniform(-n + 0.5, 3.0))
        cases.append(
            Case(f"random: n = {n}, λ = {lam:.2f}", mu=rng.normal(size=n), Sig=random_covariance(rng, n), lam=lam)
        )
    return cases


SIGMA_WHERE = (
    "chapter 9, sigma points: L Lᵀ = (n + λ)Σ with L = np.linalg.cholesky((n + λ) Σ); χ₀ = μ, "
    f"χᵢ = μ + (column i of L), χₙ₊ᵢ = μ − (column i of L); {CH9_WEIGHTS}"
)


def _sigma_variants() -> list[Variant]:
    """The catalogue of :func:`sigma_points`: each known mistake as a wrong version, with its hint."""
    SCALE = "The points sit √(n + λ) standard deviations out: take the square root of (n + λ)Σ, the whole of it."

    def variant(mistake: str, hint: str, **knobs) -> Variant:
        return Variant(mistake, lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, **knobs), hint)

    return [
        variant(
            "wrong_weights",
            "Each of the 2n outer points weighs 1/(2(n + λ)), so all 2n + 1 weights sum to 1.",
            weights="no_half",
        ),
        variant(
            "wrong_weights",
            "The outer weights are 1/(2(n + λ)), not 1/(2n): λ changes them too.",
            weights="one_over_2n",
        ),
        variant("wrong_weights", "The weights are not all equal: the centre point gets λ/(n + λ).", weights="equal"),
        variant("wrong_weights", "Here wc equals wm: the β of the scaled transform is not used.", weights="beta"),
        variant("missing_scale", SCALE, scale="none"),
        variant("missing_scale", SCALE + " (n + λ) goes under the root.", scale="out"),
        variant(
            "missing_transpose",
            "The points step along the columns of L: in NumPy, mu + L.T gives one point per row.",
            columns=False,
        ),
        variant(
            "std_not_var",
            "The points step by a standard deviation: take the (Cholesky) square root of (n + λ)Σ.",
            root="none",
        ),
        variant("points_as_columns", "Return the points one a row: chi has shape (2n + 1, n).", as_rows=False),
        variant(
            "not_cholesky",
            "Any square root gives valid sigma points, but the course (and this check) uses the lower Cholesky factor.",
            root="symmetric",
        ),
        variant(
            "not_cholesky",
            "np.sqrt takes the root of each entry, which is a matrix square root only for a diagonal Σ: "
            "use np.linalg.cholesky.",
            root="entries",
        ),
    ]


def sigma_points(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``sigma_points(mu, Sig, lam)`` against :func:`kfcourse.sigma_points`.

    Points are rows: ``chi[0] = mu``, ``chi[i] = mu + L[:, i-1]``, ``chi[n+i] = mu - L[:, i-1]``
    with ``L`` the lower Cholesky factor of ``(n + lam) Sig``; ``wc`` equals ``wm``.  The same
    points in another order (each with its weights) pass too.  The first case is chapter 9's
    worked example.  Introduced in chapter 9.

    Parameters
    ----------
    student_fn : callable ``(mu (n,), Sig (n, n), lam) -> (chi (2n+1, n), wm (2n+1,), wc (2n+1,))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _sigma_cases(np.random.default_rng(seed))
    return run_check(
        "sigma_points",
        student_fn,
        filters.sigma_points,
        cases,
        _sigma_variants(),
        ("chi", "wm", "wc"),
        SIGMA_WHERE,
        pair=_pair_points,
        steps=SIGMA_STEPS,
        probes=SIGMA_PROBES,
        invariants=tuple(
            sums_to_one(w, "w₀ = λ/(n + λ) and 2n times wᵢ = 1/(2(n + λ)) sum to 1, for every λ") for w in ("wm", "wc")
        ),
    )


# ------------------------------------------------------------ unscented_transform
class _Fn:
    """A function of the sigma points (one a row, or a single point) that shows its formula."""

    def __init__(self, formula: str, fn):
        self.formula, self.fn = formula, fn

    def __call__(self, X):
        return self.fn(np.asarray(X, dtype=float))

    def __repr__(self) -> str:
        return self.formula


SQUARE = _Fn("f(x) = x²", lambda X: X**2)
POLAR = _Fn(
    "f(r, a) = (r cos a, r sin a)",
    lambda X: np.stack([X[..., 0] * np.cos(X[..., 1]), X[..., 0] * np.sin(X[..., 1])], -1),
)


def _random_f(rng, n: int, k: int) -> _Fn:
    """A smooth nonlinear map from n to k numbers: f(x) = sin(A x) + 0.3 (A x)², with a random k x n matrix A."""
    A = np.round(rng.normal(size=(k, n)), 2)
    return _Fn(f"f(x) = sin(A x) + 0.3 (A x)², A = {A.tolist()}", lambda X: np.sin(X @ A.T) + 0.3 * (X @ A.T) ** 2)


def _unscented_with(
    mu, Sig, f, lam, *, points="f", center="weighted", weights="julier", covariance="outer", scale="in"
):
    """The unscented transform of chapter 9, with knobs for the mistakes (the defaults are right)."""
    chi, wm, wc = _sigma_points_with(mu, Sig, lam, weights=weights, scale=scale)
    Y = f(chi) if points == "f" else chi  # Y_i = f(chi_i)
    mu_y = f(mu) if center == "f_of_mu" else (Y.mean(axis=0) if weights == "plain" else wm @ Y)  # sum w_i Y_i
    d = Y if center == "none" else Y - (Y[0] if center == "deviations_from_f_mu" else mu_y)
    if weights == "plain":
        return mu_y, d.T @ d / len(Y)
    if weights == "np_cov":
        return mu_y, np.atleast_2d(np.cov(Y.T))
    if covariance == "inner":  # d_i^T d_i, a number per point
        return mu_y, wc @ np.einsum("ij,ij->i", d, d)
    if covariance == "inner_filled":  # the same number in every entry
        return mu_y, np.full((Y.shape[1],) * 2, wc @ np.einsum("ij,ij->i", d, d))
    if covariance == "points":  # (2n+1) x (2n+1), one entry per pair of points
        return mu_y, (wc[:, None] * d) @ d.T
    return mu_y, (wc[:, None] * d).T @ d  # sum w_i (Y_i - mu_y)(Y_i - mu_y)^T


IDENTITY = _Fn("f(x) = x", lambda X: X)
# Through f(x) = x the points' weighted mean and covariance are μ and Σ themselves, whatever λ: the sigma points
# and the weighted sums alone, with nothing bent by f.  Each input moved alone (run_check's diagnosis).
UT_STEPS = (
    Step(
        "f(x) = x",
        "μ and Σ themselves, from the sigma points and the weighted sums alone",
        lambda i: {**i, "f": IDENTITY},
    ),
)
UT_PROBES = (
    Probe("mu", lambda x: x + 0.5, "the sigma points, χ₀ = μ and χᵢ = μ ± Lᵢ"),
    Probe("Sig", lambda x: 2.0 * x, "the spread L of the sigma points (L Lᵀ = (n + λ)Σ)"),
    Probe("lam", lambda x: x + 0.5, "the spread L (through n + λ) and every weight"),
)


def _ut_cases(rng) -> list[Case]:
    """The cases of :func:`unscented_transform`: chapter 9's worked example, the edge cases, then seeded random ones."""
    cases = [
        Case(
            "chapter 9's worked example: x ~ N(2, 1), y = x², λ = 0",
            mu=np.array([2.0]),
            Sig=np.array([[1.0]]),
            f=SQUARE,
            lam=0.0,
        ),
        Case("n = 1, y = x², λ = 2", mu=np.array([-1.0]), Sig=np.array([[0.5]]), f=SQUARE, lam=2.0),
        Case(
            "polar to Cartesian, n = k = 2",
            mu=np.array([2.0, 0.5]),
            Sig=np.array([[0.1, 0.02], [0.02, 0.3]]),
            f=POLAR,
            lam=1.0,
        ),
    ]
    for _ in range(8):
        n, k = int(rng.integers(1, 5)), int(rng.integers(1, 4))
        lam = float(rng.uniform(-n + 0.5, 3.0))
        cases.append(
            Case(
                f"random: n = {n}, k = {k}, λ = {lam:.2f}",
                mu=rng.normal(size=n),
                Sig=random_covariance(rng, n),
                f=_random_f(rng, n, k),
                lam=lam,
            )
        )
    return cases


UT_WHERE = (
    "chapter 9, the unscented transform: the sigma points χᵢ and weights wᵢ of kf.sigma_points "
    f"({CH9_WEIGHTS}), Yᵢ = f(χᵢ), μ_y = Σ wᵢ Yᵢ, Σ_y = Σ wᵢ (Yᵢ − μ_y)(Yᵢ − μ_y)ᵀ"
)


def _ut_variants() -> list[Variant]:
    """The catalogue of :func:`unscented_transform`: each known mistake as a wrong version, with its hint."""
    PLAIN = "The transformed points are averaged with the sigma-point weights, w₀ = λ/(n + λ), wᵢ = 1/(2(n + λ))."
    OUTER = (
        "Each point adds the outer product (Yᵢ − μ_y)(Yᵢ − μ_y)ᵀ, a k x k matrix: np.outer(d, d), "
        "or for all points at once (w[:, None] * D).T @ D with one deviation a row of D."
    )

    def variant(mistake: str, hint: str, **knobs) -> Variant:
        return Variant(mistake, lambda mu, Sig, f, lam: _unscented_with(mu, Sig, f, lam, **knobs), hint)

    return [
        variant(
            "f_not_applied", "Push every sigma point through f first: Yᵢ = f(χᵢ), then average the Yᵢ.", points="chi"
        ),
        variant(
            "f_of_mean",
            "μ_y = Σ wᵢ f(χᵢ) is the point of the transform: f(μ) is the EKF's (biased) guess.",
            center="f_of_mu",
        ),
        variant(
            "mean_not_subtracted",
            "The covariance sums wᵢ (Yᵢ − μ_y)(Yᵢ − μ_y)ᵀ: deviations from the mean.",
            center="none",
        ),
        variant(
            "deviations_from_f_mu",
            "The deviations are from the transform's own mean μ_y = Σ wᵢ Yᵢ, not from the centre point's "
            "image f(μ) = Y₀: the two differ whenever f bends.",
            center="deviations_from_f_mu",
        ),
        variant("wrong_weights", PLAIN + " A plain average (dividing by 2n + 1) ignores them.", weights="plain"),
        variant("wrong_weights", PLAIN + " np.cov ignores them.", weights="np_cov"),
        variant(
            "wrong_weights",
            "Each of the 2n outer points weighs 1/(2(n + λ)), so all weights sum to 1.",
            weights="no_half",
        ),
        variant("wrong_weights", "The outer weights are 1/(2(n + λ)), not 1/(2n).", weights="one_over_2n"),
        variant("wrong_weights", "Here the covariance weights equal the mean weights (no β).", weights="beta"),
        variant("outer_product_order", OUTER, covariance="inner"),
        variant("outer_product_order", OUTER, covariance="inner_filled"),
        variant("outer_product_order", OUTER, covariance="points"),
        variant(
            "missing_scale", "The points come from the square root of (n + λ)Σ, as in kf.sigma_points.", scale="none"
        ),
        variant("missing_scale", "(n + λ) goes under the square root: L Lᵀ = (n + λ)Σ.", scale="out"),
    ]


def unscented_transform(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``unscented_transform(mu, Sig, f, lam)`` against :func:`kfcourse.unscented_transform`.

    ``f`` takes the sigma points one a row, ``(2n+1, n)``, and returns one row per point,
    ``(2n+1, k)``, as for ``kf.unscented_transform``; it also takes a single point ``(n,)``.
    The weights are those of :func:`kfcourse.sigma_points` (``wc`` equals ``wm``).  The first
    case is chapter 9's worked example, x ~ N(2, 1) through y = x² with λ = 0: (5, 16).
    Introduced in chapter 9.

    Parameters
    ----------
    student_fn : callable ``(mu (n,), Sig (n, n), f, lam) -> (mu_y (k,), Sig_y (k, k))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    cases = _ut_cases(np.random.default_rng(seed))
    return run_check(
        "unscented_transform",
        student_fn,
        filters.unscented_transform,
        cases,
        _ut_variants(),
        ("mu_y", "Sig_y"),
        UT_WHERE,
        steps=UT_STEPS,
        probes=UT_PROBES,
        invariants=(is_covariance("Sig_y", psd=False),),
    )
