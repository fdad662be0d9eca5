"""GTSAM's batch solution over CMU's Plaza2 log (kfcourse/sim/graph_run.py): what chapter 12 will say of it.

The figures are stated with margins, and those of the runs are repeated under other rounding (``fact``): the EKF
beside the graph is a long chain of numpy's rounding.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kfcourse as kf
from kfcourse.data.plaza import GTSAM_VERSION, NO_GTSAM
from kfcourse.sim.range_run import START_STD

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def plaza2():
    return kf.data.load_plaza("Plaza2")


@pytest.fixture(scope="module")
def runs(plaza2):
    """The EKF with the radio's scale, its RTS smoothing, and the graph with and without the robust loss."""
    ekf = kf.sim.range_localize(plaza2, scale=1.07)
    return {
        "ekf": ekf,
        "rts": kf.sim.smoothed(ekf),
        "robust": kf.sim.factor_graph(plaza2),
        "plain": kf.sim.factor_graph(plaza2, robust=False),
    }


@pytest.mark.fact
def test_the_batch_solution_beats_the_filter_and_matches_the_smoother(runs):
    ekf, rts = runs["ekf"].summary(), runs["rts"].summary()
    for name in ("robust", "plain"):
        run = runs[name].summary()
        assert run["mean_error"] < 0.8 * ekf["mean_error"] and run["p95_error"] < 0.7 * ekf["p95_error"]
        assert abs(run["mean_error"] - rts["mean_error"]) < 0.1 * rts["mean_error"]
        assert abs(run["p95_error"] - rts["p95_error"]) < 0.1 * rts["p95_error"]
        assert runs[name].final_error < 0.05 * runs[name].initial_error  # far from the dead reckoning it started at


@pytest.mark.fact
def test_its_covariance_is_the_smoother_s_in_the_world_s_axes(runs):
    """GTSAM's covariance of a pose is in the pose's axes; turned into the world's it is the smoother's, pose by
    pose (not turned, it would be half off at the median)."""
    graph, rts = runs["plain"].Sig[:, :2, :2], runs["rts"].Sig[:, :2, :2]
    off = np.linalg.norm(graph - rts, axis=(1, 2)) / np.linalg.norm(rts, axis=(1, 2))
    assert np.median(off) < 0.1
    assert np.all(np.linalg.eigvalsh(graph) > 0)


@pytest.mark.fact
def test_the_prior_pins_the_first_pose(runs, plaza2):
    for name in ("robust", "plain"):
        run = runs[name]
        start_std = np.sqrt(np.diag(run.Sig[0, :2, :2]))
        assert run.error[0] < 0.15 and np.all(start_std <= START_STD[0])
        np.testing.assert_array_equal(run.truth[0], plaza2.truth[0])


@pytest.mark.fact
def test_the_answer_does_not_depend_on_where_the_optimiser_starts(plaza2):
    part = kf.sim.range_localize(plaza2, scale=1.07, steps=800)
    from_dead_reckoning = kf.sim.factor_graph(plaza2, steps=800)
    from_ekf = kf.sim.factor_graph(plaza2, steps=800, initial=part.mu)
    assert from_ekf.initial_error != from_dead_reckoning.initial_error  # two starts, one answer
    np.testing.assert_allclose(from_ekf.mu[:, :2], from_dead_reckoning.mu[:, :2], atol=1e-3)
    assert from_ekf.final_error == pytest.approx(from_dead_reckoning.final_error, rel=1e-4)


@pytest.mark.fact
def test_a_part_of_the_log_takes_its_ranges_as_the_filter_does(plaza2):
    run = kf.sim.factor_graph(plaza2, steps=300)
    ekf = kf.sim.range_localize(plaza2, steps=300)
    assert run.mu.shape == (301, 3) and run.Sig.shape == (301, 3, 3) and run.t.size == 301
    np.testing.assert_array_equal(run.step, ekf.step)
    np.testing.assert_array_equal(run.z, ekf.z)
    assert np.abs(run.residual).max() < 5.0  # ranges over the scale, against the solution's distances
    assert set(run.summary()) == {"mean_error", "p95_error", "inside", "mean_nees", "verdict"}
    with pytest.raises(ValueError, match="read-only"):
        run.mu[0, 0] = 0.0


def test_without_gtsam_the_message_says_how_to_install_it(plaza2, monkeypatch):
    monkeypatch.setitem(sys.modules, "gtsam", None)  # import gtsam now raises ModuleNotFoundError
    with pytest.raises(ModuleNotFoundError, match=r"pip install gtsam==4\.3\.0") as raised:
        kf.sim.factor_graph(plaza2, steps=5)
    assert raised.value.name == "gtsam"
    assert str(raised.value) == NO_GTSAM.format(version=GTSAM_VERSION)


def test_importing_the_simulations_does_not_import_gtsam():
    code = "import sys, kfcourse as kf, kfcourse.sim; print('gtsam' in sys.modules)"
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=120, check=True
    )
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize(
    ("changed", "name"),
    [
        ({"log": "Plaza2"}, "log"),
        ({"scale": 0.0}, "scale"),
        ({"scale": "online"}, "scale"),
        ({"range_std": -0.5}, "range_std"),
        ({"odometry_std": (0.05, 0.0, 0.02)}, "odometry_std"),
        ({"odometry_std": (0.05, 0.02)}, "odometry_std"),
        ({"robust": 1}, "robust"),
        ({"steps": 0}, "steps"),
        ({"steps": 4091}, "steps"),
        ({"initial": np.zeros((5, 3))}, "initial"),
        ({"initial": np.zeros((6, 4))}, "initial"),
    ],
)
def test_a_bad_argument_is_refused_by_name(plaza2, changed, name):
    arguments = {"log": plaza2, "steps": 5, **changed}
    with pytest.raises(ValueError, match=rf"^{name} must"):
        kf.sim.factor_graph(arguments.pop("log"), **arguments)
