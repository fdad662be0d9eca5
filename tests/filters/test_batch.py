"""``kf_step_batch``: N filters at once equal N calls of ``kf_step`` (whose own worked numbers
and closed forms are in ``test_kalman.py``), and bad input is refused by name."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.filters.batch import kf_step_batch
from kfcourse.models import constant_velocity

N = 25

# ================================================================ worked numbers
# none: the lesson's numbers go through kf_step (test_kalman.py), which the batch must equal


# ================================================================ closed forms
# none: the batch is checked against kf_step below


# ================================================================ properties
def random_beliefs(rng, N: int, n: int):
    mu = rng.normal(size=(N, n))
    A = rng.normal(size=(N, n, n))
    Sig = A @ A.transpose(0, 2, 1) + 0.1 * np.eye(n)  # symmetric positive definite
    return mu, Sig


def model(dt: float = 0.5):
    F, H = constant_velocity(dt, dim=2)
    B = np.vstack([0.5 * dt**2 * np.eye(2), dt * np.eye(2)])  # an acceleration command
    R = np.diag([0.01, 0.02, 0.1, 0.2])
    Q = np.array([[0.5, 0.1], [0.1, 0.3]])
    return F, B, H, R, Q


@pytest.mark.parametrize("control", [False, True])
def test_equals_n_calls_of_kf_step(control):
    rng = np.random.default_rng(1)
    F, B, H, R, Q = model()
    mu, Sig = random_beliefs(rng, N, 4)
    z = rng.normal(size=(N, 2))
    u = rng.normal(size=(N, 2)) if control else None
    B = B if control else None
    mu_b, Sig_b = kf_step_batch(mu, Sig, u, z, F, B, H, R, Q)
    assert mu_b.shape == (N, 4) and Sig_b.shape == (N, 4, 4)
    for i in range(N):
        mu_i, Sig_i = kf.kf_step(mu[i], Sig[i], None if u is None else u[i], z[i], F, B, H, R, Q)
        np.testing.assert_allclose(mu_b[i], mu_i, rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(Sig_b[i], Sig_i, rtol=1e-10, atol=1e-12)
    assert not np.allclose(mu_b, mu)  # it did move the beliefs


def test_many_steps_stay_equal_to_kf_step():
    rng = np.random.default_rng(2)
    F, _, H, R, Q = model(0.1)
    mu, Sig = random_beliefs(rng, 5, 4)
    mu_1, Sig_1 = mu[3], Sig[3]
    for _ in range(50):
        z = rng.normal(size=(5, 2))
        mu, Sig = kf_step_batch(mu, Sig, None, z, F, None, H, R, Q)
        mu_1, Sig_1 = kf.kf_step(mu_1, Sig_1, None, z[3], F, None, H, R, Q)
    np.testing.assert_allclose(mu[3], mu_1, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(Sig[3], Sig_1, rtol=1e-9, atol=1e-12)
    assert np.allclose(Sig, Sig.transpose(0, 2, 1))


def test_no_reading_predicts_only():
    rng = np.random.default_rng(3)
    F, _, H, R, Q = model()
    mu, Sig = random_beliefs(rng, N, 4)
    mu_b, Sig_b = kf_step_batch(mu, Sig, None, None, F, None, H, R, Q)
    for i in range(N):
        mu_i, Sig_i = kf.kf_predict(mu[i], Sig[i], None, F, None, R)
        np.testing.assert_allclose(mu_b[i], mu_i, rtol=1e-12)
        np.testing.assert_allclose(Sig_b[i], Sig_i, rtol=1e-12)


def test_exported():
    assert kf.kf_step_batch is kf_step_batch
    assert kf.filters.kf_step_batch is kf_step_batch


# ================================================================ bad input
def good():
    rng = np.random.default_rng(4)
    F, _, H, R, Q = model()
    mu, Sig = random_beliefs(rng, 6, 4)
    return {"mu": mu, "Sig": Sig, "u": None, "z": rng.normal(size=(6, 2)), "F": F, "B": None, "H": H, "R": R, "Q": Q}


def asymmetric(Sig):
    Sig = Sig.copy()
    Sig[2, 0, 1] += 1.0
    return Sig


def indefinite(Sig):
    Sig = Sig.copy()
    Sig[4] = np.diag([1.0, -1.0, 1.0, 1.0])
    return Sig


def with_nan(a):
    a = np.array(a, dtype=float)
    a.flat[1] = np.nan
    return a


BAD = [
    ("mu", lambda a: a["mu"][0], "mu"),  # one filter given as a vector
    ("mu", lambda a: with_nan(a["mu"]), "mu"),
    ("Sig", lambda a: a["Sig"][:5], "Sig"),  # one covariance missing
    ("Sig", lambda a: a["Sig"][:, :3, :3], "Sig"),
    ("Sig", lambda a: asymmetric(a["Sig"]), "Sig[2]"),
    ("Sig", lambda a: indefinite(a["Sig"]), "Sig[4]"),
    ("Sig", lambda a: with_nan(a["Sig"]), "Sig"),
    ("z", lambda a: a["z"][:4], "z"),
    ("z", lambda a: with_nan(a["z"]), "z"),
    ("F", lambda a: a["F"][:3], "F"),
    ("H", lambda a: a["H"][:, :3], "H"),
    ("R", lambda a: -a["R"], "R"),
    ("Q", lambda a: with_nan(a["Q"]), "Q"),
    ("Q", lambda a: np.eye(3), "Q"),
    ("u", lambda a: np.zeros((6, 2)), "u and B"),  # u without B
]


@pytest.mark.parametrize(("arg", "spoil", "named"), BAD, ids=[f"{a}-{i}" for i, (a, _, _) in enumerate(BAD)])
def test_bad_input_is_refused_by_name(arg, spoil, named):
    args = good()
    kf_step_batch(**args)  # the good arguments pass
    args[arg] = spoil(args)
    with pytest.raises(ValueError, match=named.replace("[", r"\[").replace("]", r"\]")):
        kf_step_batch(**args)
