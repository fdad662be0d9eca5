"""The simulation helpers' error messages say what the argument is: a step, a distance or
a standard deviation is not called a variance, and a reliability is a probability."""

from __future__ import annotations

import re

import numpy as np
import pytest

import kfcourse as kf

pytestmark = pytest.mark.fact  # states facts of seeded runs: repeated under other rounding (tests/facts.py)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: kf.sim.drift_sigma(-0.1, 4), "step_std must be a standard deviation >= 0 m"),
        (lambda: kf.sim.simulate_line(sensor_std=0.0), "sensor_std must be a standard deviation > 0 m"),
        (lambda: kf.sim.motion_kernel(1.2), "reliability must be a probability in [0, 1]"),
        (lambda: kf.sim.door_likelihood([True, False], True, -0.1), "reliability must be a probability in [0, 1]"),
        (
            lambda: kf.sim.read_door(0, [True], 1.5, np.random.default_rng(0)),
            "reliability must be a probability in [0, 1]",
        ),
    ],
)
def test_message_says_what_the_argument_is(call, message):
    """A step, a distance or a standard deviation is not called a variance."""
    with pytest.raises(ValueError, match=re.escape(message)):
        call()
