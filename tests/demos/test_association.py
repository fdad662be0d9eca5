"""Chapter 8's "Try this" prompts for the data-association demo, each driven as the prose says."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.patches import Ellipse, Polygon
from matplotlib.path import Path

import kfcourse as kf
from kfcourse.demos.association import LEG_OPTIONS
from kfcourse.plots import palette
from kfcourse.plots.localization import ASSOCIATION_ROBOT as ROBOT_SIZE
from tests.demos.layout import readout

NO_LEG, LEG = LEG_OPTIONS


def estimate_drawn(demo) -> np.ndarray:
    """Centre of the teal robot triangle in the picture."""
    teal = to_rgba(palette.ESTIMATE)[:3]
    (robot,) = [
        a for a in demo.renderer.dynamic if isinstance(a, Polygon) and a.get_facecolor()[:3] == pytest.approx(teal)
    ]
    return np.asarray(robot.get_xy(), float)[:3].mean(axis=0)  # the triangle's centroid is the pose


def test_first_frame_default_gate_every_reading_accepted():
    demo = kf.demos.data_association(seed=0)
    res = demo.model.result
    assert demo.model.gate == 3.0 and not demo.model.leg
    assert res.accepted.all() and res.match.size == 4
    assert res.error_bar == pytest.approx(0.39, abs=0.005)
    assert res.error == pytest.approx(0.07, abs=0.005)
    assert estimate_drawn(demo) == pytest.approx(res.mu[:2])
    assert "nan" not in readout(demo).lower()


def test_prompt_1_the_leg_is_rejected_at_the_default_gate():
    """Try 1: gate 3 sigma, add the leg: 4.7 sigma from landmark 3, rejected; the error stays 0.07 m."""
    demo = kf.demos.data_association(seed=0)
    before = demo.model.result.mu.copy()
    demo.controls["leg"].value = LEG
    res = demo.model.result
    assert demo.model.leg and res.match.size == 5
    assert res.distances[-1].argmin() == 3
    assert res.distances[-1].min() == pytest.approx(4.7, abs=0.05)
    assert res.match[-1] == -1
    assert res.mu == pytest.approx(before)
    assert res.error == pytest.approx(0.07, abs=0.005)
    assert "rejected" in readout(demo)
    leg_point = kf.plots.reading_points(demo.model.scan.mu_bar, demo.model.scan.z[-1])
    hollow = demo.renderer.dynamic[4]  # rejected readings: hollow orange circles
    assert np.asarray(hollow.get_offsets()) == pytest.approx(leg_point)
    assert not any(Path(p.vertices).contains_points(leg_point)[0] for p in demo.renderer.dynamic[0].get_paths())


def test_prompt_2_a_wide_gate_lets_the_leg_in_and_the_estimate_slides_off():
    """Try 2: open the gate to 5 sigma: the leg is accepted as landmark 3, the error jumps to 0.29 m."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 5.0
    res = demo.model.result
    assert res.match[-1] == 3
    leg_point = kf.plots.reading_points(demo.model.scan.mu_bar, demo.model.scan.z[-1])
    assert Path(demo.renderer.dynamic[0].get_paths()[3].vertices).contains_points(leg_point)[0]  # inside gate 3
    assert res.error == pytest.approx(0.29, abs=0.005)
    assert res.error > 4 * kf.sim.gated_update(demo.model.scan, 3.0).error
    assert estimate_drawn(demo) == pytest.approx(res.mu[:2])
    truth_drawn = np.asarray(demo.renderer.dynamic[-2].get_xy(), float)[:3].mean(axis=0)  # the grey outline
    assert truth_drawn == pytest.approx(demo.model.scan.truth[:2])
    assert np.linalg.norm(estimate_drawn(demo) - truth_drawn) > ROBOT_SIZE  # the triangles no longer overlap much


def test_prompt_3_a_tight_gate_throws_good_readings_away():
    """Try 3: no leg, gate 1 sigma: three of four true readings rejected, error 0.36 m against 0.39 m predicted."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["leg"].value = NO_LEG
    demo.controls["gate"].value = 1.0
    res = demo.model.result
    assert res.match.size == 4 and res.accepted.sum() == 1
    assert res.error == pytest.approx(0.36, abs=0.005)
    assert res.error_bar == pytest.approx(0.39, abs=0.005)


def test_prompt_4_at_two_sigma_one_true_reading_is_just_outside():
    """Try 4: gate 2 sigma: reading 1 (2.01 sigma) rejected; a 2-sigma gate misses 14 % of true readings."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["gate"].value = 2.0
    res = demo.model.result
    assert list(res.match) == [0, -1, 2, 3]
    assert res.distances[1, 1] == pytest.approx(2.01, abs=0.005)
    assert 1 - demo.model.kept() == pytest.approx(0.135, abs=0.001)
    assert "14 %" in readout(demo)


def test_gates_drawn_around_every_landmark_and_they_grow_with_the_slider():
    demo = kf.demos.data_association(seed=0)
    gates = demo.renderer.dynamic[0]
    small = [np.ptp(p.vertices, axis=0) for p in gates.get_paths()]
    demo.controls["gate"].value = 6.0
    large = [np.ptp(p.vertices, axis=0) for p in gates.get_paths()]
    assert len(small) == len(large) == 4
    for s, g in zip(small, large, strict=True):
        assert (g > s).all()
    centres = [p.vertices.mean(axis=0) for p in gates.get_paths()]
    assert np.linalg.norm(np.array(centres) - demo.model.scan.landmarks, axis=1).max() < 1.5


@pytest.mark.parametrize("leg", [NO_LEG, LEG])
@pytest.mark.parametrize("gate", [1.0, 6.0])
def test_readout_and_picture_finite_at_the_extremes(leg, gate):
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = leg
    demo.controls["gate"].value = gate
    text = readout(demo).lower()
    assert "nan" not in text and "inf" not in text
    assert np.isfinite(demo.model.result.mu).all() and np.isfinite(demo.model.result.Sig).all()
    for path in demo.renderer.dynamic[0].get_paths():  # the gates, however wide
        assert np.isfinite(path.vertices).all()


def test_question_3_the_readout_either_side_of_the_leg():
    """Q3: the slider steps by 0.1; at 4.7 the leg is rejected (0.0016 %), at 4.8 accepted (0.00099 %)."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 4.7
    assert demo.model.result.match[-1] == -1 and "0.0016 %" in readout(demo)
    demo.controls["gate"].value = 4.8
    assert demo.model.result.match[-1] == 3 and "0.00099 %" in readout(demo)


def test_the_estimate_ellipse_is_drawn_over_the_robots_and_every_gate_fits_the_picture():
    """The teal 2-sigma ellipse is the last artist drawn; the 6-sigma gates (the slider's end) lie inside the axes."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 6.0
    ellipse = demo.renderer.dynamic[-1]
    assert isinstance(ellipse, Ellipse) and ellipse.get_edgecolor()[:3] == pytest.approx(to_rgba(palette.ESTIMATE)[:3])
    assert max(ellipse.width, ellipse.height) < 0.25  # m: after four readings, smaller than the robot triangle
    (ax,) = demo.renderer.fig.axes
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for path in demo.renderer.dynamic[0].get_paths():
        (px0, py0), (px1, py1) = path.vertices.min(axis=0), path.vertices.max(axis=0)
        assert x0 < px0 and px1 < x1 and y0 < py0 and py1 < y1


def test_the_leg_label_stands_at_the_leg_reading_only_with_the_leg():
    demo = kf.demos.data_association(seed=0)
    label = demo.renderer.dynamic[5]
    assert label.get_text() == "leg" and not label.get_visible()
    demo.controls["leg"].value = LEG
    point = kf.plots.reading_points(demo.model.scan.mu_bar, demo.model.scan.z[-1])[0]
    assert label.get_visible() and np.linalg.norm(np.asarray(label.get_position()) - point) < 0.2
    demo.controls["leg"].value = NO_LEG
    assert not label.get_visible()
