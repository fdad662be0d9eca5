"""Data association (chapter 8): ``mahalanobis`` and ``associate``.  The lesson's
innovation measured in standard deviations, distances and the gate by hand, the gate's
edge, a spurious reading gated out, and the bad input they refuse.

(Named ``test_data_association.py``: ``tests/demos/test_association.py`` holds the
demo's tests, and two test modules of one name cannot be collected together here.)

Noise letters follow the course: R = process noise, Q = measurement noise.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import kfcourse as kf
from kfcourse.models import range_bearing_residual
from tests.filters.strategies import (
    FAST,
    I2,
    I3,
    INDEFINITE,
    INF,
    LANDMARK,
    NAN,
    NONSYM,
    POSE,
    Q_CH8,
    SIG_BAR_CH8,
    Z_CH8,
    assert_raises_naming,
    assert_raises_saying,
    assert_unique_ids,
    bad_input_cases,
    reals,
    spd,
)


# ================================================================ worked numbers (chapter 8)
def test_ch8_mahalanobis_of_the_worked_innovation():
    H = kf.range_bearing_jacobian(POSE, LANDMARK)
    S, _ = kf.kf_gain(SIG_BAR_CH8, H, Q_CH8)
    nu = kf.models.range_bearing_residual(Z_CH8, kf.range_bearing(POSE, LANDMARK))
    d = kf.mahalanobis(nu, S)
    assert d == pytest.approx(math.sqrt(nu @ np.linalg.inv(S) @ nu), rel=1e-12)
    assert d < 3.0  # a plausible reading


# ================================================================ closed forms
def test_mahalanobis_matches_closed_form_on_a_diagonal():
    assert kf.mahalanobis([3.0, -4.0], np.diag([9.0, 4.0])) == pytest.approx(math.sqrt(1.0 + 4.0), rel=1e-12)


def _linear_h(x, m):
    return x[:2] - m  # a sensor that reads the offset of the robot from a landmark


def _linear_H(x, m):
    return np.eye(2)


LIN_MAP = np.array([[0.0, 0.0], [100.0, 0.0]])


def test_associate_closed_form_distance_and_gate():
    # Sig_bar = Q = 0.5 I, H = I: S = I, so d is the plain Euclidean length of the innovation.
    # Reading (1.2, 1.6) at the robot (0, 0) against landmark 0: nu = (1.2, 1.6), d = 2 (and d^2 = 4).
    z = np.array([1.2, 1.6])
    for gate, expected in [(2.5, 0), (2.0 + 1e-9, 0), (1.999, None), (1.5, None), (3.9, 0)]:
        idx, dist = kf.associate(z, [0.0, 0.0], 0.5 * np.eye(2), LIN_MAP, _linear_h, _linear_H, 0.5 * np.eye(2), gate)
        assert dist[0] == pytest.approx(2.0, rel=1e-14)
        assert dist[1] == pytest.approx(math.hypot(101.2, 1.6), rel=1e-14)
        assert idx == expected, gate


# ================================================================ properties
@FAST
@given(nu=st.tuples(reals(-5, 5), reals(-5, 5)).map(np.array), S=spd(2), scale=reals(0.1, 10))
def test_mahalanobis_is_the_whitened_length(nu, S, scale):
    L = np.linalg.cholesky(S)
    d = kf.mahalanobis(nu, S)
    assert d == pytest.approx(np.linalg.norm(np.linalg.solve(L, nu)), rel=1e-9, abs=1e-12)
    # a distance, not a squared one: scaling nu scales d linearly
    assert kf.mahalanobis(scale * nu, S) == pytest.approx(scale * d, rel=1e-9, abs=1e-12)


MAP = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])
SIG_POSE = np.diag([0.05, 0.05, 0.01])
Q_RB = np.diag([0.01, 0.001])


def _associate(z, pose, gate=3.0):
    return kf.associate(
        z,
        pose,
        SIG_POSE,
        MAP,
        kf.range_bearing,
        kf.range_bearing_jacobian,
        Q_RB,
        gate=gate,
        residual=range_bearing_residual,
    )


@FAST
@given(
    pose=st.tuples(reals(2, 8), reals(2, 8), reals(-math.pi, math.pi)).map(np.array),
    j=st.integers(0, len(MAP) - 1),
    noise=st.tuples(reals(-1, 1), reals(-1, 1)),
    spurious_range=reals(0.2, 1.0),
    spurious_bearing=reals(-math.pi, math.pi),
)
def test_mahalanobis_gate(pose, j, noise, spurious_range, spurious_bearing):
    # a good reading of landmark j, off by at most one sensor sigma per channel
    z_good = kf.range_bearing(pose, MAP[j]) + np.array(noise) * np.sqrt(np.diag(Q_RB))
    z_good[1] = kf.wrap_angle(z_good[1])
    idx, dist = _associate(z_good, pose)
    assert idx == j
    assert dist.shape == (len(MAP),)
    assert dist[j] <= 3.0
    for i, m in enumerate(MAP):  # each distance is the Mahalanobis length of its innovation
        S, _ = kf.kf_gain(SIG_POSE, kf.range_bearing_jacobian(pose, m), Q_RB)
        nu = range_bearing_residual(z_good, kf.range_bearing(pose, m))
        assert dist[i] == pytest.approx(kf.mahalanobis(nu, S), rel=1e-9)
    # a pedestrian's leg: closer than any landmark (all >= 2.8 m away) -> gated out
    z_bad = np.array([spurious_range, spurious_bearing])
    idx_bad, dist_bad = _associate(z_bad, pose)
    assert idx_bad is None
    assert dist_bad.min() > 3.0
    # ... and it is the gate that rejects it: without one, the nearest landmark is taken
    idx_open, _ = _associate(z_bad, pose, gate=1e9)
    assert idx_open == int(np.argmin(dist_bad))


@settings(max_examples=80, deadline=None)
@given(
    pose=st.tuples(reals(2, 8), reals(2, 8), reals(-math.pi, math.pi)).map(np.array),
    j=st.integers(0, len(MAP) - 1),
    direction=reals(-math.pi, math.pi),
    gate=reals(0.3, 5.0),
    side=st.sampled_from([1 - 1e-6, 1 + 1e-6]),
)
def test_associate_accepts_just_inside_and_rejects_just_outside_the_gate(pose, j, direction, gate, side):
    z_hat = kf.range_bearing(pose, MAP[j])
    H = kf.range_bearing_jacobian(pose, MAP[j])
    S = H @ SIG_POSE @ H.T + Q_RB  # textbook innovation covariance
    # an innovation of Mahalanobis length exactly side * gate: L e with |e| = side * gate, L L^T = S
    nu = np.linalg.cholesky(S) @ (side * gate * np.array([math.cos(direction), math.sin(direction)]))
    z = z_hat + nu
    z[1] = math.remainder(z[1], 2 * math.pi)
    idx, dist = _associate(z, pose, gate=gate)
    assert dist[j] == pytest.approx(side * gate, rel=1e-9)
    assume(np.delete(dist, j).min() > gate * 1.01)  # no other landmark competes (true in practice)
    assert idx == (j if side < 1 else None)


# ================================================================ bad input
ASSOC_OK = {
    "z": [4.6, 0.95],
    "mu_bar": POSE,
    "Sig_bar": 0.1 * I3,
    "landmarks": np.array([[4.0, 6.0], [-3.0, 0.0]]),
    "h": kf.range_bearing,
    "H": kf.range_bearing_jacobian,
    "Q": Q_CH8,
}

BAD_INPUT = [
    ("mahalanobis/nu NaN", lambda: kf.mahalanobis([NAN, 0.0], I2), "nu"),
    ("mahalanobis/S wrong shape", lambda: kf.mahalanobis([1.0, 0.0], I3), "S"),
    ("mahalanobis/S indefinite", lambda: kf.mahalanobis([1.0, 0.0], INDEFINITE), "S"),
    ("mahalanobis/S singular", lambda: kf.mahalanobis([1.0, 0.0], np.diag([1.0, 0.0])), "S"),
    ("mahalanobis/S non-symmetric", lambda: kf.mahalanobis([1.0, 0.0], NONSYM), "S"),
    *[
        (f"associate/{label}", (lambda kw=kw: kf.associate(**{**ASSOC_OK, **kw})), arg)
        for label, kw, arg in [
            ("z NaN", {"z": [NAN, 0.9]}, "z"),
            ("gate zero", {"gate": 0.0}, "gate"),
            ("gate negative", {"gate": -3.0}, "gate"),
            ("landmarks 3-D", {"landmarks": np.zeros((2, 2, 2))}, "landmarks"),
            ("landmarks NaN", {"landmarks": [[NAN, 6.0]]}, "landmarks"),
            ("h not callable", {"h": "range"}, "h"),
            ("H not callable", {"H": 0}, "H"),
            ("h wrong shape", {"h": lambda x, m: [1.0]}, "h"),
            ("H wrong shape", {"H": lambda x, m: I2}, "H"),
            ("Q wrong shape", {"Q": I3}, "Q"),
            ("Sig_bar non-symmetric", {"Sig_bar": np.triu(np.ones((3, 3)))}, "Sig_bar"),
            ("mu_bar inf", {"mu_bar": [INF, 2.0, 0.0]}, "mu_bar"),
        ]
    ],
]


@pytest.mark.parametrize(("call", "arg"), bad_input_cases(BAD_INPUT))
def test_bad_input_raises_value_error_naming_the_argument(call, arg):
    assert_raises_naming(call, arg)


def test_case_ids_are_unique():
    assert_unique_ids(BAD_INPUT)


def test_the_valid_baselines_do_not_raise():
    """Each case spoils one argument of an otherwise valid call; check the valid calls."""
    kf.mahalanobis([1.0, 0.0], I2)
    idx, _ = kf.associate(**ASSOC_OK)
    assert idx == 0


@pytest.mark.parametrize(
    ("call", "message"),
    [(lambda: kf.associate(**ASSOC_OK, gate=-3.0), "gate must be a distance > 0 standard deviations")],
)
def test_message_says_what_the_argument_is(call, message):
    """A step, a distance or a standard deviation is not called a variance."""
    assert_raises_saying(call, message)
