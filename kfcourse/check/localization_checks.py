"""Checker for chapter 10's exercise: your own EKF localization step.

Noise letters follow the course: ``R`` is process (motion) noise, here ``W M Wᵀ`` from the
odometry noise ``M``; ``Q`` is the reading noise.
"""

from __future__ import annotations

import numpy as np

from .. import filters, models
from ._core import Case, CheckResult, Probe, Step, Variant, angle_in_range, is_covariance, run_check
from .exercises import _function

DT = 0.2  # s, the capstone's time step
M = np.diag([0.1, 0.05]) ** 2  # the capstone's odometry noise: 0.1 m/s on V, 0.05 rad/s on omega
Q = np.diag([0.1, 0.03]) ** 2  # the capstone's reading noise: 0.1 m in range, 0.03 rad in bearing
GATE = 4.0  # the capstone's gate, in standard deviations

#: Chapter 10's step 60 (seed 0, gate 4), rounded: the estimate after step 59, the odometry
#: of step 60, and the two landmarks in view with their readings.
CHAPTER_STEP = {
    "mu": np.array([0.16944, 5.03044, -3.12898]),
    "Sig": np.array(
        [
            [6.384e-4, -0.4351e-4, 0.4976e-4],
            [-0.4351e-4, 2.1356e-4, -0.4751e-4],
            [0.4976e-4, -0.4751e-4, 1.6767e-4],
        ]
    ),
    "u": np.array([1.07876, 0.04220]),
    "z": np.array([[1.52142, -1.55732], [2.46052, 1.59850]]),
    "landmarks": np.array([[0.0, 6.5], [0.0, 2.5]]),
}


def _step_with(
    mu,
    Sig,
    u,
    z,
    landmarks,
    dt,
    M,
    Q,
    gate,
    *,
    R_as="WMWT",
    predict_when_blind=True,
    linearize_at="current",
    wrap_gate=True,
    wrap_update=True,
    wrap_heading=True,
    Q_in_gate=True,
    Q_in_update=True,
    gate_test="d2 <= gate2",
    flags="used",
):
    """Chapter 10's step written out, with a knob for each mistake."""
    mu, Sig = np.asarray(mu, dtype=float), np.asarray(Sig, dtype=float)
    z, landmarks = np.asarray(z, dtype=float).reshape(-1, 2), np.asarray(landmarks, dtype=float).reshape(-1, 2)
    used = np.zeros(len(z), dtype=bool)
    if len(z) == 0 and not predict_when_blind:
        return mu, Sig, used
    # (1) predict
    G, W = models.unicycle_jacobian(mu, u, dt), models.unicycle_control_jacobian(mu, u, dt)
    R = {"WMWT": W @ M @ W.T, "none": np.zeros((3, 3)), "M": M}[R_as]
    mu_bar = models.unicycle(mu, u, dt)
    Sig_bar = G @ Sig @ G.T + R  # R = M raises: (3, 3) + (2, 2)
    mu, Sig = mu_bar, Sig_bar
    for j, m in enumerate(landmarks):
        restart = linearize_at == "mu_bar only"  # every update starts again from the prediction
        at, P = (mu, Sig) if linearize_at == "current" else (mu_bar, Sig_bar if restart else Sig)
        if linearize_at == "mu_bar, Sig_bar in S and K":  # the prediction's H, S and K, applied to the current belief
            at, P = mu_bar, Sig_bar
        H, z_hat = models.range_bearing_jacobian(at, m), models.range_bearing(at, m)
        raw = z[j] - z_hat
        wrapped = np.array([raw[0], models.wrap_angle(raw[1])])
        # (2)-(3) gate
        nu = wrapped if wrap_gate else raw
        S = H @ P @ H.T + (Q if Q_in_gate else 0)
        d2 = nu @ np.linalg.solve(S, nu)
        inside = {"d2 <= gate2": d2 <= gate**2, "d2 <= gate": d2 <= gate, "d <= gate2": np.sqrt(d2) <= gate**2}
        if gate_test != "none" and not inside[gate_test]:
            continue
        # (4) update
        nu = wrapped if wrap_update else raw
        S = H @ P @ H.T + (Q if Q_in_update else 0)
        K = P @ H.T @ np.linalg.inv(S)
        mu = (mu_bar if restart else mu) + K @ nu
        Sig = (np.eye(3) - K @ H) @ (Sig if linearize_at == "mu_bar, Sig_bar in S and K" else P)
        # (5) wrap the heading
        if wrap_heading:
            mu = np.array([mu[0], mu[1], models.wrap_angle(mu[2])])
        used[j] = True
    if flags == "all":
        used[:] = True
    elif flags == "none":
        used[:] = False
    return mu, Sig, used


def _predict_given_M(mu, Sig, u, z, landmarks, dt, M, Q, gate):
    """kf.ekf_predict handed the odometry noise M as its R: it refuses the 2 x 2 matrix."""
    g, G = lambda x, c: models.unicycle(x, c, dt), lambda x, c: models.unicycle_jacobian(x, c, dt)
    return filters.ekf_predict(mu, Sig, u, g, G, M)


def _predicted(mu, Sig, u):
    """The prediction of one step on the capstone, and its W M Wᵀ."""
    W = models.unicycle_control_jacobian(mu, u, DT)
    G = models.unicycle_jacobian(mu, u, DT)
    return models.unicycle(mu, u, DT), G @ Sig @ G.T + W @ M @ W.T


def _reading_at(distance, mu, Sig, u, landmark, direction):
    """A reading of ``landmark`` whose innovation after the prediction lies ``distance`` standard
    deviations (Mahalanobis) from the predicted reading, along ``direction``."""
    mu_bar, Sig_bar = _predicted(mu, Sig, u)
    H = models.range_bearing_jacobian(mu_bar, landmark)
    S = H @ Sig_bar @ H.T + Q
    d = np.asarray(direction, dtype=float)
    nu = distance * d / np.sqrt(d @ np.linalg.solve(S, d))
    z = models.range_bearing(mu_bar, landmark) + nu
    return np.array([z[0], models.wrap_angle(z[1])])


def _cases(rng) -> list[Case]:
    wide = np.diag([0.04, 0.04, 0.01])  # a belief 20 cm and 0.1 rad wide: one reading moves it visibly
    ahead = np.array([0.0, 0.0, 0.0])
    straight = np.array([1.0, 0.0])  # m/s, rad/s
    capstone = {"dt": DT, "M": M, "Q": Q}

    def case(label, mu, Sig, u, z, landmarks, gate=GATE):
        return Case(
            label,
            mu=mu,
            Sig=Sig,
            u=u,
            z=np.array(z, dtype=float).reshape(-1, 2),
            landmarks=np.array(landmarks, dtype=float).reshape(-1, 2),
            **capstone,
            gate=gate,
        )

    behind = np.array([-3.0, 0.01])  # straight behind the robot once it has moved to (0.2, 0): bearing near +pi
    across = [[3.2, -np.pi + 0.01]]  # read just across the seam, at -pi + 0.01
    gate_landmark = np.array([3.0, 2.0])
    cases = [
        case("chapter 10's step 60: two landmarks in view", *CHAPTER_STEP.values()),
        case("a landmark straight behind, bearing read across ±π", ahead, wide, straight, across, behind),
        case(
            "a landmark straight behind, bearing read across ±π, no gate", ahead, wide, straight, across, behind, np.inf
        ),
    ]
    unsure = np.diag([0.25, 0.25, 0.04])  # a belief so wide that Q hardly changes a reading's distance
    for distance, label in [
        (20.0, "far outside the gate, a stray one"),
        (4.2, "just outside the gate"),
        (3.8, "just inside the gate"),
    ]:
        z = _reading_at(distance, ahead, unsure, straight, gate_landmark, [1.0, 0.02])
        cases.append(
            case(f"a reading {label} ({distance:g} standard deviations)", ahead, unsure, straight, z, gate_landmark)
        )
    sure = np.diag([4e-4, 4e-4, 1e-4])  # a belief 2 cm wide: S is about Q, whose entries are far below 1
    z = _reading_at(20.0, ahead, sure, straight, gate_landmark, [1.0, 0.02])
    cases.append(
        case("a stray reading against a sure belief (20 standard deviations)", ahead, sure, straight, z, gate_landmark)
    )
    cases += [
        case(
            "two readings: the second is linearized where the first left the estimate",
            ahead,
            wide,
            straight,
            [[3.3, 0.45], [2.9, -0.95]],
            [[3.0, 1.5], [2.0, -2.5]],
            np.inf,
        ),
        case(
            "no reading in view: the step only predicts", np.array([1.0, 2.0, 0.5]), wide, np.array([0.8, 0.3]), [], []
        ),
        case(
            "the update turns the heading across ±π",
            np.array([0.0, 0.0, np.pi - 0.01]),
            wide,
            straight,
            [[2.95, 0.05]],
            [[-3.1, -0.3]],
        ),
    ]
    for _ in range(6):  # random steps on the capstone's room: one to three landmarks in view
        mu = np.array([*rng.uniform(-4, 4, 2), rng.uniform(-np.pi, np.pi)])
        u = np.array([rng.uniform(0.5, 1.5), rng.uniform(-0.8, 0.8)])
        k = int(rng.integers(1, 4))
        landmarks = mu[:2] + rng.uniform(1.0, 4.0, (k, 1)) * np.column_stack(
            [np.cos(a := rng.uniform(-np.pi, np.pi, k)), np.sin(a)]
        )
        mu_bar, _ = _predicted(mu, wide, u)
        z = np.array([models.range_bearing(mu_bar, m) for m in landmarks]) + rng.normal(0, [0.15, 0.05], (k, 2))
        z[:, 1] = models.wrap_angle(z[:, 1])
        cases.append(
            case(
                f"random: {k} reading{'s' if k > 1 else ''}",
                mu,
                wide,
                u,
                z,
                landmarks,
                [GATE, np.inf][int(rng.integers(2))],
            )
        )
    return cases


WHERE = (
    "chapter 10, the loop: predict μ̄ = g(μ, u), Σ̄ = GΣGᵀ + W M Wᵀ; then for each reading in turn, at the current "
    "mean: ν = z − h(μ) (bearing wrapped), S = HΣHᵀ + Q, used if νᵀS⁻¹ν ≤ gate², then K = ΣHᵀS⁻¹, μ ← μ + Kν "
    "(heading wrapped), Σ ← (I − KH)Σ"
)


def _variants() -> list[Variant]:
    def with_(**knobs):
        return lambda *args: _step_with(*args, **knobs)

    current = "Linearize each reading at the current mean μ, the one the previous reading's update left, not at μ̄."
    Q_hint = "Q is the reading noise: S = HΣHᵀ + Q, both in the gate's νᵀS⁻¹ν and in the gain K = ΣHᵀS⁻¹."
    R_hint = (
        "The odometry noise M is a 2 x 2 covariance of [V, ω]; the pose needs it as 3 x 3: R = W M Wᵀ with "
        "W = kf.unicycle_control_jacobian(mu, u, dt), added in Σ̄ = GΣGᵀ + R."
    )
    used_hint = "used[j] is True exactly when reading j passed the gate and updated the estimate, False otherwise."
    return [
        Variant("R_not_mapped", with_(R_as="M"), R_hint),
        Variant("R_not_mapped", _predict_given_M, R_hint),
        Variant("forgot_R", with_(R_as="none"), R_hint),
        Variant(
            "no_predict_when_blind",
            with_(predict_when_blind=False),
            "The robot moved even when it sees nothing: predict first, at every step; the readings come after.",
        ),
        Variant("stale_mean", with_(linearize_at="mu_bar"), current),
        Variant("stale_mean", with_(linearize_at="mu_bar only"), current + " Each update also starts from there."),
        Variant(
            "stale_mean",
            with_(linearize_at="mu_bar, Sig_bar in S and K"),
            current + " H, S and K of each reading come from the belief the previous reading left, not from μ̄, Σ̄.",
        ),
        Variant(
            "bearing_not_wrapped",
            with_(wrap_gate=False, wrap_update=False),
            "A bearing read at −π + 0.01 and predicted at π − 0.01 differ by 0.02, not 2π − 0.02: wrap the "
            "bearing of ν = z − h(μ), e.g. with kf.models.range_bearing_residual.",
        ),
        Variant(
            "bearing_not_wrapped",
            with_(wrap_update=False),
            "The innovation of the update needs its bearing wrapped too: pass "
            "residual=kf.models.range_bearing_residual to kf.ekf_update.",
        ),
        Variant(
            "heading_not_wrapped",
            with_(wrap_heading=False),
            "The update can turn the heading past π: wrap μ's θ with kf.wrap_angle after each update.",
        ),
        Variant("forgot_Q", with_(Q_in_gate=False, Q_in_update=False), Q_hint),
        Variant("forgot_Q", with_(Q_in_gate=False), Q_hint + " Here it is missing from the gate's S."),
        Variant("forgot_Q", with_(Q_in_update=False), Q_hint + " Here it is missing from the update's S."),
        Variant(
            "gate_on_d_not_d2",
            with_(gate_test="d2 <= gate"),
            "νᵀS⁻¹ν is the squared distance d²: compare it with gate², not with gate (or take its square root).",
        ),
        Variant(
            "gate_on_d_not_d2",
            with_(gate_test="d <= gate2"),
            "The distance d = √(νᵀS⁻¹ν) is compared with gate itself; only d² goes with gate².",
        ),
        Variant(
            "no_gate",
            with_(gate_test="none"),
            "A reading further than gate standard deviations from its predicted reading (νᵀS⁻¹ν > gate²) "
            "is refused: skip its update and leave used[j] False.",
        ),
        Variant("used_wrong", with_(flags="all"), used_hint),
        Variant("used_wrong", with_(flags="none"), used_hint),
    ]


# Chapter 10's step, the prediction, the updates and the gate apart, and its inputs one at a time (run_check's
# diagnosis), by the exercise's numbers: (1) predict, (2) H, ν and S, (3) the gate, (4) the update, (5) the wrap.
STEPS = (
    Step(
        "no reading (z and landmarks empty)",
        "the prediction (1), μ̄ = g(μ, u), Σ̄ = GΣGᵀ + W M Wᵀ, alone",
        lambda i: {**i, "z": np.zeros((0, 2)), "landmarks": np.zeros((0, 2))},
    ),
    Step(
        "u = 0 and M = 0",
        "the updates (2)-(5) alone",
        lambda i: {**i, "u": np.zeros(2), "M": np.zeros((2, 2))},
    ),
    Step(
        "gate = ∞ (no reading refused)", "(1), (2), (4) and (5), without the gate (3)", lambda i: {**i, "gate": np.inf}
    ),
)
PROBES = (
    Probe("Sig", lambda x: x + 0.01 * np.eye(3), "the prediction (1), Σ̄ = GΣGᵀ + W M Wᵀ"),
    Probe("u", lambda x: x + np.array([0.1, 0.1]), "the prediction (1), μ̄ = g(μ, u), and its G and W"),
    Probe("M", lambda x: 2.0 * x, "the prediction (1), Σ̄ = GΣGᵀ + W M Wᵀ"),
    Probe("Q", lambda x: 2.0 * x, "S = HΣHᵀ + Q (2), and through it the gate (3) and the update (4)"),
    Probe("z", lambda x: x + np.array([0.05, 0.02]), "the innovation ν = z − h(μ) (2)"),
)


def localization_step(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``localization_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)`` against
    :func:`kfcourse.ekf_localization_step`.

    The cases: chapter 10's step 60 (two landmarks in view), then one case for each classic
    mistake (a bearing read across ±π, a reading just outside and one just inside the gate, a stray
    one against a sure belief, two readings, no reading, a heading turned across ±π) and seeded
    random steps.  Every case
    uses the capstone's ``dt``, ``M``, ``Q``; the gate is 4 or ``np.inf``.  Introduced in chapter 10.

    Parameters
    ----------
    student_fn : callable ``(mu (3,), Sig (3, 3), u (2,), z (k, 2), landmarks (k, 2), dt, M (2, 2), Q (2, 2), gate)
        -> (mu (3,), Sig (3, 3), used (k,) bool)``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    _function(student_fn, "localization_step")
    cases = _cases(np.random.default_rng(seed))
    return run_check(
        "ekf_localization_step",
        student_fn,
        filters.ekf_localization_step,
        cases,
        _variants(),
        ("mu", "Sig", "used"),
        WHERE,
        steps=STEPS,
        probes=PROBES,
        invariants=(is_covariance("Sig"), angle_in_range("mu", 2, "heading θ (5)")),
    )
