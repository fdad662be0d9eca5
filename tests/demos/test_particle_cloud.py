"""The particle-cloud demo (chapter 11): every control reruns the lap with its setting, moving in time
only redraws, the readout tells the step, the corners of the controls stay finite, and the picture with
its column fits a laptop."""

from __future__ import annotations

import itertools

import ipywidgets as widgets
import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.particle_cloud import (
    COLUMN_WIDTH,
    FIRST_FRAME,
    IMAGE_WIDTH,
    INJECTION,
    PARTICLES,
    SCHEME_BUTTON,
)
from tests.demos.layout import readout
from tests.demos.particle_drive import model_with

# Only the tests marked `fact` state facts of seeded runs: they are repeated under other rounding; the others
# are listed in tests/facts.py UNMARKED with the reason they need no repeat.

LAPTOP_PX = 680  # a 1280x800 laptop: the whole demo within 680 px
CAPTION_PX, DESCRIPTION_PX = 19, 25  # the caption folded under its title, the description: one line each


def make(seed=0):
    return kf.demos.particle_cloud(seed=seed)


def expected_run(model):
    return kf.sim.particle_loop(
        model.seed,
        n_particles=model.n_particles,
        resample=model.resample,
        global_start=model.global_start,
        kidnap=model.kidnap,
        injection=INJECTION if model.injection else 0.0,
    )


def assert_run_matches(model):
    expected = expected_run(model)
    np.testing.assert_array_equal(model.run.mu, expected.mu)
    np.testing.assert_array_equal(model.run.particles[model.frame], expected.particles[model.frame])


# --------------------------------------------------------------------------- controls
def test_first_frame():
    demo = make()
    m = demo.model
    assert m.frame == FIRST_FRAME == demo.controls["frame"].value
    assert demo.controls["frame"].max == m.run.t.size - 1
    assert (m.n_particles, m.resample, m.global_start, m.injection, m.kidnap) == (PARTICLES, "systematic", 0, 0, None)
    assert m.run.n_particles == 2000 and m.run.injection == 0.0
    assert_run_matches(m)
    text = readout(demo)
    assert f"step {FIRST_FRAME}" in text and "run 0" in text and "2000 particles" in text
    assert f"{m.run.ess[FIRST_FRAME]:.0f}" in text


@pytest.mark.pixels
@pytest.mark.fact
def test_every_setting_reruns_the_lap_with_it():
    demo = make()
    m, c = demo.model, demo.controls
    picture = bytes(demo.image.value)
    c["particles"].value = 10.0 ** c["particles"].min
    assert m.n_particles == 100 == m.run.n_particles and "100 particles" in readout(demo)
    assert bytes(demo.image.value) != picture
    c["particles"].value = 10.0 ** c["particles"].max
    assert m.n_particles == 10_000 == m.run.particles.shape[1]
    c["particles"].value = 500
    for scheme in ("multinomial", "stratified", "systematic"):
        c["resample"].value = scheme
        assert m.resample == m.run.resample == scheme
        assert_run_matches(m)
    c["global_start"].value = True
    assert m.run.global_start
    assert_run_matches(m)
    c["injection"].value = True
    assert m.run.injection == INJECTION == 0.05
    assert_run_matches(m)
    c["kidnap"].click()
    assert m.kidnap == m.run.kidnap == FIRST_FRAME and c["kidnap"].description == "Undo kidnap"
    assert "kidnapped" in readout(demo)
    assert_run_matches(m)
    c["new"].click()
    assert m.seed == 1 and "run 1" in readout(demo)
    assert_run_matches(m)
    c["kidnap"].click()
    assert m.kidnap is None and m.run.kidnap is None and c["kidnap"].description == "Kidnap"


def test_kidnap_acts_at_the_step_shown():
    demo = make()
    demo.controls["frame"].value = 90
    demo.controls["kidnap"].click()
    assert demo.model.kidnap == demo.model.run.kidnap == 90


def test_moving_in_time_only_redraws():
    demo = make()
    run = demo.model.run
    for k in (0, 30, demo.controls["frame"].max):
        picture = bytes(demo.image.value)
        demo.controls["frame"].value = k
        assert demo.model.run is run and demo.model.frame == k
        assert bytes(demo.image.value) != picture
        assert f"step {k}," in readout(demo)


def test_readout_says_what_happened_after_the_weights():
    demo = make()
    demo.controls["injection"].value = True
    run = demo.model.run
    kept = int(np.flatnonzero(~run.resampled)[0])
    resampled = int(np.flatnonzero(run.resampled)[0])
    demo.controls["frame"].value = kept
    assert "weights kept" in readout(demo) and "injected" not in readout(demo)
    demo.controls["frame"].value = resampled
    text = readout(demo)
    assert "<b>resampled</b> (systematic)" in text
    assert f"{run.injected[resampled]} particles injected" in text and run.injected[resampled] == 100


@pytest.mark.fact
@pytest.mark.parametrize(
    ("n", "global_start", "injection"), list(itertools.product([100, 10_000], [False, True], [False, True]))
)
def test_corners_stay_finite(n, global_start, injection):
    model = model_with(3, n_particles=n, global_start=global_start, injection=injection, kidnap=100)
    run = model.run
    for field in (run.mu, run.Sig, run.error, run.ess, run.particles):
        assert np.isfinite(field).all()
    assert (run.ess >= 1 - 1e-9).all() and (run.ess <= n + 1e-6).all()


def test_the_column_fits_a_laptop():
    """Picture and column side by side in 848 px; each row of the column within its 340 px; within 680 px tall."""
    demo = make()
    assert IMAGE_WIDTH + COLUMN_WIDTH <= 848
    picture, column = demo.children[1].children
    assert picture is demo.image and demo.display_width == IMAGE_WIDTH
    for row in column.children:
        parts = row.children if isinstance(row, widgets.HBox) else [row]
        widths = [int(str(w.layout.width).removesuffix("px")) for w in parts if w.layout.width]
        assert sum(widths) <= COLUMN_WIDTH
    scheme = demo.controls["resample"]
    assert 3 * SCHEME_BUTTON + 3 * 4 <= COLUMN_WIDTH and SCHEME_BUTTON >= 100  # three whole names and their gaps
    assert len(scheme.options) == 3
    width, height = demo.renderer.fig.canvas.get_width_height()
    assert CAPTION_PX + IMAGE_WIDTH * height / width + DESCRIPTION_PX <= LAPTOP_PX  # the picture IMAGE_WIDTH wide
    text = readout(demo).replace("<br>", "\n")
    lines = sum(1 + len(line) // 60 for line in text.split("\n"))  # HTML included: more than it shows
    assert CAPTION_PX + 5 * 34 + lines * 20 <= LAPTOP_PX  # five rows of controls, the readout's lines at 13 px x 1.5
