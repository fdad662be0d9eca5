"""The particle-cloud picture (chapter 11): the cloud, the estimate, the truth and the ESS strip show the
run at the step asked for, in place, and a new run (a kidnap) moves them without a new figure; it and the
hallway picture draw their particles in the one purple colormap of the palette."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.colors import to_hex, to_rgba
from matplotlib.figure import Figure

import kfcourse as kf
from kfcourse.demos.particle_hallway import ParticleHallwayModel
from kfcourse.filters.gaussian import ellipse_axes
from kfcourse.plots import palette
from kfcourse.plots.particle_hallway_view import particle_hallway_view, update_particle_hallway
from kfcourse.plots.particles import DOT_SIZE, RESAMPLE_LINE, cloud_chart, cloud_view, update_cloud_view, weight_shades

# No test here states a fact of a seeded run: those that run one are listed in tests/facts.py UNMARKED with the
# reason they need no repeat.


@pytest.fixture(scope="module")
def run():
    return kf.sim.particle_loop(0, n_particles=500)


def test_weight_shades_put_the_heaviest_on_top():
    order, shade = weight_shades([0.1, 0.6, 0.3])
    assert order.tolist() == [0, 2, 1]
    np.testing.assert_allclose(shade, [1 / 6, 0.5, 1.0])
    order, shade = weight_shades(np.full(4, 0.25))  # after resampling: every particle as heavy
    assert order.tolist() == [0, 1, 2, 3] and (shade == 1.0).all()


@pytest.mark.parametrize("k", [0, 60, 121])
def test_the_picture_shows_the_step(run, k):
    model = SimpleNamespace(run=run, frame=k)
    view = cloud_view(model)
    order, shade = weight_shades(run.w[k])
    np.testing.assert_allclose(view.cloud.get_offsets(), run.particles[k, order, :2])
    np.testing.assert_allclose(view.cloud.get_array(), shade)
    assert view.cloud.get_array().max() == 1.0 and view.cloud.get_array().min() >= 0.0
    np.testing.assert_allclose(view.ring.get_center(), run.mu[k, :2])
    w, h, _ = ellipse_axes(run.Sig[k, :2, :2], 2.0)
    assert (view.ring.get_width(), view.ring.get_height()) == pytest.approx((w, h))
    np.testing.assert_allclose(view.robot.get_xy()[:3].mean(axis=0), run.mu[k, :2], atol=1e-9)
    np.testing.assert_allclose(view.truth_robot.get_xy()[:3].mean(axis=0), run.truth[k, :2], atol=1e-9)
    assert len(view.beams.get_segments()) == run.visible[k].sum()
    for segment, m in zip(view.beams.get_segments(), run.landmarks[run.visible[k]], strict=True):
        np.testing.assert_allclose(segment, [run.mu[k, :2], m])
    np.testing.assert_allclose(view.trail.get_xydata(), run.mu[: k + 1, :2])
    share = run.ess / run.n_particles
    np.testing.assert_allclose(view.past.get_xydata(), np.column_stack([run.t, share])[: k + 1])
    np.testing.assert_allclose(view.future.get_xydata(), np.column_stack([run.t, share])[k:])
    assert view.cursor.get_xdata()[0] == run.t[k]
    assert not view.kidnap.get_visible() and view.note.get_text() == ""
    assert len(view.truth_before.get_xydata()) == run.t.size and len(view.truth_after.get_xydata()) == 0
    assert RESAMPLE_LINE == 0.5


def test_a_kidnap_splits_the_truth_and_marks_the_strip(run):
    model = SimpleNamespace(run=run, frame=30)
    view = cloud_view(model)
    artists = view.moving
    model.run, model.frame = kf.sim.particle_loop(0, n_particles=500, kidnap=50), 40
    update_cloud_view(view, model)
    assert view.moving == artists  # the same artists, moved
    assert view.note.get_text() == "" and view.kidnap.get_visible()
    assert view.kidnap.get_xdata()[0] == model.run.t[50]
    assert len(view.truth_before.get_xydata()) == 50
    model.frame = 70
    update_cloud_view(view, model)
    assert view.note.get_text().startswith("kidnapped")


def test_a_bigger_cloud_replaces_the_offsets(run):
    model = SimpleNamespace(run=run, frame=10)
    view = cloud_view(model)
    model.run = kf.sim.particle_loop(0, n_particles=3000)
    update_cloud_view(view, model)
    assert view.cloud.get_offsets().shape == (3000, 2)
    assert view.cloud in view.moving


def test_bad_step(run):
    view = cloud_view(SimpleNamespace(run=run, frame=0))
    with pytest.raises(ValueError, match="k must be"):
        update_cloud_view(view, SimpleNamespace(run=run, frame=run.t.size))


@pytest.mark.parametrize("k", [5, None])
def test_the_cloud_chart_is_the_picture_of_one_step(run, k):
    fig = cloud_chart(run, k)
    assert isinstance(fig, Figure)
    step = run.t.size - 1 if k is None else k
    ax = fig.axes[0]
    clouds = [c for c in ax.collections if len(c.get_offsets()) == run.n_particles]
    assert len(clouds) == 1
    order, shade = weight_shades(run.w[step])
    np.testing.assert_allclose(clouds[0].get_offsets(), run.particles[step, order, :2])
    np.testing.assert_allclose(clouds[0].get_array(), shade)
    np.testing.assert_allclose(ax.lines[2].get_xydata(), run.mu[: step + 1, :2])  # the estimate's trail to step k
    with pytest.raises(ValueError, match="k must be"):
        cloud_chart(run, run.t.size)
    assert kf.plots.cloud_chart is cloud_chart


def test_the_dots_take_the_size_asked_for(run):
    small, large = cloud_chart(run, 5), cloud_chart(run, 5, dot_size=30.0)
    sizes = [
        next(c.get_sizes() for c in fig.axes[0].collections if len(c.get_offsets()) == run.n_particles)
        for fig in (small, large)
    ]
    assert sizes[0][0] == DOT_SIZE and sizes[1][0] == 30.0


def test_both_particle_pictures_shade_the_particles_with_the_palettes_purple(run):
    """Particles are purple everywhere: the map's cloud and the hallway's dots use palette.PARTICLE_WEIGHTS,
    pale for the lightest particle to the prediction purple for the heaviest."""
    cmap = palette.PARTICLE_WEIGHTS
    assert to_hex(cmap(1.0)) == palette.PREDICTION and to_hex(cmap(0.0)) == palette.PARTICLE_LIGHT
    cloud = cloud_view(SimpleNamespace(run=run, frame=60))
    model = ParticleHallwayModel(0, n_particles=200)
    model.predict()
    model.update()  # weights before resampling: light and heavy dots
    hallway = particle_hallway_view(model.doors)
    update_particle_hallway(hallway, model)
    for dots in (cloud.cloud, hallway.dots):
        assert dots.get_cmap() is cmap
        assert dots.get_clim() == (0.0, 1.0)
        dots.update_scalarmappable()
        np.testing.assert_allclose(dots.get_facecolors(), cmap(dots.get_array()))
    heaviest = hallway.dots.get_facecolors()[np.argmax(hallway.dots.get_array())]
    np.testing.assert_allclose(heaviest, to_rgba(palette.PREDICTION))
    legend = cloud.fig.axes[0].get_legend()
    handles = dict(zip([t.get_text() for t in legend.texts], legend.legend_handles, strict=True))
    assert to_hex(handles["heavy particle"].get_color()) == palette.PREDICTION
    assert to_hex(handles["light particle"].get_color()) in {to_hex(cmap(x)) for x in np.linspace(0, 1, 101)}
