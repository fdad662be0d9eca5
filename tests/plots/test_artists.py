"""The map artists: each draws where it should, moves in place, and never draws NaN."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.colors import to_rgba

from kfcourse.plots import (
    beams,
    covariance_ellipse,
    landmarks,
    new_figure,
    palette,
    robot,
    update_beams,
    update_covariance_ellipse,
    update_robot,
)


@pytest.fixture
def ax():
    fig, ax = new_figure()
    yield ax
    fig.clf()


def corners(patch):
    """The triangle's three corners (matplotlib repeats the first to close it)."""
    xy = np.asarray(patch.get_xy(), float)
    assert xy.shape == (4, 2) and np.array_equal(xy[0], xy[-1])
    return xy[:3]


# ---------------------------------------------------------------- robot
@pytest.mark.parametrize("pose", [(0.0, 0.0, 0.0), (2.0, -1.0, math.pi / 2), (-3.5, 4.0, 2.5), (1.0, 1.0, math.pi)])
def test_robot_centre_sits_on_the_pose_and_nose_points_along_the_heading(ax, pose):
    size = 0.5
    patch = robot(ax, pose, palette.TRUTH, size=size)
    xy = corners(patch)
    x, y, theta = pose
    assert np.allclose(xy.mean(axis=0), [x, y])  # centroid at the position
    nose = xy[0] - [x, y]
    assert np.allclose(nose, size * np.array([math.cos(theta), math.sin(theta)]))
    # the two rear corners sit symmetrically behind the centre
    rear = xy[1:] - [x, y]
    heading = np.array([math.cos(theta), math.sin(theta)])
    assert np.allclose(rear @ heading, [-size / 2, -size / 2])
    assert np.isclose(np.linalg.norm(rear[0] - rear[1]), size)


def test_robot_colour_is_the_one_asked_for(ax):
    truth = robot(ax, (0, 0, 0), palette.TRUTH)
    estimate = robot(ax, (0, 0, 0))
    assert truth.get_facecolor()[:3] == to_rgba(palette.TRUTH)[:3]
    assert estimate.get_facecolor()[:3] == to_rgba(palette.ESTIMATE)[:3]
    assert truth in ax.patches and estimate in ax.patches


def test_update_robot_moves_the_same_polygon(ax):
    patch = robot(ax, (0.0, 0.0, 0.0), palette.ESTIMATE, size=0.4)
    before = corners(patch).copy()
    update_robot(patch, (1.0, 2.0, -math.pi / 2))
    xy = corners(patch)
    assert ax.patches[-1] is patch and len(ax.patches) == 1
    assert not np.allclose(xy, before)
    assert np.allclose(xy.mean(axis=0), [1.0, 2.0])
    assert np.allclose(xy[0], [1.0, 2.0 - 0.4])  # heading -90 degrees: nose straight down
    assert np.all(np.isfinite(xy))


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [({"pose": (0, 0)}, "pose"), ({"pose": (0, np.nan, 0)}, "pose"), ({"pose": (0, 0, 0), "size": 0.0}, "size")],
)
def test_robot_bad_input_names_the_argument(ax, kwargs, name):
    with pytest.raises(ValueError, match=name):
        robot(ax, color=palette.ESTIMATE, **kwargs)


def test_update_robot_rejects_nan_and_keeps_the_old_pose(ax):
    patch = robot(ax, (1.0, 1.0, 0.0))
    before = corners(patch).copy()
    with pytest.raises(ValueError, match="pose"):
        update_robot(patch, (np.nan, 0.0, 0.0))
    assert np.array_equal(corners(patch), before)


# ---------------------------------------------------------------- landmarks
def test_landmarks_are_purple_squares_at_their_positions(ax):
    m = np.array([[-5.0, -1.0], [0.0, 6.5], [5.5, 6.0]])
    points, texts = landmarks(ax, m)
    assert np.array_equal(np.asarray(points.get_offsets(), float), m)
    assert np.allclose(points.get_facecolors()[0][:3], to_rgba(palette.LANDMARK)[:3])
    square = points.get_paths()[0].vertices
    assert len(np.unique(np.round(square[:, 0], 9))) == 2 and len(np.unique(np.round(square[:, 1], 9))) == 2
    assert texts == []


def test_landmarks_labels(ax):
    m = np.array([[0.0, 0.0], [3.0, 4.0]])
    _, numbered = landmarks(ax, m, labels=True)
    assert [t.get_text() for t in numbered] == ["0", "1"]
    assert [t.xy for t in numbered] == [(0.0, 0.0), (3.0, 4.0)]
    _, named = landmarks(ax, m, labels=["door", "tree"])
    assert [t.get_text() for t in named] == ["door", "tree"]
    with pytest.raises(ValueError, match="labels"):
        landmarks(ax, m, labels=["only one"])


def test_landmarks_bad_positions_name_the_argument(ax):
    with pytest.raises(ValueError, match="positions"):
        landmarks(ax, [[0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="positions"):
        landmarks(ax, [[0.0, np.inf]])


# ---------------------------------------------------------------- beams
def test_beams_start_empty_and_point_from_the_robot_to_each_target(ax):
    lines = beams(ax, palette.ESTIMATE)
    assert lines.get_segments() == []
    pose = (1.0, 2.0, 0.7)
    targets = np.array([[4.0, 6.0], [-1.0, 0.0]])
    update_beams(lines, pose, targets)
    segments = lines.get_segments()
    assert len(segments) == 2
    for seg, target in zip(segments, targets, strict=True):
        assert np.array_equal(seg, [[1.0, 2.0], target])
    assert lines in ax.collections


def test_update_beams_replaces_segments_in_place(ax):
    lines = beams(ax, palette.ESTIMATE)
    update_beams(lines, (0.0, 0.0, 0.0), [[1.0, 1.0], [2.0, 0.0], [0.0, 3.0]])
    update_beams(lines, (5.0, 5.0, 0.0), [[6.0, 5.0]])
    assert len(ax.collections) == 1 and ax.collections[0] is lines
    assert [s.tolist() for s in lines.get_segments()] == [[[5.0, 5.0], [6.0, 5.0]]]
    assert all(np.all(np.isfinite(s)) for s in lines.get_segments())


@pytest.mark.parametrize("empty", [[], np.empty((0, 2)), ()])
def test_no_targets_draw_no_beam(ax, empty):
    lines = beams(ax, palette.ESTIMATE)
    update_beams(lines, (0.0, 0.0, 0.0), [[1.0, 1.0]])
    update_beams(lines, (0.0, 0.0, 0.0), empty)
    assert lines.get_segments() == []
    ax.figure.canvas.draw()  # drawing an empty collection works


def test_beams_bad_input_names_the_argument(ax):
    lines = beams(ax, palette.ESTIMATE)
    with pytest.raises(ValueError, match="targets"):
        update_beams(lines, (0.0, 0.0, 0.0), [[1.0, np.nan]])
    with pytest.raises(ValueError, match="pose"):
        update_beams(lines, (0.0, 0.0, 0.0, 0.0), [[1.0, 1.0]])


# ---------------------------------------------------------------- covariance ellipse of a pose
def semi_axes(patch):
    return sorted([patch.width / 2, patch.height / 2])


def test_ellipse_of_a_pose_covariance_uses_its_position_block(ax):
    mu = np.array([1.0, 2.0, 0.3])
    Sig = np.array([[0.5, 0.2, 0.05], [0.2, 0.3, -0.02], [0.05, -0.02, 0.1]])
    patch = covariance_ellipse(ax, mu, Sig[:2, :2], nsig=2.0)
    assert patch.center == (1.0, 2.0)
    lam = np.linalg.eigvalsh(Sig[:2, :2])
    assert np.allclose(semi_axes(patch), 2.0 * np.sqrt(lam))  # 2-sigma: semi-axes 2 sqrt(lambda)
    major = np.linalg.eigh(Sig[:2, :2])[1][:, 1]
    tilt = math.radians(patch.angle)
    assert abs(abs(major @ [math.cos(tilt), math.sin(tilt)]) - 1.0) < 1e-9  # width lies along the major axis
    assert np.all(np.isfinite(patch.get_verts()))


def test_update_ellipse_keeps_nsig_and_the_same_patch(ax):
    patch = covariance_ellipse(ax, (0.0, 0.0, 0.0), np.eye(2), nsig=2.0)
    update_covariance_ellipse(patch, (3.0, -1.0, 1.0), np.diag([4.0, 0.25]))
    assert list(ax.patches) == [patch]
    assert patch.center == (3.0, -1.0)
    assert np.allclose(semi_axes(patch), [2.0 * 0.5, 2.0 * 2.0])


def test_ellipse_of_a_collapsed_covariance_draws_no_nan(ax):
    patch = covariance_ellipse(ax, (0.0, 0.0), np.zeros((2, 2)), nsig=2.0)
    assert semi_axes(patch) == [0.0, 0.0]
    assert np.all(np.isfinite(patch.get_verts()))
