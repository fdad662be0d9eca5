"""Chapter 12: a filter over a real robot's log, the Plaza2 run, and the settings that make it honest.

A run over the whole log costs 1.3 s (EKF) to 2.5 s (PF, N = 1000): far more than a control may take.  So
each demo's model keeps the last :data:`KEEP_RUNS` runs it made, by their settings (the trust sliders move in
steps of ×√10, so a setting comes back); nothing is kept at module level, and two demos share no run.  A
setting not run yet runs in the demo's worker process: the change is answered at once with the truth and the
ranges and the words "running the PF over the log…", and the run is drawn when it is done.  A process, not a
thread: a thread running the log would hold Python's lock, and the kernel's threads that send the picture, and
the next control's change, would wait for it.  Moving in time only redraws.  The first run, and every run
without an event loop (a script, a test), is made at once where it is first asked for: a script that changes
three settings, then looks, makes one run.  Either way the run is the same call to :mod:`kfcourse.sim`
(:meth:`RealRunModel.recipe`).
"""

from __future__ import annotations

import asyncio
import multiprocessing
import os
import signal
import threading
import weakref
from collections import OrderedDict
from collections.abc import Callable
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

import ipywidgets as widgets
import numpy as np

from .. import _validate as v
from ..data import load_plaza
from ..plots.real_run_view import real_run_view, update_real_run_view
from ..plots.style import FigureRenderer
from ..sim.range_particles import PF_NOISE, SCALE, range_particles
from ..sim.range_run import range_localize, smoothed
from ..sim.scores import HONEST_NEES, NEES_BAND, verdict
from ._base import Demo, shown, slider

LOG = "Plaza2"  # 410 s, 1.35 km, 4 090 odometry steps and 1 816 ranges
FIRST_FRAME = 60  # the second shown first: a minute in, the robot found by every filter from a known start
FILTERS = {  # the choice shown -> (the filter, the scale estimated and the gate whatever the toggles say)
    "EKF": ("ekf", False, False),
    "EKF + scale and gate": ("ekf", True, True),
    "UKF": ("ukf", False, False),
    "PF": ("pf", False, False),  # the PF assumes chapter 12's scale, 1.07, and has no gate: the toggles do nothing
}
# The EKF's and UKF's noise: chapter 12's honest tuning, odometry noise per metre driven.
NOISE = {"speed_std": 0.05, "turn_std": 0.01, "range_std": 0.7, "noise_per": "metre"}
GATE = 3.0  # standard deviations (chapter 8)
GUESS = (0.0, 0.0, 0.0)  # the EKF's start when it is not told: the plaza's origin, facing east ...
GUESS_STD = (30.0, 30.0, 3.0)  # ... with a first ellipse as wide as the plaza (chapter 12)
TRUST_RANGE = (-2.0, 2.0)  # log10 of the filter's R and Q against its tuning: 0.01x to 100x
TRUST_STEP = 0.5  # in log10: nine settings per slider, each a run the model keeps
SLIDER_FORMAT = ".2g"
N_PARTICLES = 1000
KEEP_RUNS = 32  # runs each model keeps, the least recently used dropped first: about 1 MB each
IMAGE_WIDTH = 460  # CSS px: the picture beside the column of controls, within a laptop's 848 px
COLUMN_WIDTH = 340  # CSS px


def _running_loop():
    """The event loop running in this thread (the kernel's), or None (a script, a test)."""
    try:
        return asyncio.get_running_loop()
    except RuntimeError:
        return None


def _worker_started() -> None:
    """In the worker process, once: deaf to the kernel's interrupt, which reaches the kernel's whole process group
    (the run under way ends, and the worker stays for the next ones), and second to the kernel, the browser and
    the server on the CPU (a run in the background must not slow the pictures that answer the student); it ends
    when the kernel is gone (:func:`_end_with_kernel`)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(os, "nice"):
        os.nice(10)
    threading.Thread(target=_end_with_kernel, daemon=True).start()


def _end_with_kernel() -> None:
    """In the worker process: end it once the process that started it is gone.  A kernel that exits cleanly tells
    its worker to stop; one killed outright (or a test process that leaves by ``os._exit``) cannot, and the worker
    would wait for work for ever, holding its memory."""
    multiprocessing.parent_process().join()  # returns when the kernel's end of the pipe to this process closes
    os._exit(0)


class RealRunModel:
    """Model: the settings of the filter over the log, its run, and the second shown.

    Attributes
    ----------
    log : PlazaLog
    seed : int
        The particle filter's draws.
    filter : str
        A key of :data:`FILTERS`.
    trust_motion, trust_sensor : float
        The filter's R and Q as multiples of its tuning (1: chapter 12's honest noise).
    scale, gate, known_start, smoothed : bool
        The toggles: the radio's scale estimated, the gate at :data:`GATE` (both for the EKF and the UKF, on
        whatever they say for "EKF + scale and gate", nothing for the PF, which assumes chapter 12's scale 1.07
        and has no gate; :meth:`settings`); the filter told where the robot starts; the RTS path shown (EKF).
    frame : int
        The second shown; ``row`` is the last pose at or before it.
    run : RangeRun, RangeParticleRun or None
        The run with these settings, or None while it is being made (or if it failed).  Without an event loop,
        and for the first picture, it is made at once when first read.
    smooth : RangeRun or None
        The smoother over ``run`` when shown (EKF runs) and ready.
    on_ready : callable
        Called on the event loop when a run made in the background is drawn; the wiring sets it.

    Notes
    -----
    The runs made are the model's own: an ordered dict by their settings (:meth:`key`), the one used last at
    its end, at most :data:`KEEP_RUNS` of them.  Only the event loop's thread reads or writes it (or the one
    thread of a script).  The worker process is started when a run is first made in the background, is handed
    the call that makes it (:meth:`recipe`), and hands the run back to the loop; it ends with the model.
    """

    def __init__(self, seed: int = 0):
        self.seed = v.whole(seed, "seed", 0)
        self.log = load_plaza(LOG)
        self.filter = "EKF"
        self.trust_motion = self.trust_sensor = 1.0
        self.scale = self.gate = self.smoothed = False
        self.known_start = True
        self.frame = FIRST_FRAME
        self.on_ready: Callable[[], None] = lambda: None
        self._runs: OrderedDict = OrderedDict()  # the runs made, by their settings (key), latest used last
        self._worker: ProcessPoolExecutor | None = None  # started when first needed (:meth:`_submit`)
        self._busy = None  # the settings being run in the background, if any
        self._failed: set = set()  # settings whose run raised: not tried again
        self._first = True  # the first run asked for is made at once, even on an event loop: the first picture

    # --- settings ---------------------------------------------------------------------------------

    def key(self, smooth: bool = False) -> tuple:
        """The settings that make the run (the seed only for the PF)."""
        kind, scale, gate = self.settings()
        trust = (round(np.log10(self.trust_motion), 3), round(np.log10(self.trust_sensor), 3))
        seed = self.seed if kind == "pf" else None
        return (LOG, kind, *trust, scale, gate, self.known_start, seed, smooth)

    def settings(self) -> tuple[str, bool, bool]:
        """The filter ("ekf", "ukf", "pf"), whether it estimates the scale and whether it gates: the toggles, or
        the filter's choice where it says so (:data:`FILTERS`); the PF neither (it assumes 1.07)."""
        kind, scale, gate = FILTERS[self.filter]
        if kind == "pf":
            return kind, False, False
        return kind, scale or self.scale, gate or self.gate

    def _kept(self, key: tuple):
        """The run kept for ``key``, or None; on the event loop's thread only, as :meth:`_keep`."""
        run = self._runs.get(key)
        if run is not None:
            self._runs.move_to_end(key)
        return run

    def _keep(self, key: tuple, run) -> None:
        """Keep ``run`` for ``key``, dropping the runs least recently used beyond :data:`KEEP_RUNS`."""
        self._runs[key] = run
        self._runs.move_to_end(key)
        while len(self._runs) > KEEP_RUNS:
            self._runs.popitem(last=False)

    def _make(self, key: tuple, base=None):
        """The run with the settings ``key``, made here (:meth:`recipe`)."""
        function, args, kwargs = self.recipe(key, base)
        return function(*args, **kwargs)

    def recipe(self, key: tuple, base=None) -> tuple[Callable, tuple, dict]:
        """The call that makes the run with the settings ``key``, as (function, arguments, keywords): the course's
        filters over the whole log, or the smoother over ``base``, the filter's run, for the smoother's settings."""
        _, kind, log_r, log_q, scale, gate, known, seed, smooth = key
        if smooth:
            return smoothed, (base,), {}
        r, q = np.sqrt(10.0**log_r), np.sqrt(10.0**log_q)  # R and Q scale as their standard deviations squared
        if kind == "pf":
            noise = {"speed_std": PF_NOISE["speed_std"] * r, "turn_std": PF_NOISE["turn_std"] * r}
            start = self.log.truth[0] if known else None
            kwargs = {"n_particles": N_PARTICLES, "seed": seed, **noise, "range_std": PF_NOISE["range_std"] * q}
            return range_particles, (self.log,), {**kwargs, "scale": SCALE, "start": start}
        noise = {**NOISE, "speed_std": NOISE["speed_std"] * r, "turn_std": NOISE["turn_std"] * r}
        noise["range_std"] = NOISE["range_std"] * q
        start = {} if known else {"start": GUESS, "start_std": GUESS_STD}
        kwargs = {"filter": kind, **noise, "scale": "online" if scale else 1.0, "gate": GATE if gate else None}
        return range_localize, (self.log,), {**kwargs, **start}

    def _wanted(self) -> list[tuple]:
        """The runs the picture needs: the filter's, and the smoother's over it when shown."""
        return [self.key(), self.key(smooth=True)] if self.smoother_shown else [self.key()]

    def _rerun(self) -> None:
        """On an event loop, have the worker process make the runs the settings need that are not kept, one at a
        time; without one, nothing: each run is made at once when it is first asked for (:meth:`_ready`)."""
        loop = _running_loop()
        if loop is None or self._busy is not None:
            return
        missing = [key for key in self._wanted() if self._kept(key) is None and key not in self._failed]
        if missing:
            self._busy = missing[0]
            base = self._kept((*missing[0][:-1], False))  # the smoother's input, read here: the runs are the loop's
            loop.call_soon(self._submit, missing[0], base, loop)  # once the change's picture is on its way

    def _ready(self, key: tuple):
        """The run for ``key``: the one kept; else, without an event loop or for the demo's first picture, made at
        once; else None (the worker is making it, or it failed)."""
        run = self._kept(key)
        if run is not None or key in self._failed or (_running_loop() is not None and not self._first):
            return run
        self._first = False
        base = self._ready((*key[:-1], False)) if key[-1] else None  # the smoother's: over the filter's run
        run = self._attempt(key, base)
        if run is None:
            self._failed.add(key)
        else:
            self._keep(key, run)
        return run

    def _attempt(self, key: tuple, base):
        """The run for ``key`` (:meth:`_make`), or None if it raised: a run that fails must neither leave the demo
        waiting for ever nor raise out of a control; it is said (:meth:`busy`) and not tried again."""
        try:
            return self._make(key, base)
        except Exception:
            return None

    def _submit(self, key: tuple, base, loop) -> None:
        """Hand the worker process the call that makes the run for ``key`` (starting it if need be); its run, or
        None if the call raised or the process died, comes back to the event loop (:meth:`_made`).  A process that
        died (killed, say) is replaced: before a run, the run goes to a new one; under a run, that run is said
        to have failed, and the next one starts a new process."""
        if self._worker is None:
            spawn = multiprocessing.get_context("spawn")  # a fresh interpreter: forking a kernel's threads is unsafe
            self._worker = ProcessPoolExecutor(1, mp_context=spawn, initializer=_worker_started)
            weakref.finalize(self, self._worker.shutdown, wait=False, cancel_futures=True)
        worker = self._worker
        function, args, kwargs = self.recipe(key, base)
        try:
            future = worker.submit(function, *args, **kwargs)
        except BrokenProcessPool:  # it died while idle
            self._worker = None
            self._submit(key, base, loop)
            return
        except Exception:  # it cannot take work (the kernel is shutting down): said as the run failing
            self._made(key, None)
            return

        def back(done: Future) -> None:  # in the executor's thread
            error = None if done.cancelled() else done.exception()
            run = None if done.cancelled() or error is not None else done.result()
            try:
                if isinstance(error, BrokenProcessPool):  # it died under this run
                    loop.call_soon_threadsafe(self._retire, worker)
                loop.call_soon_threadsafe(self._made, key, run)
            except RuntimeError:  # the loop was closed meanwhile: nobody waits for the run
                pass

        future.add_done_callback(back)

    def _retire(self, worker: ProcessPoolExecutor) -> None:
        """On the event loop: forget a worker whose process died; the next run starts a new one."""
        if self._worker is worker:
            self._worker = None

    def _made(self, key: tuple, run) -> None:
        """On the event loop: keep the run (or note that it failed), start the next one the settings need, redraw
        if it is shown."""
        self._busy = None
        if run is None:
            self._failed.add(key)
        else:
            self._keep(key, run)
        self._rerun()  # the settings may have moved on meanwhile: make what they need now
        if key in self._wanted():
            self.on_ready()

    @property
    def run(self):
        return self._ready(self.key())

    @property
    def smoother_shown(self) -> bool:
        """Whether the picture shows the smoother's path: asked for, and the filter an EKF (RTS is the EKF's)."""
        return self.smoothed and FILTERS[self.filter][0] == "ekf"

    @property
    def smooth(self):
        return self._ready(self.key(smooth=True)) if self.smoother_shown else None

    def busy(self) -> str:
        """What the picture says while a run it needs is not ready: the filter's, named with the settings that make
        it and whether the smoother follows (so that each setting's picture says which it waits for), or the
        smoother's ("" when all are ready)."""
        settings = self.changed()
        name = self.kind_name() + (f" ({settings})" if settings else "")
        if self.run is None:
            if self.key() in self._failed:
                return f"the {name} failed on this setting"
            return f"running the {name} over the log{', then the smoother' if self.smoother_shown else ''}…"
        if self.smoother_shown and self.smooth is None:
            failed = self.key(smooth=True) in self._failed
            return "the smoother failed on this run" if failed else "smoothing the EKF's run…"
        return ""

    def kind_name(self) -> str:
        return {"ekf": "EKF", "ukf": "UKF", "pf": "PF"}[FILTERS[self.filter][0]]

    # --- the controls' setters ------------------------------------------------------------------

    def set_filter(self, name: str) -> None:
        self.filter = name
        self._rerun()

    def set_trust_motion(self, ratio: float) -> None:
        self.trust_motion = float(ratio)
        self._rerun()

    def set_trust_sensor(self, ratio: float) -> None:
        self.trust_sensor = float(ratio)
        self._rerun()

    def set_scale(self, on: bool) -> None:
        self.scale = bool(on)
        self._rerun()

    def set_gate(self, on: bool) -> None:
        self.gate = bool(on)
        self._rerun()

    def set_start(self, start: str) -> None:
        self.known_start = start == "known"
        self._rerun()

    def set_smoothed(self, on: bool) -> None:
        self.smoothed = bool(on)
        self._rerun()

    # --- what is shown --------------------------------------------------------------------------

    @property
    def row(self) -> int:
        """The last pose at or before the second shown."""
        return int(np.searchsorted(self.log.t_truth, self.frame, side="right") - 1)

    def arrivals(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The ranges that arrived in the second shown: their beacons (R, 2), the ranges (R,), and whether the
        filter used each (all of them while its run is not ready, and for the PF)."""
        log = self.log
        i = np.flatnonzero((log.t_range > self.frame - 1) & (log.t_range <= self.frame))
        run = self.run
        used = run.used[i] if run is not None and hasattr(run, "used") else np.ones(i.size, bool)
        return log.beacons[log.beacon[i]], log.range[i], used

    def describe(self) -> str:
        """The time shown, the ranges of that second, the filter's error there and whether the truth is inside its
        3σ ellipse (a position NEES of at most 9, :attr:`~kfcourse.sim.RangeRun.inside`), then the whole run's
        mean error and what its mean NEES says (:func:`~kfcourse.sim.verdict`: honest within
        :data:`~kfcourse.sim.HONEST_NEES`)."""
        k, run = self.row, self.run
        _, ranges, used = self.arrivals()
        refused = int(np.count_nonzero(~used))
        heard = f"{ranges.size} range{'s' if ranges.size != 1 else ''} arrived this second"
        heard += f", {refused} refused by the gate" if refused else ""
        at = f"At t = {self.frame} s"
        settings = self.changed()
        name = f"the {self.filter}" + (f" ({settings})" if settings else "")
        if run is None and self.key() in self._failed:
            return f"{at}: {heard}; {name} failed on this setting, so no estimate is drawn: choose another setting."
        if run is None:
            return f"{at}: {heard}; {name} is still running over the log, its estimate comes when it is done."
        inside = "inside" if run.inside[k] else "outside"  # the drawn 3σ ellipse: a NEES of at most 3²
        mean_nees = float(np.mean(run.nees))
        if np.isfinite(mean_nees):
            nees_said = f"mean NEES {mean_nees:.3g}"
        else:  # a cloud collapsed onto one particle: a flat ellipse the truth is off (kf.sim.nees)
            flat = int(np.count_nonzero(~np.isfinite(run.nees)))
            poses = f"{flat} pose{'s' if flat != 1 else ''}"
            nees_said = f"mean NEES without bound (at {poses} its ellipse is flat, the truth off it)"
        said = (
            f"{at}: {heard}; {name} is {shown(float(run.error[k]), '.2f')} m off, the truth {inside} its 3σ "
            f"ellipse. Over the whole run it is {shown(float(np.mean(run.error)), '.2f')} m off on average, "
            f"{nees_said}: {verdict(mean_nees)} (honest: a mean of {HONEST_NEES[0]:g} to {HONEST_NEES[1]:g})."
        )
        smooth = self.smooth
        if self.smoothed and not self.smoother_shown:
            said = said[:-1] + "; the smoother here is the EKF's (RTS): choose an EKF to see it."
        elif smooth is not None:
            said = said[:-1] + f"; smoothed, {shown(float(np.mean(smooth.error)), '.2f')} m off on average."
        return said

    def changed(self) -> str:
        """The settings the filter's name does not say: trust, scale, gate, start ("" if none)."""
        parts = [
            f"{label} ×{shown(value, SLIDER_FORMAT)}"
            for label, value in (("R", self.trust_motion), ("Q", self.trust_sensor))
            if shown(value, SLIDER_FORMAT) != shown(1.0, SLIDER_FORMAT)
        ]
        kind, scale, gate = FILTERS[self.filter]
        if kind != "pf":
            parts += ["scale estimated"] if self.scale and not scale else []
            parts += ["gated"] if self.gate and not gate else []
        if not self.known_start:
            parts.append("start unknown")
        return ", ".join(parts)


def _controls(model: RealRunModel) -> dict:
    """The filter, its trust in its odometry (R) and in its ranges (Q), the scale, the gate, the start, the smoother.

    A new setting runs the whole log once, in the background: the sliders report where they are let go."""
    log = {"readout_format": SLIDER_FORMAT, "continuous_update": False, "base": 10}
    R, Q = (slider(widgets.FloatLogSlider, f"filter's {x} ×", 1.0, *TRUST_RANGE, TRUST_STEP, **log) for x in "RQ")
    choice = widgets.ToggleButtons(
        options=list(FILTERS), value=model.filter, description="filter",
        style={"button_width": "auto", "description_width": "40px"},
    )  # fmt: skip
    toggles = {
        key: widgets.ToggleButton(value=value, description=label, tooltip=tip, layout=widgets.Layout(width="105px"))
        for key, value, label, tip in (
            ("scale", model.scale, "scale", "Estimate the radio's scale (EKF, UKF)"),
            ("gate", model.gate, "gate", f"Refuse a range more than {GATE:g} standard deviations off"),
            ("smoothed", model.smoothed, "smoothed", "Show the RTS smoother's path (EKF)"),
        )
    }
    start = widgets.ToggleButtons(options=["known", "unknown"], value="known", description="start")
    return {
        "filter": (choice, model.set_filter),
        "trust_motion": (R, model.set_trust_motion),
        "trust_sensor": (Q, model.set_trust_sensor),
        "scale": (toggles["scale"], model.set_scale),
        "gate": (toggles["gate"], model.set_gate),
        "start": (start, model.set_start),
        "smoothed": (toggles["smoothed"], model.set_smoothed),
    }


CAPTION = (
    "<b>The real run.</b> Plaza2: 410 s of a real robot's wheel odometry and radio ranges to four beacons (purple "
    "squares). Grey: the true path (dotted) and robot. Orange: each range as an arc of its circle about its beacon, "
    "in the second it arrives (dotted: refused by the gate). Teal: the filter's trail, robot and 3σ ellipse (the "
    "truth inside it: a position NEES of at most 9); pale band: the smoother's path. Strip: the position NEES of "
    f"every pose; shaded, where an honest filter's lies at 95 % of its poses ({NEES_BAND[0]:.2f} to "
    f"{NEES_BAND[1]:.1f}, chi-square with 2 degrees of freedom), dotted its average, 2. The verdict under the "
    f"picture reads the whole run's mean NEES: honest from {HONEST_NEES[0]:g} to {HONEST_NEES[1]:g}. "
    "<i>filter's R</i> / <i>Q</i>: its odometry and range noise, times chapter 12's tuning. "
    "<i>scale</i>: the EKF or UKF estimates the radio's scale; <i>gate</i>: it refuses ranges over 3σ off "
    "(<i>EKF + scale and gate</i> does both; the PF assumes the scale 1.07, without a gate). <i>start</i>: told, "
    "or a guess 57 m off with an ellipse as wide as the plaza (the PF: its cloud spread over it). "
    "<i>smoothed</i>: the EKF's RTS path."
)


def real_run(seed: int = 0) -> Demo:
    """Demo "the real run" (chapter 12): the course's EKF, UKF or particle filter over the Plaza2 log.

    Run plays the log a second per frame, the time slider scrubs it.  The filter's choice, its R and Q (log
    sliders), the scale, the gate and the start each pick a setting; a setting not seen yet runs the whole log
    in the background (1 to 3 s) while the picture shows the truth and the ranges.  *smoothed* overlays the RTS
    smoother's path (EKF runs).  ``seed`` seeds the particle filter.

    Returns
    -------
    Demo (an ipywidgets.VBox)
    """
    model = RealRunModel(seed)
    view = real_run_view(model)
    controls = _controls(model)
    demo = Demo(
        name="real-run",
        caption=CAPTION,
        model=model,
        renderer=FigureRenderer(view.fig, view.moving),
        draw=lambda: update_real_run_view(view, model),
        describe=model.describe,
        frames=int(np.floor(model.log.t_truth[-1])) + 1,
        controls=controls,
        beside=[["play", "frame"], "filter", "trust_motion", "trust_sensor", ["scale", "gate", "smoothed"], "start"],
        display_width=IMAGE_WIDTH,
    )
    demo.controls["frame"].layout.width = f"{COLUMN_WIDTH - 90}px"
    demo.controls["frame"].description = "t (s)"  # a frame is a second of the log
    demo.description.names = {**demo.description.names, "frame": "t (s)"}
    model.on_ready = demo.refresh
    return demo
