"""Chapter 10's promises about the landmark loop, checked on the run records of both filters.

Blind, the filter only predicts, so its position ellipse can only grow; the first
step with readings after the blind stretch collapses it (a wide prediction makes
the gain near 1); and on a normal lap the filter is honest: the true position
lies inside its 3-sigma ellipse at 95 % of the steps or more.  Each holds for the
default filter and for the gated one the chapter's demo runs.
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.demos.landmark_loop import GATE
from kfcourse.sim.capstone_world import BEARING_STD, RANGE_STD
from kfcourse.sim.loop_filters import UKF_LAM

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

FILTERS = ["ekf", "ukf"]
GATES = [None, GATE]
DROPOUT = (40, 70)  # six blind seconds on the left side of the loop (the chapter's cells)
WINDOWS = [DROPOUT, (10, 60), (85, 110)]  # six seconds, a long one from the first straight, one ending in a corner
SEEDS = range(10)


def ellipse_area(Sig) -> np.ndarray:
    """Area of the 1-sigma ellipse of the position block: pi sqrt(det Sig_xy) (m²), for a stack of covariances."""
    Sig = np.asarray(Sig)
    return np.pi * np.sqrt(np.linalg.det(Sig[..., :2, :2]))


def first_sight_after(run, t1: int) -> int:
    """The first step at or after ``t1`` with a reading used."""
    seen = np.flatnonzero(run.used[t1:].any(axis=1))
    assert seen.size, "the sensor never saw a landmark again"
    return t1 + int(seen[0])


@pytest.mark.parametrize("gate", GATES)
@pytest.mark.parametrize("window", WINDOWS)
@pytest.mark.parametrize("filter", FILTERS)
def test_blind_the_ellipse_never_shrinks(filter, window, gate):
    run = kf.sim.landmark_loop(0, filter=filter, dropout=window, gate=gate)
    t0, t1 = window
    assert run.used[t0 - 1].any()  # it could see just before
    assert not run.used[t0:t1].any()  # and nothing while blind
    np.testing.assert_allclose(run.area, ellipse_area(run.Sig), rtol=1e-12)  # the record's area is what it says
    blind = run.area[t0 - 1 : t1]  # from the last step with readings to the last blind step
    assert np.all(np.diff(blind) >= 0.0), f"shrank at steps {t0 + np.flatnonzero(np.diff(blind) < 0)}"
    assert blind[-1] > 5 * blind[0]  # and it balloons: more than 5 times the area it had
    np.testing.assert_array_equal(run.mu[t0:t1], run.mu_bar[t0:t1])  # blind steps are predictions only
    np.testing.assert_array_equal(run.Sig[t0:t1], run.Sig_bar[t0:t1])


@pytest.mark.parametrize("gate", GATES)
@pytest.mark.parametrize("window", WINDOWS)
@pytest.mark.parametrize("filter", FILTERS)
def test_first_reading_back_at_least_halves_the_ellipse(filter, window, gate):
    run = kf.sim.landmark_loop(0, filter=filter, dropout=window, gate=gate)
    k = first_sight_after(run, window[1])
    assert k == window[1]  # a landmark is in view the moment sight returns
    before = ellipse_area(run.Sig_bar[k])  # the prediction, just before the readings of step k
    assert run.area[k] <= 0.5 * before
    assert run.area[k] <= 0.5 * run.area[k - 1]  # and half of the last blind step's


@pytest.mark.parametrize("filter", FILTERS)
def test_one_reading_alone_halves_the_ballooned_ellipse(filter):
    """The lesson's "a single good reading collapses the ellipse": only the first landmark's update of the step."""
    run = kf.sim.landmark_loop(0, filter=filter, dropout=DROPOUT)
    k = DROPOUT[1]
    j = int(np.flatnonzero(run.used[k])[0])
    m = run.landmarks[j]
    h = lambda x: kf.range_bearing(x, m)  # noqa: E731
    Q = np.diag([RANGE_STD, BEARING_STD]) ** 2 * run.sensor_noise**2  # the filter's Q
    if filter == "ekf":
        _, Sig = kf.ekf_update(
            run.mu_bar[k],
            run.Sig_bar[k],
            run.z[k, j],
            h,
            lambda x: kf.range_bearing_jacobian(x, m),
            Q,
            residual=kf.models.range_bearing_residual,
        )
    else:
        _, Sig = kf.ukf_update(
            run.mu_bar[k], run.Sig_bar[k], run.z[k, j], h, Q, UKF_LAM, residual=kf.models.range_bearing_residual
        )
    assert ellipse_area(Sig) <= 0.5 * ellipse_area(run.Sig_bar[k])


@pytest.mark.parametrize("gate", GATES)
@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("filter", FILTERS)
def test_normal_lap_is_honest(filter, seed, gate):
    run = kf.sim.landmark_loop(seed, filter=filter, gate=gate)
    e = run.truth[:, :2] - run.mu[:, :2]
    d2 = np.einsum("ti,tij,tj->t", e, np.linalg.inv(run.Sig[:, :2, :2]), e)  # squared Mahalanobis distance
    np.testing.assert_array_equal(run.inside, d2 <= 9.0)  # "inside" means inside the 3-sigma ellipse
    assert run.inside.mean() >= 0.95, f"truth inside the 3-sigma ellipse at only {run.inside.mean():.1%} of the steps"


@pytest.mark.parametrize("filter", FILTERS)
def test_kidnapped_the_gated_filter_stays_confidently_wrong(filter):
    """The demo's kidnap: after it the error is metres, the ellipse a few tenths of a metre, the truth never inside."""
    run = kf.sim.landmark_loop(0, filter=filter, kidnap=60, gate=GATE)
    after = slice(60, None)
    assert run.error[after].min() > 2.0
    assert np.sqrt(run.area[after] / np.pi).max() < 0.5  # geometric-mean radius of the 1-sigma ellipse (m)
    assert not run.inside[after].any()
    assert run.rejected[after].sum() > run.used[after].sum()  # it refuses most of what it sees
