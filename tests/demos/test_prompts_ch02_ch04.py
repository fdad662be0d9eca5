"""The "Try this" prompts of chapters 2 and 4, driven as the prose says.

Each test moves the demo's controls the way a prompt tells the student to and
asserts what the prose promises they will see, in the picture where it can
(ellipse patches, curves, the readout) and in the model.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from matplotlib.colors import to_hex
from matplotlib.patches import Ellipse

import kfcourse as kf
from kfcourse.plots import palette

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

# ---------------------------------------------------------------- chapter 2: covariance ellipse


@pytest.fixture
def ellipse_demo():
    return kf.demos.covariance_ellipse(seed=0)


def rings(demo) -> list[Ellipse]:
    """The 1σ, 2σ, 3σ contours, smallest first."""
    found = [p for p in demo.renderer.fig.axes[0].patches if isinstance(p, Ellipse)]
    assert len(found) == 3
    return sorted(found, key=lambda e: e.width)


def shadow(ring: Ellipse) -> tuple[float, float]:
    """How far a drawn ellipse reaches along x and along y from its centre."""
    a, b, t = ring.width / 2, ring.height / 2, math.radians(ring.angle)
    return math.hypot(a * math.cos(t), b * math.sin(t)), math.hypot(a * math.sin(t), b * math.cos(t))


def shadow_box(demo) -> tuple[float, float]:
    """Half-width and half-height of the dashed box drawn around the ellipses."""
    (box,) = [line for line in demo.renderer.fig.axes[0].get_lines() if line.get_linestyle() == "--"]
    assert box.get_visible() and box in demo.renderer.dynamic  # redrawn on every change
    xy = box.get_xydata()
    assert len(xy) == 5 and np.allclose(xy[0], xy[-1])  # a closed rectangle
    assert np.allclose(xy.min(axis=0), -xy.max(axis=0))  # centred on the mean
    return float(xy[:, 0].max()), float(xy[:, 1].max())


def readout(demo) -> str:
    """All text drawn in the demo's figure outside the plot itself."""
    return "\n".join(t.get_text() for ax in demo.renderer.fig.axes[1:] for t in ax.texts)


def inside_table(demo) -> dict[int, tuple[float, float]]:
    """The table's rows: k -> (share of samples inside, theory), in percent."""
    rows = re.findall(r"(\d)σ\s+([\d.]+)%\s+([\d.]+)%", readout(demo))
    assert len(rows) == 3, readout(demo)
    return {int(k): (float(s), float(t)) for k, s, t in rows}


def shown_sigma(demo) -> np.ndarray:
    """The matrix Σ as the readout prints it."""
    numbers = re.findall(r"\[\s*(-?[\d.]+)\s+(-?[\d.]+)\]", readout(demo))
    assert len(numbers) == 2, readout(demo)
    return np.array(numbers, float)


def test_ch02_variance_sliders_stretch_along_x_and_y_and_the_shares_stay(ellipse_demo):
    """Prompt: drag σx² and σy²: the ellipses stretch along x or y, and the shares
    inside do not change at all."""
    demo = ellipse_demo
    table = inside_table(demo)
    for key, axis in (("var_x", 0), ("var_y", 1)):
        for value in (0.5, 4.0):
            demo.controls[key].value = value
            for k, ring in zip((1, 2, 3), rings(demo), strict=True):
                assert shadow(ring)[axis] == pytest.approx(k * math.sqrt(value))
            assert inside_table(demo) == table
    sig = shown_sigma(demo)
    assert sig[0, 0] == pytest.approx(4.0) and sig[1, 1] == pytest.approx(4.0)


def test_ch02_rho_tilts_and_thins_the_ellipse_and_sets_the_off_diagonal(ellipse_demo):
    """Prompt: drag ρ towards +0.9 and then −0.9: the ellipse tilts and thins; the
    off-diagonal entries of Σ change; its shadow stays ±σx along x and ±σy along y, the dashed box."""
    demo = ellipse_demo
    start = rings(demo)[0]
    start_angle, start_minor = start.angle, min(start.width, start.height)
    off = 0.9 * math.sqrt(2.0 * 1.0)  # ρ σx σy with σx² = 2, σy² = 1
    for rho, sign in ((0.9, 1), (-0.9, -1)):
        demo.controls["rho"].value = rho
        ring = rings(demo)[0]
        assert sign * ring.angle > 0  # leans up for ρ > 0, down for ρ < 0
        assert abs(ring.angle) > abs(start_angle)  # tilts further than at ρ = 0.6
        assert min(ring.width, ring.height) < 0.75 * start_minor  # and thins
        for k, each in zip((1, 2, 3), rings(demo), strict=True):
            assert shadow(each) == pytest.approx((k * math.sqrt(2.0), k * 1.0))  # the shadow stays put
        box = shadow_box(demo)
        assert box == pytest.approx((math.sqrt(2.0), 1.0))  # the dashed box is drawn at ±σx, ±σy
        assert shadow(rings(demo)[0]) == pytest.approx(box)  # and the 1σ ellipse reaches exactly to it
        sig = shown_sigma(demo)
        assert sig[0, 1] == pytest.approx(sign * off, abs=0.006)
        assert sig[1, 0] == pytest.approx(sign * off, abs=0.006)


def test_ch02_the_shadow_box_follows_the_variance_sliders(ellipse_demo):
    """The dashed shadow box is ±σx, ±σy for every slider setting, and the 1σ ellipse touches it."""
    demo = ellipse_demo
    for var_x, var_y, rho in ((0.1, 4.0, 0.95), (4.0, 0.1, -0.95), (2.5, 2.5, 0.0), (0.3, 0.7, -0.4)):
        demo.controls["var_x"].value, demo.controls["var_y"].value = var_x, var_y
        demo.controls["rho"].value = rho
        assert shadow_box(demo) == pytest.approx((math.sqrt(var_x), math.sqrt(var_y)))
        assert shadow(rings(demo)[0]) == pytest.approx(shadow_box(demo))


@pytest.mark.parametrize("var_x", [0.1, 4.0])
@pytest.mark.parametrize("var_y", [0.1, 3.1, 4.0])
@pytest.mark.parametrize("rho", [-0.95, 0.0, 0.95])
def test_ch02_every_contour_and_its_label_fit_in_the_view(ellipse_demo, var_x, var_y, rho):
    """No slider position clips a contour or a contour's label: every ring and label, as drawn on
    the picture, lies inside the plot area."""
    demo = ellipse_demo
    demo.controls["var_x"].value, demo.controls["var_y"].value = var_x, var_y
    demo.controls["rho"].value = rho
    fig = demo.renderer.fig
    ax = fig.axes[0]
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    labels = [t for t in ax.texts if t.get_text().endswith("σ")]
    assert len(labels) == 3
    for artist in [*rings(demo), *labels]:
        box = artist.get_window_extent(renderer)
        inside = frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
        assert inside, f"{artist} at {box} is outside the plot {frame}"


def test_ch02_rho_zero_and_equal_variances_draw_circles(ellipse_demo):
    """Prompt: set ρ = 0 and σx² = σy²: a circle."""
    demo = ellipse_demo
    demo.controls["rho"].value = 0.0
    demo.controls["var_y"].value = demo.controls["var_x"].value
    for k, ring in zip((1, 2, 3), rings(demo), strict=True):
        assert ring.width == pytest.approx(ring.height)
        assert ring.width / 2 == pytest.approx(k * math.sqrt(demo.controls["var_x"].value))
    sig = shown_sigma(demo)
    assert sig[0, 1] == 0.0 and sig[0, 0] == sig[1, 1]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_ch02_shares_inside_match_39_86_99_percent(seed):
    """Prose: the table shows the share of dots inside each contour next to the
    theory 1 − e^(−k²/2): about 39 %, 86 %, 99 %, whatever the sliders."""
    demo = kf.demos.covariance_ellipse(seed=seed)
    for rho in (0.6, -0.95, 0.0):
        demo.controls["rho"].value = rho
        table = inside_table(demo)
        points = demo.renderer.fig.axes[0].collections[0].get_offsets()
        Sig = demo.model.Sig
        d2 = np.einsum("ij,jk,ik->i", points, np.linalg.inv(Sig), points)  # the dots actually drawn
        for k, theory in ((1, 39.3), (2, 86.5), (3, 98.9)):
            sampled, shown_theory = table[k]
            assert shown_theory == pytest.approx(theory, abs=0.05)
            assert sampled == pytest.approx(theory, abs=3.0)  # 1000 samples: within about 2 standard errors
            assert sampled == pytest.approx(100 * np.mean(d2 <= k * k), abs=0.051)


# ---------------------------------------------------------------- chapter 4: trust slider


@pytest.fixture
def trust_demo():
    return kf.demos.trust_slider(seed=0)


def curve(demo, colour: str) -> np.ndarray:
    """The (x, density) points of the curve drawn in ``colour``."""
    lines = [line for line in demo.renderer.fig.axes[0].get_lines() if to_hex(line.get_color()) == colour]
    assert len(lines) == 1
    return lines[0].get_xydata()


def peak_x(demo, colour: str) -> float:
    xy = curve(demo, colour)
    return float(xy[np.argmax(xy[:, 1]), 0])


def gauge_K(demo) -> float:
    """K as the gauge under the plot shows it (bar length and label)."""
    ax = demo.renderer.fig.axes[1]
    label = [t.get_text() for t in ax.texts if t.get_text().startswith("K =")]
    assert len(label) == 1
    bars = [p for p in ax.patches if to_hex(p.get_facecolor()) == palette.ESTIMATE]
    assert len(bars) == 1
    assert float(label[0].split("=")[1]) == pytest.approx(bars[0].get_width(), abs=0.0005)
    return bars[0].get_width()


def trust_readout(demo) -> str:
    return "\n".join(t.get_text() for t in demo.renderer.fig.axes[0].texts)


def on_log_grid(control, value: float) -> float:
    """The value a student can reach on a log slider nearest to ``value``."""
    step = control.step
    return control.base ** (round(math.log(value, control.base) / step) * step)


def test_ch04_shrinking_the_measurement_variance_trusts_the_reading(trust_demo):
    """Prompt: shrink the measurement variance towards 0.01: K climbs towards 1 and
    the teal peak slides onto the orange one."""
    demo = trust_demo
    z, mu_pred = demo.controls["z"].value, demo.controls["mu_pred"].value
    demo.controls["var_meas"].value = 0.01
    assert gauge_K(demo) > 0.99
    assert demo.model.fused()[0] == pytest.approx(z, abs=0.01 * abs(z - mu_pred))
    assert peak_x(demo, palette.ESTIMATE) == pytest.approx(peak_x(demo, palette.MEASUREMENT), abs=0.05)


def test_ch04_growing_the_measurement_variance_trusts_the_prediction(trust_demo):
    """Prompt: grow it towards 10: K falls towards 0 and teal sits on purple."""
    demo = trust_demo
    z, mu_pred = demo.controls["z"].value, demo.controls["mu_pred"].value
    demo.controls["var_meas"].value = 10.0
    assert gauge_K(demo) < 0.1
    teal = peak_x(demo, palette.ESTIMATE)
    assert abs(teal - peak_x(demo, palette.PREDICTION)) < 0.1 * abs(z - mu_pred)
    assert abs(teal - mu_pred) < abs(teal - z) / 5


def test_ch04_the_prediction_variance_moves_K_the_other_way(trust_demo):
    """Prompt: do the same with the prediction variance and watch K move the other way."""
    demo = trust_demo
    demo.controls["var_pred"].value = 0.01
    low = gauge_K(demo)
    demo.controls["var_pred"].value = 10.0
    high = gauge_K(demo)
    assert low < 0.05 and high > 0.95
    # along the whole slider: K rises with the prediction variance, falls with the measurement variance
    grid = 10.0 ** np.arange(-2.0, 1.0001, 0.25)
    for key, direction in (("var_pred", 1), ("var_meas", -1)):
        demo.controls["var_pred"].value = demo.controls["var_meas"].value = 1.0
        gains = []
        for value in grid:
            demo.controls[key].value = value
            gains.append(gauge_K(demo))
        assert (direction * np.diff(gains) > 0).all(), gains


@pytest.mark.parametrize(("var_pred", "var_meas"), [(1.0, 10**-0.5), (0.1, 10**0.5), (10**-1.5, 10.0), (3.0, 3.0)])
def test_ch04_the_fused_mean_stays_between_and_nearer_the_sharper_curve(trust_demo, var_pred, var_meas):
    """Prompt: drag the two means apart: the teal mean always stays between them,
    closer to the sharper curve."""
    demo = trust_demo
    demo.controls["var_pred"].value = var_pred
    demo.controls["var_meas"].value = var_meas
    for mu_pred, z in ((-4.0, 4.0), (3.0, -2.5), (-1.0, 0.5)):
        demo.controls["mu_pred"].value = mu_pred
        demo.controls["z"].value = z
        mu_f = demo.model.fused()[0]
        teal = peak_x(demo, palette.ESTIMATE)
        assert teal == pytest.approx(mu_f, abs=0.02)
        assert min(mu_pred, z) < mu_f < max(mu_pred, z)
        to_pred, to_meas = abs(mu_f - mu_pred), abs(mu_f - z)
        if var_pred < var_meas:
            assert to_pred < to_meas
        elif var_meas < var_pred:
            assert to_meas < to_pred
        else:
            assert to_pred == pytest.approx(to_meas)


def test_ch04_teal_is_always_narrower_and_the_readout_says_so(trust_demo):
    """Prompt: whatever you do, the teal curve is always narrower (taller) than both
    inputs; the readout above the plot checks it."""
    demo = trust_demo
    grid = 10.0 ** np.arange(-2.0, 1.0001, 0.75)
    for var_pred in grid:
        for var_meas in grid:
            demo.controls["var_pred"].value = var_pred
            demo.controls["var_meas"].value = var_meas
            mu_f, var_f = demo.model.fused()
            assert var_f < min(var_pred, var_meas)
            teal = curve(demo, palette.ESTIMATE)
            assert teal[:, 1] == pytest.approx(kf.gaussian_pdf(teal[:, 0], mu_f, var_f))  # the picture shows it
            for colour, var in ((palette.PREDICTION, var_pred), (palette.MEASUREMENT, var_meas)):
                if var > 1.05 * var_f:  # taller where the 800-point grid can tell the peaks apart
                    assert teal[:, 1].max() > curve(demo, colour)[:, 1].max()
            text = trust_readout(demo)
            assert "narrower than both" in text
            assert f"{var_f:.3g}" in text


def test_ch04_the_readout_computes_its_verdict(trust_demo, monkeypatch):
    """The readout's "narrower than both" is computed, not printed regardless: fed a
    fused variance that is not narrower, it must not claim it is."""
    demo = trust_demo
    mu_f, _ = demo.model.fused()
    monkeypatch.setattr(demo.model, "fused", lambda: (mu_f, 2.0))  # wider than both 1.0 and 0.316
    demo.refresh()
    text = trust_readout(demo)
    assert "narrower than both" not in text.replace("not narrower than both", "")
    assert "not narrower" in text


def test_ch04_cycle_1_again(trust_demo):
    """Prompt: set the prediction near N(3.0, 0.6) and the measurement near
    N(3.6, 0.1) to see cycle 1 again (K 0.857, mean 3.514, variance 0.086)."""
    demo = trust_demo
    demo.controls["mu_pred"].value = 3.0
    demo.controls["var_pred"].value = on_log_grid(demo.controls["var_pred"], 0.6)
    demo.controls["z"].value = 3.6
    demo.controls["var_meas"].value = on_log_grid(demo.controls["var_meas"], 0.1)
    mu_f, var_f = demo.model.fused()
    assert gauge_K(demo) == pytest.approx(0.857, abs=0.01)
    assert mu_f == pytest.approx(3.514, abs=0.01)
    assert var_f == pytest.approx(0.086, abs=0.002)
    assert peak_x(demo, palette.ESTIMATE) == pytest.approx(3.514, abs=0.02)
    assert "μ = 3.51" in trust_readout(demo)


@pytest.mark.pixels
@pytest.mark.parametrize("var_pred", [0.01, 0.1, 1.0, 10.0])
@pytest.mark.parametrize("var_meas", [0.01, 0.3, 10.0])
def test_ch04_the_density_label_is_never_cut_off(trust_demo, var_pred, var_meas):
    """The layout is found once; whatever the y tick labels become, the "density" label and the
    tick labels stay inside the picture."""
    demo = trust_demo
    demo.controls["var_pred"].value = var_pred
    demo.controls["var_meas"].value = var_meas
    demo.renderer.png()  # drawn in full if the limits moved: the axis label next to the current tick labels
    fig = demo.renderer.fig
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    for text in [ax.yaxis.label, *ax.get_yticklabels()]:
        if text.get_visible() and text.get_text():
            box = text.get_window_extent(renderer)
            assert box.x0 >= 0 and box.x1 <= fig.bbox.x1, f"{text.get_text()!r} at {box}"


def test_ch02_your_turn_the_skeleton_waits_and_the_sandwich_passes():
    path = Path(__file__).resolve().parents[2] / "notebooks" / "02_gaussians.ipynb"
    cells = ["".join(c["source"]) for c in json.loads(path.read_text(encoding="utf-8"))["cells"]]
    assert "kf.check.affine_gaussian(my_affine_gaussian)" in cells
    (source,) = [s for s in cells if s.startswith("def my_affine_gaussian(")]
    space = {"np": np}
    exec(source, space)
    waiting = kf.check.affine_gaussian(space["my_affine_gaussian"])
    assert not waiting.passed and "Not yet" in waiting.message
    exec(source.replace('raise NotImplementedError("your turn")', "return A @ mu + b, A @ Sig @ A.T"), space)
    assert kf.check.affine_gaussian(space["my_affine_gaussian"]).passed
