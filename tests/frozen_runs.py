"""One build per test process of each frozen run the tests share.

``kf.sim.landmark_loop`` and ``kf.sim.particle_loop`` are functions of their arguments alone: the
same seed and settings give the same run, bit for bit, and the record they return is frozen, its
arrays read-only.  Many tests build the same run (a demo's opening lap, seed 0's normal lap, the
prompts' seeds), so within one pytest process each is built once and handed out again.

Only a call whose every argument is a number, a string, a bool, None or a tuple of those is kept:
a call given a function (a student's step), an array or another run (``since=``) is run each
time.  Handing out a kept run counts as making a seeded generator (``tests/facts.py``): a test
that uses a seeded run is seen by the ``fact`` guard whether the run was built for it or before.
The repeats run in processes of their own, so a run kept there was built under their rounding.
``kf.sim.family_table`` is left to build its own runs: it times one of them.
"""

from __future__ import annotations

import functools
import sys

import numpy as np

_PLAIN = (int, float, str, bool, type(None), np.integer, np.floating, np.bool_)


def _plain(value) -> bool:
    """Whether ``value`` is a number, a string, a bool, None, or a tuple of those."""
    if isinstance(value, tuple):
        return all(_plain(v) for v in value)
    return isinstance(value, _PLAIN)


def _kept(build, counted):
    """``build`` with its plain calls kept; ``counted()`` is called on each run handed out again."""
    runs = {}

    @functools.wraps(build)
    def run(*args, **kwargs):
        if not (all(_plain(a) for a in args) and all(_plain(v) for v in kwargs.values())):
            return build(*args, **kwargs)
        key = (args, tuple(sorted(kwargs.items())))
        if key in runs:
            counted()
            return runs[key]
        runs[key] = build(*args, **kwargs)
        return runs[key]

    return run


def install(counted) -> None:
    """Keep the runs of ``landmark_loop`` and ``particle_loop`` wherever the course's modules hold them."""
    import kfcourse.demos  # noqa: F401  (every module that holds a run's builder, imported)
    from kfcourse.sim import family, landmark_lap, particle_lap  # noqa: F401

    for build in (landmark_lap.landmark_loop, particle_lap.particle_loop):
        kept = _kept(build, counted)
        for name, module in list(sys.modules.items()):
            # family_table times a lap of particle_loop: a kept run would time nothing, so it builds its own
            if (name == "kfcourse" or name.startswith("kfcourse.")) and name != "kfcourse.sim.family":
                for attribute, value in list(vars(module).items()):
                    if value is build:
                        setattr(module, attribute, kept)
