"""Add the "Your turn" exercises to chapters 8 and 9, then store the two notebooks.

    python tools/add_exercises_8_9.py            # insert, then run tools/store_outputs.py on them
    python tools/add_exercises_8_9.py --no-store # insert only

Each chapter gets its section just before its last cell (the recap): a short
introduction, the exercise, a stub that raises ``NotImplementedError("your turn")``,
a ``# NBVAL_CHECK_OUTPUT`` cell that calls the checker on the stub (it shows "not
yet") and a link to the solution in ``notebooks/solutions.ipynb``, whose section
heading for the chapter becomes a link to it.  A notebook that already has its
section, or does not exist yet, is left alone.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
HEADING = "## Your turn"


def reflow(text: str) -> str:
    """Each paragraph as lines of at most 115 characters."""
    paragraphs = [p for p in text.strip().split("\n\n") if p.strip()]
    return "\n\n".join(textwrap.fill(" ".join(p.split()), 115) for p in paragraphs)


def intro(lead: str, cases: str) -> str:
    return f"""
{HEADING}

{lead} The exercise gives the first line of a function with the same signature as the package's; the body is
yours to write, in place of the line `raise NotImplementedError("your turn")`. The cell after it hands your
function to a checker, `kf.check.<name>`, which runs it on a dozen or more cases ({cases}; the random ones are
seeded, so they are the same every time) and compares each answer with `kfcourse`'s. It answers ✔ with what it
checked, or ✘ with the first case that differs (the inputs, the expected answer and yours) and, when a known wrong
version gives exactly your answer, the likely mistake and the equation to look at. Until you write the body it
says *not yet*.
"""


def section(text: str, stub: str, check: str, chapter: int) -> list:
    solutions = f"[solutions notebook](solutions.ipynb#Chapter-{chapter})"
    link = f"Stuck, or done and curious? One way to write it is in the {solutions}; try first."
    return [
        nbformat.v4.new_markdown_cell(reflow(text)),
        nbformat.v4.new_code_cell(stub.strip("\n")),
        nbformat.v4.new_code_cell(f"# NBVAL_CHECK_OUTPUT\n{check}"),
        nbformat.v4.new_markdown_cell(reflow(link)),
    ]


CHAPTER_8 = section(
    intro(
        "Now write the motion model yourself.",
        "the chapter's example θ = 0, V = 0.5, Δt = 1 and other straight lines with ω = 0, turning on the spot, a "
        "quarter circle, headings that cross ±π, and random poses and controls",
    )
    + r"""
**Exercise · The unicycle model.** Write `my_unicycle(state, u, dt)` for one pose `state = [x, y, theta]` and the
control `u = [V, omega]`: the pose after driving for `dt` seconds along this chapter's arc, returned as
`np.array([x, y, theta])`. Two details matter. At $\omega = 0$ the arc formula divides by zero, so drive the
straight line it tends to as $\omega \to 0$ there. And the new heading must lie in $(-\pi, \pi]$: wrap it
(`kf.wrap_angle` does).
""",
    '''
def my_unicycle(state, u, dt):
    """The pose after driving with u = [V, omega] for dt seconds from state = [x, y, theta]."""
    raise NotImplementedError("your turn")  # replace this line with your code
''',
    "kf.check.unicycle(my_unicycle)",
    8,
)

CHAPTER_9 = section(
    intro(
        "Now write the sigma points yourself.",
        "n = 1 with λ = 0, where the weights are 0, ½, ½, n = 1 with λ = 2, correlated covariances in two and three "
        "dimensions, and random ones up to n = 4 with negative λ too",
    )
    + r"""
**Exercise · Sigma points.** Write `my_sigma_points(mu, Sig, lam)` returning `(chi, wm, wc)`: the $2n + 1$ sigma
points of $\mathcal N(\mu, \Sigma)$, one a row of `chi` (first $\mu$, then $\mu$ plus each column of the lower
Cholesky factor $L$ of $(n + \lambda)\Sigma$, from `np.linalg.cholesky`, then $\mu$ minus each column), the weights
$w_0 = \lambda/(n + \lambda)$ and $w_i = 1/(2(n + \lambda))$ as `wm`, and the covariance weights `wc`, which here
equal `wm`.
""",
    '''
def my_sigma_points(mu, Sig, lam):
    """The 2n+1 sigma points of N(mu, Sig), one a row, and their weights: returns (chi, wm, wc)."""
    raise NotImplementedError("your turn")  # replace this line with your code
''',
    "kf.check.sigma_points(my_sigma_points)",
    9,
)

SECTIONS = {
    "08_ekf_localization.ipynb": (CHAPTER_8, "Chapter 8 · EKF localization with a known map"),
    "09_unscented_kalman_filter.ipynb": (CHAPTER_9, "Chapter 9 · The unscented Kalman filter"),
}


def add(name: str, cells: list) -> bool:
    """Insert ``cells`` before the last cell of the notebook ``name``; whether it changed."""
    path = NOTEBOOKS / name
    if not path.exists():
        print(f"{path}: not there yet, left alone")
        return False
    nb = nbformat.read(path, as_version=4)
    if any(c.cell_type == "markdown" and c.source.startswith(HEADING) for c in nb.cells):
        print(f"{path}: already has its {HEADING!r} section")
        return False
    nb.cells[-1:-1] = cells
    nbformat.write(nb, path)
    print(f"{path}: {len(cells)} cells inserted before the last cell")
    return True


def link_solution(name: str, title: str) -> None:
    """Make the chapter's name in its solutions section a link to the chapter."""
    path = NOTEBOOKS / "solutions.ipynb"
    nb = nbformat.read(path, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "markdown" and f"{title}." in cell.source and f"[{title}]" not in cell.source:
            cell.source = cell.source.replace(f"{title}.", f"[{title}]({name}).", 1)
            nbformat.write(nb, path)
            print(f"{path}: the chapter's section now links to {name}")


def main(store: bool) -> None:
    changed = []
    for name, (cells, title) in SECTIONS.items():
        if add(name, cells):
            link_solution(name, title)
            changed.append(str(NOTEBOOKS / name))
    if store and changed:
        subprocess.run([sys.executable, str(ROOT / "tools" / "store_outputs.py"), *changed], check=True)


if __name__ == "__main__":
    main(store="--no-store" not in sys.argv[1:])
