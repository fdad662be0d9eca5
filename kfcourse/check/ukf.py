"""Checker for chapter 9: sigma points and their weights."""

from __future__ import annotations

import numpy as np

from .. import filters
from ._core import Case, CheckResult, Variant, random_covariance, run_check


def _sigma_points_with(mu, Sig, lam, *, root="cholesky", columns=True, weights="julier", as_rows=True):
    """The sigma points of chapter 9, with knobs for the mistakes."""
    n = mu.size
    A = (n + lam) * Sig
    if root == "cholesky":
        L = np.linalg.cholesky(A)  # L L^T = (n + lam) Sig
    elif root == "symmetric":
        w, V = np.linalg.eigh(A)
        L = V @ np.diag(np.sqrt(w)) @ V.T
    else:  # no square root at all
        L = A
    D = L.T if columns else L  # one row per column of L
    chi = np.vstack([mu, mu + D, mu - D])
    if weights == "julier":
        wm = np.full(2 * n + 1, 0.5 / (n + lam))  # w_i = 1 / (2 (n + lam))
        wm[0] = lam / (n + lam)  # w_0 = lam / (n + lam)
    elif weights == "no_half":
        wm = np.full(2 * n + 1, 1.0 / (n + lam))
        wm[0] = lam / (n + lam)
    else:  # all equal
        wm = np.full(2 * n + 1, 1.0 / (2 * n + 1))
    return (chi if as_rows else chi.T), wm, wm.copy()


def sigma_points(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``sigma_points(mu, Sig, lam)`` against :func:`kfcourse.sigma_points`.

    Points are rows: ``chi[0] = mu``, ``chi[i] = mu + L[:, i-1]``, ``chi[n+i] = mu - L[:, i-1]``
    with ``L`` the lower Cholesky factor of ``(n + lam) Sig``; ``wc`` equals ``wm``.
    Introduced in chapter 9.

    Parameters
    ----------
    student_fn : callable ``(mu (n,), Sig (n, n), lam) -> (chi (2n+1, n), wm (2n+1,), wc (2n+1,))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    rng = np.random.default_rng(seed)
    cases = [
        Case("the chapter's n = 1, λ = 0 (weights 0, ½, ½)", mu=np.array([2.0]), Sig=np.array([[1.0]]), lam=0.0),
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
    where = (
        "chapter 9, sigma points: L Lᵀ = (n + λ)Σ with L = np.linalg.cholesky((n + λ) Σ); χ₀ = μ, "
        "χᵢ = μ + (column i of L), χₙ₊ᵢ = μ − (column i of L); w₀ = λ/(n + λ), wᵢ = 1/(2(n + λ))"
    )
    variants = [
        Variant(
            "wrong_weights",
            lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, weights="no_half"),
            "Each of the 2n outer points weighs 1/(2(n + λ)), so all 2n + 1 weights sum to 1.",
        ),
        Variant(
            "wrong_weights",
            lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, weights="equal"),
            "The weights are not all equal: the centre point gets λ/(n + λ).",
        ),
        Variant(
            "missing_transpose",
            lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, columns=False),
            "The points step along the columns of L: in NumPy, mu + L.T gives one point per row.",
        ),
        Variant(
            "std_not_var",
            lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, root="none"),
            "The points step by a standard deviation: take the (Cholesky) square root of (n + λ)Σ.",
        ),
        Variant(
            "points_as_columns",
            lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, as_rows=False),
            "Return the points one a row: chi has shape (2n + 1, n).",
        ),
        Variant(
            "not_cholesky",
            lambda mu, Sig, lam: _sigma_points_with(mu, Sig, lam, root="symmetric"),
            "Any square root gives valid sigma points, but the course (and this check) uses the lower Cholesky factor.",
        ),
    ]
    return run_check("sigma_points", student_fn, filters.sigma_points, cases, variants, ("chi", "wm", "wc"), where)
