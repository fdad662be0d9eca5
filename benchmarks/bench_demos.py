"""Kernel-side latency of every demo: control change -> new picture ready.

Run by hand (not part of the test suite):

    .venv/bin/python benchmarks/bench_demos.py

For each demo, every slider is swept back and forth across its range, every
button pressed, every row of toggle buttons switched through its options, and
the animation frame stepped; each change is timed from the moment the control's
value is set until the demo's image widget holds the new PNG (observers run
synchronously, so that is the time the kernel is busy).
Targets: median <= 50 ms, p95 <= 100 ms.
"""

from __future__ import annotations

import time

import ipywidgets as widgets
import numpy as np

import kfcourse as kf

DEMOS = kf.demos.__all__  # every demo the course ships
SWEEP = 40  # changes per slider
PRESSES = 30  # presses per button
MEDIAN_TARGET = 50.0  # ms
P95_TARGET = 100.0  # ms


def sweep_values(control) -> list:
    lo, hi = control.min, control.max
    values = np.concatenate([np.linspace(lo, hi, SWEEP // 2), np.linspace(hi, lo, SWEEP // 2)])
    if isinstance(control, widgets.FloatLogSlider):
        values = control.base**values
    if isinstance(control, widgets.IntSlider):
        values = np.round(values).astype(int)
    return [v.item() for v in values]


def timed(change) -> float:
    t0 = time.perf_counter()
    change()
    return 1e3 * (time.perf_counter() - t0)


def measure(name: str) -> list[float]:
    demo = getattr(kf.demos, name)(seed=0)
    samples = []
    for control in demo.controls.values():
        if isinstance(control, (widgets.IntSlider, widgets.FloatSlider, widgets.FloatLogSlider)):
            for value in sweep_values(control):
                if value != control.value:
                    samples.append(timed(lambda c=control, v=value: setattr(c, "value", v)))
        elif isinstance(control, widgets.Button):
            samples += [timed(control.click) for _ in range(PRESSES)]
        elif isinstance(control, widgets.ToggleButtons):  # every option in turn
            options = list(control.options)
            for i in range(1, PRESSES + 1):
                option = options[i % len(options)]
                samples.append(timed(lambda c=control, v=option: setattr(c, "value", v)))
    return samples


def main() -> None:
    print(f"{'demo':<20}{'changes':>8}{'median ms':>11}{'p95 ms':>9}{'max ms':>9}")
    ok = True
    for name in DEMOS:
        ms = np.array(measure(name))
        med, p95 = np.median(ms), np.percentile(ms, 95)
        ok &= med <= MEDIAN_TARGET and p95 <= P95_TARGET
        print(f"{name:<20}{ms.size:>8}{med:>11.1f}{p95:>9.1f}{ms.max():>9.1f}")
    verdict = "met" if ok else "NOT met"
    print(f"targets (median <= {MEDIAN_TARGET:.0f} ms, p95 <= {P95_TARGET:.0f} ms): {verdict}")


if __name__ == "__main__":
    main()
