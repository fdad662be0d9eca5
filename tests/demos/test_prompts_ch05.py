"""Every prompt and claim of chapter 5, as the prose states it.

Chapter 5 has no live demo: its prompts are the worked example, the four questions, the
exercise, and what the chapter claims for its hand-written ``kf_step`` and the Joseph form.
The claims about any gain are tested on 20 seeded random cases (seeds 0-19).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

CHAPTER = Path(__file__).resolve().parents[2] / "notebooks" / "05_matrix_kalman.ipynb"
SEEDS = range(20)

F = np.array([[1.0, 1.0], [0.0, 1.0]])
B = np.zeros((2, 1))
H = np.array([[1.0, 0.0]])
R = 0.01 * np.eye(2)
Q = np.array([[0.5]])
MU, SIG, U, Z = np.array([0.0, 1.0]), np.eye(2), np.zeros(1), np.array([1.2])


def cells(kind: str) -> list[str]:
    nb = json.loads(CHAPTER.read_text(encoding="utf-8"))
    return ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == kind]


def hand_kf_step():
    """The chapter's hand-written kf_step, run from the notebook's own cell."""
    (source,) = [s for s in cells("code") if s.startswith("def kf_step(")]
    space = {"np": np}
    exec(source, space)
    return source, space["kf_step"]


def joseph(K, Sig_bar, H, Q):
    I_KH = np.eye(Sig_bar.shape[0]) - K @ H
    return I_KH @ Sig_bar @ I_KH.T + K @ Q @ K.T


def random_case(seed: int):
    """A random predicted covariance, H, Q, and the optimal and an arbitrary gain."""
    rng = np.random.default_rng(seed)
    n, k = rng.integers(2, 6), rng.integers(1, 4)
    A = rng.normal(size=(n, n))
    Sig_bar = A @ A.T + 1e-3 * np.eye(n)
    C = rng.normal(size=(k, k))
    Q = C @ C.T + 1e-3 * np.eye(k)
    H = rng.normal(size=(k, n))
    S, K_opt = kf.kf_gain(Sig_bar, H, Q)
    return Sig_bar, H, Q, S, K_opt, rng.normal(size=(n, k))


# ------------------------------------------------------------------ the code, line by line


def test_the_hand_written_kf_step_has_the_lines_the_prose_counts():
    source, _ = hand_kf_step()
    body = source.strip().splitlines()[1:]
    assert body[-1].strip().startswith("return")
    equations = body[:-1]
    assert len(equations) == 6  # "six lines and a return"
    numbers = [re.search(r"# \((\d)\)", line).group(1) for line in equations]
    assert numbers == ["1", "2", "3", "3", "4", "5"]  # one line per equation, two for (3)
    prose = "\n".join(cells("markdown"))
    assert "six lines and a `return`, one line per equation and two for equation (3)" in prose
    assert "five-line" not in prose


def test_the_hand_written_kf_step_gives_the_worked_example():
    _, kf_step = hand_kf_step()
    mu, Sig = kf_step(MU, SIG, U, Z, F, B, H, R, Q)
    assert mu.round(3) == pytest.approx([1.16, 1.08])
    mu_pkg, Sig_pkg = kf.kf_step(MU, SIG, U, Z, F, B, H, R, Q)
    assert np.allclose(mu, mu_pkg, rtol=0, atol=1e-12) and np.allclose(Sig, Sig_pkg, rtol=0, atol=1e-12)


def test_the_worked_example():
    mu_bar, Sig_bar = kf.kf_predict(MU, SIG, U, F, B, R)
    assert mu_bar == pytest.approx([1.0, 1.0])
    assert Sig_bar == pytest.approx(np.array([[2.01, 1.0], [1.0, 1.01]]))
    S, K = kf.kf_gain(Sig_bar, H, Q)
    assert S[0, 0] == pytest.approx(2.51) and K.ravel() == pytest.approx([201 / 251, 100 / 251])
    mu, Sig = kf.kf_update(mu_bar, Sig_bar, Z, H, Q)
    assert mu == pytest.approx([1.160159, 1.079681], abs=1e-6)
    assert Sig.round(3) == pytest.approx(np.array([[0.400, 0.199], [0.199, 0.612]]))


def test_without_the_correlation_the_velocity_gain_is_zero():
    _, Sig_bar = kf.kf_predict(MU, SIG, U, F, B, R)
    uncorrelated = np.diag(np.diag(Sig_bar))
    _, K = kf.kf_gain(uncorrelated, H, Q)
    mu, Sig = kf.kf_update(np.array([1.0, 1.0]), uncorrelated, Z, H, Q)
    assert K[1, 0] == 0.0 and mu[1] == 1.0 and Sig[1, 1] == pytest.approx(1.01)


# ------------------------------------------------------------------ the Joseph form


@pytest.mark.parametrize("seed", SEEDS)
def test_joseph_is_a_covariance_for_any_gain(seed):
    """A sum of two terms A M A^T: symmetric positive semi-definite for any K, up to rounding."""
    Sig_bar, H, Q, _, _, K_any = random_case(seed)
    P = joseph(K_any, Sig_bar, H, Q)
    scale = np.abs(P).max()
    assert np.allclose(P, P.T, rtol=0, atol=1e-12 * scale)
    assert np.linalg.eigvalsh((P + P.T) / 2).min() >= -1e-12 * scale
    short = (np.eye(Sig_bar.shape[0]) - K_any @ H) @ Sig_bar
    assert not np.allclose(short, short.T)  # the short form is not even symmetric for this gain


@pytest.mark.parametrize("seed", SEEDS)
def test_a_gain_error_moves_joseph_only_at_second_order(seed):
    """Joseph(K* + dK) - Joseph(K*) = dK S dK^T exactly; the short form moves by -dK H Sig_bar."""
    Sig_bar, H, Q, S, K_opt, K_any = random_case(seed)
    dK = 1e-3 * K_any
    I = np.eye(Sig_bar.shape[0])
    moved = joseph(K_opt + dK, Sig_bar, H, Q) - joseph(K_opt, Sig_bar, H, Q)
    assert np.allclose(moved, dK @ S @ dK.T, rtol=1e-5, atol=1e-12 * np.abs(Sig_bar).max())
    short_moved = (I - (K_opt + dK) @ H) @ Sig_bar - (I - K_opt @ H) @ Sig_bar
    assert np.allclose(short_moved, -dK @ H @ Sig_bar)
    assert np.abs(short_moved).max() > 100 * np.abs(moved).max()


def test_the_chapters_gain_error_example():
    _, Sig_bar = kf.kf_predict(MU, SIG, U, F, B, R)
    _, K = kf.kf_gain(Sig_bar, H, Q)
    dK = np.array([[0.001], [0.0]])
    I = np.eye(2)
    short = np.abs((I - (K + dK) @ H) @ Sig_bar - (I - K @ H) @ Sig_bar).max()
    jos = np.abs(joseph(K + dK, Sig_bar, H, Q) - joseph(K, Sig_bar, H, Q)).max()
    assert f"{short:.1e}" == "2.0e-03" and f"{jos:.1e}" == "2.5e-06"
    assert round(short / jos, -1) == 800  # "800 times less"


def test_the_package_update_is_joseph_and_exactly_symmetric():
    rng = np.random.default_rng(0)
    for seed in SEEDS:
        Sig_bar, H, Q, _, K_opt, _ = random_case(seed)
        mu_bar = rng.normal(size=Sig_bar.shape[0])
        z = rng.normal(size=H.shape[0])
        _, Sig = kf.kf_update(mu_bar, Sig_bar, z, H, Q)
        assert np.array_equal(Sig, Sig.T)
        assert np.allclose(Sig, joseph(K_opt, Sig_bar, H, Q))


# ------------------------------------------------------------------ questions


def test_question_1_shapes_of_the_2d_tracker():
    F2, H2 = kf.models.constant_velocity(dt=1.0, dim=2)
    _, Sig_bar2 = kf.kf_predict(np.zeros(4), np.eye(4), None, F2, None, 0.01 * np.eye(4))
    S2, K2 = kf.kf_gain(Sig_bar2, H2, 0.5 * np.eye(2))
    assert (F2.shape, H2.shape, S2.shape, K2.shape) == ((4, 4), (2, 4), (2, 2), (4, 2))


def test_question_2_a_velocity_sensor_moves_the_position_too():
    mu_bar, Sig_bar = kf.kf_predict(MU, SIG, U, F, B, R)
    H_vel = np.array([[0.0, 1.0]])
    S, K = kf.kf_gain(Sig_bar, H_vel, Q)
    mu, _ = kf.kf_update(mu_bar, Sig_bar, Z, H_vel, Q)
    assert S[0, 0] == pytest.approx(1.51)
    assert K.ravel().round(3) == pytest.approx([0.662, 0.669])
    assert mu.round(3) == pytest.approx([1.132, 1.134])


def test_question_3_a_fixed_gain_breaks_the_short_form_only():
    _, Sig_bar = kf.kf_predict(MU, SIG, U, F, B, R)
    K = np.array([[0.5], [0.1]])
    short = (np.eye(2) - K @ H) @ Sig_bar
    assert short[0, 1].round(3) == 0.5 and short[1, 0].round(3) == 0.799
    P = joseph(K, Sig_bar, H, Q)
    assert np.allclose(P, P.T) and np.linalg.eigvalsh(P).min() > 0


def test_question_4_a_confirming_reading_still_shrinks_sigma():
    mu_bar, Sig_bar = kf.kf_predict(MU, SIG, U, F, B, R)
    mu, Sig = kf.kf_update(mu_bar, Sig_bar, np.array([1.0]), H, Q)
    _, Sig_12 = kf.kf_update(mu_bar, Sig_bar, Z, H, Q)
    assert mu == pytest.approx([1.0, 1.0]) and np.allclose(Sig, Sig_12)


# ------------------------------------------------------------------ the exercise


def test_the_exercise_says_not_yet_to_the_skeleton_and_passes_the_chapters_own_step():
    (skeleton,) = [s for s in cells("code") if s.startswith("def my_kf_step(")]
    space = {"np": np}
    exec(skeleton, space)
    waiting = kf.check.kf_step(space["my_kf_step"])
    assert not waiting.passed and "Not yet" in waiting.message
    _, kf_step = hand_kf_step()
    assert kf.check.kf_step(kf_step).passed


def test_the_chapter_links_the_notation_table():
    assert "[the notation table](notation.ipynb)" in cells("markdown")[1]
