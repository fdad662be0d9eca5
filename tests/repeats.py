"""The repeats of the run-fact tests: each as another CPU's rounding, perturbed.

    python -m tests.repeats                              one a line: name;features;size
    python -m tests.repeats run TIMES PYTEST ARGS...     run them, one after the other

Each line is ``name;features;size``: run the repeat with ``NPY_DISABLE_CPU_FEATURES="features"``
and ``pytest --perturb=size`` (``tests/rounding.py``), and call its report ``name``.  ``run`` does
that with the pytest command given, writing each report to ``TIMES/2-repeat-<name>.xml``, at a lower
priority (nice 10) and in a process group of its own: ``make test`` runs it beside the browser
suite and stops the whole group when it is interrupted.

numpy picks its SIMD code paths at run time, by CPU, and another level rounds the last bit of a
sine or an arctangent differently (``docs/development.md``).  A repeat runs as each level below
the one this CPU runs at, with the levels above it disabled, as a CPU of that level would:

- a CPU with AVX-512 (numpy's ``X86_V4``): once as an AVX2 machine (``X86_V3``), once at the
  x86-64-v2 baseline;
- an AVX2 CPU: once at the baseline;
- a baseline-only CPU, or another architecture: once as itself (nothing lower to stand in for).

Each repeat also scales every normal draw by ``1 + size``, with ``size`` = +1e-12, then -1e-12 in
the next repeat: a run whose last digits a chapter states moves under either change, so one pass
that makes both tests both, in the time of one.  Disabling a level this CPU lacks would only
repeat the main pass, so the levels come from ``numpy._core._multiarray_umath.__cpu_features__``.

A faster CPU can stand in for a slower one: ``NPY_DISABLE_CPU_FEATURES="X86_V4 AVX512_ICL" make test`` runs
every pass on an AVX-512 CPU as an AVX2 one would (numpy reads the variable in pass 1, the browser suite and
every kernel), and each repeat keeps those features off beside its own.
"""

from __future__ import annotations

import os
import shlex
import subprocess
import sys

# numpy 2's x86 dispatch levels, lowest first; a level's extra features come with it.
LEVELS = (
    ("X86_V3",),
    ("X86_V4", "AVX512_ICL", "AVX512_SPR"),
)
NAMES = ("x86-64-v2", "X86_V3")  # the level a repeat runs as, when the levels from LEVELS[i] up are off
SIZE = 1e-12  # the perturbation: every normal draw scaled by 1 +- SIZE


def simd_levels(features: dict[str, bool]) -> list[tuple[str, str]]:
    """For each level below this CPU's highest, nearest first: its name and the features to disable to run as it."""
    have = [i for i, level in enumerate(LEVELS) if features.get(level[0], False)]
    out = []
    for i in have:  # run as the level below LEVELS[i]: disable it and everything above it
        off = [name for level in LEVELS[i:] for name in level if features.get(name, False)]
        out.append((NAMES[i], " ".join(off)))
    return out[::-1]


def repeats(features: dict[str, bool], disabled: str = "") -> list[tuple[str, str, float]]:
    """The repeats: (name, features to disable, perturbation) for each level below this CPU's, signs alternating;
    one perturbed repeat as this CPU where there is no level below.  ``features`` are numpy's as this run sees
    them, with ``disabled`` (the environment's ``NPY_DISABLE_CPU_FEATURES``) off: they stay off in every repeat."""
    levels = simd_levels(features) or [("this-cpu", "")]
    kept = disabled.split()
    return [
        (name, " ".join(dict.fromkeys(kept + off.split())), SIZE if i % 2 == 0 else -SIZE)
        for i, (name, off) in enumerate(levels)
    ]


def run(times: str, pytest: list[str], planned: list[tuple[str, str, float]]) -> int:
    """Run each planned repeat with the ``pytest`` command, one after the other; the first failure's code, or 0."""
    os.setpgid(0, 0)  # a group of its own, which the caller can stop whole
    os.nice(10)  # its pytest processes and their kernels yield the CPU to the browser suite beside it
    for name, off, size in planned:
        command = [*pytest, f"--perturb={size!r}", f"--junitxml={times}/2-repeat-{name}.xml"]
        print(f'NPY_DISABLE_CPU_FEATURES="{off}" {shlex.join(command)}', flush=True)
        code = subprocess.call(command, env={**os.environ, "NPY_DISABLE_CPU_FEATURES": off})
        if code:
            return code
    return 0


def main() -> None:
    from numpy._core._multiarray_umath import __cpu_features__

    planned = repeats(__cpu_features__, os.environ.get("NPY_DISABLE_CPU_FEATURES", ""))
    if sys.argv[1:2] == ["run"]:
        sys.exit(run(sys.argv[2], sys.argv[3:], planned))
    for name, off, size in planned:
        print(f"{name};{off};{size!r}")


if __name__ == "__main__":
    main()
