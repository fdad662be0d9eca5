"""axe-core in a Playwright page: the WCAG 2.1 A and AA checks a browser test can run.

axe-core is pinned in ``package.json`` / ``package-lock.json`` and installed by ``npm ci``
(``make test`` runs it when ``node_modules/axe-core/axe.min.js`` is missing or older than
the lock file).  Two functions::

    from tests.browser.axe import run_axe, format_violations

    violations = run_axe(page, ["main"], exclude=[".some-widget"])
    assert not violations, format_violations(violations)

:func:`run_axe` injects ``axe.min.js`` into the page (once) and runs every rule tagged
``wcag2a``, ``wcag2aa``, ``wcag21a`` or ``wcag21aa`` on the elements the selectors name;
:func:`format_violations` says what failed, where, and why, for an assertion message.
Without ``axe.min.js`` the calling test fails and says to run ``npm ci`` (it never skips:
a skipped check would look like a passed one).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
AXE_JS = REPO_ROOT / "node_modules" / "axe-core" / "axe.min.js"
WCAG_TAGS = ("wcag2a", "wcag2aa", "wcag21a", "wcag21aa")
NODES_SHOWN = 8  # per rule in format_violations; the rest are counted

JS_RUN = """async ([include, exclude, tags]) => {
    const context = exclude.length ? {include, exclude} : {include};
    const options = {runOnly: {type: "tag", values: tags}, resultTypes: ["violations"]};
    const results = await window.axe.run(context, options);
    return results.violations.map(v => ({
        id: v.id, impact: v.impact, help: v.help, helpUrl: v.helpUrl,
        nodes: v.nodes.map(n => ({target: n.target, html: n.html, summary: n.failureSummary})),
    }));
}"""


def run_axe(page, include: Sequence[str], exclude: Sequence[str] = ()) -> list[dict]:
    """The WCAG 2.1 A/AA violations axe-core finds in the parts of ``page`` that ``include`` names.

    Parameters
    ----------
    page : playwright.sync_api.Page
        A page that has loaded (and drawn what is to be checked).
    include : sequence of str
        CSS selectors of the parts to check, e.g. ``["main"]`` or ``["html"]`` for the whole page.
        A selector that matches nothing makes axe-core raise (as a Playwright error).
    exclude : sequence of str, optional
        CSS selectors of parts inside those to leave out.

    Returns
    -------
    list of dict
        One dict per rule that failed: ``id``, ``impact``, ``help``, ``helpUrl`` and ``nodes``,
        each node a dict with ``target`` (its selectors), ``html`` (its opening) and ``summary``
        (axe-core's account of what is wrong).  Empty when nothing failed.
    """
    if isinstance(include, str) or not include:
        raise ValueError(f"include must be a non-empty sequence of CSS selectors, got {include!r}")
    if isinstance(exclude, str):
        raise ValueError(f"exclude must be a sequence of CSS selectors, got {exclude!r}")
    if not AXE_JS.exists():
        pytest.fail(
            f"{AXE_JS.relative_to(REPO_ROOT)} is missing: run `npm ci` in {REPO_ROOT} "
            "(make test does) to install the pinned axe-core",
            pytrace=False,
        )
    if not page.evaluate("() => typeof window.axe === 'object' && typeof window.axe.run === 'function'"):
        page.add_script_tag(path=str(AXE_JS))
    return page.evaluate(JS_RUN, [list(include), list(exclude), list(WCAG_TAGS)])


def format_violations(violations: list[dict]) -> str:
    """``violations`` from :func:`run_axe` as readable lines: each rule's id, impact and help,
    then each failing element's selector and what is wrong with it (at most ``NODES_SHOWN``)."""
    if not violations:
        return "no accessibility violations"
    lines = [f"{len(violations)} WCAG 2.1 A/AA rule(s) failed:"]
    for v in violations:
        lines.append(f"- {v['id']} ({v['impact']}): {v['help']}, {len(v['nodes'])} element(s); {v['helpUrl']}")
        for node in v["nodes"][:NODES_SHOWN]:
            target = " ".join(str(t) for t in node["target"])
            summary = " ".join(node["summary"].split()) if node["summary"] else ""
            lines.append(f"    {target}: {summary}")
        if len(v["nodes"]) > NODES_SHOWN:
            lines.append(f"    ... and {len(v['nodes']) - NODES_SHOWN} more")
    return "\n".join(lines)
