"""Checker for chapter 12's exercise (a): the EKF update of a pose with one range to a beacon.

Noise letters follow the course: ``R`` is process (motion) noise, ``Q`` the range's noise.

The exercise's equations, numbered as the verdicts say them: at the predicted pose μ̄ = [x, y, θ],
with p = (x, y) and r = ‖p − b‖,

(1) ẑ = r and H = [(x − bx)/r, (y − by)/r, 0];
(2) S = HΣ̄Hᵀ + Q and K = Σ̄HᵀS⁻¹;
(3) μ = μ̄ + K(z − ẑ);
(4) Σ = (I − KH)Σ̄ (the Joseph form (I − KH)Σ̄(I − KH)ᵀ + KQKᵀ is the same to rounding).

Two decisions, the checker's:

- **The heading.**  A range does not depend on θ, yet the update moves θ through Σ̄'s correlation of θ
  with x and y (K's third entry); with none, θ comes back unchanged.  The update does not wrap θ, and
  the checker does not ask it to: a heading that differs from ``kf.range_update``'s by whole turns
  (wrapped into (−π, π], or left past π) is the same heading and passes.  A heading held fixed where
  it should move is a mistake (``heading_held``); one case turns θ past π.
- **A robot exactly at the beacon.**  There r = 0 and H = (p − b)/r is 0/0: ``kf.range_update``
  refuses it with a ``ValueError`` (``kf.models.range_only_jacobian`` does).  After every other case
  passes, the checker runs this one: the function passes if it raises ``ValueError``; returning an
  answer (NaN, inf or numbers) fails with ``r_zero_not_refused``, raising another error fails unnamed.
  A tiny range (r = 1e-6) is no such case: its H is still a unit vector, and it is compared as usual.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from .. import filters, models
from ._core import (
    MISTAKES,
    RTOL,
    Case,
    CheckResult,
    Invariant,
    Probe,
    Step,
    Variant,
    _as_array,
    _block,
    _kind,
    _named,
    _parts,
    _quietly,
    _where,
    is_covariance,
    moved,
    random_covariance,
    run_check,
)
from .exercises import _function

#: Chapter 12's worked example: the robot at (2, 1) heading 0.3 rad, the beacon at (6, 4), so that
#: r = 5 (a 3-4-5 triangle); the radio reads 5.35 m with a 0.5 m standard deviation.
WORKED = {
    "mu_bar": np.array([2.0, 1.0, 0.3]),
    "Sig_bar": np.diag([0.5, 0.5, 0.1]),
    "z": np.array([5.35]),
    "beacon": np.array([6.0, 4.0]),
    "Q": np.array([[0.25]]),
}
#: The worked example's belief with the heading correlated with x: the range then moves θ too.
CORRELATED = np.array([[0.5, 0.0, 0.1], [0.0, 0.5, 0.0], [0.1, 0.0, 0.1]])
#: A robot standing exactly on the beacon: r = 0, where H is undefined (run apart: kf.range_update refuses it).
AT_BEACON = Case(
    "a robot exactly at the beacon (r = 0)",
    mu_bar=np.array([6.0, 4.0, 0.3]),
    Sig_bar=np.diag([0.5, 0.5, 0.1]),
    z=np.array([0.2]),
    beacon=np.array([6.0, 4.0]),
    Q=np.array([[0.25]]),
)

WHERE = (
    "chapter 12, exercise (a): at μ̄, (1) ẑ = ‖p − b‖ = r and H = [(x − bx)/r, (y − by)/r, 0]; "
    "(2) S = HΣ̄Hᵀ + Q, K = Σ̄HᵀS⁻¹; (3) μ = μ̄ + K(z − ẑ); (4) Σ = (I − KH)Σ̄"
)


def _update_with(mu_bar, Sig_bar, z, beacon, Q, **mistake):
    """Equations (1)-(4), written out; a keyword of :func:`_variants` makes one mistake (the defaults are right)."""
    wrong = mistake.get
    mu_bar, Sig_bar = np.asarray(mu_bar, dtype=float), np.asarray(Sig_bar, dtype=float)
    z, b, Q = np.asarray(z, dtype=float).reshape(1), np.asarray(beacon, dtype=float), np.asarray(Q, dtype=float)
    dx, dy = mu_bar[0] - b[0], mu_bar[1] - b[1]  # from the beacon to the robot
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    z_hat = np.array([q if wrong("z_hat_q") else r])  # (1)
    sx, sy = (-dx, -dy) if wrong("H_sign") else (dy, dx) if wrong("H_swapped") else (dx, dy)
    over = {"r": r, "q": q, "1": 1.0, "q/2": 0.5}[wrong("H_over") or "r"]  # q/2: H = 2(p − b), the Jacobian of q
    H = np.array([[sx / over, sy / over, wrong("H_theta") or 0.0]])  # (1)
    noise = {None: Q, "squared": Q**2, "root": np.sqrt(Q), "none": 0.0 * Q}[wrong("noise")]
    S = H @ Sig_bar @ H.T + noise  # (2)
    K = Sig_bar @ H.T @ (S if wrong("no_inverse") else np.linalg.inv(S))  # (2)
    if wrong("K_heading_zero"):
        K[2] = 0.0
    nu = z_hat - z if wrong("innovation_sign") else z - z_hat
    mu = mu_bar + K @ nu  # (3)
    if wrong("heading_held"):
        mu[2] = mu_bar[2]
    I_KH = np.eye(3) + K @ H if wrong("covariance_sign") else np.eye(3) - K @ H
    Sig = {
        None: I_KH @ Sig_bar,  # (4)
        "right_side": Sig_bar @ I_KH,
        "no_Sig_bar": I_KH,
        "unchanged": Sig_bar,
    }[wrong("Sig")]
    return mu, Sig


def _variant(mistake: str, hint: str, **knobs) -> Variant:
    return Variant(mistake, lambda *args: _update_with(*args, **knobs), hint)


def _dot_not_outer(mu_bar, Sig_bar, z, beacon, Q):
    """H as a 1-D array: K = Σ̄H/S is 1-D too, and K @ H is their dot product, a number, in I − KH."""
    mu, _ = _update_with(mu_bar, Sig_bar, z, beacon, Q)
    H = models.range_only_jacobian(mu_bar, beacon)[0]
    K = np.asarray(Sig_bar, dtype=float) @ H / (H @ np.asarray(Sig_bar, dtype=float) @ H + float(np.ravel(Q)[0]))
    return mu, (np.eye(3) - K @ H) @ np.asarray(Sig_bar, dtype=float)


def _variants() -> list[Variant]:
    """The catalogue of :func:`range_update`: each known mistake as a wrong version, with its hint."""
    wrong_way = (
        "With ν = z − ẑ and H = [(x − bx)/r, (y − by)/r, 0], the unit vector from the beacon to the robot, a "
        "reading longer than predicted pushes the robot away from the beacon. Yours pulls it the other way: "
        "either ν is ẑ − z, or H has the sign of b − p (chapter 7's Δx = m − x without its range row's minus). "
        "The two give one and the same answer, and Σ is right with either: only the mean (3) shows it."
    )
    unit = "Differentiate r = √((x − bx)² + (y − by)²): ∂r/∂x = (x − bx)/r and ∂r/∂y = (y − by)/r."
    q_hint = (
        "r is the square root of q = (x − bx)² + (y − by)²: ẑ = r = √q in (1), and H = [(x − bx)/r, (y − by)/r, 0] "
        "divides by r, not by q."
    )
    heading = (
        "Turning in place keeps the distance to the beacon, so H's third entry is 0 (the −1 belongs to the bearing "
        "row of chapter 7's H)."
    )
    held = (
        "K = Σ̄HᵀS⁻¹ has a heading entry Σ̄_θx H_x + Σ̄_θy H_y: when Σ̄ correlates θ with x or y, the range moves θ "
        "too. Let μ = μ̄ + Kν update all three entries, and Σ = (I − KH)Σ̄ with the whole K."
    )
    return [
        _variant("shift_wrong_way", wrong_way, H_sign=True),
        _variant("shift_wrong_way", wrong_way, innovation_sign=True),
        _variant("forgot_Q", "The innovation covariance (2) adds the range's noise: S = HΣ̄Hᵀ + Q.", noise="none"),
        _variant(
            "std_not_var", "Q is already the range's variance σ²: add it to S as it is, not squared.", noise="squared"
        ),
        _variant(
            "std_not_var", "Q is already the range's variance σ²: add it to S as it is, no square root.", noise="root"
        ),
        _variant("q_not_sqrt_q", q_hint, z_hat_q=True),
        _variant("q_not_sqrt_q", q_hint, H_over="q"),
        _variant("q_not_sqrt_q", q_hint + " H = 2(p − b) is the Jacobian of q, not of r.", z_hat_q=True, H_over="q/2"),
        _variant("H_not_unit", unit, H_over="1"),
        _variant(
            "dx_dy_swapped",
            "H's first entry goes with x, the second with y: [(x − bx)/r, (y − by)/r, 0].",
            H_swapped=True,
        ),
        _variant("heading_in_H", heading, H_theta=-1.0),
        _variant("heading_in_H", heading, H_theta=1.0),
        _variant("no_inverse", "The gain (2) divides by S: K = Σ̄HᵀS⁻¹, with np.linalg.inv(S).", no_inverse=True),
        _variant(
            "sign_flip", "Equation (4) is Σ = (I − KH)Σ̄: the update shrinks the covariance.", covariance_sign=True
        ),
        _variant("wrong_order", "Equation (4) is Σ = (I − KH)Σ̄, with (I − KH) on the left.", Sig="right_side"),
        _variant("no_Sig_bar", "Equation (4) multiplies: Σ = (I − KH) @ Sig_bar.", Sig="no_Sig_bar"),
        _variant(
            "Sig_not_updated",
            "Return Σ = (I − KH)Σ̄ (4), not Σ̄ itself: a reading shrinks the covariance along H.",
            Sig="unchanged",
        ),
        _variant("heading_held", held, heading_held=True),
        _variant("heading_held", held, K_heading_zero=True),
        Variant(
            "dot_not_outer",
            _dot_not_outer,
            "With H a 1-D array, K is 1-D too and K @ H is a number: keep H as a (1, 3) matrix, so that K is "
            "(3, 1) and K @ H the 3 x 3 matrix of (4) (or write np.outer(K, H)).",
        ),
    ]


def _cases(rng) -> list[Case]:
    """The cases: chapter 12's worked example, the edge cases, then seeded random ones."""

    def case(label, mu_bar, Sig_bar, z, beacon, Q):
        return Case(
            label,
            mu_bar=np.array(mu_bar, dtype=float),
            Sig_bar=np.array(Sig_bar, dtype=float),
            z=np.array(z, dtype=float).reshape(1),
            beacon=np.array(beacon, dtype=float),
            Q=np.array(Q, dtype=float).reshape(1, 1),
        )

    worked = WORKED
    ahead = np.array([1.0, -1.0, 0.6])  # the beacon 4 m straight ahead along the heading
    sure = np.array([[0.2, 0.05, 0.04], [0.05, 0.3, -0.06], [0.04, -0.06, 0.05]])  # correlated every way
    near_pi = np.array([0.0, 0.0, np.pi - 0.02])  # heading just short of π
    turns = np.array([[0.3, 0.0, 0.12], [0.0, 0.3, 0.0], [0.12, 0.0, 0.1]])  # θ follows x closely
    tiny = 1e-6 * np.array([0.6, 0.8])  # the beacon 1 µm from the robot
    cases = [
        case("chapter 12's worked example: r = 5 (a 3-4-5 triangle), z = 5.35", *worked.values()),
        case(
            "the worked example with θ correlated with x: the range moves the heading",
            worked["mu_bar"],
            CORRELATED,
            worked["z"],
            worked["beacon"],
            worked["Q"],
        ),
        case(
            "a reading exactly as predicted, z = r: μ = μ̄, and Σ still shrinks",
            worked["mu_bar"],
            CORRELATED,
            [5.0],
            worked["beacon"],
            worked["Q"],
        ),
        case(
            "a beacon straight ahead along the heading",
            ahead,
            sure,
            [4.3],
            ahead[:2] + 4.0 * np.array([np.cos(ahead[2]), np.sin(ahead[2])]),
            [[0.09]],
        ),
        case("a beacon due north: x = bx, so H = [0, −1, 0]", [2.0, 1.0, -1.2], sure, [3.1], [2.0, 4.5], [[0.09]]),
        case(
            "the update turns the heading past π (wrapped or not, either passes)",
            near_pi,
            turns,
            [3.85],
            [4.0, 0.0],
            [[0.04]],
        ),
        case(
            "a tiny range, r = 1e-6: H is still a unit vector",
            worked["mu_bar"],
            CORRELATED,
            [0.4],
            worked["mu_bar"][:2] + tiny,
            worked["Q"],
        ),
        case(
            "a large Q (σ = 20 m): the reading barely counts",
            worked["mu_bar"],
            CORRELATED,
            [7.0],
            worked["beacon"],
            [[400.0]],
        ),
    ]
    for _ in range(8):
        mu_bar = np.array([*rng.uniform(-5, 5, 2), rng.uniform(-np.pi, np.pi)])
        distance, direction = rng.uniform(0.5, 15.0), rng.uniform(-np.pi, np.pi)
        beacon = mu_bar[:2] + distance * np.array([np.cos(direction), np.sin(direction)])
        Sig_bar = random_covariance(rng, 3, rng.uniform(0.05, 1.0))
        Q = rng.uniform(0.01, 1.0)
        z = abs(distance + rng.normal(0.0, math.sqrt(Q + Sig_bar[0, 0])))
        cases.append(case("random poses, beliefs and beacons", mu_bar, Sig_bar, [z], beacon, [[Q]]))
    return cases


def _same_heading(expected, got):
    """The student's answer with its heading turned by the whole turns that make it the package's, when some
    do: θ and θ ± 2π are one heading, wrapped or not.  Any other answer as it is."""
    mu, Sig = got
    mu = np.array(mu, dtype=float)
    e = float(np.asarray(expected[0], dtype=float)[2])
    if mu.shape != (3,) or not np.isfinite(mu[2]):
        return got
    turned = mu[2] + 2 * math.pi * round((e - mu[2]) / (2 * math.pi))
    if turned == mu[2] or abs(turned - e) > RTOL * max(1.0, abs(e)):
        return got
    mu[2] = turned
    return mu, Sig


# The reading exactly as predicted (z = ẑ) leaves the mean alone, so the answer is the covariance update alone;
# and each input moved alone (run_check's diagnosis), by the exercise's numbers (1)-(4).
STEPS = (
    Step(
        "z = ẑ = ‖p − b‖ (the reading exactly as predicted)",
        "μ = μ̄ with the covariance update (2) and (4) alone",
        lambda i: {**i, "z": models.range_only(i["mu_bar"], i["beacon"])},
    ),
)


PROBES = (
    Probe("mu_bar", moved(0, 0.3), "ẑ = r and H (1), and through them S, K (2), μ (3) and Σ (4)", "the robot's x"),
    Probe("mu_bar", moved(2, 0.3), "μ's heading alone: neither ẑ nor H depends on θ", "the heading θ of mu_bar"),
    Probe("Sig_bar", lambda S: S + 0.05 * np.eye(3), "S and K (2), and Σ = (I − KH)Σ̄ (4)"),
    Probe("z", lambda z: z + 0.2, "the innovation z − ẑ of the mean (3) alone"),
    Probe("beacon", lambda b: b + np.array([0.3, -0.2]), "ẑ = r and H (1), and through them (2)-(4)"),
    Probe("Q", lambda Q: 2.0 * Q + 0.05, "S = HΣ̄Hᵀ + Q (2), and through K both μ (3) and Σ (4)"),
)


def _surer(inputs, parts) -> bool:
    """Σ̄ − Σ = KSKᵀ is positive semi-definite (up to rounding): a reading never makes the belief less sure."""
    Sig_bar, Sig = np.asarray(inputs["Sig_bar"], dtype=float), np.asarray(parts["Sig"], dtype=float)
    if Sig.shape != Sig_bar.shape:
        return True  # another invariant, or the comparison, says what is wrong
    gap = Sig_bar - Sig
    return bool(np.linalg.eigvalsh((gap + gap.T) / 2)[0] >= -1e-9 * max(float(np.abs(Sig_bar).max()), 1e-300))


INVARIANTS = (
    is_covariance("Sig"),
    Invariant(
        _surer,
        "your Sig is larger than Sig_bar in some direction, and a reading never makes the belief less sure: "
        "Σ = Σ̄ − KSKᵀ",
    ),
)

_REFUSE = (
    "At the beacon r = 0, and H = (p − b)/r divides 0 by 0: test r == 0 and raise ValueError, saying why (as "
    "kf.models.range_only_jacobian does), so that a loop stops there instead of carrying NaN on. Only exactly 0: "
    "a tiny r > 0 still has a direction, and its H is a unit vector."
)


def _at_the_beacon(result: CheckResult, student_fn, n_cases: int) -> CheckResult:
    """``result``, a pass, extended by the case at the beacon: a ``ValueError`` there passes; an answer fails."""
    who = getattr(student_fn, "__name__", "your function")
    outcome = _quietly(student_fn, AT_BEACON, copy.deepcopy(AT_BEACON.inputs))
    if outcome[0] == "raised" and isinstance(outcome[1], ValueError):
        headline = (
            f"{result.headline.rstrip('.')}; and it refuses {AT_BEACON.label} with ValueError, as kf.range_update does."
        )
        return CheckResult(True, None, headline, headline)
    details = "inputs:\n" + _block(list(AT_BEACON.inputs.items()), suppress_small=False)
    details += "\nexpected:\n    ValueError (r = 0: the range has no direction, H is undefined)"
    if outcome[0] == "raised":
        error = outcome[1]
        what = f"it raised {type(error).__name__}: {str(error).rstrip('.')}"
        details += _where(error, student_fn)
        mistake = None
        hint = f"Refuse it with a ValueError, the error the course's functions raise for a bad input. {_REFUSE}"
    else:  # an answer where there is none: named when it is one of the right kind, a (mu, Sig) pair
        got = outcome[1]
        parts = _parts(got, ("mu", "Sig"))
        values = [_as_array(p) for p in parts or ()]
        details += "\ngot:\n" + _block(_named(got, ("mu", "Sig")))
        if parts is None or any(a is None for a in values):
            what, mistake, hint = f"it returned {_kind(got)}", None, _REFUSE
        else:
            bad = next(
                (word for word, test in (("NaN", np.isnan), ("inf", np.isinf)) if any(test(a).any() for a in values)),
                "",
            )
            what = f"it returned an answer with {bad} in it" if bad else "it returned an answer"
            mistake = "r_zero_not_refused"
            hint = f"Likely mistake: {MISTAKES[mistake]}. {_REFUSE}"
    headline = (
        f"✘ {who} is not right yet: it matches kf.range_update on all {n_cases} cases, but on one more, "
        f"{AT_BEACON.label}, {what}."
    )
    hint += f" See {WHERE}."
    return CheckResult(False, mistake, "\n".join([headline, details, hint]), headline, details, hint)


def range_update(student_fn, seed: int = 0) -> CheckResult:
    """Check your ``range_update(mu_bar, Sig_bar, z, beacon, Q)`` against :func:`kfcourse.range_update`.

    The cases: chapter 12's worked example (the robot at (2, 1) heading 0.3, the beacon at (6, 4),
    r = 5, z = 5.35, Q = 0.25), the same with θ correlated with x, then one case for each classic
    mistake (a reading exactly as predicted, a beacon straight ahead, one due north, an update that
    turns the heading past π, a tiny range r = 1e-6, a large Q) and seeded random ones.  Both forms
    of the covariance pass, (I − KH)Σ̄ and Joseph's; a heading that differs by whole turns (wrapped or
    not) passes.  Last, a robot exactly at the beacon (r = 0): your function must raise
    ``ValueError`` there, as ``kf.range_update`` does; an answer (NaN or numbers) fails.
    Introduced in chapter 12.

    Parameters
    ----------
    student_fn : callable ``(mu_bar (3,), Sig_bar (3, 3), z (1,), beacon (2,), Q (1, 1)) -> (mu (3,), Sig (3, 3))``
    seed : int
        Seed of the random cases.

    Returns
    -------
    CheckResult
    """
    _function(student_fn, "range_update")
    cases = _cases(np.random.default_rng(seed))
    result = run_check(
        "range_update",
        student_fn,
        filters.range_update,
        cases,
        _variants(),
        ("mu", "Sig"),
        WHERE,
        pair=_same_heading,
        steps=STEPS,
        probes=PROBES,
        invariants=INVARIANTS,
    )
    return _at_the_beacon(result, student_fn, len(cases)) if result.passed else result
