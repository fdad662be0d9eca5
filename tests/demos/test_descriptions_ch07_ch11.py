"""Chapters 7 to 11: every demo says in words what its picture shows.

For each demo: moving a control changes the description, and the description names the new
value as the student sees it (a slider's readout text, a choice's word, a button's effect);
at every slider's ends the description is one or two sentences with no "nan" or "inf" in it.
The readouts beside the pictures write coloured text in the palette's text shades, and a
group of choice buttons without a label has a tooltip to name it.
"""

from __future__ import annotations

import re

import ipywidgets as widgets
import numpy as np
import pytest

import kfcourse as kf
from kfcourse.plots import palette
from kfcourse.plots.style import FigureRenderer
from tests.demos.layout import readout, widgets_in
from tests.demos.test_landmark_loop import reference_step

SENTENCE_END = re.compile(r"[.!?](?=\s|$)")
NOT_A_NUMBER = re.compile(r"\b(nan|inf|infinity)\b", re.IGNORECASE)
SEEDS = (0, 1, 2)
TEXT_SHADES = {palette.PREDICTION_TEXT, palette.MEASUREMENT_TEXT, palette.ESTIMATE_TEXT, palette.TRUTH_TEXT}


@pytest.fixture(autouse=True)
def words_not_pictures(monkeypatch):
    """These tests read the words; each demo's own tests check its pictures.  The artists are still
    updated at every change (the readouts with them), but the crisp picture is not encoded."""
    monkeypatch.setattr(FigureRenderer, "jpeg", lambda self: b"\xff\xd8\xff")


def said(demo) -> str:
    """The demo's description, checked: one or two sentences, every number finite."""
    text = demo.description.text
    assert text and not NOT_A_NUMBER.search(text), text
    assert 1 <= len(SENTENCE_END.findall(text)) <= 2, text
    return text


def move(demo, name: str, value) -> str:
    """Set a control, and return the new description, which must differ from the one before."""
    before = said(demo)
    demo.controls[name].value = value
    after = said(demo)
    assert after != before, (name, value, after)
    return after


def press(demo, name: str) -> str:
    """Click a button, and return the new description, which must differ from the one before."""
    before = said(demo)
    demo.controls[name].click()
    after = said(demo)
    assert after != before, (name, after)
    return after


def at_the_ends(demo, names) -> None:
    """Each slider of ``names`` at its minimum and its maximum (a log slider: 10 to the power of its ends)."""
    for name in names:
        control = demo.controls[name]
        ends = (control.min, control.max)
        if isinstance(control, widgets.FloatLogSlider):
            ends = tuple(control.base**end for end in ends)
        for end in ends:
            control.value = end
            said(demo)


# --------------------------------------------------------------------------- chapter 7: linearization
@pytest.mark.parametrize("seed", SEEDS)
def test_linearization_names_f_m_and_s_and_says_how_the_tangent_did(seed):
    demo = kf.demos.linearization(seed=seed)
    assert "m = 1.00 and s = 0.50" in said(demo)
    assert "m = −1.25" in move(demo, "m", -1.25)  # the readout's minus sign
    assert "s = 0.05" in move(demo, "s", 0.05)
    assert "nearly straight" in said(demo)  # a narrow input: the tangent is good
    assert "f = sin x" in move(demo, "function", "sin x")
    demo.controls["function"].value, demo.controls["m"].value = "x²", 0.0
    assert "m = 0.00" in said(demo) and "flat" in said(demo)  # the tangent of x² at 0: no spread at all
    assert "s = 1.50" in move(demo, "s", 1.5)


@pytest.mark.parametrize("function", ["x²", "sin x", "range √(x² + 1)"])
def test_linearization_at_the_ends_of_its_sliders(function):
    demo = kf.demos.linearization(seed=0)
    demo.controls["function"].value = function
    for s in (demo.controls["s"].min, demo.controls["s"].max):
        demo.controls["s"].value = s
        at_the_ends(demo, ["m"])


# --------------------------------------------------------------------------- chapter 9: sigma points
@pytest.mark.parametrize("seed", SEEDS)
def test_sigma_points_name_lambda_and_the_nearer_answer(seed):
    demo = kf.demos.sigma_points(seed=seed)
    assert "λ = 0.0" in said(demo) and "sit at 1.00, 2.00 and 3.00" in said(demo)
    text = move(demo, "lam", 2.0)
    assert "λ = 2.0" in text and "UKF is closer in both" in text  # λ = 2: the UKF's x² moments are exact
    assert "m = −1.50" in move(demo, "m", -1.5)
    assert "s = 0.70" in move(demo, "s", 0.7)
    assert "f = sin x" in move(demo, "function", "sin x") and "sampled output" in said(demo)


@pytest.mark.parametrize("function", ["x²", "sin x", "range √(x² + 1)"])
def test_sigma_points_at_the_ends_of_their_sliders(function):
    demo = kf.demos.sigma_points(seed=0)
    demo.controls["function"].value = function
    for s in (demo.controls["s"].min, demo.controls["s"].max):
        demo.controls["s"].value = s
        for lam in (demo.controls["lam"].min, demo.controls["lam"].max):
            demo.controls["lam"].value = lam
            at_the_ends(demo, ["m"])


# --------------------------------------------------------------------------- chapter 8: data association
@pytest.mark.parametrize("seed", SEEDS)
def test_association_names_the_gate_the_leg_and_the_scan(seed):
    demo = kf.demos.data_association(seed=seed)
    assert said(demo).startswith(f"Scan {seed}, gate γ = 3.0σ")
    assert "γ = 4.5σ" in move(demo, "gate", 4.5)
    text = move(demo, "leg", "a pedestrian's leg")
    leg_match = demo.model.result.match[-1]  # the leg's reading comes last
    assert ("leg rejected" in text) == (leg_match < 0) and ("leg taken for landmark" in text) == (leg_match >= 0)
    assert f"Scan {seed + 1}," in press(demo, "new_scan")
    at_the_ends(demo, ["gate"])


def test_association_counts_the_readings_that_pass():
    demo = kf.demos.data_association(seed=0)
    for gate in (1.0, 3.0, 6.0):
        demo.controls["gate"].value = gate
        result = demo.model.result
        assert f"{int(result.accepted.sum())} of {result.match.size} readings pass" in said(demo)


# --------------------------------------------------------------------------- chapter 10: landmark loop
@pytest.mark.parametrize("seed", (0, 1))
def test_landmark_loop_names_each_setting_as_its_slider_shows_it(seed):
    demo = kf.demos.landmark_loop(seed=seed)
    assert said(demo).startswith("Step 60:") and "×" not in said(demo)  # honest settings: nothing to name
    assert "the filter's R ×1.0e+2" in move(demo, "trust_motion", 100.0)  # the readout of ".2g" at 100
    assert "the filter's Q ×0.010" in move(demo, "trust_sensor", 0.01)
    assert "process noise ×3.2" in move(demo, "motion", 10**0.5)
    assert "measurement noise ×0.10" in move(demo, "sensor", 0.1)
    assert "Step 30" in move(demo, "frame", 30)
    assert "UKF" in move(demo, "filter", "UKF")


def test_landmark_loop_says_blind_kidnapped_and_honest():
    demo = kf.demos.landmark_loop(seed=0)
    verdict = demo.model.run.honesty()[1]
    assert f"the filter is {verdict}" in said(demo)
    assert "blind" in move(demo, "dropout", True)
    assert "kidnapped at step 60" in press(demo, "kidnap")
    assert "a kidnap comes at step 60" in move(demo, "frame", 10)


def test_landmark_loop_names_your_filter_and_says_when_it_failed():
    def certain(mu, Sig, u, z, landmarks, dt, M, Q, gate):  # a flat ellipse: the NEES has no bound
        mu, _, used = reference_step(mu, Sig, u, z, landmarks, dt, M, Q, gate)
        return mu, np.zeros((3, 3)), used

    def not_written(mu, Sig, u, z, landmarks, dt, M, Q, gate):
        raise NotImplementedError("write my_step")

    text = said(kf.demos.landmark_loop(seed=0, filter=certain))
    assert "the your filter" not in text and "your filter uses" in text and "mean NEES unbounded" in text
    demo = kf.demos.landmark_loop(seed=0, filter=not_written)
    assert "your filter failed: the course's EKF is shown" in said(demo) and "the EKF uses" in said(demo)
    assert "process noise ×2.0" in move(demo, "motion", 2.0)  # still alive: every control works


@pytest.mark.parametrize("seed", (0, 1))
def test_landmark_loop_at_the_ends_of_its_sliders(seed):
    demo = kf.demos.landmark_loop(seed=seed)
    at_the_ends(demo, ["motion", "sensor", "trust_motion", "trust_sensor", "frame"])


# --------------------------------------------------------------------------- chapter 11: particle hallway
@pytest.mark.parametrize("seed", SEEDS)
def test_particle_hallway_names_the_press_and_the_particle_count(seed):
    demo = kf.demos.particle_hallway(seed=seed)
    assert said(demo).startswith("After an Update") and "200 particles" in said(demo)
    assert press(demo, "predict").startswith("After Predict (1 move so far)")
    assert press(demo, "update").startswith("After an Update")
    assert "the 10 particles'" in move(demo, "n_particles", 10.0)  # the readout ".0f" of 10
    assert "the 5000 particles'" in move(demo, "n_particles", 5000.0)
    assert f"TV = {demo.model.tv:.2f}" in said(demo) and f"the robot is in cell {demo.model.true_cell}." in said(demo)
    assert "(0 moves so far)" in press(demo, "reset")


@pytest.mark.parametrize("seed", SEEDS)
def test_particle_hallway_at_the_ends_of_its_slider(seed):
    demo = kf.demos.particle_hallway(seed=seed)
    for _ in range(3):
        demo.controls["predict"].click()
        demo.controls["update"].click()
    at_the_ends(demo, ["n_particles"])


def test_particle_hallway_new_run_changes_the_description():
    demo = kf.demos.particle_hallway(seed=0)
    for _ in range(4):  # the first looks of two seeds may agree: after a few presses they differ
        demo.controls["predict"].click()
    press(demo, "new_run")


# --------------------------------------------------------------------------- chapter 11: particle cloud
@pytest.mark.parametrize("seed", (0, 1))
def test_particle_cloud_names_the_count_the_scheme_and_the_settings(seed):
    demo = kf.demos.particle_cloud(seed=seed)
    assert said(demo).startswith("Step 60: the 2000 particles'") and "systematic resampling" in said(demo)
    assert "the 100 particles'" in move(demo, "particles", 100.0)
    assert "multinomial resampling" in move(demo, "resample", "multinomial")
    assert "a global start" in move(demo, "global_start", True)
    assert "5% injected" in move(demo, "injection", True)
    assert "a kidnap at step 60" in press(demo, "kidnap")
    assert "Step 30:" in move(demo, "frame", 30) and "a kidnap to come at step 60" in said(demo)
    assert f"Run {seed + 1}," in press(demo, "new")


def test_particle_cloud_says_whether_it_resampled():
    demo = kf.demos.particle_cloud(seed=0)
    for k in (0, 60, 100):
        demo.controls["frame"].value = k
        resampled = bool(demo.model.run.resampled[k])
        assert ("the cloud is resampled" in said(demo)) == resampled
        assert ("the weights are kept" in said(demo)) == (not resampled)


def test_particle_cloud_at_the_ends_of_its_sliders():
    demo = kf.demos.particle_cloud(seed=0)  # the other seeds' words: in the test above
    at_the_ends(demo, ["frame", "particles"])


# --------------------------------------------------------------------------- text colours and group names
MAKERS = {
    "linearization": kf.demos.linearization,
    "data_association": kf.demos.data_association,
    "sigma_points": kf.demos.sigma_points,
    "landmark_loop": kf.demos.landmark_loop,
    "particle_hallway": kf.demos.particle_hallway,
    "particle_cloud": kf.demos.particle_cloud,
}


@pytest.mark.parametrize("name", ["data_association", "landmark_loop", "particle_cloud"])
def test_readouts_write_colours_in_the_text_shades(name):
    demo = MAKERS[name](seed=0)
    if name == "landmark_loop":
        demo.controls["trust_sensor"].value = 0.01  # readings rejected: the orange words show
    colours = set(re.findall(r"color:\s*(#[0-9a-fA-F]{6})", readout(demo)))
    assert colours and colours <= TEXT_SHADES, colours


@pytest.mark.parametrize("name", list(MAKERS))
def test_every_group_of_choice_buttons_has_a_name(name):
    demo = MAKERS[name](seed=0)
    groups = [w for w in widgets_in(demo) if isinstance(w, widgets.ToggleButtons)]
    for group in groups:
        assert group.description or group.tooltip, group.options
