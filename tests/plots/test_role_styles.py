"""Colour is never the only cue: the figures draw each role in its line style (palette.py).

Every line drawn in a role's colour is checked: the truth dotted, a prediction dashed, a
measurement joined into a line dash-dot unless its readings are marked on it.  An estimate
beside another estimate may be dashed (the EKF beside the UKF), so the estimate is only
checked not to be dotted.  Lines in ink (guides, the moment of a kidnap) are no role's and
keep their own styles.
"""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.collections import LineCollection
from matplotlib.colors import to_hex
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

import kfcourse as kf
from kfcourse.plots import palette
from kfcourse.plots.ekf_figures import linearization_view
from kfcourse.plots.raw_vs_filtered_view import raw_vs_filtered_view
from kfcourse.plots.step_through_view import step_through_view
from kfcourse.plots.tracking import tracker_view
from kfcourse.plots.trust_view import trust_view
from kfcourse.plots.ukf_figures import sigma_points_view

DOTTED, DASHED, DASH_DOT = ":", "--", "-."
LIMITS = {"x²": (-1.0, 9.0), "sin x": (-1.25, 1.25), "range √(x² + 1)": (0.5, 5.5)}


def figures():
    """Every figure of the plots package, as (name, figure)."""
    walk = kf.sim.simulate_walk(seed=0)
    right, wrong = kf.sim.run_ekf(flipped=False, seed=0), kf.sim.run_ekf(flipped=True, seed=0)
    ekf, ukf = kf.sim.landmark_loop(0, filter="ekf"), kf.sim.landmark_loop(0, filter="ukf")
    Sig_bar, Sig = np.array([[2.0, 0.8], [0.8, 1.0]]), np.array([[0.4, 0.1], [0.1, 0.7]])
    y = np.random.default_rng(0).normal(2.0, 2.0, 5000) ** 2
    plaza2 = kf.data.load_plaza("Plaza2")
    plaza_ekf = kf.sim.range_localize(plaza2, scale=1.07, steps=300)
    plaza_runs = (plaza_ekf, kf.sim.smoothed(plaza_ekf), kf.sim.range_localize(plaza2, steps=300, filter="ukf"))
    return {
        "raw vs filtered": raw_vs_filtered_view(50).fig,
        "step through": step_through_view().fig,
        "trust": trust_view().fig,
        "tracker": tracker_view(kf.sim.simulate_target(0)).fig,
        "linearization": linearization_view(LIMITS).fig,
        "sigma points": sigma_points_view(LIMITS).fig,
        "run chart": kf.plots.kf_run_chart(walk),
        "jacobian runs": kf.plots.jacobian_runs_chart(right, wrong, every=12),
        "filter comparison": kf.plots.filter_comparison_chart(ekf, ukf),
        "moments": kf.plots.transform_moments_chart(y, (5.0, 16.0), (4.0, 16.0), bins=40, y_range=(-1.0, 25.0)),
        "predict update": kf.plots.predict_update_chart([0.0, 1.0], Sig_bar, [0.8, 1.3], Sig, z=1.2, Q=0.5),
        "update ellipse": kf.plots.update_ellipse_chart(
            [1, 2, 0], np.diag([0.5, 0.3, 0.1]), [1.3, 2.2, 0], np.diag([0.2, 0.2, 0.1]), [4.0, 6.0]
        ),
        "loop": kf.plots.loop_chart(ekf, k=55),
        "plaza": kf.plots.plaza_chart(plaza2, *plaza_runs),
        "ranges": kf.plots.ranges_chart(plaza2),
        "plaza nees": kf.plots.nees_chart(*plaza_runs),
    }.items()


def role_lines(fig):
    """(colour, line style, with markers) of every line in the figure: Line2D with a line, line collections,
    patch edges."""
    for ax in fig.axes:
        for line in ax.get_lines():
            if line.get_linestyle() not in ("None", "", " "):
                yield to_hex(line.get_color()), line.get_linestyle(), line.get_marker() not in ("None", "", " ", None)
        for collection in ax.collections:
            if isinstance(collection, LineCollection) and len(collection.get_colors()):
                yield to_hex(collection.get_colors()[0]), _style_of(collection.get_linestyle()[0]), False
        for patch in ax.patches:
            if isinstance(patch, Patch) and not patch.get_fill() and patch.get_linewidth() > 0:
                yield to_hex(patch.get_edgecolor()), patch.get_linestyle(), False


def _style_of(dashes) -> str:
    """A collection keeps (offset, pattern); name it like Line2D does."""
    _, pattern = dashes
    if not pattern:
        return "-"
    return {2: DASHED, 4: DASH_DOT}.get(len(pattern), DASHED) if pattern[0] > pattern[1] else DOTTED


@pytest.mark.parametrize(("name", "fig"), list(figures()), ids=lambda x: x if isinstance(x, str) else "")
def test_each_role_keeps_its_line_style(name, fig):
    seen = list(role_lines(fig))
    assert seen, f"{name}: no lines found"
    for colour, style, markers in seen:
        if colour == palette.TRUTH:
            assert style == DOTTED, f"{name}: a truth line drawn {style!r}"
        elif colour == palette.PREDICTION:
            assert style == DASHED, f"{name}: a prediction line drawn {style!r}"
        elif colour == palette.MEASUREMENT and not markers:  # readings joined by a line: their dots are the cue
            assert style == DASH_DOT, f"{name}: a measurement line drawn {style!r}"
        elif colour == palette.ESTIMATE:
            assert style != DOTTED, f"{name}: an estimate drawn dotted, the truth's style"


def test_helpers_take_the_style_of_the_colour():
    fig = kf.plots.new_figure(3, 2)[0]
    ax = fig.axes[0]
    x = np.linspace(-3, 3, 50)
    assert kf.plots.gaussian_curve(ax, x, 0, 1, palette.PREDICTION)[0].get_linestyle() == DASHED
    assert kf.plots.gaussian_curve(ax, x, 0, 1, palette.MEASUREMENT)[0].get_linestyle() == DASH_DOT
    assert kf.plots.gaussian_curve(ax, x, 0, 1, palette.ESTIMATE)[0].get_linestyle() == "-"
    assert kf.plots.gaussian_curve(ax, x, 0, 1, palette.INK)[0].get_linestyle() == "-"
    assert kf.plots.gaussian_curve(ax, x, 0, 1, palette.PREDICTION, ls="-")[0].get_linestyle() == "-"
    assert kf.plots.covariance_ellipse(ax, (0, 0), np.eye(2), color=palette.PREDICTION).get_linestyle() == DASHED
    assert kf.plots.covariance_ellipse(ax, (0, 0), np.eye(2)).get_linestyle() == "-"


def test_dotted_truth_lines_are_wide_enough_to_see():
    for name, fig in figures():
        for ax in fig.axes:
            for line in ax.get_lines():
                if to_hex(line.get_color()) == palette.TRUTH and line.get_linestyle() == DOTTED:
                    assert line.get_linewidth() >= palette.TRUTH_WIDTH, name


def test_line2d_is_what_the_figures_draw():
    """The scan above reads Line2D styles as matplotlib names them."""
    assert Line2D([], [], ls=":").get_linestyle() == DOTTED
    assert Line2D([], [], ls="-.").get_linestyle() == DASH_DOT
