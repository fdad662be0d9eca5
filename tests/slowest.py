"""The slowest tests of ``make test``, from the JUnit XML reports its passes write.

    python -m tests.slowest DIR [N]

Reads every ``DIR/*.xml`` (one a pass, named after it) and prints the N slowest test cases
(default 15) with their pass, and each pass's test count and summed time: the figures
``docs/development.md`` quotes.
"""

from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def cases(folder: Path) -> list[tuple[float, str, str]]:
    """(seconds, pass, test) for every test case of every report in ``folder``."""
    out = []
    for report in sorted(folder.glob("*.xml")):
        for case in ET.parse(report).iter("testcase"):
            name = f"{case.get('classname', '')}::{case.get('name', '')}".lstrip(":")
            out.append((float(case.get("time", 0.0)), report.stem, name))
    return out


def main(argv: list[str]) -> int:
    folder, n = Path(argv[0]), int(argv[1]) if len(argv) > 1 else 15
    found = cases(folder)
    if not found:
        print(f"no test reports in {folder}")
        return 1
    print("\nper pass: tests, and their summed time (two workers share it)")
    for stem in sorted({p for _, p, _ in found}):
        times = [t for t, p, _ in found if p == stem]
        print(f"  {stem:<24}{len(times):>6} tests {sum(times):>9.1f} s")
    print(f"the {n} slowest tests of make test")
    for seconds, stem, name in sorted(found, reverse=True)[:n]:
        print(f"  {seconds:8.2f} s  {stem:<22} {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
