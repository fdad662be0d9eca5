"""The exercise checkers: the package's own functions pass, each known mistake is named,
and a function that raises, returns NaN or the wrong shape gets a clear verdict.

The wrong functions below are written the way a student might write them, independently
of the checker's own wrong variants.  Noise letters: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kfcourse as kf

CHECKERS = [
    "bayes_predict",
    "bayes_update",
    "fuse",
    "kf_1d_step",
    "kf_step",
    "range_bearing",
    "range_bearing_jacobian",
    "sigma_points",
    "unicycle",
]


def test_every_checker_named_in_the_task_exists():
    required = {"bayes_predict", "bayes_update", "kf_1d_step", "kf_step", "range_bearing_jacobian"}
    assert required | {"unicycle", "sigma_points"} <= set(kf.check.__all__)
    assert set(CHECKERS) <= set(kf.check.__all__)


def test_the_catalogue_has_the_required_mistakes():
    required = {
        "not_normalised",
        "shift_wrong_way",
        "swapped_R_Q",
        "std_not_var",
        "missing_transpose",
        "sign_flip",
        "divides_by_omega",
        "unwrapped_angle",
        "wrong_weights",
    }
    assert required <= set(kf.check.MISTAKES)


@pytest.mark.parametrize("name", CHECKERS)
def test_the_package_function_passes(name):
    result = getattr(kf.check, name)(getattr(kf, name))
    assert result.passed, result.message
    assert result.mistake is None
    assert result.message.startswith("✔") and f"kf.{name}" in result.message


@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("name", CHECKERS)
def test_the_package_function_passes_with_other_seeds(name, seed):
    assert getattr(kf.check, name)(getattr(kf, name), seed=seed).passed


# ----------------------------------------------------- right answers, written by hand
def hand_bayes_predict(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = (i + offset) % n if boundary == "wrap" else min(max(i + offset, 0), n - 1)
            out[j] += p * belief[i]
    return out


def hand_kf_step(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def hand_unicycle(state, u, dt):
    x, y, theta = state
    V, w = u
    if abs(w) < 1e-9:
        x, y = x + V * dt * math.cos(theta), y + V * dt * math.sin(theta)
    else:
        x = x + V / w * (math.sin(theta + w * dt) - math.sin(theta))
        y = y + V / w * (math.cos(theta) - math.cos(theta + w * dt))
    return np.array([x, y, math.atan2(math.sin(theta + w * dt), math.cos(theta + w * dt))])


def hand_sigma_points(mu, Sig, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    chi = [mu] + [mu + L[:, i] for i in range(n)] + [mu - L[:, i] for i in range(n)]
    w = [lam / (n + lam)] + [1 / (2 * (n + lam))] * (2 * n)
    return np.array(chi), np.array(w), np.array(w)


@pytest.mark.parametrize(
    ("name", "fn"),
    [
        ("bayes_predict", hand_bayes_predict),
        ("kf_step", hand_kf_step),
        ("unicycle", hand_unicycle),
        ("sigma_points", hand_sigma_points),
    ],
)
def test_a_right_answer_written_differently_passes(name, fn):
    """The checker compares with a tolerance, not bit for bit: textbook code in another form passes."""
    result = getattr(kf.check, name)(fn)
    assert result.passed, result.message


# ------------------------------------------------------ wrong answers, one per mistake
def predict_backwards(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = (i - offset) % n if boundary == "wrap" else min(max(i - offset, 0), n - 1)  # wrong: minus
            out[j] += p * belief[i]
    return out


def predict_always_ring(belief, kernel, boundary="wall"):
    return sum(p * np.roll(belief, offset) for offset, p in kernel.items())  # wrong: ignores boundary


def predict_leaky(belief, kernel, boundary="wall"):
    n = len(belief)
    out = np.zeros(n)
    for i in range(n):
        for offset, p in kernel.items():
            j = i + offset
            if boundary == "wrap":
                out[j % n] += p * belief[i]
            elif 0 <= j < n:  # wrong: what hits the wall is lost
                out[j] += p * belief[i]
    return out


def update_unnormalised(belief, likelihood):
    return np.multiply(likelihood, belief)  # wrong: no eta


def kf_1d_swapped(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + Q  # wrong: Q in the predict step
    K = c * var_bar / (c**2 * var_bar + R)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_squares_noise(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a**2 * var + R**2  # wrong: R is already a variance
    K = c * var_bar / (c**2 * var_bar + Q**2)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def kf_1d_a_once(mu, var, u, z, a=1.0, b=1.0, c=1.0, R=0.2, Q=0.1):
    mu_bar, var_bar = a * mu + b * u, a * var + R  # wrong: a, not a squared
    K = c * var_bar / (c**2 * var_bar + Q)
    return mu_bar + K * (z - c * mu_bar), (1 - K * c) * var_bar


def fuse_own_weights(mu1, var1, mu2, var2):
    return (var1 * mu1 + var2 * mu2) / (var1 + var2), 1 / (1 / var1 + 1 / var2)  # wrong: weights swapped


def fuse_squares(mu1, var1, mu2, var2):
    w1, w2 = 1 / var1**2, 1 / var2**2  # wrong: var1 and var2 are already variances
    return (w1 * mu1 + w2 * mu2) / (w1 + w2), 1 / (w1 + w2)


def fuse_adds(mu1, var1, mu2, var2):
    K = var1 / (var1 + var2)
    return mu1 + K * (mu2 - mu1), var1 + var2  # wrong: variances add in a predict, not in a fusion


def kf_step_swapped(mu, Sig, u, z, F, B, H, R, Q):
    return hand_kf_step(mu, Sig, u, z, F, B, H, Q, R)  # wrong: R and Q swapped


def kf_step_no_transpose(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F + R  # wrong: F^T
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (z - H @ mu_bar), (np.eye(len(mu)) - K @ H) @ Sig_bar


def kf_step_innovation_backwards(mu, Sig, u, z, F, B, H, R, Q):
    mu_bar = F @ mu + B @ u
    Sig_bar = F @ Sig @ F.T + R
    K = Sig_bar @ H.T @ np.linalg.inv(H @ Sig_bar @ H.T + Q)
    return mu_bar + K @ (H @ mu_bar - z), (np.eye(len(mu)) - K @ H) @ Sig_bar  # wrong: H mu_bar - z


def range_bearing_unwrapped(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), np.arctan2(dy, dx) - state[2]])  # wrong: not wrapped


def range_bearing_atan(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    return np.array([np.hypot(dx, dy), kf.wrap_angle(np.arctan(dy / dx) - state[2])])  # wrong: atan


def jacobian_robot_minus_landmark(state, landmark):
    dx, dy = state[0] - landmark[0], state[1] - landmark[1]  # wrong: robot minus landmark
    q = dx**2 + dy**2
    return np.array([[-dx / np.sqrt(q), -dy / np.sqrt(q), 0], [dy / q, -dx / q, -1]])


def jacobian_q_and_r_mixed(state, landmark):
    dx, dy = landmark[0] - state[0], landmark[1] - state[1]
    q = dx**2 + dy**2
    return np.array([[-dx / q, -dy / q, 0], [dy / np.sqrt(q), -dx / np.sqrt(q), -1]])  # wrong: q <-> sqrt(q)


def unicycle_no_limit(state, u, dt):
    x, y, theta = state
    V, w = u
    x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))  # wrong: no branch for w = 0
    y = y + V / w * (np.cos(theta) - np.cos(theta + w * dt))
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_no_limit_floats(state, u, dt):
    x, y, theta = map(float, state)
    V, w = map(float, u)
    x = x + V / w * (math.sin(theta + w * dt) - math.sin(theta))  # wrong: raises at w = 0
    y = y + V / w * (math.cos(theta) - math.cos(theta + w * dt))
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_unwrapped(state, u, dt):
    x, y, _ = hand_unicycle(state, u, dt)
    return np.array([x, y, state[2] + u[1] * dt])  # wrong: heading not wrapped


def unicycle_y_backwards(state, u, dt):
    x, y, theta = state
    V, w = u
    if w == 0:
        return hand_unicycle(state, u, dt)
    x = x + V / w * (np.sin(theta + w * dt) - np.sin(theta))
    y = y + V / w * (np.cos(theta + w * dt) - np.cos(theta))  # wrong: the cosines the other way round
    return np.array([x, y, kf.wrap_angle(theta + w * dt)])


def unicycle_euler(state, u, dt):
    x, y, theta = state
    V, w = u
    return np.array([x + V * dt * np.cos(theta), y + V * dt * np.sin(theta), kf.wrap_angle(theta + w * dt)])


def sigma_points_rows_of_L(mu, Sig, lam):
    n = len(mu)
    L = np.linalg.cholesky((n + lam) * Sig)
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + L, mu - L]), w, w  # wrong: rows of L, not columns


def sigma_points_no_root(mu, Sig, lam):
    n = len(mu)
    A = (n + lam) * Sig  # wrong: no square root
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + A.T, mu - A.T]), w, w


def sigma_points_weights_without_half(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    w = np.array([lam / (len(mu) + lam)] + [1 / (len(mu) + lam)] * (2 * len(mu)))  # wrong: no 1/2
    return chi, w, w


def sigma_points_columns(mu, Sig, lam):
    chi, w, _ = hand_sigma_points(mu, Sig, lam)
    return chi.T, w, w  # wrong: one point per column


def sigma_points_symmetric_root(mu, Sig, lam):
    n = len(mu)
    vals, vecs = np.linalg.eigh((n + lam) * Sig)
    S = vecs @ np.diag(np.sqrt(vals)) @ vecs.T  # a square root, but not the Cholesky factor
    _, w, _ = hand_sigma_points(mu, Sig, lam)
    return np.vstack([mu, mu + S.T, mu - S.T]), w, w


WRONG = [
    ("bayes_predict", predict_backwards, "shift_wrong_way"),
    ("bayes_predict", predict_always_ring, "ignores_boundary"),
    ("bayes_predict", predict_leaky, "leaks_at_wall"),
    ("bayes_update", update_unnormalised, "not_normalised"),
    ("kf_1d_step", kf_1d_swapped, "swapped_R_Q"),
    ("kf_1d_step", kf_1d_squares_noise, "std_not_var"),
    ("kf_1d_step", kf_1d_a_once, "a_not_squared"),
    ("fuse", fuse_own_weights, "wrong_weights"),
    ("fuse", fuse_squares, "std_not_var"),
    ("fuse", fuse_adds, "adds_variances"),
    ("kf_step", kf_step_swapped, "swapped_R_Q"),
    ("kf_step", kf_step_no_transpose, "missing_transpose"),
    ("kf_step", kf_step_innovation_backwards, "sign_flip"),
    ("range_bearing", range_bearing_unwrapped, "unwrapped_angle"),
    ("range_bearing", range_bearing_atan, "atan_not_atan2"),
    ("range_bearing_jacobian", jacobian_robot_minus_landmark, "sign_flip"),
    ("range_bearing_jacobian", jacobian_q_and_r_mixed, "q_not_sqrt_q"),
    ("unicycle", unicycle_no_limit, "divides_by_omega"),
    ("unicycle", unicycle_no_limit_floats, "divides_by_omega"),
    ("unicycle", unicycle_unwrapped, "unwrapped_angle"),
    ("unicycle", unicycle_y_backwards, "sign_flip"),
    ("unicycle", unicycle_euler, "euler_step"),
    ("sigma_points", sigma_points_rows_of_L, "missing_transpose"),
    ("sigma_points", sigma_points_no_root, "std_not_var"),
    ("sigma_points", sigma_points_weights_without_half, "wrong_weights"),
    ("sigma_points", sigma_points_columns, "points_as_columns"),
    ("sigma_points", sigma_points_symmetric_root, "not_cholesky"),
]


@pytest.mark.parametrize(("name", "fn", "mistake"), WRONG, ids=[f"{n}-{m}" for n, _, m in WRONG])
def test_a_known_mistake_is_named(name, fn, mistake):
    result = getattr(kf.check, name)(fn)
    assert not result.passed
    assert result.mistake == mistake, result.message
    assert result.message.startswith("✘")
    assert f"Likely mistake: {kf.check.MISTAKES[mistake]}" in result.message
    assert "expected:" in result.message and "inputs:" in result.message
    assert "hapter" in result.hint  # the hint points at the chapter's equation


def test_every_catalogue_key_is_exercised_by_a_wrong_function():
    assert {mistake for _, _, mistake in WRONG} == set(kf.check.MISTAKES)


# ------------------------------------------------------------- functions that misbehave
def test_an_unknown_mistake_gets_the_generic_verdict():
    def off_by_a_bit(belief, likelihood):
        bel = np.multiply(likelihood, belief)
        return bel / bel.sum() + 0.01

    result = kf.check.bayes_update(off_by_a_bit)
    assert not result.passed and result.mistake is None
    assert "No known mistake gives this answer" in result.message
    assert "case 1 of" in result.message and "got:" in result.message


def test_not_yet_is_no_failure():
    def my_kf_step(mu, Sig, u, z, F, B, H, R, Q):
        raise NotImplementedError("your turn")

    result = kf.check.kf_step(my_kf_step)
    assert result.passed is False and result.mistake is None
    assert "Not yet" in result.message and "my_kf_step" in result.message


def test_a_function_written_only_in_part_is_not_yet_done():
    def walls_only(belief, kernel, boundary="wall"):
        if boundary == "wrap":
            raise NotImplementedError("rings come later")
        return hand_bayes_predict(belief, kernel, boundary)

    result = kf.check.bayes_predict(walls_only)
    assert result.passed is False and result.mistake is None and "Not yet" in result.message


def test_a_function_that_raises_gets_a_clear_verdict():
    def broken(state, landmark):
        return np.array([1.0, 2.0]) @ np.ones(3)

    result = kf.check.range_bearing(broken)
    assert not result.passed and result.mistake is None
    assert "it raised ValueError" in result.message
    assert "raised in broken" in result.message  # the line of the student's code that raised
    assert "Traceback" not in result.message


def test_a_function_that_returns_nan_gets_a_clear_verdict():
    result = kf.check.fuse(lambda mu1, var1, mu2, var2: (math.nan, 0.1))
    assert not result.passed and "mu contains NaN" in result.message


def test_a_function_that_returns_the_wrong_shape_gets_a_clear_verdict():
    result = kf.check.range_bearing_jacobian(lambda state, landmark: np.zeros((3, 2)))
    assert not result.passed and "H has shape (3, 2); expected (2, 3)" in result.message


def test_a_function_that_returns_too_few_values_gets_a_clear_verdict():
    result = kf.check.kf_1d_step(lambda mu, var, u, z, a, b, c, R, Q: mu)
    assert not result.passed and "expected 2 values (mu, var)" in result.message


def test_a_function_that_returns_no_numbers_gets_a_clear_verdict():
    result = kf.check.bayes_predict(lambda belief, kernel, boundary: "moved right")
    assert not result.passed and "bel_bar is not a number" in result.message


def test_a_function_that_changes_its_inputs_does_not_change_the_expected_answer():
    def sloppy(mu, Sig, u, z, F, B, H, R, Q):
        Sig += R  # changes the caller's array
        return hand_kf_step(mu, Sig - R, u, z, F, B, H, R, Q)

    assert kf.check.kf_step(sloppy).passed


def test_prints_and_warnings_of_the_function_stay_quiet(capsys, recwarn):
    def chatty(belief, likelihood):
        print("debugging")
        np.log(np.zeros(1))  # a RuntimeWarning
        bel = np.multiply(likelihood, belief)
        return bel / bel.sum()

    assert kf.check.bayes_update(chatty).passed
    assert capsys.readouterr().out == ""
    assert len(recwarn) == 0


def test_anything_but_a_function_is_refused():
    with pytest.raises(ValueError, match="student_fn"):
        kf.check.kf_step(np.eye(2))


# ------------------------------------------------------------------------ the display
def test_the_verdict_displays_in_a_notebook():
    result = kf.check.kf_step(kf_step_no_transpose)
    assert repr(result) == result.message
    page = result._repr_html_()
    assert "<pre>" in page and "Likely mistake" in page and "&lt;" not in result.headline
    ok = kf.check.kf_step(kf.kf_step)
    assert "✔" in ok._repr_html_() and repr(ok) == ok.message


def test_the_same_seed_gives_the_same_verdict_and_another_seed_other_cases():
    first = kf.check.unicycle(unicycle_y_backwards, seed=5)
    assert first.message == kf.check.unicycle(unicycle_y_backwards, seed=5).message
    odd = kf.check.kf_step(kf_step_no_transpose, seed=0).details
    assert odd != kf.check.kf_step(kf_step_no_transpose, seed=1).details
