"""The "Try this" prompts of chapter 9 (the sigma-points demo), driven through the demo's controls as the prose says.

The UKF's, the EKF's and the exact rows of the readout are exact numbers; the sampled row comes from 20 000
seeded draws.  Each prompt is driven through the controls of the demo as it opens (seed 0) and read off its
readout; every promise about the sampled row is checked again on the demo's model for seeds 0 to 19, and holds
for all of them.
"""

from __future__ import annotations

import pytest

import kfcourse as kf
from kfcourse.demos.sigma_points import SigmaPointsModel

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

SQUARE, SINE, RANGE = "x²", "sin x", "range √(x² + 1)"
SEEDS = range(20)


def demo_at(function: str = SQUARE, m: float = 2.0, s: float = 1.0, lam: float = 0.0, seed: int = 0):
    demo = kf.demos.sigma_points(seed=seed)
    demo.controls["function"].value = function
    demo.controls["m"].value = m
    demo.controls["s"].value = s
    demo.controls["lam"].value = lam
    return demo


def readout(demo) -> dict[str, tuple[float, float]]:
    """The (mean, var) rows of the readout the picture shows."""
    rows = [line.split() for line in demo.view.info.get_text().split("\n")]
    return {
        row[0]: (float(row[1]), float(row[2])) for row in rows if row and row[0] in ("sampled", "UKF", "EKF", "exact")
    }


def exact_square(m: float, s: float) -> tuple[float, float]:
    return m * m + s * s, 4 * m * m * s * s + 2 * s**4


def test_prompt_1_widen_and_narrow_the_input(seed=0):
    """From the first frame drag s to 1.5: the UKF's mean follows the truth to m² + s² = 6.25 while the EKF stays
    at 4; the UKF's variance, 36, falls well short of the exact row's 46.1.  Drag s to 0.1: all three agree."""
    demo = kf.demos.sigma_points(seed=seed)
    demo.controls["s"].value = 1.5
    rows = readout(demo)
    assert rows["exact"] == pytest.approx((6.25, 46.125), abs=1e-3)
    assert rows["UKF"] == pytest.approx((6.25, 36.0)) and rows["EKF"] == pytest.approx((4.0, 36.0))
    assert rows["exact"][1] - rows["UKF"][1] > 10.0
    assert rows["sampled"][0] == pytest.approx(6.25, abs=0.15)
    assert rows["sampled"][1] - rows["UKF"][1] > 8.0
    demo.controls["s"].value = 0.1
    rows = readout(demo)
    for name in ("UKF", "EKF"):
        assert rows[name][0] == pytest.approx(rows["sampled"][0], abs=0.02)
        assert rows[name][1] == pytest.approx(rows["sampled"][1], rel=0.05)


def test_prompt_2_lam_two_makes_the_variance_exact():
    """Back at m = 2, s = 1, λ = 2: the UKF's variance is 18, the exact row's, and it stays equal to the exact row
    wherever m and s go (the slider's whole range); λ = 3 overshoots: 19."""
    demo = demo_at(SQUARE, 2.0, 1.0, 2.0)
    assert readout(demo)["UKF"] == pytest.approx((5.0, 18.0)) and readout(demo)["UKF"] == readout(demo)["exact"]
    m_slider = demo.controls["m"]
    for m in (m_slider.min, -1.0, 0.0, 1.5, m_slider.max):
        for s in (0.05, 0.5, 1.2, 1.5):
            demo.controls["m"].value, demo.controls["s"].value = m, s
            assert readout(demo)["UKF"] == pytest.approx(exact_square(m, s), abs=1e-3)
            assert readout(demo)["UKF"] == pytest.approx(readout(demo)["exact"], abs=1.01e-3)
    demo.controls["m"].value, demo.controls["s"].value = 2.0, 1.0
    demo.controls["lam"].value = 3.0
    assert readout(demo)["UKF"][1] == pytest.approx(19.0)


def test_prompt_3_the_bottom_of_the_bowl(seed=0):
    """x², m = 0, s = 1, λ = 0: the EKF says mean 0, variance 0; the UKF gets the mean right, 1, but also says
    variance 0; λ = 2 gives the true 2 (the samples' variance, within Monte-Carlo error)."""
    demo = demo_at(SQUARE, 0.0, 1.0, 0.0, seed=seed)
    rows = readout(demo)
    assert rows["EKF"] == (0.0, 0.0)
    assert rows["UKF"] == pytest.approx((1.0, 0.0), abs=1e-9)
    assert rows["sampled"] == pytest.approx((1.0, 2.0), rel=0.07)
    demo.controls["lam"].value = 2.0
    assert readout(demo)["UKF"] == pytest.approx((1.0, 2.0)) == readout(demo)["exact"]


def test_prompt_4_the_range_to_a_landmark(seed=0):
    """The range, m = 2, s = 1, λ = 2: the UKF's mean and variance agree with the samples to about 0.01; the EKF's
    mean is short by about 0.07 and its variance too wide."""
    rows = readout(demo_at(RANGE, 2.0, 1.0, 2.0, seed=seed))
    assert rows["UKF"][0] == pytest.approx(rows["sampled"][0], abs=0.02)
    assert rows["UKF"][1] == pytest.approx(rows["sampled"][1], abs=0.02)
    assert rows["sampled"][0] - rows["EKF"][0] == pytest.approx(0.07, abs=0.015)
    assert rows["EKF"][1] > rows["sampled"][1] + 0.1


def test_prompt_5_sine_at_its_peak_the_ukf_is_an_approximation_too(seed=0):
    """sin x, m = 1.5, s = 1.5: the EKF claims about 1.0 and is very sure; at λ = 0 the UKF says about 0.07 with
    almost no spread (its outer points land at sin 0 = 0 and sin 3 = 0.14); at λ = 2 its mean, 0.38, is close to
    the samples' 0.33, its variance too wide."""
    demo = demo_at(SINE, 1.5, 1.5, 0.0, seed=seed)
    rows = readout(demo)
    assert rows["EKF"][0] == pytest.approx(1.0, abs=0.01) and rows["EKF"][1] < 0.02
    assert rows["sampled"][0] == pytest.approx(0.33, abs=0.02) and rows["sampled"][1] > 0.3
    assert rows["UKF"][0] == pytest.approx(0.07, abs=0.01) and rows["UKF"][1] < 0.01
    chi, _ = demo.model.sigma_points()
    assert sorted(demo.model.f(chi)[1:]) == pytest.approx([0.0, 0.14], abs=0.005)
    demo.controls["lam"].value = 2.0
    rows = readout(demo)
    assert rows["UKF"][0] == pytest.approx(0.38, abs=0.01)
    assert abs(rows["UKF"][0] - rows["sampled"][0]) < 0.1
    assert rows["UKF"][1] > rows["sampled"][1] * 1.5


def model_at(seed: int, function: str, m: float, s: float, lam: float) -> SigmaPointsModel:
    model = SigmaPointsModel(seed=seed, function=function)
    model.set_m(m)
    model.set_s(s)
    model.set_lam(lam)
    return model


@pytest.mark.parametrize("seed", SEEDS)
def test_the_sampled_row_keeps_every_prompts_promise_for_any_seed(seed):
    """The prompts' claims that involve the samples, on the demo's model opened with another seed."""
    wide = model_at(seed, SQUARE, 2.0, 1.5, 0.0)  # prompt 1: the samples follow the truth, the UKF falls short
    assert wide.sampled()[0] == pytest.approx(6.25, abs=0.15) and wide.sampled()[1] - wide.ukf()[1] > 8.0
    narrow = model_at(seed, SQUARE, 2.0, 0.1, 0.0)  # prompt 1: all three agree
    for mean, var in (narrow.ukf(), narrow.ekf()):
        assert mean == pytest.approx(narrow.sampled()[0], abs=0.02) and var == pytest.approx(
            narrow.sampled()[1], rel=0.05
        )
    bowl = model_at(seed, SQUARE, 0.0, 1.0, 2.0)  # prompt 3: the true variance, 2
    assert bowl.sampled() == pytest.approx((1.0, 2.0), rel=0.07)
    ranged = model_at(seed, RANGE, 2.0, 1.0, 2.0)  # prompt 4
    assert ranged.ukf() == pytest.approx(ranged.sampled(), abs=0.02)
    assert ranged.sampled()[0] - ranged.ekf()[0] == pytest.approx(0.07, abs=0.015)
    assert ranged.ekf()[1] > ranged.sampled()[1] + 0.1
    sine = model_at(seed, SINE, 1.5, 1.5, 2.0)  # prompt 5
    assert sine.sampled()[0] == pytest.approx(0.33, abs=0.02) and abs(sine.ukf()[0] - sine.sampled()[0]) < 0.1
    assert sine.ukf()[1] > 1.5 * sine.sampled()[1]
