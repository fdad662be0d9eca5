"""Every solution of the fixed set through its checker, and what each verdict says.

    .venv/bin/python -m tests.check.wrong_set.report [checker ...] [--all]

For each wrong solution: caught (✘), named (the catalogue's key, when the verdict names one), and
"mentions": the verdict names a mistake, or its own words (not the closing "Compare your code with ..."
or "See ...", which name the exercise's equations whatever the mistake) mention the equation the
solution breaks or an input whose part it gets wrong.  That is a floor, counted by machine: whether a
verdict points at the mistake is a reader's judgement (docs/development.md, "The checkers", gives the
last reader's count), since many solutions name neither an equation nor an input.  Right solutions must
pass.  Prints one line per wrong solution whose verdict mentions neither (every one with --all), then a
summary per checker.
"""

from __future__ import annotations

import argparse
import importlib
import re
from collections import defaultdict
from pathlib import Path

import kfcourse as kf
from tests.check.wrong_set import SOLUTIONS, Solution

MODULES = sorted(p.stem for p in Path(__file__).parent.glob("ch*.py"))


def load() -> list[Solution]:
    for name in MODULES:
        importlib.import_module(f"tests.check.wrong_set.{name}")
    return SOLUTIONS


def _own_words(hint: str) -> str:
    """The verdict's hint without its closing pointer to the exercise's equations."""
    return re.split(r"(?:Compare your code with|See) chapter", hint)[0]


def _labels(text: str) -> set[str]:
    """The equation labels a text mentions, a range "(1)-(3)" as each of 1, 2, 3: {"1", "2", "3", "3'"}."""
    found = set(re.findall(r"\((\d+'?)\)", text))
    for a, b in re.findall(r"\((\d+)\)\s*[-–]\s*\((\d+)\)", text):
        found |= {str(n) for n in range(int(a), int(b) + 1)}
    return found


def verdict(solution: Solution) -> dict:
    result = getattr(kf.check, solution.checker)(solution.fn)
    words = _own_words(result.hint) + (result.headline if result.mistake == "changes_input" else "")
    at_equation = bool(_labels(solution.equation) & _labels(words))
    at_input = any(re.search(rf"(?<![\w]){re.escape(name)}(?![\w])", words) for name in solution.inputs)
    return {
        "caught": not result.passed,
        "named": result.mistake,
        "mentions": bool(result.mistake) or at_equation or at_input,
        "result": result,
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkers", nargs="*")
    parser.add_argument("--all", action="store_true", help="print every solution, not only the misses")
    args = parser.parse_args(argv)
    totals = defaultdict(lambda: defaultdict(int))
    for s in load():
        if args.checkers and s.checker not in args.checkers:
            continue
        v = verdict(s)
        t = totals[s.checker]
        if s.right:
            t["right"] += 1
            t["right passed"] += not v["caught"]
            if v["caught"] or args.all:
                print(f"RIGHT {s.checker:22s} {s.fn.__name__:40s} {'passed' if not v['caught'] else 'FAILED'}")
                if v["caught"]:
                    print("      " + v["result"].message.replace("\n", "\n      ")[:1500])
            continue
        t["wrong"] += 1
        t["caught"] += v["caught"]
        t["named"] += bool(v["named"])
        t["mentions"] += v["caught"] and v["mentions"]
        if args.all or not (v["caught"] and v["mentions"]):
            mark = "✘" if v["caught"] else "MISSED"
            print(
                f"{mark:6s} {s.checker:22s} {s.fn.__name__:40s} {s.equation:8s} {','.join(s.inputs):12s} "
                f"named={v['named']} mentions={v['mentions']}"
            )
            print(f"       meant: {s.what}")
            print(f"       said:  {_own_words(v['result'].hint)[:600]}")
    print(f"\n{'checker':24s} wrong caught mentions named | right passed")
    for checker, t in sorted(totals.items()):
        counts = f"{t['wrong']:5d} {t['caught']:6d} {t['mentions']:8d} {t['named']:5d}"
        print(f"{checker:24s} {counts} | {t['right']:5d} {t['right passed']:6d}")
    w = sum(t["wrong"] for t in totals.values())
    print(
        f"{'all':24s} {w:5d} {sum(t['caught'] for t in totals.values()):6d} "
        f"{sum(t['mentions'] for t in totals.values()):8d} {sum(t['named'] for t in totals.values()):5d}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
