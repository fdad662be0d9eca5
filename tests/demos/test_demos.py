"""Every demo driven without a browser: controls to their extremes, every button,
the animation stepped; the model changes as it should and nothing drawn is NaN."""

from __future__ import annotations

import asyncio
import pickle

import ipywidgets as widgets
import numpy as np
import pytest
from matplotlib.collections import Collection
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text

import kfcourse as kf
from kfcourse.demos.hallway import DOORS

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.

DEMOS = kf.demos.__all__  # every demo the course ships gets the generic checks
# The demos with buttons, named here so that collecting the tests builds no demo;
# test_first_frame_is_drawn_and_repeatable checks the list against every demo.
BUTTON_DEMOS = [
    "data_association",
    "hallway",
    "landmark_loop",
    "nees_panel",
    "particle_cloud",
    "particle_hallway",
    "raw_vs_filtered",
    "step_through",
    "tracker",
]


def make(name, seed=0):
    return getattr(kf.demos, name)(seed=seed)


def plotted_arrays(fig):
    """Every coordinate array and text drawn in the figure."""
    for ax in fig.axes:
        for artist in ax.get_children():
            if not artist.get_visible():
                continue
            if isinstance(artist, Line2D):
                yield np.asarray(artist.get_xydata(), float)
            elif isinstance(artist, Collection):
                yield np.asarray(artist.get_offsets(), float)
                for path in artist.get_paths():
                    yield path.vertices
            elif isinstance(artist, Patch):
                yield artist.get_verts()
            elif isinstance(artist, Text):
                assert "nan" not in artist.get_text().lower(), artist.get_text()
                assert "inf" not in artist.get_text().replace("info", ""), artist.get_text()


def assert_finite(demo, what: str = "the first picture"):
    arrays = list(plotted_arrays(demo.renderer.fig))
    assert arrays, what
    for a in arrays:
        assert np.isfinite(a).all(), f"not finite after {what}"
    assert bytes(demo.image.value[:3]) == b"\xff\xd8\xff", what  # a JPEG


def model_state(demo) -> bytes:
    """Everything the model holds, as bytes, to tell whether an action changed it."""
    return pickle.dumps(vars(demo.model))


def sliders(demo):
    kinds = (widgets.IntSlider, widgets.FloatSlider, widgets.FloatLogSlider)
    return {k: c for k, c in demo.controls.items() if isinstance(c, kinds)}


def buttons(demo):
    return {k: c for k, c in demo.controls.items() if isinstance(c, widgets.Button)}


@pytest.mark.parametrize("name", DEMOS)
def test_first_frame_is_drawn_and_repeatable(name):
    a, b = make(name), make(name)
    assert bool(buttons(a)) == (name in BUTTON_DEMOS), "BUTTON_DEMOS lists exactly the demos with buttons"
    assert len(a.image.value) > 5000  # a real picture, not an empty canvas
    assert bytes(a.image.value) == bytes(b.image.value)  # same seed, same first frame
    assert "kf-demo" in a._dom_classes
    assert_finite(a)


@pytest.mark.pixels
@pytest.mark.fact
@pytest.mark.parametrize("name", DEMOS)
def test_every_slider_at_min_max_and_middle(name):
    demo = make(name)
    found = sliders(demo)
    assert found, "a demo without a slider"
    for key, control in found.items():
        for value in (control.min, control.max, (control.min + control.max) / 2):
            before = demo.image.value
            if isinstance(control, widgets.IntSlider):
                value = round(value)
            if isinstance(control, widgets.FloatLogSlider):
                value = control.base**value
            if np.isclose(control.value, value):
                continue
            control.value = value
            assert bytes(demo.image.value) != bytes(before), f"{key}={value} did not change the picture"
            assert_finite(demo, f"{key} = {value}")


@pytest.mark.fact
@pytest.mark.parametrize("name", BUTTON_DEMOS)
def test_every_button_changes_the_picture_or_the_model(name):
    for key in buttons(make(name)):
        demo = make(name)
        for other_key, other in buttons(demo).items():  # leave the first state (Reset at the start does nothing)
            if other_key != key:
                other.click()
        picture, state = bytes(demo.image.value), model_state(demo)
        demo.controls[key].click()
        changed = bytes(demo.image.value) != picture or model_state(demo) != state
        assert changed, f"{key} changed neither the picture nor the model"
        assert_finite(demo, f"{key} pressed")


@pytest.mark.pixels
@pytest.mark.fact
def test_raw_vs_filtered_animation_and_noise():
    demo = make("raw_vs_filtered")
    frame = demo.controls["frame"]
    assert isinstance(demo.controls["play"], widgets.ToggleButton)
    assert frame.max == demo.model.run.t.size - 1
    frame.value = 10
    assert demo.model.frame == 10
    before = bytes(demo.image.value)
    assert demo.step()
    assert demo.model.frame == frame.value == 11
    assert bytes(demo.image.value) != before  # one more ping drawn
    demo.controls["play"].value = True  # no event loop here: Run switches itself off, nothing moves
    assert demo.controls["play"].value is False and demo.model.frame == 11
    frame.value = 10
    assert demo.model.frame == 10
    frame.value = frame.max
    assert demo.model.frame == frame.max
    assert not demo.step()  # the last frame: nothing to advance
    assert demo.model.frame == frame.max
    demo.controls["sensor_noise"].value = demo.controls["sensor_noise"].max
    raw, filt = demo.model.rms_errors()
    assert filt < raw / 2  # the raw trace explodes, the filter holds
    seed = demo.model.seed
    z = demo.model.run.z.copy()
    demo.controls["new_noise"].click()
    assert demo.model.seed == seed + 1
    assert not np.allclose(demo.model.run.z, z)


def test_hallway_predict_update_reset():
    demo = make("hallway")
    m = demo.model
    first = m.belief.copy()
    demo.controls["predict"].click()
    assert m.phase == "predicted"
    assert m.belief.sum() == pytest.approx(1.0)
    assert not np.allclose(m.belief, first)
    kernel = kf.sim.motion_kernel(m.motion_reliability)
    assert m.belief == pytest.approx(kf.bayes_predict(first, kernel, m.boundary))
    demo.controls["update"].click()
    assert m.phase == "updated"
    assert m.belief.sum() == pytest.approx(1.0)
    demo.controls["boundary"].value = "wrap"
    for _ in range(8):
        demo.controls["predict"].click()
        demo.controls["update"].click()
        assert m.belief.sum() == pytest.approx(1.0)
        assert np.isfinite(m.belief).all()
    # Perfect motion on a ring: Predict shifts the belief and the robot exactly one cell right,
    # and Update is Bayes' rule with the likelihood of what the sensor read.
    demo.controls["sensor_reliability"].value = demo.controls["sensor_reliability"].max
    demo.controls["motion_reliability"].value = 1.0
    for _ in range(6):
        prior, cell = m.belief.copy(), m.true_cell
        demo.controls["predict"].click()
        assert m.belief == pytest.approx(np.roll(prior, 1))
        assert m.true_cell == (cell + 1) % prior.size
        prior = m.belief.copy()
        demo.controls["update"].click()
        likelihood = kf.sim.door_likelihood(DOORS, m.saw_door, m.sensor_reliability)
        assert m.likelihood == pytest.approx(likelihood)
        assert m.belief == pytest.approx(prior * likelihood / np.sum(prior * likelihood))
    demo.controls["reset"].click()
    demo.controls["motion_reliability"].value = 0.8
    demo.controls["sensor_reliability"].value = 0.8
    assert m.steps == 0


def test_hallway_reset_restores_first_frame():
    demo = make("hallway")
    first = demo.image.value
    demo.controls["predict"].click()
    demo.controls["update"].click()
    demo.controls["reset"].click()
    assert bytes(demo.image.value) == bytes(first)


@pytest.mark.fact
def test_covariance_tilts_with_rho_and_fractions():
    demo = make("covariance_ellipse")
    ring = demo.renderer.dynamic[1]
    demo.controls["rho"].value = 0.9
    up = ring.get_angle() % 180
    demo.controls["rho"].value = -0.9
    down = ring.get_angle() % 180
    assert 0 < up < 90 < down < 180
    frac = demo.model.fractions()
    assert frac == pytest.approx(kf.mass_inside(np.array([1, 2, 3])), abs=0.04)
    samples = demo.model.samples()
    assert np.corrcoef(samples.T)[0, 1] == pytest.approx(-0.9, abs=0.03)


def test_step_through_reproduces_the_lesson():
    demo = make("step_through")
    for key in ("predict", "update", "predict", "update"):
        demo.controls[key].click()
    rows = demo.model.rows
    assert [round(r[5], 3) for r in rows] == [0.857, 0.741]
    assert [round(r[6], 3) for r in rows] == [3.514, 4.652]
    demo.controls["R"].value = 1.0
    assert demo.model.rows[0][5] > 0.9  # replayed with the new R
    demo.controls["reset"].click()
    assert demo.model.rows == [] and demo.model.phase == "prior"


def test_trust_gauge_and_narrowing():
    demo = make("trust_slider")
    m = demo.model
    bar = demo.renderer.dynamic[-2]
    for vp in (0.01, 1.0, 10.0):
        for vm in (0.01, 1.0, 10.0):
            demo.controls["var_pred"].value = vp
            demo.controls["var_meas"].value = vm
            _mu, var = m.fused()
            assert var < min(m.var_pred, m.var_meas)
            assert bar.get_width() == pytest.approx(m.K)
            assert_finite(demo)
    demo.controls["var_pred"].value = 10.0
    demo.controls["var_meas"].value = 0.01
    assert m.K > 0.99
    assert m.fused()[0] == pytest.approx(m.z, abs=0.01)


def test_run_plays_to_the_end_on_an_event_loop(monkeypatch):
    monkeypatch.setattr(kf.demos._base, "FRAME_INTERVAL", 0.001)
    monkeypatch.setattr(kf.demos._base, "FRAME_GAP", 0.0)
    demo = make("raw_vs_filtered")
    play, frame = demo.controls["play"], demo.controls["frame"]
    frame.value = frame.max - 20
    shown = []
    demo.image.observe(lambda _: shown.append(demo.model.frame), "value")

    async def run_and_wait():
        play.value = True
        assert play.description == "Pause"
        while play.value:
            await asyncio.sleep(0.01)

    asyncio.run(run_and_wait())
    assert demo.model.frame == frame.max and play.description == "Run"
    assert shown == sorted(shown) and shown[-1] == frame.max  # forward only, possibly skipping frames
    asyncio.run(run_and_wait())  # Run at the last frame starts again from the first
    assert shown.count(0) == 1 and demo.model.frame == frame.max


def test_pause_stops_before_the_next_frame(monkeypatch):
    # Frames every 10 ms: a slow render (2x pictures on a busy machine) makes the run skip frames, not reach the end
    monkeypatch.setattr(kf.demos._base, "FRAME_INTERVAL", 0.01)
    demo = make("raw_vs_filtered")
    play, frame = demo.controls["play"], demo.controls["frame"]
    frame.value = 0
    paused_at = []

    def pause(_) -> None:
        if demo.model.frame >= 5 and play.value:
            play.value = False
            paused_at.append(demo.model.frame)

    demo.image.observe(pause, "value")

    async def run_then_wait():
        play.value = True
        await asyncio.sleep(0.3)  # time for many more frames, were it still running

    asyncio.run(run_then_wait())
    assert len(paused_at) == 1 and demo.model.frame == paused_at[0] < frame.max
    assert play.description == "Run"
