"""Chapter 5's chart: the prediction and posterior ellipses are the filter's own
matrices, in the course colours, with the position-only reading as a band."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.patches import Ellipse

import kfcourse as kf
from kfcourse.plots import FigureRenderer, palette, predict_update_chart

# The chapter's worked example: constant velocity, position sensor.
F = np.array([[1.0, 1.0], [0.0, 1.0]])
H = np.array([[1.0, 0.0]])
R = 0.01 * np.eye(2)
Q = np.array([[0.5]])


def worked_example():
    mu_bar, Sig_bar = kf.kf_predict(np.array([0.0, 1.0]), np.eye(2), None, F, None, R)
    mu, Sig = kf.kf_update(mu_bar, Sig_bar, np.array([1.2]), H, Q)
    return mu_bar, Sig_bar, mu, Sig


def ellipses(fig):
    """The chart's ellipses by legend label: {'prediction': patch, 'posterior': patch}."""
    (ax,) = fig.axes
    found = {p.get_label().split()[0]: p for p in ax.patches if isinstance(p, Ellipse)}
    assert set(found) == {"prediction", "posterior"}
    return found


def assert_geometry(patch, mu, Sig, nsig):
    width, height, angle = kf.ellipse_axes(Sig, nsig)
    assert np.allclose(patch.get_center(), mu)
    assert math.isclose(patch.get_width(), width, rel_tol=1e-12)
    assert math.isclose(patch.get_height(), height, rel_tol=1e-12)
    assert math.isclose(patch.get_angle(), angle, abs_tol=1e-9)


def assert_no_nan(fig):
    (ax,) = fig.axes
    assert np.isfinite(ax.get_xlim()).all() and np.isfinite(ax.get_ylim()).all()
    for patch in ax.patches:
        assert np.isfinite(patch.get_path().vertices).all()
        assert np.isfinite(patch.get_patch_transform().get_matrix()).all()
    for line in ax.lines:
        assert np.isfinite(np.asarray(line.get_xydata(), float)).all()


@pytest.mark.parametrize("nsig", [1.0, 2.0])
def test_ellipses_are_the_prediction_and_the_posterior(nsig):
    mu_bar, Sig_bar, mu, Sig = worked_example()
    fig = predict_update_chart(mu_bar, Sig_bar, mu, Sig, z=1.2, Q=0.5, nsig=nsig)
    found = ellipses(fig)
    assert_geometry(found["prediction"], mu_bar, Sig_bar, nsig)
    assert_geometry(found["posterior"], mu, Sig, nsig)
    # the update shrinks the belief: the posterior ellipse has less area
    area = {name: p.get_width() * p.get_height() for name, p in found.items()}
    assert area["posterior"] < area["prediction"]
    assert_no_nan(fig)


def test_correlation_tilts_the_prediction_and_its_absence_does_not():
    mu_bar, Sig_bar, mu, Sig = worked_example()
    tilted = ellipses(predict_update_chart(mu_bar, Sig_bar, mu, Sig, z=1.2, Q=0.5))
    assert 10.0 < tilted["prediction"].get_angle() < 80.0  # positive correlation: rising to the right
    flat_bar = np.diag(np.diag(Sig_bar))
    mu_f, Sig_f = kf.kf_update(mu_bar, flat_bar, np.array([1.2]), H, Q)
    flat = ellipses(predict_update_chart(mu_bar, flat_bar, mu_f, Sig_f, z=1.2, Q=0.5))
    for patch in flat.values():
        assert patch.get_angle() % 90.0 == pytest.approx(0.0, abs=1e-9)  # axis-aligned


def test_course_colours_and_the_measurement_band():
    mu_bar, Sig_bar, mu, Sig = worked_example()
    fig = predict_update_chart(mu_bar, Sig_bar, mu, Sig, z=1.2, Q=0.5, nsig=2.0)
    found = ellipses(fig)
    assert found["prediction"].get_edgecolor()[:3] == to_rgba(palette.PREDICTION)[:3]
    assert found["posterior"].get_edgecolor()[:3] == to_rgba(palette.ESTIMATE)[:3]
    (ax,) = fig.axes
    bands = [p for p in ax.patches if not isinstance(p, Ellipse)]
    assert len(bands) == 1
    band = bands[0]
    assert band.get_facecolor()[:3] == to_rgba(palette.MEASUREMENT)[:3]
    xs = band.get_path().transformed(band.get_patch_transform()).vertices[:, 0]  # axvspan: data x, axes y
    assert xs.min() == pytest.approx(1.2 - 2.0 * math.sqrt(0.5))
    assert xs.max() == pytest.approx(1.2 + 2.0 * math.sqrt(0.5))
    reading = [line for line in ax.lines if line.get_color() == palette.MEASUREMENT]
    assert len(reading) == 1 and np.allclose(reading[0].get_xdata(), 1.2)
    # everything drawn is inside the axes
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    for patch in found.values():
        box = patch.get_path().transformed(patch.get_patch_transform()).vertices
        assert x0 < box[:, 0].min() and box[:, 0].max() < x1
        assert y0 < box[:, 1].min() and box[:, 1].max() < y1
    assert x0 < xs.min() and xs.max() < x1


def test_draws_to_a_png():
    fig = predict_update_chart(*worked_example(), z=1.2, Q=0.5)
    png = FigureRenderer(fig).png()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 1000


def test_without_a_reading_there_is_no_band():
    mu_bar, Sig_bar, mu, Sig = worked_example()
    fig = predict_update_chart(mu_bar, Sig_bar, mu, Sig)
    (ax,) = fig.axes
    assert [p for p in ax.patches if not isinstance(p, Ellipse)] == []
    assert len(ellipses(fig)) == 2


@pytest.mark.parametrize(
    "Sig_bar, Sig, Q",
    [
        (np.zeros((2, 2)), np.zeros((2, 2)), 0.5),  # a collapsed belief
        (np.array([[1.0, 1.0], [1.0, 1.0]]), np.zeros((2, 2)), 0.0),  # singular, perfect sensor
        (np.diag([1e8, 1e-8]), np.diag([1e-8, 1e8]), 1e8),  # extreme scales
    ],
)
def test_degenerate_beliefs_draw_no_nan(Sig_bar, Sig, Q):
    fig = predict_update_chart([0.0, 0.0], Sig_bar, [0.0, 0.0], Sig, z=0.0, Q=Q)
    assert_no_nan(fig)
    FigureRenderer(fig).png()


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"mu_bar": [1.0, 2.0, 3.0]}, "mu_bar"),
        ({"mu": [np.nan, 0.0]}, "mu"),
        ({"Sig_bar": np.eye(3)}, "Sig_bar"),
        ({"Sig": [[1.0, 2.0], [0.0, 1.0]]}, "Sig"),
        ({"Q": -0.5}, "Q"),
        ({"z": None}, "z and Q"),
        ({"nsig": 0.0}, "nsig"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    mu_bar, Sig_bar, mu, Sig = worked_example()
    args = {"mu_bar": mu_bar, "Sig_bar": Sig_bar, "mu": mu, "Sig": Sig, "z": 1.2, "Q": 0.5} | kwargs
    with pytest.raises(ValueError, match=name):
        predict_update_chart(**args)


def test_legend_is_mathtext_and_inside_the_figure():
    mu_bar, Sig_bar, mu, Sig = worked_example()
    fig = predict_update_chart(mu_bar, Sig_bar, mu, Sig, z=1.2, Q=0.5)
    (legend,) = fig.legends
    labels = [t.get_text() for t in legend.get_texts()]
    assert labels == [
        r"reading $z \pm 1\sigma_Q$",
        r"prediction $\bar\Sigma$ ($1\sigma$)",
        r"posterior $\Sigma$ ($1\sigma$)",
    ]
    FigureRenderer(fig).png()  # lays the figure out
    box, page = legend.get_window_extent(), fig.bbox
    assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 and box.y1 <= page.y1
