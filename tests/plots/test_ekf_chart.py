"""Chapter 7's Jacobian chart draws both runs, finite, with their numbers in the titles."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.patches import Ellipse

import kfcourse as kf
from kfcourse.plots import palette

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


@pytest.fixture(scope="module")
def runs():
    return kf.sim.run_ekf(flipped=False, seed=0), kf.sim.run_ekf(flipped=True, seed=0)


@pytest.mark.pixels
def test_chart_draws_both_runs(runs):
    right, wrong = runs
    fig = kf.plots.jacobian_runs_chart(right, wrong, every=12)
    ax_a, ax_b, ax_e = fig.axes
    for ax, run in ((ax_a, right), (ax_b, wrong)):
        est = [line for line in ax.get_lines() if line.get_color() == palette.ESTIMATE]
        assert len(est) == 1 and np.allclose(est[0].get_xydata(), run.mu[:, :2])
        ellipses = [p for p in ax.patches if isinstance(p, Ellipse)]
        assert len(ellipses) == len(range(0, run.t.size, 12))
        assert f"largest error {run.error.max():.1f} m" in ax.get_title()  # not the final error: chaotic
        assert kf.plots.ekf_figures.share_outside(run) in ax.get_title()
        for p in ellipses:
            assert np.isfinite(p.get_verts()).all()
    errors = [np.asarray(line.get_ydata()) for line in ax_e.get_lines()]
    assert np.allclose(errors[0], right.error) and np.allclose(errors[1], wrong.error)
    png = fig._repr_png_()
    assert png[:4] == b"\x89PNG" and len(png) > 10_000


def test_bad_every(runs):
    with pytest.raises(ValueError, match="every"):
        kf.plots.jacobian_runs_chart(*runs, every=0)


def test_samples_chart_draws_both_histograms():
    x = np.random.default_rng(0).normal(1.0, 0.5, 5000)
    fig = kf.plots.nonlinear_samples_chart(x, x**2, bins=40)
    ax_x, ax_y = fig.axes
    assert len(ax_x.patches) == 40 and len(ax_y.patches) == 40
    heights = np.array([p.get_height() for p in ax_y.patches])
    widths = np.array([p.get_width() for p in ax_y.patches])
    assert np.sum(heights * widths) == pytest.approx(1.0)  # a density
    (gauss,) = ax_y.get_lines()
    assert np.isfinite(gauss.get_xydata()).all()
    with pytest.raises(ValueError, match="same length"):
        kf.plots.nonlinear_samples_chart(x, x[:10])


@pytest.mark.parametrize(
    ("inside", "words"),
    [
        ([True] * 20, "never"),
        ([True] * 19 + [False], "at fewer than 1 step in 10"),  # 5 %
        ([True] * 2 + [False] * 18, "at least 9 steps in 10"),  # 90 %
        ([True] + [False] * 19, "at least 9 steps in 10"),  # 95 %: whole tenths, rounded down
        ([False] * 20, "at least 10 steps in 10"),
    ],
)
def test_share_outside_in_whole_tenths(inside, words):
    class Run:
        pass

    run = Run()
    run.inside = np.array(inside)
    assert kf.plots.ekf_figures.share_outside(run) == words
