"""The real-run demo (chapter 12): each setting is the run kf.sim makes with it, made once and kept; moving in
time only redraws; on an event loop a new setting answers at once and its run is drawn when the worker has made
it; the picture shows the ranges of the second shown, and the description the error and the verdict."""

from __future__ import annotations

import asyncio
import sys
from collections import OrderedDict

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.real_run import (
    COLUMN_WIDTH,
    FIRST_FRAME,
    GATE,
    GUESS,
    GUESS_STD,
    IMAGE_WIDTH,
    NOISE,
    TRUST_STEP,
    RealRunModel,
)
from kfcourse.plots.real_run_view import range_arcs
from tests.demos.describing import at_the_ends, move, said

# Only the tests marked `fact` state facts of seeded runs (the PF's): the EKF and the UKF draw nothing.

LOG = kf.data.load_plaza("Plaza2")
real_run_module = sys.modules["kfcourse.demos.real_run"]  # the module: kf.demos.real_run is the demo function


def make(seed=0):
    return kf.demos.real_run(seed=seed)


def engine(**settings):
    """The run kf.sim.range_localize makes over Plaza2 with the demo's tuning and ``settings``."""
    return kf.sim.range_localize(LOG, **{**NOISE, **settings})


def nothing_kept(monkeypatch) -> None:
    """No run kept from an earlier test: every setting is new."""
    monkeypatch.setattr(real_run_module, "_KEPT", OrderedDict())


def counting(monkeypatch) -> list:
    """Every run the models make from now on, by its settings, none kept from before."""
    nothing_kept(monkeypatch)
    made = []
    real = RealRunModel._make

    def make_and_count(self, key, base=None):
        made.append(key)
        return real(self, key, base)

    monkeypatch.setattr(RealRunModel, "_make", make_and_count)
    return made


def test_first_frame_is_the_data_sheet_ekf_a_minute_in():
    demo = make()
    m = demo.model
    assert m.frame == FIRST_FRAME == demo.controls["frame"].value == 60
    assert demo.controls["frame"].max == int(LOG.t_truth[-1]) == 409
    assert demo.controls["frame"].description == demo.description.names["frame"] == "t (s)"  # a frame a second
    assert (m.filter, m.scale, m.gate, m.known_start, m.smoothed) == ("EKF", False, False, True, False)
    np.testing.assert_array_equal(m.run.mu, engine().mu)
    assert m.smooth is None
    assert LOG.t_truth[m.row] <= 60 < LOG.t_truth[m.row + 1]


@pytest.mark.parametrize(
    ("key", "value", "settings"),
    [
        (
            "trust_motion",
            10.0,
            {"speed_std": NOISE["speed_std"] * np.sqrt(10), "turn_std": NOISE["turn_std"] * np.sqrt(10)},
        ),
        ("trust_sensor", 0.1, {"range_std": NOISE["range_std"] * np.sqrt(0.1)}),
        ("scale", True, {"scale": "online"}),
        ("gate", True, {"gate": GATE}),
        ("start", "unknown", {"start": GUESS, "start_std": GUESS_STD}),
        ("filter", "EKF + scale and gate", {"scale": "online", "gate": GATE}),
        ("filter", "UKF", {"filter": "ukf"}),
    ],
)
def test_each_control_is_the_run_kf_sim_makes_with_it(key, value, settings):
    demo = make()
    picture = bytes(demo.image.value)
    demo.controls[key].value = value
    run = demo.model.run
    expected = engine(**settings)
    np.testing.assert_allclose(run.mu, expected.mu, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(run.used, expected.used)
    assert bytes(demo.image.value) != picture
    assert demo.model.frame == FIRST_FRAME  # the second shown stays


@pytest.mark.fact
def test_the_pf_is_kf_sim_range_particles_and_says_the_smoother_is_the_ekfs():
    demo = make(seed=2)
    demo.controls["filter"].value = "PF"
    demo.controls["start"].value = "unknown"
    expected = kf.sim.range_particles(LOG, n_particles=1000, seed=2, start=None)
    np.testing.assert_array_equal(demo.model.run.mu, expected.mu)
    demo.controls["smoothed"].value = True
    assert demo.model.smooth is None and "the EKF's (RTS)" in demo.description.text
    demo.controls["scale"].value = demo.controls["gate"].value = True  # nothing for the PF
    np.testing.assert_array_equal(demo.model.run.mu, expected.mu)


def test_the_sliders_report_where_they_are_let_go_in_steps_that_come_back():
    demo = make()
    for key in ("trust_motion", "trust_sensor"):
        assert demo.controls[key].continuous_update is False, key  # a run per dragged pixel would queue up
        assert demo.controls[key].step == TRUST_STEP
    assert demo.controls["frame"].continuous_update is True  # moving in time only redraws: follows the drag


def test_moving_in_time_never_reruns_and_a_setting_seen_is_kept(monkeypatch):
    made = counting(monkeypatch)
    demo = make()
    first = demo.model.run
    for k in (0, 100, 409, 60):
        demo.controls["frame"].value = k
    assert len(made) == 1
    demo.controls["trust_sensor"].value = 10.0
    demo.controls["trust_sensor"].value = 1.0  # back: the run kept, not made again
    assert len(made) == 2 and demo.model.run is first


def test_smoothed_is_the_rts_smoother_over_the_run_shown():
    demo = make()
    demo.controls["gate"].value = demo.controls["scale"].value = True
    demo.controls["smoothed"].value = True
    np.testing.assert_allclose(demo.model.smooth.mu, kf.sim.smoothed(demo.model.run).mu, rtol=0, atol=1e-12)
    view_smooth = demo.renderer.dynamic[0]
    assert view_smooth.get_visible() and len(view_smooth.get_xdata()) == LOG.t_truth.size
    assert "; smoothed, " in demo.description.text


def test_the_arcs_are_the_ranges_of_the_second_shown():
    demo = make()
    demo.controls["filter"].value = "EKF + scale and gate"
    m = demo.model
    for k in (1, 60, 200, 409):
        demo.controls["frame"].value = k
        beacons, ranges, used = m.arrivals()
        i = np.flatnonzero((LOG.t_range > k - 1) & (LOG.t_range <= k))
        np.testing.assert_array_equal(ranges, LOG.range[i])
        np.testing.assert_array_equal(used, m.run.used[i])  # the run's ranges are the log's, in order
        used_arcs, refused_arcs = demo.renderer.dynamic[1:3]
        assert len(used_arcs.get_segments()) == used.sum() and len(refused_arcs.get_segments()) == (~used).sum()
    arcs = range_arcs(beacons, ranges, LOG.truth[m.row])
    np.testing.assert_allclose(
        np.hypot(*(arcs - beacons[:, None, :]).transpose(2, 0, 1)), ranges[:, None] + 0 * arcs[..., 0]
    )


def test_some_second_shows_a_range_refused_by_the_gate():
    demo = make()
    demo.controls["filter"].value = "EKF + scale and gate"
    assert demo.model.run.used.all()  # tuned per metre, Plaza2 has no range 3σ off
    demo.controls["trust_sensor"].value = 0.01  # a filter sure of its ranges to 7 cm refuses some
    refused = np.flatnonzero(~demo.model.run.used)
    assert refused.size
    demo.controls["frame"].value = int(np.ceil(LOG.t_range[refused[0]]))
    assert "refused by the gate" in demo.description.text


def test_the_description_says_the_error_and_the_verdict():
    demo = make()
    m = demo.model
    text = demo.description.text
    assert text.startswith("At t = 60 s: ")
    assert f"{m.run.error[m.row]:.2f} m off" in text and "over-confident" in text
    demo.controls["filter"].value = "EKF + scale and gate"
    assert "honest" in demo.description.text and "over-confident" not in demo.description.text
    demo.controls["trust_sensor"].value = 100.0
    assert "(Q ×1.0e+2)" in demo.description.text


def test_on_an_event_loop_a_new_setting_answers_at_once_and_is_drawn_when_made(monkeypatch):
    nothing_kept(monkeypatch)
    seen = {}

    async def scenario():
        demo = make()  # the first run is made at once, even on a loop
        assert demo.model.run is not None
        drawn = []
        demo.image.observe(lambda _: drawn.append((demo.image.format, demo.model.run is not None)), "value")
        demo.controls["filter"].value = "UKF"
        seen["at once"] = (demo.model.run, demo.model.busy(), list(drawn))
        seen["waiting"] = demo.description.text
        while demo.model.run is None:
            await asyncio.sleep(0.05)
        await asyncio.sleep(0.05)
        seen["drawn"] = list(drawn)
        seen["said"] = demo.description.text
        return demo

    demo = asyncio.run(scenario())
    run, busy, drawn = seen["at once"]
    assert run is None and busy == "running the UKF over the log…" and drawn == [("webp", False)]
    assert seen["drawn"][-1] == ("jpeg", True)  # the run drawn crisp once made
    assert "UKF" in seen["said"] and "m off" in seen["said"]
    np.testing.assert_allclose(demo.model.run.mu, engine(filter="ukf").mu, rtol=0, atol=1e-9)


def test_a_run_that_fails_in_the_worker_is_said_and_not_tried_again(monkeypatch):
    nothing_kept(monkeypatch)

    async def scenario():
        demo = make()
        tries = []

        def broken(self, key, base=None):
            tries.append(key)
            raise FloatingPointError("boom")

        monkeypatch.setattr(RealRunModel, "_make", broken)
        demo.controls["gate"].value = True
        for _ in range(40):
            await asyncio.sleep(0.02)
        return demo, tries

    demo, tries = asyncio.run(scenario())
    assert len(tries) == 1 and demo.model.busy() == "the EKF failed on this setting"


def test_the_picture_and_its_column_fit_a_laptop():
    demo = make()
    fig = demo.renderer.fig
    height = IMAGE_WIDTH * fig.get_figheight() / fig.get_figwidth()
    assert height <= 580  # with the caption's line and the description, within 680 px
    assert IMAGE_WIDTH + COLUMN_WIDTH <= 848  # JupyterLab's output on a 1280 px laptop


def test_a_bad_seed_is_refused_by_name():
    with pytest.raises(ValueError, match=r"^seed must be a whole number >= 0"):
        kf.demos.real_run(seed=-1)


def test_the_runs_kept_are_bounded_and_shared_by_every_demo(monkeypatch):
    made = counting(monkeypatch)
    monkeypatch.setattr(real_run_module, "KEEP_RUNS", 2)
    demo = make()
    demo.controls["trust_motion"].value = 10.0
    assert len(made) == 2 and len(real_run_module._KEPT) == 2
    make()  # the first setting is kept: a second demo makes nothing
    assert len(made) == 2
    demo.controls["trust_sensor"].value = 10.0  # a third run: the least recently used one goes
    assert len(made) == 3 and len(real_run_module._KEPT) == 2


def test_the_description_is_two_sentences_and_names_each_slider_as_it_shows():
    demo = make()
    move(demo, "frame", 200)
    for key in ("trust_motion", "trust_sensor"):
        texts = at_the_ends(demo, [key])
        assert all("m off" in text for text in texts)
        demo.controls[key].value = 1.0
    move(demo, "start", "unknown")
    move(demo, "smoothed", True)
    assert "; smoothed, " in said(demo)
    move(demo, "filter", "UKF")
    assert "the EKF's (RTS)" in said(demo)
