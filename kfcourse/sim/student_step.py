"""A student's whole localization step, run round the loop (chapter 10's exercise).

:func:`localize_with_step` runs a function that does a whole step, prediction and updates, and checks what it
returns at every step, so that a mistake becomes a ``ValueError`` that names the function, the step and what went wrong.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import _validate as v
from ..filters.localization import _gate
from .loop_filters import _world
from .loop_records import Track
from .robot import RobotRun


def localize_with_step(world: RobotRun, step: Callable, Sig0, M, Q, gate: float, name: str = "step", mu0=None) -> Track:
    """The localization loop run by one function: ``step`` does a whole step, prediction and updates.

    ``step(mu, Sig, u, z, landmarks, dt, M, Q, gate) -> (mu, Sig, used)`` gets the readings
    of the landmarks in view at each step (chapter 10's exercise, the interface of
    :func:`~kfcourse.ekf_localization_step`).  Its prediction, for the record, is the same
    function with no reading.  What it returns is checked at every step: a
    ``ValueError`` names the function, the step and what went wrong.  The readings are labelled; the
    filter starts at ``mu0``, by default the true start.  Introduced in chapter 10.
    """
    world = _world(world)
    step = v.function(step, "step")
    Sig0 = v.covariance(Sig0, "Sig0", 3)
    M, Q = v.covariance(M, "M", 2), v.covariance(Q, "Q", 2)
    gate = _gate(gate)
    mu0 = world.start if mu0 is None else v.vector(mu0, "mu0", 3)
    T, L = world.visible.shape
    mu, Sig = np.array(mu0, dtype=float), np.array(Sig0, dtype=float)
    mu_bar, Sig_bar = np.empty((T, 3)), np.empty((T, 3, 3))
    mus, Sigs, used = np.empty_like(mu_bar), np.empty_like(Sig_bar), np.zeros((T, L), dtype=bool)
    nothing = np.empty((0, 2))
    for k in range(T):
        seen = np.flatnonzero(world.visible[k])
        u = world.odometry[k]
        mu_bar[k], Sig_bar[k], _ = _step_output(step, name, k, 0, mu, Sig, u, nothing, nothing, world.dt, M, Q, gate)
        z, marks = world.z[k, seen], world.landmarks[seen]
        mu, Sig, used[k, seen] = _step_output(step, name, k, len(seen), mu, Sig, u, z, marks, world.dt, M, Q, gate)
        mus[k], Sigs[k] = mu, Sig
    matched = np.where(used, np.arange(L), -1)  # each reading used as its own landmark's
    return Track(mu_bar=mu_bar, Sig_bar=Sig_bar, mu=mus, Sig=Sigs, used=used, matched=matched)


def _step_output(step, name, k, n_seen, *args):
    """Call a step function on copies of its inputs; its output checked, or a ValueError saying what went wrong."""
    where = f"the filter {name} at step {k} ({n_seen} reading{'s' if n_seen != 1 else ''})"
    try:
        out = step(*(np.array(a) if isinstance(a, np.ndarray) else a for a in args))
    except Exception as err:  # the student's code: whatever it raises becomes a message
        raise ValueError(f"{where} raised {type(err).__name__}: {err}") from None
    if not isinstance(out, tuple | list) or len(out) != 3:
        raise ValueError(f"{where} must return (mu, Sig, used), got {type(out).__name__}")
    try:
        mu = v.vector(out[0], "mu", 3)
    except ValueError as err:
        raise ValueError(f"{where} returned {_briefly(err, out[0])}") from None
    try:
        Sig = v.covariance(out[1], "Sig", 3)
    except ValueError as err:
        raise ValueError(f"{where} returned {_briefly(err, out[1])}") from None
    used = np.asarray(out[2])
    if used.shape != (n_seen,) or not (used.dtype == bool or np.isin(used, (0, 1)).all()):
        raise ValueError(f"{where} must return used, one True or False per reading, shape ({n_seen},); got {out[2]!r}")
    return mu, Sig, used.astype(bool)


def _briefly(err: ValueError, value) -> str:
    """A long message about a returned array, with the array printed to 3 digits on one line."""
    text = str(err)
    if len(text) <= 100 or ", got " not in text:
        return text
    try:
        shown = np.array2string(np.asarray(value, dtype=float), precision=3, separator=", ").replace("\n", "")
    except (TypeError, ValueError):
        return text[:100] + "..."
    return f"{text.split(', got ')[0]}, got {' '.join(shown.split())}"
