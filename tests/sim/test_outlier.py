"""One wild reading (chapter 4): a plain and a gated 1-D filter fed the same readings.

The run record must hold the chapter's table, and the same numbers must come out of
the public steps alone (kf_1d_step for the plain filter; kf_1d_predict, mahalanobis
and kf_1d_update for the gated one).
"""

from __future__ import annotations

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)

R, Q = 0.04, 0.25  # the chapter's steady-state example (m²)
K_INF, VAR_BAR_INF, VAR_INF = kf.steady_state_1d(R, Q)
OUTLIER = 10 * np.sqrt(Q)  # 10 sensor standard deviations: 5 m
READINGS = [0.0, 0.0, OUTLIER, 0.0, 0.0, 0.0, 0.0, 0.0]  # the robot stands at x = 0


def chapter_run():
    return kf.sim.plain_and_gated(READINGS, mu0=0.0, var0=VAR_INF, R=R, Q=Q, gate=3.0)


def by_hand(readings, mu0, var0, gate):
    """Both filters written out with the public steps, as the chapter describes them."""
    plain, gated, rows = (mu0, var0), (mu0, var0), []
    for z in readings:
        plain = kf.kf_1d_step(*plain, u=0.0, z=z, b=0.0, R=R, Q=Q)
        mu_bar, var_bar = kf.kf_1d_predict(*gated, u=0.0, b=0.0, R=R)
        d = kf.mahalanobis([z - mu_bar], [[var_bar + Q]])
        gated = kf.kf_1d_update(mu_bar, var_bar, z, Q=Q) if d <= gate else (mu_bar, var_bar)
        rows.append((*plain, d, d <= gate, *gated))
    return np.array(rows, dtype=float)


def test_the_chapter_table():
    run = chapter_run()
    np.testing.assert_allclose(run.mu_plain.round(3), [0, 0, 1.640, 1.102, 0.741, 0.498, 0.335, 0.225])
    np.testing.assert_allclose(run.d.round(2), [0, 0, 8.20, 0, 0, 0, 0, 0])
    np.testing.assert_array_equal(run.used, [True, True, False, True, True, True, True, True])
    np.testing.assert_array_equal(run.mu_gated, np.zeros(8))  # the gated filter stays on the truth
    assert run.mu_plain[2] == pytest.approx(K_INF * OUTLIER)  # the jump K∞ · 10 σ_Q
    lines = run.table().splitlines()
    assert len(lines) == 2 + len(READINGS)
    assert lines[4].split() == ["3", "5.00", "1.640", "8.20", "SKIPPED", "0.000"]


@pytest.mark.parametrize("gate", [0.5, 3.0, 10.0])
def test_the_record_is_the_public_steps(gate):
    readings = [0.3, -0.2, OUTLIER, 0.1, -2.0, 0.4]
    run = kf.sim.plain_and_gated(readings, mu0=0.1, var0=0.5, R=R, Q=Q, gate=gate)
    want = by_hand(readings, 0.1, 0.5, gate)
    have = np.column_stack([run.mu_plain, run.var_plain, run.d, run.used, run.mu_gated, run.var_gated])
    np.testing.assert_allclose(have, want, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(run.S, run.var_bar + Q)


def test_a_skipped_reading_is_a_predict_without_an_update():
    run = chapter_run()
    assert run.var_gated[2] == pytest.approx(VAR_INF + R)  # the variance grows by R for one tick
    assert run.mu_gated[2] == run.mu_bar[2]
    assert run.S[2] == pytest.approx(VAR_BAR_INF + Q)  # the chapter's S = 0.372


def test_a_wide_gate_makes_the_gated_filter_plain():
    run = kf.sim.plain_and_gated(READINGS, mu0=0.0, var0=VAR_INF, R=R, Q=Q, gate=100.0)
    assert run.used.all()
    np.testing.assert_allclose(run.mu_gated, run.mu_plain, rtol=1e-12)


def test_the_record_is_frozen():
    run = chapter_run()
    with pytest.raises(ValueError):
        run.mu_plain[0] = 1.0
    with pytest.raises(AttributeError):
        run.gate = 5.0


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"z": []}, "z"),
        ({"z": [[0.0, 1.0], [2.0, 3.0]]}, "z"),
        ({"z": [0.0, np.nan]}, "z"),
        ({"mu0": "here"}, "mu0"),
        ({"var0": -0.1}, "var0"),
        ({"R": -0.04}, "R"),
        ({"Q": 0.0}, "Q"),
        ({"Q": np.inf}, "Q"),
        ({"gate": 0.0}, "gate"),
        ({"gate": -3.0}, "gate"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    args = {"z": READINGS, "mu0": 0.0, "var0": VAR_INF, "R": R, "Q": Q, "gate": 3.0, **kwargs}
    with pytest.raises(ValueError, match=rf"^{name} must"):
        kf.sim.plain_and_gated(**args)
