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
    assert rows["dead reckoning"].mean_error > 5.0 and rows["dead reckoning"].global_start is False
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
