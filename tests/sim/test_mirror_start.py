"""Chapter 11: why no Kalman filter localizes globally.  Chapter 10's map is point-symmetric about
c = (0, 2.5): the half-turn (x, y, theta) -> (-x, 5 - y, theta + pi) maps it onto itself.  A filter
started at the mirror of the true start, its readings without labels, matches every reading to the
mirror landmark, finds it exactly where it expects it, and converges confidently to the wrong place.
Started at the true start, the same association localizes; with labels, no gate drags it back.

Every statement is checked over the seeds 0-19, with margins far from the measured values."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.sim.capstone_world import BEARING_STD, RANGE_STD

# Facts of seeded runs that chapter 11 states and checks too, and every repeat runs the chapter: here they run
# once (slow: 20 laps without labels each).
pytestmark = [pytest.mark.fact, pytest.mark.slow]

SEEDS = range(20)
START = np.zeros(3)  # the true start of chapter 10's lap
C = np.array([0.0, 2.5])  # the centre of the map's symmetry (m)
Q = np.diag([RANGE_STD, BEARING_STD]) ** 2  # the reading noise the filter assumes at sensor_noise = 1


def mirror(pose) -> np.ndarray:
    """The half-turn about C: (x, y, theta) -> (-x, 5 - y, theta + pi), the heading wrapped."""
    pose = np.asarray(pose, float)
    return np.stack([-pose[..., 0], 5.0 - pose[..., 1], kf.wrap_angle(pose[..., 2] + np.pi)], axis=-1)


def mirror_index(landmarks) -> np.ndarray:
    """For each landmark, the row of its mirror image on the map."""
    images = mirror(np.column_stack([landmarks, np.zeros(len(landmarks))]))[:, :2]
    return np.array([int(np.argmin(np.linalg.norm(landmarks - m, axis=1))) for m in images])


def used_nis(run) -> np.ndarray:
    """The NIS of every used reading, as the reading of the landmark it was matched to, at the step's prediction."""
    out = []
    for k, j in zip(*np.nonzero(run.used), strict=True):
        m = run.landmarks[run.matched[k, j]]
        H = kf.range_bearing_jacobian(run.mu_bar[k], m)
        nu = kf.models.range_bearing_residual(run.z[k, j], kf.range_bearing(run.mu_bar[k], m))
        out.append(nu @ np.linalg.solve(H @ run.Sig_bar[k] @ H.T + Q, nu))
    return np.array(out)


def mirror_start(seed, **settings):
    """The lap of ``seed`` with the filter started at the mirror of the true start."""
    return kf.sim.landmark_loop(seed, start=mirror(START), **settings)


@cache
def unlabelled(seed: int, filter: str, gate: float | None, mirrored: bool):
    """A lap with readings without labels, from the true start or its mirror (each run once per module)."""
    start = mirror(START) if mirrored else START
    return kf.sim.landmark_loop(seed, filter=filter, gate=gate, labelled=False, start=start)


def test_the_map_is_symmetric_and_the_mirror_start_is_its_image():
    marks = kf.sim.DEFAULT_LANDMARKS
    index = mirror_index(marks)
    np.testing.assert_allclose(mirror(np.column_stack([marks, np.zeros(len(marks))]))[:, :2], marks[index])
    assert sorted(index) == list(range(len(marks))) and (index == np.arange(len(marks))).sum() == 1  # c alone
    np.testing.assert_array_equal(kf.sim.landmark_loop(0).start, START)
    np.testing.assert_allclose(mirror(START), [0.0, 5.0, np.pi])


@pytest.mark.parametrize("filter", ["ekf", "ukf"])
@pytest.mark.parametrize("gate", [4.0, None])
def test_a_filter_started_at_the_mirror_converges_confidently_to_the_wrong_place(filter, gate):
    """Unlabelled readings, mirror start: every reading matched to the mirror landmark and used, its NIS
    near 2 (the readings fit the wrong place as well as the right one), an error at the lap's end near twice
    the distance from c, a small ellipse, and the truth outside its 3-sigma ellipse at every step."""
    held = 0
    for seed in SEEDS:
        run = unlabelled(seed, filter, gate, True)
        index = mirror_index(run.landmarks)
        seen = run.used | run.rejected
        twice = 2 * np.linalg.norm(run.truth[-1, :2] - C)
        held += (
            np.array_equal(run.matched[run.used], index[np.nonzero(run.used)[1]])  # each to the mirror landmark
            and run.used.sum() >= 0.95 * seen.sum()  # and used
            and 1.0 <= used_nis(run).mean() <= 3.5  # found where it was expected (2 on average)
            and abs(run.error[-1] - twice) < 0.25
            and run.error[-1] > 4.5
            and run.area[-1] < 0.01  # m^2: confident
            and run.inside.mean() <= 0.05
        )
    assert held == len(SEEDS)


@pytest.mark.parametrize("filter", ["ekf", "ukf"])
def test_the_mirror_run_is_the_true_start_run_turned_half_round(filter):
    """The readings cannot tell the two poses apart: the run from the mirror start is the run from the
    true start, turned half round c, step for step (to rounding)."""
    for seed in SEEDS:
        true, lost = unlabelled(seed, filter, 4.0, False), unlabelled(seed, filter, 4.0, True)
        gap = mirror(true.mu) - lost.mu
        gap[:, 2] = kf.wrap_angle(gap[:, 2])
        assert np.abs(gap).max() < 1e-6
        np.testing.assert_allclose(lost.Sig[:, :2, :2], true.Sig[:, :2, :2], atol=1e-9)
        np.testing.assert_array_equal(lost.used, true.used)


@pytest.mark.parametrize("gate", [4.0, None])
def test_the_same_association_from_the_true_start_localizes(gate):
    """It is the start, not the association, that fails the filter: from the true start every reading is
    matched to its own landmark and the filter ends the lap within centimetres, honest."""
    for seed in SEEDS:
        run = unlabelled(seed, "ekf", gate, False)
        assert np.array_equal(run.matched[run.used], np.nonzero(run.used)[1])
        assert run.error[-1] < 0.1 and run.error.max() < 0.3
        assert run.inside.mean() >= 0.9


def test_labelled_readings_and_a_gate_leave_the_mirror_filter_lost():
    """With labels and chapter 10's gate of 4, the mirror filter refuses every reading but the centre
    landmark's (which reads the same from both poses): it stays lost, sure of itself."""
    for seed in SEEDS:
        run = mirror_start(seed, gate=4.0)
        centre = int(np.argmin(np.linalg.norm(run.landmarks - C, axis=1)))
        assert (np.nonzero(run.used)[1] == centre).all() and run.used.any()
        assert run.rejected.sum() > 2 * run.used.sum()
        assert run.error[20:].min() > 4.5 and run.inside.mean() <= 0.05


def test_labelled_readings_without_a_gate_drag_the_mirror_filter_back():
    """Chapter 10's question 3: with labels and no gate, the readings pull the filter across the map to
    the truth, within 10 cm by step 40 (8 s), and it stays there, honest, to the lap's end."""
    for seed in SEEDS:
        run = mirror_start(seed)
        back = np.flatnonzero(run.error < 0.1)[0]
        assert run.error[0] > 4.0 and back <= 40
        assert run.error[back:].max() < 0.3 and run.error[-1] < 0.1
        assert run.inside[back:].mean() >= 0.85
