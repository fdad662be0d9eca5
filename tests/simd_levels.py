"""numpy's SIMD levels below this CPU's highest, as ``NPY_DISABLE_CPU_FEATURES`` values, one a line.

    python -m tests.simd_levels

numpy picks its SIMD code paths at run time, by CPU, and another level rounds the last bit of
a sine or an arctangent differently (``docs/development.md``).  ``make test`` repeats the
run-fact tests once for every level below the one this CPU runs at, with the levels above it
disabled, as a CPU of that level would run them:

- a CPU with AVX-512 (numpy's ``X86_V4``): once as an AVX2 machine (``X86_V3``), once at the
  x86-64-v2 baseline;
- an AVX2 CPU: once at the baseline;
- a baseline-only CPU, or another architecture: none (nothing lower to stand in for).

Disabling a level this CPU lacks would only repeat the main pass, so the list comes from
``numpy._core._multiarray_umath.__cpu_features__``.
"""

from __future__ import annotations

# numpy 2's x86 dispatch levels, lowest first; a level's extra features come with it.
LEVELS = (
    ("X86_V3",),
    ("X86_V4", "AVX512_ICL", "AVX512_SPR"),
)


def repeats(features: dict[str, bool]) -> list[str]:
    """For each level below this CPU's highest, the features to disable to run as that level."""
    have = [level for level in LEVELS if features.get(level[0], False)]
    out = []
    for i in range(len(have)):  # run as the level below have[i]: disable it and everything above it
        off = [name for level in have[i:] for name in level if features.get(name, False)]
        out.append(" ".join(off))
    return out[::-1]  # the nearest level first


def main() -> None:
    from numpy._core._multiarray_umath import __cpu_features__

    for line in repeats(__cpu_features__):
        print(line)


if __name__ == "__main__":
    main()
