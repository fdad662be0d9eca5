"""Chapter 8's pictures: readings and gates in the plane, one update's ellipses, the wrap runs."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.patches import Ellipse
from matplotlib.path import Path

import kfcourse as kf
from kfcourse.plots import palette

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


def test_a_predicted_reading_points_at_its_landmark():
    pose, mark = np.array([1.0, 2.0, 0.7]), np.array([4.0, 6.0])
    z_hat = kf.range_bearing(pose, mark)
    assert kf.plots.reading_points(pose, z_hat) == pytest.approx(mark[None, :])
    assert kf.plots.reading_points(pose, np.empty((0, 2))).shape == (0, 2)


@pytest.mark.parametrize("gate", [1.0, 3.0, 6.0])
def test_a_reading_is_inside_the_drawn_gate_exactly_when_its_distance_is_within_the_gate(gate):
    """The faithful drawing: sampled readings land inside the outline iff d <= gate."""
    scan = kf.sim.association_scan(0)
    rng = np.random.default_rng(1)
    for z_hat, S in zip(scan.z_hat, scan.S, strict=True):
        outline = Path(kf.plots.gate_outline(scan.mu_bar, z_hat, S, gate, n=720))
        L = np.linalg.cholesky(S)
        # readings at distances well inside or well outside the gate, in every direction
        u = rng.standard_normal((200, 2))
        u /= np.linalg.norm(u, axis=1, keepdims=True)
        d = np.where(rng.random(200) < 0.5, 0.9, 1.1) * gate
        z = z_hat + d[:, None] * (u @ L.T)
        z = z[z[:, 0] > 0.05]  # a physical reading has a positive range
        d = np.array([kf.mahalanobis(zi - z_hat, S) for zi in z])
        inside = outline.contains_points(kf.plots.reading_points(scan.mu_bar, z))
        assert list(inside) == list(d <= gate)


def test_gate_outline_is_closed_and_never_has_negative_range():
    scan = kf.sim.association_scan(0)
    pts = kf.plots.gate_outline(scan.mu_bar, scan.z_hat[3], scan.S[3], 30.0, n=50)
    assert pts.shape == (50, 2) and pts[0] == pytest.approx(pts[-1])
    dist = np.linalg.norm(pts - scan.mu_bar[:2], axis=1)
    assert np.isfinite(pts).all() and (dist >= 0).all()
    assert dist.min() == pytest.approx(0.0, abs=1e-12)  # a 30-sigma gate reaches down to range 0


@pytest.mark.parametrize(
    "call",
    [
        lambda: kf.plots.gate_outline([0, 0, 0], [1, 0], np.eye(2), 0.0),
        lambda: kf.plots.gate_outline([0, 0, 0], [1, 0], -np.eye(2), 3.0),
        lambda: kf.plots.gate_outline([0, 0], [1, 0], np.eye(2), 3.0),
        lambda: kf.plots.reading_points([0, 0, 0], [[1, 2, 3]]),
        lambda: kf.plots.update_ellipse_chart([1, 2, 0], np.eye(3), [1, 2, 0], np.eye(3), [4, 6], nsig=0),
    ],
)
def test_bad_input_raises_value_error(call):
    with pytest.raises(ValueError):
        call()


def test_update_chart_draws_both_ellipses_and_the_landmark():
    mu_bar, Sig_bar = np.array([1.0, 2.0, 0.0]), np.diag([0.3, 0.3, 0.1])
    mu, Sig = np.array([1.2, 2.3, 0.0]), np.diag([0.1, 0.2, 0.05])
    fig = kf.plots.update_ellipse_chart(mu_bar, Sig_bar, mu, Sig, [4.0, 6.0])
    (ax,) = fig.axes
    ellipses = [p for p in ax.patches if isinstance(p, Ellipse)]
    assert [e.get_center() for e in ellipses] == [pytest.approx((1.0, 2.0)), pytest.approx((1.2, 2.3))]
    assert ellipses[0].get_edgecolor() == pytest.approx(to_rgba(palette.PREDICTION))
    assert ellipses[1].get_edgecolor() == pytest.approx(to_rgba(palette.ESTIMATE))
    assert (2 * 2 * np.sqrt(0.3)) == pytest.approx(max(ellipses[0].width, ellipses[0].height))
    assert np.allclose(ax.collections[0].get_offsets(), [[4.0, 6.0]])


def fake_run(error, shift):
    t = np.arange(error.size, dtype=float)
    truth = np.column_stack([np.cos(t / 10), np.sin(t / 10), t / 10])
    mu = truth + shift
    Sig = np.tile(np.diag([0.01, 0.01, 0.001]), (t.size, 1, 1))
    return SimpleNamespace(t=t, truth=truth, mu=mu, Sig=Sig, error=error, landmarks=np.array([[0.0, 0.0], [1.0, 1.0]]))


def test_wrap_chart_draws_both_runs_with_their_numbers():
    good = fake_run(np.full(40, 0.05), 0.0)
    bad = fake_run(np.linspace(0, 3, 40), 0.5)
    fig = kf.plots.wrap_runs_chart(good, bad)
    ax_a, ax_b, ax_e = fig.axes
    assert "3.00 m" in ax_b.get_title() and "0.05 m" in ax_a.get_title()
    errors, reaches = ax_e.get_lines()[0::2], ax_e.get_lines()[1::2]
    assert [np.asarray(line.get_ydata()).max() for line in errors] == pytest.approx([0.05, 3.0])
    for line in reaches:  # 3 sigma along the longest axis of diag(0.01, 0.01): 0.3 m at every step
        assert np.asarray(line.get_ydata()) == pytest.approx(np.full(40, 0.3))


def test_wrap_chart_marks_where_the_runs_part():
    good = fake_run(np.full(40, 0.05), 0.0)
    bad = fake_run(np.linspace(0, 3, 40), np.where(np.arange(40)[:, None] >= 25, 0.5, 0.0))
    fig = kf.plots.wrap_runs_chart(good, bad)
    (mark,) = [line for line in fig.axes[1].get_lines() if line.get_marker() == "x"]
    assert (mark.get_xdata()[0], mark.get_ydata()[0]) == pytest.approx(tuple(bad.truth[25, :2]))
