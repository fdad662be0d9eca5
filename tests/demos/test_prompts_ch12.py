"""Chapter 12's "Try this" prompts for the real run, each driven as its text says through the setters of the
demo's model (:class:`~kfcourse.demos.real_run.RealRunModel`), on the runs the model itself makes and keeps.

The EKF draws nothing: prompts 1 to 3 hold for every seed, and share one model (its runs kept between them).  The
particle filter's prompt 4 is checked for seeds 0 to 9.  Without an event loop a run is made when it is first
read, so a prompt's intermediate settings cost nothing.  Every claim is checked with a margin, never to the
digits a description shows."""

from __future__ import annotations

import numpy as np
import pytest

from kfcourse.demos.real_run import RealRunModel
from kfcourse.plots.real_run_view import MAP_MARGIN
from kfcourse.sim.scores import NEES_BAND, verdict

pytestmark = pytest.mark.fact  # states facts of runs over a real log, the PF's seeded: repeated under other rounding

PF_SEEDS = range(10)


@pytest.fixture(scope="module")
def model():
    """The demo's model, shared by the EKF's prompts: its runs are kept."""
    return RealRunModel(0)


def as_opened(model) -> RealRunModel:
    """The model's settings as the demo opens (runs kept)."""
    model.set_filter("EKF")
    model.set_trust_motion(1.0)
    model.set_trust_sensor(1.0)
    model.set_scale(False)
    model.set_gate(False)
    model.set_start("known")
    model.set_smoothed(False)
    model.frame = 60
    return model


def above_band(run) -> float:
    """The share of poses whose NEES the strip draws above its shaded band."""
    return float(np.mean(run.nees > NEES_BAND[1]))


def in_band(run) -> float:
    """The share of poses whose NEES the strip draws inside its shaded band (an honest filter's: 95 %)."""
    return float(np.mean((run.nees >= NEES_BAND[0]) & (run.nees <= NEES_BAND[1])))


def refused(run) -> float:
    """The share of the log's ranges the gate refused."""
    return float(np.mean(~run.used))


def at(run, t: float) -> int:
    """The pose shown at second ``t``."""
    return int(np.searchsorted(run.t, t, side="right") - 1)


def test_prompt_1_scale_and_gate_bring_the_strip_into_its_band_and_the_smoother_closer(model):
    """The demo opens on the EKF with chapter 12's noise but the radio's scale taken as 1, though its ranges read
    about 7 % long. Press Run (or drag t (s)): the NEES strip stays far above its shaded band, and the verdict under
    the picture says over-confident (mean NEES about 180) while the filter is about 3.7 m off on average. Choose
    EKF + scale and gate: the strip comes down into its band and stays there at about 96 % of the poses (an honest
    filter's 95 %), the verdict turns honest, and the filter is 0.35 m off on average. Press smoothed: the pale path
    lies closer to the truth still, about 0.25 m off on average."""
    run = as_opened(model).run
    assert run.scale == 1.0
    assert above_band(run) > 0.98 and np.median(run.nees) > 10 * NEES_BAND[1]  # far above, nearly everywhere
    mean_nees = float(run.nees.mean())
    assert 150 < mean_nees < 210 and verdict(mean_nees) == "over-confident"
    assert "over-confident" in model.describe()
    assert 3.5 < run.error.mean() < 3.9

    model.set_filter("EKF + scale and gate")
    honest = model.run
    assert honest.scale == "online" and 1.06 < honest.mu[-1, 3] < 1.08  # the ranges read about 7 % long
    assert 0.93 < in_band(honest) < 0.99
    assert verdict(float(honest.nees.mean())) == "honest" and "honest (honest: a mean" in model.describe()
    assert 0.33 < honest.error.mean() < 0.37

    model.set_smoothed(True)
    smooth = model.smooth
    assert smooth.error.mean() < honest.error.mean() - 0.05 and 0.22 < smooth.error.mean() < 0.28
    assert "smoothed, 0.2" in model.describe()


def test_prompt_2_too_sure_of_the_ranges_is_over_confident_too_unsure_of_the_odometry_timid(model):
    """Keep EKF + scale and gate and move filter's Q × down to 0.10: the filter now believes its ranges to 22 cm
    (0.7 m × √0.1). The strip climbs above its band at most poses, the verdict turns over-confident, and the gate
    starts refusing good ranges (dotted arcs: about a quarter of them). At 0.010 it refuses most of them and wanders
    off, more than 10 m from the robot for much of the log. Put Q back to 1.0 and move filter's R × up to 100
    (1.0e+2): the strip sinks below its dotted average, to the middle of its band, and the verdict turns timid (mean
    NEES under 1), while the filter is 0.53 m off, half as much again as at R x 1: a timid filter is safe, but its
    ellipse tells you less than it could."""
    as_opened(model).set_filter("EKF + scale and gate")
    honest = model.run
    assert refused(honest) == 0.0  # at Q x 1 the gate refuses none: every refusal below is Q's doing

    model.set_trust_sensor(0.1)
    sure = model.run
    assert sure.range_std == pytest.approx(0.7 * np.sqrt(0.1)) and round(sure.range_std, 2) == 0.22
    assert above_band(sure) > 0.5
    assert verdict(float(sure.nees.mean())) == "over-confident" and "over-confident" in model.describe()
    assert 0.15 < refused(sure) < 0.35

    model.set_trust_sensor(0.01)
    surer = model.run
    assert refused(surer) > 0.5
    assert np.mean(surer.error > 10.0) > 0.25

    model.set_trust_sensor(1.0)
    model.set_trust_motion(100.0)
    timid = model.run
    assert np.median(timid.nees) < 0.5 * np.median(honest.nees) and in_band(timid) > 0.9  # low in its band
    assert float(timid.nees.mean()) < 0.97 and verdict(float(timid.nees.mean())) == "timid"
    assert "timid" in model.describe()
    assert np.median(timid.nees) < 1.0  # below the strip's dotted average, 2
    assert 0.48 < timid.error.mean() < 0.58 and 1.3 < timid.error.mean() / honest.error.mean() < 1.7


def test_prompt_3_from_an_unknown_start_the_gate_loses_the_robot_and_the_scale_alone_finds_it(model):
    """Put R back to 1.0 and set start to unknown: the filter starts at the plaza's origin, 57 m from the robot,
    with an ellipse as wide as the plaza. With EKF + scale and gate, the first ranges shrink its 3σ ellipse to a few
    metres within a second while the estimate is still about 20 m off; from then on the gate refuses the ranges that
    would pull it back (most of the log's, dotted), and the filter is lost for good: over-confident, the truth
    outside its ellipse at almost every pose, tens of metres off on average. Now choose EKF and press scale (no
    gate): from the same start the ranges to the four beacons pull it onto the robot, and from t = 40 s on it stays
    within 2 m of it. Its verdict still reads over-confident: the first half-minute's search weighs on the mean
    NEES; from t = 40 s on, its NEES averages about 2.6, honest."""
    as_opened(model).set_filter("EKF + scale and gate")
    model.set_start("unknown")
    lost = model.run
    assert 55.0 < lost.error[0] < 58.0 and np.allclose(np.sqrt(np.diag(lost.Sig[0])[:2]), 30.0)
    k = at(lost, 1.0)
    assert 3 * np.sqrt(np.linalg.eigvalsh(lost.Sig[k][:2, :2])).max() < 5.0  # the 3σ half-axes: a few metres
    assert 15.0 < lost.error[k] < 25.0
    assert refused(lost) > 0.75
    assert np.mean(lost.inside[lost.t >= 1.0]) < 0.02
    assert verdict(float(lost.nees.mean())) == "over-confident" and lost.error.mean() > 20.0

    model.set_filter("EKF")
    model.set_scale(True)
    found = model.run
    assert found.gate is None and found.scale == "online" and found.error[0] == lost.error[0]
    assert found.error[found.t >= 40.0].max() < 2.0
    assert verdict(float(found.nees.mean())) == "over-confident"
    later = float(found.nees[found.t >= 40.0].mean())
    assert 2.2 < later < 3.0 and verdict(later) == "honest"
    model.frame = 409
    assert "start unknown" in model.describe()


@pytest.mark.parametrize("seed", PF_SEEDS)
def test_prompt_4_the_pf_finds_the_robot_from_nowhere(seed):
    """Choose PF, the start still unknown: its particles start spread over the whole plaza. Drag t (s) to 0: the
    estimate stands mid-plaza, more than 10 m from the robot, its 3σ ellipse so wide that its outline lies off the
    map (the description: the truth inside it). Press Run: within the first minute the estimate lands on the robot
    and stays within 2 m of it to the end of the log. So it does for every seed from 0 to 9. The verdict under the
    picture depends on the search: while the cloud searches, its mean can stray metres from the robot with the truth
    outside its ellipse, and those poses weigh on the whole run's mean NEES (seed 0: over-confident); from the first
    minute on, its NEES averages under 1 in every seed, timid, as a cloud told wide noise is."""
    model = RealRunModel(seed)
    model.set_start("unknown")
    model.set_filter("PF")
    run = model.run
    assert run.start is None and run.seed == seed
    model.frame = 0
    k = model.row
    assert run.error[k] > 10.0
    points = np.vstack([model.log.beacons, model.log.truth[:, :2]])  # the map's limits, as the view sets them
    lo, hi = points.min(axis=0) - MAP_MARGIN, points.max(axis=0) + MAP_MARGIN
    assert np.hypot(*(run.mu[k, :2] - (lo + hi) / 2)) < 5.0  # mid-plaza
    corners = np.array([[x, y] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])]) - run.mu[k, :2]
    d2 = np.einsum("ni,ij,nj->n", corners, np.linalg.inv(np.asarray(run.Sig[k])[:2, :2]), corners)
    assert (d2 < 9.0).all()  # every corner of the map inside the 3σ ellipse: its outline lies off the map
    assert "the truth inside its 3σ ellipse" in model.describe()
    found = run.found(2.0)
    assert found is not None and run.t[found] < 60.0
    assert float(run.nees[run.t >= 60.0].mean()) < 1.0
    if seed == 0:
        assert verdict(float(run.nees.mean())) == "over-confident"
