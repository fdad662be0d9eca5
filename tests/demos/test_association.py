"""Chapter 8's data-association demo: what it draws, where, and that it holds at every slider position.

Its "Try this" prompts are driven in ``tests/demos/test_prompts_ch08.py``.
"""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.patches import Ellipse, Polygon

import kfcourse as kf
from kfcourse.demos.data_association import LEG_OPTIONS
from kfcourse.plots import palette
from kfcourse.plots.localization_figures import CLOSE_UP_X, CLOSE_UP_Y
from tests.demos.layout import readout

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.

NO_LEG, LEG = LEG_OPTIONS
TEAL = to_rgba(palette.ESTIMATE)[:3]


def centre(robot: Polygon) -> np.ndarray:
    """The robot triangle's centroid: its pose's position."""
    return np.asarray(robot.get_xy(), float)[:3].mean(axis=0)


def is_grey_outline(patch) -> bool:
    """A grey edge with nothing inside: the true pose."""
    return patch.get_edgecolor()[:3] == pytest.approx(to_rgba(palette.TRUTH)[:3]) and patch.get_facecolor()[3] == 0


@pytest.mark.fact
def test_first_frame_default_gate_every_reading_accepted():
    demo = kf.demos.data_association(seed=0)
    res = demo.model.result
    assert demo.model.gate == 3.0 and not demo.model.leg and demo.model.seed == 0
    assert res.accepted.all() and res.match.size == 4
    assert res.error_bar == pytest.approx(0.39, abs=0.005)
    assert res.error == pytest.approx(0.07, abs=0.005)
    view = demo.view
    for robot, ellipse in ((view.estimate, view.ellipse), (view.close_estimate, view.close_ellipse)):
        assert centre(robot) == pytest.approx(res.mu[:2])
        assert ellipse.get_center() == pytest.approx(res.mu[:2])
    assert "Scan 0." in readout(demo) and "nan" not in readout(demo).lower()


def test_the_estimate_is_drawn_over_the_truth_and_its_ellipse_over_the_estimate():
    """The teal robot is opaque and above the grey dotted truth (a static artist: drawn first); its ellipse is
    above it, edged in white so that it shows on the teal; both again in the close-up."""
    demo = kf.demos.data_association(seed=0)
    view, dynamic = demo.view, demo.renderer.dynamic
    for ax, robot, ellipse in ((demo.renderer.fig.axes[0], view.estimate, view.ellipse),
                               (view.close_up, view.close_estimate, view.close_ellipse)):  # fmt: skip
        assert robot in dynamic and ellipse in dynamic and dynamic.index(ellipse) > dynamic.index(robot)
        assert robot.get_facecolor()[:3] == pytest.approx(TEAL) and robot.get_alpha() >= 0.9
        assert ellipse.get_edgecolor()[:3] == pytest.approx(TEAL) and ellipse.get_path_effects()
        (truth,) = [p for p in ax.patches if isinstance(p, Polygon) and is_grey_outline(p)]
        assert truth not in dynamic and centre(truth) == pytest.approx(demo.model.scan.truth[:2])
        assert truth.get_linestyle() != "-" and truth.get_linewidth() < 2.0  # dotted, thinner than before


@pytest.mark.fact
def test_the_close_up_shows_the_robots_larger_wherever_the_estimate_goes():
    """The close-up's window holds the prediction, the truth and every estimate the demo can show
    (60 scans, with and without the leg, every gate), and it is drawn several times larger than the map."""
    demo = kf.demos.data_association(seed=0)
    fig, view = demo.renderer.fig, demo.view
    fig.canvas.draw()
    ax = fig.axes[0]
    map_scale = ax.get_window_extent().width / np.ptp(ax.get_xlim())  # pixels per metre
    close_scale = view.close_up.get_window_extent().width / np.ptp(view.close_up.get_xlim())
    assert close_scale > 3.0 * map_scale
    (x0, x1), (y0, y1) = CLOSE_UP_X, CLOSE_UP_Y
    scan = demo.model.scan
    for point in (scan.mu_bar[:2], scan.truth[:2]):
        assert x0 < point[0] < x1 and y0 < point[1] < y1
    for seed in range(60):
        for leg in (False, True):
            s = kf.sim.association_scan(seed, leg=leg)
            for gate in np.arange(1.0, 6.01, 0.5):
                x, y = kf.sim.gated_update(s, gate).mu[:2]
                assert x0 + 0.08 < x < x1 - 0.08 and y0 + 0.08 < y < y1 - 0.08  # with the robot around it


def test_the_close_up_sits_where_no_gate_reaches():
    """At the slider's 6 sigma no gate outline enters the close-up's box on the map."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 6.0
    fig = demo.renderer.fig
    fig.canvas.draw()
    ax, close_up = fig.axes[0], demo.view.close_up
    box = close_up.get_tightbbox(fig.canvas.get_renderer())  # with its title, in pixels
    for path in demo.view.gates.get_paths():
        pixels = ax.transData.transform(path.vertices)
        assert not box.count_contains(pixels), "a gate runs into the close-up"


@pytest.mark.fact
def test_new_scan_draws_new_noise_and_keeps_the_scene_and_the_controls():
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 4.0
    before = demo.model.scan
    demo.controls["new_scan"].click()
    after = demo.model.scan
    assert demo.model.seed == 1 and demo.model.leg and demo.model.gate == 4.0
    assert after.truth == pytest.approx(before.truth) and after.mu_bar == pytest.approx(before.mu_bar)
    assert not np.allclose(after.z, before.z)
    assert after.z == pytest.approx(kf.sim.association_scan(1, leg=True).z)
    assert centre(demo.view.estimate) == pytest.approx(demo.model.result.mu[:2])
    assert "Scan 1." in readout(demo)


def test_gates_drawn_around_every_landmark_and_they_grow_with_the_slider():
    demo = kf.demos.data_association(seed=0)
    gates = demo.view.gates
    small = [np.ptp(p.vertices, axis=0) for p in gates.get_paths()]
    demo.controls["gate"].value = 6.0
    large = [np.ptp(p.vertices, axis=0) for p in gates.get_paths()]
    assert len(small) == len(large) == 4
    for s, g in zip(small, large, strict=True):
        assert (g > s).all()
    centres = [p.vertices.mean(axis=0) for p in gates.get_paths()]
    assert np.linalg.norm(np.array(centres) - demo.model.scan.landmarks, axis=1).max() < 1.5


@pytest.mark.fact
@pytest.mark.parametrize("leg", [NO_LEG, LEG])
@pytest.mark.parametrize("gate", [1.0, 6.0])
def test_readout_and_picture_finite_at_the_extremes(leg, gate):
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = leg
    demo.controls["gate"].value = gate
    for _ in range(3):
        text = readout(demo).lower()
        assert "nan" not in text and "inf" not in text
        assert np.isfinite(demo.model.result.mu).all() and np.isfinite(demo.model.result.Sig).all()
        for path in demo.view.gates.get_paths():  # the gates, however wide
            assert np.isfinite(path.vertices).all()
        demo.controls["new_scan"].click()


@pytest.mark.fact
def test_question_3_the_readout_either_side_of_the_leg():
    """Q3: the slider steps by 0.1; at 4.7 the leg is rejected (0.0016 %), at 4.8 accepted (0.00099 %)."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 4.7
    assert demo.model.result.match[-1] == -1 and "0.0016 %" in readout(demo)
    demo.controls["gate"].value = 4.8
    assert demo.model.result.match[-1] == 3 and "0.00099 %" in readout(demo)


@pytest.mark.fact
def test_the_estimate_ellipse_is_small_and_every_gate_fits_the_picture():
    """After four readings the 2-sigma ellipse is smaller than the map's robot; the 6-sigma gates fit the axes."""
    demo = kf.demos.data_association(seed=0)
    demo.controls["leg"].value = LEG
    demo.controls["gate"].value = 6.0
    ellipse = demo.view.ellipse
    assert isinstance(ellipse, Ellipse) and max(ellipse.width, ellipse.height) < 0.25
    ax = demo.renderer.fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for path in demo.view.gates.get_paths():
        (px0, py0), (px1, py1) = path.vertices.min(axis=0), path.vertices.max(axis=0)
        assert x0 < px0 and px1 < x1 and y0 < py0 and py1 < y1


def test_the_leg_label_stands_at_the_leg_reading_only_with_the_leg():
    demo = kf.demos.data_association(seed=0)
    label = demo.view.leg_label
    assert label.get_text() == "leg" and not label.get_visible()
    demo.controls["leg"].value = LEG
    point = kf.plots.reading_points(demo.model.scan.mu_bar, demo.model.scan.z[-1])[0]
    assert label.get_visible() and np.linalg.norm(np.asarray(label.get_position()) - point) < 0.2
    demo.controls["leg"].value = NO_LEG
    assert not label.get_visible()
