"""Chapter 8: the association scene. The gate rejects a pedestrian's leg; opened too wide, it lets the leg
in and the leg drags the estimate away from the truth."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

SEEDS = [0, 1, 2]


@pytest.mark.parametrize("seed", SEEDS)
def test_default_gate_accepts_every_landmark_and_rejects_the_leg(seed):
    scan = kf.sim.association_scan(seed, leg=True)
    res = kf.sim.gated_update(scan)  # default gate 3 sigma
    assert res.gate == 3.0
    assert scan.source[-1] == -1  # the leg's reading comes last
    assert res.match[-1] == -1  # rejected
    assert list(res.match[:-1]) == list(scan.source[:-1])  # every true reading matched to its own landmark
    assert res.distances[-1].min() > 3.0


@pytest.mark.parametrize("seed", SEEDS)
def test_a_rejected_leg_changes_nothing(seed):
    with_leg = kf.sim.gated_update(kf.sim.association_scan(seed, leg=True))
    without = kf.sim.gated_update(kf.sim.association_scan(seed, leg=False))
    assert with_leg.mu == pytest.approx(without.mu)
    assert with_leg.Sig == pytest.approx(without.Sig)


@pytest.mark.parametrize("seed", SEEDS)
def test_the_leg_let_in_moves_the_estimate_away_from_the_truth(seed):
    scan = kf.sim.association_scan(seed, leg=True)
    tight, wide = kf.sim.gated_update(scan, 3.0), kf.sim.gated_update(scan, 6.0)
    assert wide.match[-1] == 3  # matched to the landmark it stands next to
    assert tight.error < 0.15  # m: the honest readings alone put the robot right
    assert wide.error > 2.5 * tight.error
    assert wide.error > 0.25
    assert np.linalg.det(wide.Sig[:2, :2]) < np.linalg.det(tight.Sig[:2, :2])  # further off, yet surer of itself


def test_the_estimate_with_good_readings_beats_the_prediction():
    res = kf.sim.gated_update(kf.sim.association_scan(0))
    assert res.error_bar == pytest.approx(np.hypot(0.3, 0.25))
    assert res.error < res.error_bar / 4
    assert np.linalg.det(res.Sig[:2, :2]) < np.linalg.det(kf.sim.association_scan(0).Sig_bar[:2, :2]) / 10


def test_a_tight_gate_throws_away_good_readings():
    scan = kf.sim.association_scan(0)
    res = kf.sim.gated_update(scan, 1.0)
    assert res.accepted.sum() == 1
    assert res.error > 0.3  # hardly better than the prediction (0.39 m)


def test_verdict_is_the_gate_on_the_smallest_distance():
    scan = kf.sim.association_scan(0, leg=True)
    for gate in (1.0, 2.0, 3.0, 4.5, 6.0):
        res = kf.sim.gated_update(scan, gate)
        nearest = res.distances.argmin(axis=1)
        expect = np.where(res.distances.min(axis=1) <= gate, nearest, -1)
        assert list(res.match) == list(expect)


def test_distances_are_the_mahalanobis_lengths_of_the_wrapped_innovations():
    scan = kf.sim.association_scan(0, leg=True)
    res = kf.sim.gated_update(scan)
    for k, z in enumerate(scan.z):
        for j in range(len(scan.landmarks)):
            nu = kf.models.range_bearing_residual(z, scan.z_hat[j])
            assert res.distances[k, j] == pytest.approx(kf.mahalanobis(nu, scan.S[j]))


def test_the_leg_does_not_change_the_landmarks_readings():
    a, b = kf.sim.association_scan(4, leg=False), kf.sim.association_scan(4, leg=True)
    assert b.z[:-1] == pytest.approx(a.z)
    assert b.leg is not None and a.leg is None
    assert np.allclose(kf.sim.association_scan(4).z, a.z)  # same seed, same readings
    assert not np.allclose(kf.sim.association_scan(5).z, a.z)


def test_record_is_read_only_and_bearings_in_range():
    scan = kf.sim.association_scan(0, leg=True)
    assert np.all((scan.z[:, 1] > -np.pi) & (scan.z[:, 1] <= np.pi))  # (-pi, pi], like h
    with pytest.raises(ValueError):
        scan.z[0, 0] = 1.0
    with pytest.raises(ValueError):
        kf.sim.gated_update(scan).mu[0] = 1.0


@pytest.mark.parametrize(
    "call",
    [
        lambda: kf.sim.association_scan(-1),
        lambda: kf.sim.association_scan(0.5),
        lambda: kf.sim.association_scan(0, leg="yes"),
        lambda: kf.sim.gated_update(kf.sim.association_scan(0), 0.0),
        lambda: kf.sim.gated_update(kf.sim.association_scan(0), float("nan")),
        lambda: kf.sim.gated_update("scan"),
    ],
)
def test_bad_input_raises_value_error(call):
    with pytest.raises(ValueError):
        call()


def test_landmark_update_is_ekf_update_with_the_landmark_bound_and_the_bearing_wrapped():
    """Chapter 8's worked update, and a reading straight behind the robot whose bearing crosses +-pi."""
    mu_bar, Sig_bar, Q = np.array([1.0, 2.0, 0.0]), np.diag([0.3, 0.3, 0.1]), np.diag([0.04, 0.01])
    mu, Sig = kf.sim.scan.landmark_update(mu_bar, Sig_bar, [4.6, 0.95], [4.0, 6.0], Q)
    assert mu[:2] - mu_bar[:2] == pytest.approx([0.2207, 0.2757], abs=5e-5)
    sight = np.array([0.6, 0.8])  # toward the landmark
    assert sight @ Sig[:2, :2] @ sight == pytest.approx(0.035, abs=5e-4)  # the chapter's 0.3 -> 0.035
    behind = np.array([-2.0, 2.0])  # straight behind the robot: predicted bearing pi
    mu, _ = kf.sim.scan.landmark_update(mu_bar, Sig_bar, [3.0, -np.pi + 0.01], behind, Q)
    assert abs(mu[2]) < 0.05  # a wrapped innovation of 0.01 rad, not -2 pi
    with pytest.raises(ValueError, match="landmark"):
        kf.sim.scan.landmark_update(mu_bar, Sig_bar, [4.6, 0.95], [4.0, 6.0, 1.0], Q)
