"""Chapter 12's blind tuning round (kfcourse/sim/tuning.py) and the verdict every honesty test shares."""

from __future__ import annotations

import math

import pytest

import kfcourse as kf


def test_the_verdict_reads_a_mean_nees_against_its_band():
    assert [kf.sim.verdict(x) for x in (0.5, 1.0, 2.0, 4.0, 4.5)] == [
        "timid",
        "honest",
        "honest",
        "honest",
        "over-confident",
    ]
    assert kf.sim.verdict(2.5, band=(1.5, 2.2)) == "over-confident"


def test_the_nees_band_holds_95_percent_of_an_honest_nees():
    low, high = kf.sim.NEES_BAND  # chi-square, 2 degrees of freedom: P(NEES <= x) = 1 - exp(-x / 2)
    assert 1 - math.exp(-low / 2) == pytest.approx(0.025, abs=1e-12)
    assert 1 - math.exp(-high / 2) == pytest.approx(0.975, abs=1e-12)


@pytest.mark.fact
@pytest.mark.parametrize(
    ("noises", "expected"),
    [
        ({}, "over-confident"),  # the data sheet's noises and an unbiased radio
        ({"speed_std": 0.3, "turn_std": 0.1, "range_std": 0.7, "scale": "online"}, "honest"),
        ({"speed_std": 0.05, "turn_std": 0.01, "noise_per": "metre", "range_std": 0.7, "scale": "online"}, "honest"),
        ({"speed_std": 1.0, "turn_std": 0.5, "range_std": 3.0, "scale": "online"}, "timid"),
    ],
)
def test_a_choice_is_scored_on_the_log_it_was_not_tuned_on(noises, expected):
    score = kf.sim.tuning_score(**noises)
    assert score.log == "Plaza2" and score.verdict == expected
    if expected == "honest":
        assert score.in_band > 0.9 and score.mean_error < 0.5
    if expected == "over-confident":
        assert score.in_band < 0.1 and score.mean_error > 2.0
    assert str(score).startswith("On Plaza2: mean error") and str(score).endswith(f"{expected}.")


def test_an_unknown_log_is_refused():
    with pytest.raises(ValueError, match=r"^log must be one of \('Plaza1', 'Plaza2'\)"):
        kf.sim.tuning_score(log="Plaza3")
