"""The family on a real log (kfcourse/sim/plaza_family.py): what chapter 12's table will show, with margins."""

from __future__ import annotations

import pytest

import kfcourse as kf


@pytest.fixture(scope="module")
def family():
    return kf.sim.plaza_family(kf.data.load_plaza("Plaza2"), steps=1500)


@pytest.mark.fact
def test_the_table_ranks_the_family_as_the_chapter_says(family):
    rows = {row.name: row for row in family.rows}
    assert list(rows) == [
        "dead reckoning",
        "EKF, data sheet",
        "EKF, tuned",
        "RTS smoother",
        "UKF, tuned",
        "PF, N = 1000",
    ]
    assert rows["dead reckoning"].mean_error > 5.0 and rows["dead reckoning"].global_start is None
    assert rows["EKF, data sheet"].mean_error > 2.0 and rows["EKF, data sheet"].inside < 0.1
    for name in ("EKF, tuned", "UKF, tuned", "PF, N = 1000"):
        assert rows[name].mean_error < 0.5 and rows[name].inside > 0.9
    assert rows["RTS smoother"].mean_error < rows["EKF, tuned"].mean_error
    assert rows["PF, N = 1000"].global_start is True and rows["EKF, tuned"].global_start is True
    assert all(row.ms_per_step > 0 for row in family.rows)


def test_the_table_prints_a_row_per_filter_and_how_it_was_measured(family):
    text = family.table()
    assert text.startswith("Filter") and "Plaza2, 1500 odometry steps" in text
    assert all(row.name in text for row in family.rows)


def test_a_bad_log_or_step_count_is_refused():
    with pytest.raises(ValueError, match=r"^log must be a PlazaLog"):
        kf.sim.plaza_family("Plaza2")
    with pytest.raises(ValueError, match=r"^steps must be at most 4090"):
        kf.sim.plaza_family(kf.data.load_plaza("Plaza2"), steps=5000)


@pytest.mark.fact
def test_the_ukf_lost_from_the_plazas_middle_is_locked_out_by_its_gate():
    """Chapter 12: from the plaza's middle the tuned UKF does not find the robot, because its first ranges make it
    sure of a wrong place and its gate then refuses the ranges that would bring it back; without the gate it finds
    the robot."""
    from kfcourse.sim.plaza_family import LOST
    from kfcourse.sim.range_particles import plaza_box

    plaza2 = kf.data.load_plaza("Plaza2")
    lost = {"start": [*plaza_box(plaza2).mean(axis=1), 0.0], "start_std": LOST, "steps": 1500}
    gated = kf.sim.range_localize(plaza2, filter="ukf", **kf.sim.TUNED, **lost)
    ungated = kf.sim.range_localize(plaza2, filter="ukf", **{**kf.sim.TUNED, "gate": None}, **lost)
    assert gated.error[750:].min() > 5.0 and gated.summary()["verdict"] == "over-confident"
    assert gated.used.mean() < 0.5  # most ranges refused
    assert ungated.error[750:].max() < 1.5
