"""Chapter 8: forgetting to wrap the bearing innovation breaks the EKF on the loop; wrapping it does not."""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


@pytest.fixture(scope="module")
def runs():
    return {(seed, wrap): kf.sim.landmark_loop(seed, wrap_bearing=wrap) for seed in (0, 1, 3) for wrap in (True, False)}


@pytest.mark.parametrize("seed", [0, 3])
def test_unwrapped_bearing_breaks_the_estimate(runs, seed):
    wrapped, unwrapped = runs[seed, True], runs[seed, False]
    assert not unwrapped.wrap_bearing and wrapped.wrap_bearing
    assert unwrapped.error.max() > 1.0  # m: the estimate jumps off the loop
    assert unwrapped.error.max() > 5 * wrapped.error.max()
    assert unwrapped.share_inside < 0.85  # and is confidently wrong for a stretch of the drive
    assert np.allclose(unwrapped.truth, wrapped.truth) and np.allclose(unwrapped.z, wrapped.z)  # same world


@pytest.mark.parametrize("seed", [0, 1, 3])
def test_wrapped_bearing_tracks_and_is_honest(runs, seed):
    wrapped = runs[seed, True]
    assert wrapped.error.max() < 0.3  # m
    assert wrapped.share_inside > 0.95


def test_the_break_starts_at_a_reading_across_plus_minus_pi(runs):
    """Before the first reading whose raw bearing difference exceeds pi, both filters agree exactly."""
    wrapped, unwrapped = runs[0, True], runs[0, False]
    across = [
        k
        for k, j in zip(*np.nonzero(unwrapped.used), strict=True)
        if abs(unwrapped.z[k, j, 1] - kf.range_bearing(unwrapped.mu_bar[k], unwrapped.landmarks[j])[1]) > np.pi
    ]
    assert across, "no reading crossed +-pi: the run does not show the bug"
    k0 = min(across)
    assert np.allclose(unwrapped.mu[:k0], wrapped.mu[:k0])
    assert not np.allclose(unwrapped.mu[k0], wrapped.mu[k0])


def test_a_run_without_a_crossing_does_not_show_the_bug(runs):
    """Seed 1: no reading lands across +-pi from its prediction, so the missing wrap never matters."""
    assert np.allclose(runs[1, True].mu, runs[1, False].mu)


def test_the_wrap_table_prints_each_seeds_largest_and_final_errors(runs):
    table = kf.sim.ekf_runs.wrap_table({seed: (runs[seed, True], runs[seed, False]) for seed in (0, 1, 3)})
    lines = table.splitlines()
    assert len(lines) == 2 + 3 and "final error (cm)" in lines[0]
    cells = lines[2].split()  # seed 0
    assert cells[:3] == ["0", "0.15", "1.51"]
    assert [float(c) for c in cells[3:5]] == pytest.approx(
        100 * np.array([runs[0, w].error[-1] for w in (1, 0)]), abs=0.05
    )
    assert lines[3].split()[1] == lines[3].split()[2]  # seed 1: the wrap never mattered


def test_the_unwrapped_filter_finds_its_way_back(runs):
    """The recap: on seed 0 the error peaks at 1.51 m and the lap ends 2.5 cm off, as close as with the wrap."""
    wrapped, unwrapped = runs[0, True], runs[0, False]
    assert unwrapped.error.max() == pytest.approx(1.51, abs=0.005)
    assert unwrapped.error[-1] == pytest.approx(0.025, abs=0.0005)
    assert abs(unwrapped.error[-1] - wrapped.error[-1]) < 0.005


def test_the_failure_report_starts_at_the_first_bad_step_and_says_how_it_ends(runs):
    report = kf.sim.ekf_runs.wrap_failure_report(runs[0, True], runs[0, False])
    lines = report.splitlines()
    assert lines[2].split()[0] == "76" and lines[3].split()[:4] == ["77", "15.6", "4,", "5"]  # the step before, then 77
    assert "step 77: raw bearing innovations" in report and "6.22" in report
    assert "largest error 1.51 m at t = 18.0 s" in report and "at the end of the lap 2.5 cm" in report
    assert "from step 77 to 104 (5.6 s)" in report
    with pytest.raises(ValueError, match="part"):
        kf.sim.ekf_runs.wrap_failure_report(runs[1, True], runs[1, False])  # seed 1: the two never part
