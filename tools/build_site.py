"""Build the static HTML edition of the course: every chapter executed, with pictures of the demos.

    python tools/build_site.py            # -> site/index.html and one page per chapter
    python tools/build_site.py --out DIR --notebooks DIR

Every ``notebooks/NN_*.ipynb`` becomes ``NN_*.html``; the notation table (``notation.ipynb``)
and the solutions (``solutions.ipynb``), where there are, come last.  The notebooks are stored
clean, so each one is executed here, with nbclient and the course's own kernel: two chapters at
a time, each in a kernel of its own (``--jobs``), the longest first, and every kernel talks to
the build over CurveZMQ-encrypted transport, as under ``make lab`` (``kernel_config``).
nbconvert's JupyterLab template turns it into HTML; equations are typeset in the reader's
browser by a copy of MathJax 2.7 from the ``jupyter-server-mathjax`` package
(requirements-dev.txt), served from ``_static/mathjax`` beside the pages: no CDN.

A page has no kernel, so a demo's live widget cannot show there.  A demo shown as the last
value of a cell also hands the notebook a PNG of the picture it shows at first
(``Demo._repr_mimebundle_``); the page shows that picture, with the demo's description (one
sentence from its numbers: the picture's alt text, and the first line under it) and its
caption under it.  A demo with Run/Pause also gets a recording of its run
(``tools/recording.py``, run in the same kernel, saved as a ``.webp`` file in ``media/``), as
many pixels wide as the still and shown in its place, but only when the reader presses
"Play the run" (a toggle button; pressed again, the still comes back): nothing on a page
moves by itself (WCAG 2.2.2).  ``site/demos.json`` lists the pages and their demo pictures.

Every page is meant to pass the WCAG 2.1 A and AA checks of axe-core
(tests/browser/test_site.py): the chapter inside a ``<main>`` landmark with the navigation
outside it, code colours and ``In [n]:`` prompts at 4.5:1 contrast or more, links in running
text underlined, and one small inline script (the play buttons), nothing from outside the site.

The ``# NBVAL_CHECK_OUTPUT`` line that opens the cells whose printed numbers the tests check
is left out of the pages: it speaks to the test runner, not to a reader.
"""

from __future__ import annotations

import argparse
import asyncio
import base64
import html
import io
import json
import os
import re
import shutil
import sys
import tempfile
import time
from importlib import resources
from pathlib import Path

import jinja2
import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter
from PIL import Image

if __package__ in (None, ""):  # run as a script: the repository's root on the path, as with -m
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from kfcourse.plots.palette import ESTIMATE_TEXT
from tools.kernels import kernel_config

ROOT = Path(__file__).resolve().parents[1]
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
PROBE_MIME = "application/vnd.kfcourse.demo+json"
CHAPTER = re.compile(r"\d\d_[a-z0-9_]+\.ipynb")
CELL_TIMEOUT_S = 600
JOBS = min(2, os.cpu_count() or 1)  # chapters executed at once, each in its own kernel
MATHJAX_URL = "_static/mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full,Safe"
RECORDING = ROOT / "tools" / "recording.py"
NBVAL_MARKER = re.compile(r"\A# NBVAL_[A-Z_]+[ \t]*\r?(\n|\Z)")  # a first line that speaks to nbval alone

# Run in the notebook's kernel after a cell that showed a demo: its caption (whole: the live demo
# folds its key under the title, a printed page has room for it), its description (the sentence
# that says what its picture shows), and for a demo with Run/Pause a recording of its run and the
# description of the run's last frame, made in one pass over the run by tools/recording.py
# (``record``) loaded from its file.  The widget is found by the model id of its view.
PROBE = """\
import base64 as _b64, importlib.util as _iu, ipywidgets as _w
from IPython.display import display as _display
_demo = _w.widget_serialization["from_json"]("IPY_MODEL_{model_id}", None)
_spec = _iu.spec_from_file_location("kfsite_recording", {recording!r})
_recording = _iu.module_from_spec(_spec)
_spec.loader.exec_module(_recording)
_runs = "frame" in _demo.controls
_run, _last = _recording.record(_demo) if _runs else (None, None)
_display({{"{mime}": {{
    "caption": _demo.caption,
    "description": _demo.description.text,
    "recording": _b64.b64encode(_run).decode() if _runs else None,
    "last_frame": _last,
}}}}, raw=True)
del _demo, _spec, _recording, _runs, _run, _last
"""

TEMPLATE = r"""{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{%- block jupyter_widgets -%}{%- endblock jupyter_widgets -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
{%- block html_head_js_mathjax -%}
<script type="text/x-mathjax-config">
MathJax.Hub.Config({
  tex2jax: {inlineMath: [["$", "$"], ["\\(", "\\)"]], displayMath: [["$$", "$$"], ["\\[", "\\]"]],
            processEscapes: true, processEnvironments: true},
  TeX: {equationNumbers: {autoNumber: "AMS", useLabelIds: true}},
  "HTML-CSS": {availableFonts: [], preferredFont: null, webFont: "STIX-Web", imageFont: null},
  displayAlign: "center",
  messageStyle: "none"
});
{# The combined config also starts the NativeMML output (unused: HTML-CSS typesets), whose styles
    declare @font-face rules for MathJax's TeX fonts, which jupyter-server-mathjax does not ship.  The
    hidden MathML copy kept for screen readers (AssistiveMML) matches them, e.g. \mathcal N is
    <mi mathvariant="script">, so Chromium asked for fonts/HTML-CSS/TeX/otf/MathJax_Script-Regular.otf
    and got a 404.  Those rules are dropped before NativeMML adds its styles to the page. -#}
MathJax.Hub.Register.StartupHook("NativeMML Jax Startup", function () {
  var styles = MathJax.OutputJax.NativeMML.config.styles;
  for (var rule in styles) { if (rule.indexOf("@font-face") === 0) { delete styles[rule]; } }
});
</script>
<script src="{{ resources.mathjax_url }}"></script>
{%- endblock html_head_js_mathjax -%}
{%- block html_head_css -%}
<style type="text/css">
{{ resources.kf_css }}
</style>
{%- endblock html_head_css -%}
{%- block body_header -%}
<body class="jp-Notebook" data-jp-theme-light="true" data-jp-theme-name="JupyterLab Light">
{{ resources.kf_nav }}
<main>
{%- endblock body_header -%}
{%- block body_footer -%}
</main>
{{ resources.kf_nav_bottom }}
<script>
{{ resources.kf_script }}
</script>
</body>
{%- endblock body_footer -%}
"""

# After JupyterLab's own styles, so that these win.  The light theme's code colours and its
# dimmed prompts fall below WCAG AA: here every code colour is at least 4.5:1 on the code
# background (#f5f5f5), the prompts at least 4.5:1 on white (the ratios in the comments),
# with the hues of JupyterLab's theme kept.
SITE_CSS = """
:root {
  --jp-mirror-editor-keyword-color: #007000;    /* 5.8:1 */
  --jp-mirror-editor-builtin-color: #007000;
  --jp-mirror-editor-number-color: #0b6e4f;     /* 5.7:1 */
  --jp-mirror-editor-comment-color: #3b6e6e;    /* 5.3:1 */
  --jp-mirror-editor-operator-color: #8b1ed6;   /* 5.9:1 */
  --jp-mirror-editor-meta-color: #8b1ed6;
  --jp-mirror-editor-string-color: #ba2121;     /* 5.8:1 */
  --jp-mirror-editor-punctuation-color: #0055aa; /* 6.7:1 */
  --jp-mirror-editor-property-color: #0055aa;
  --jp-mirror-editor-def-color: #0000ff;        /* 7.9:1 */
  --jp-mirror-editor-atom-color: #4646d8;       /* 6.2:1 */
  --jp-mirror-editor-variable-color: #212121;   /* 14.8:1 */
  --jp-mirror-editor-qualifier-color: #555555;  /* 6.8:1 */
  --jp-mirror-editor-bracket-color: #6b6b52;    /* 5.0:1 */
  --jp-mirror-editor-tag-color: #117700;        /* 5.3:1 */
  --jp-mirror-editor-attribute-color: #0000cc;  /* 10.3:1 */
  --jp-mirror-editor-link-color: #0000cc;
  --jp-mirror-editor-header-color: #0000ff;
  --jp-mirror-editor-quote-color: #007a00;      /* 5.1:1 */
  --jp-mirror-editor-error-color: #d00000;      /* 5.2:1 */
  --jp-mirror-editor-hr-color: #6e6e6e;
  --jp-cell-prompt-not-active-opacity: 1;
  --jp-cell-prompt-not-active-font-color: #616161; /* 6.2:1 on white */
  --jp-cell-inprompt-font-color: #2a6fab;       /* 5.3:1 on white */
  --jp-cell-outprompt-font-color: #a8462a;      /* 5.9:1 on white */
}
/* a link in running text is underlined, not told apart by its colour alone */
.jp-RenderedHTMLCommon a:link, .jp-RenderedHTMLCommon a:visited, .jp-RenderedText pre a:link,
.jp-RenderedText pre a:visited { text-decoration: underline; }
nav.kf-nav { display: flex; justify-content: space-between; gap: 1em; padding: 0.6em 1em;
  font: 14px/1.4 var(--jp-ui-font-family, sans-serif); border-bottom: 1px solid #ddd; }
nav.kf-nav.kf-bottom { border-top: 1px solid #ddd; border-bottom: none; margin-top: 2em; }
div.kf-demo-static figure { margin: 0.5em 0 1em; }
div.kf-demo-static img { max-width: 100%; height: auto; display: block; margin: 0.4em 0; }
div.kf-demo-static img[hidden] { display: none; }
div.kf-demo-static .kf-description { color: #212121; font-size: 14px; line-height: 1.45; margin: 0.3em 0; }
div.kf-demo-static .kf-caption { color: #333333; font-size: 13px; line-height: 1.4; }
div.kf-demo-static .kf-note { color: #595959; font-size: 12px; font-style: italic; margin: 0.3em 0 0; }
div.kf-demo-static .kf-run { display: flex; align-items: center; gap: 0.8em; margin: 0.3em 0 0.5em; }
div.kf-demo-static .kf-run .kf-note { margin: 0; }
button.kf-play { font: 600 14px/1.2 var(--jp-ui-font-family, sans-serif); padding: 0.4em 0.9em;
  flex: none; white-space: nowrap; cursor: pointer;
  color: {accent}; background: #ffffff; border: 2px solid {accent}; border-radius: 4px; }
button.kf-play:hover { background: #e6f2f0; }
button.kf-play[aria-pressed="true"] { color: #ffffff; background: {accent}; }
button.kf-play:focus-visible { outline: 3px solid #1a1a1a; outline-offset: 2px; }
button.kf-play .kf-icon::before { content: "\\25B6\\FE0E"; }
button.kf-play[aria-pressed="true"] .kf-icon::before { content: "\\25A0\\FE0E"; }
button.kf-play .kf-icon { display: inline-block; width: 1.2em; }
""".replace("{accent}", ESTIMATE_TEXT)  # the course's teal of the estimate, as text on white

# The "Play the run" buttons: pressed, the recording replaces the still and plays from its
# first picture; pressed again, the still comes back and nothing moves.  The recording's file
# is fetched on the first press only.
SITE_SCRIPT = """
document.addEventListener("click", (event) => {
  const button = event.target.closest("button.kf-play");
  if (!button) return;
  const figure = button.closest("figure");
  const still = figure.querySelector("img.kf-demo-picture");
  const run = figure.querySelector("img.kf-demo-animation");
  const play = button.getAttribute("aria-pressed") !== "true";
  if (play) run.src = run.dataset.src;
  else run.removeAttribute("src");
  run.hidden = !play;
  still.hidden = play;
  button.setAttribute("aria-pressed", String(play));
});
"""

INDEX = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1.0">
<title>kfcourse: the Kalman filter family, step by step</title>
<style>
  body {{ font: 16px/1.5 system-ui, sans-serif; max-width: 46em; margin: 2em auto; padding: 0 1em; color: #222; }}
  ul.kf-chapters {{ list-style: none; padding-left: 0; }} li {{ margin: 0.5em 0; }} .kf-lead {{ color: #555; }}
</style>
</head>
<body>
<main>
<h1>kfcourse</h1>
<p class="kf-lead">An interactive course on the Kalman filter family for robotics students. This is the
static edition: every chapter executed, each demo shown as a picture of its first frame (and, where it
has Run/Pause, a short recording of its run, played when you ask for it). To drag the sliders, open the
notebooks in JupyterLab (<code>make lab</code>).</p>
<ul class="kf-chapters">
{items}
</ul>
</main>
</body>
</html>
"""


def chapters(folder: Path) -> list[Path]:
    """Every chapter notebook in order, then the notation table and the solutions where there are."""
    found = sorted(p for p in folder.glob("*.ipynb") if CHAPTER.fullmatch(p.name))
    return found + [p for p in (folder / "notation.ipynb", folder / "solutions.ipynb") if p.exists()]


def title_of(nb) -> str:
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return "untitled"


def mathjax_folder() -> Path:
    try:
        return Path(str(resources.files("jupyter_server_mathjax") / "static"))
    except ModuleNotFoundError:
        sys.exit("tools/build_site.py needs jupyter-server-mathjax: pip install -r requirements-dev.txt")


# jupyter_client interrupts a kernel (SIGINT) before it asks it to shut down; a kernel still handling a
# message then logs this to its stderr, an error that is not one.
SHUTDOWN_NOISE = "KeyboardInterrupt caught in kernel."


class SiteClient(NotebookClient):
    """Executes a notebook and, after every cell that showed a demo, asks the kernel for the demo's
    caption, its description and the recording of its run; the demo's output becomes a static figure."""

    def __init__(self, nb, *, media: Path, stem: str, **kwargs):
        super().__init__(nb, **kwargs)
        self.media = media
        self.stem = stem
        self.demos: list[dict] = []
        self.demo_seconds = 0.0  # asking the kernel about its demos: captions, descriptions, recordings

    async def async_execute_cell(self, cell, cell_index, execution_count=None, store_history=True):
        cell = await super().async_execute_cell(cell, cell_index, execution_count, store_history)
        if cell.cell_type != "code" or not store_history:
            return cell
        for out in cell.get("outputs", []):
            if out.get("output_type") == "stream" and out.get("name") == "stderr":
                raise RuntimeError(f"{self.stem}: cell {cell_index} wrote to stderr:\n{out['text']}")
        outputs = []
        for out in cell.outputs:
            data = out.get("data", {})
            if WIDGET_VIEW in data and "image/png" in data:  # a Demo: widget view + first frame
                outputs.append(await self._static_demo(out, cell_index))
            elif is_stream(out) and outputs and is_stream(outputs[-1], out["name"]):
                # Printed text arrives in pieces, cut wherever the kernel flushed (which depends on
                # what else runs on the machine); JupyterLab shows consecutive pieces as one block.
                outputs[-1]["text"] += out["text"]
            else:
                data.pop(WIDGET_VIEW, None)  # no widget manager on a static page
                outputs.append(out)
        cell.outputs = outputs
        self.nb.cells[cell_index] = cell  # nbclient stored the last cell it ran there: a probe's
        return cell

    async def _static_demo(self, out, cell_index: int):
        model_id = out["data"][WIDGET_VIEW]["model_id"]
        probe = nbformat.v4.new_code_cell(PROBE.format(model_id=model_id, mime=PROBE_MIME, recording=str(RECORDING)))
        t0 = time.monotonic()
        await super().async_execute_cell(probe, cell_index, store_history=False)
        self.demo_seconds += time.monotonic() - t0
        found = [o["data"][PROBE_MIME] for o in probe.outputs if PROBE_MIME in o.get("data", {})]
        if not found:
            raise RuntimeError(f"{self.stem}: cell {cell_index}: no answer about demo {model_id}: {probe.outputs}")
        info = found[0]
        record = {"cell": cell_index, "picture": True, "description": info["description"], "animation": None}
        recording = None
        if info["recording"]:
            name = f"{self.stem}-demo{len(self.demos)}.webp"
            (self.media / name).write_bytes(base64.b64decode(info["recording"]))
            record["animation"] = f"media/{name}"
            record["animation_alt"] = recording_alt(info["last_frame"])
            recording = (record["animation"], record["animation_alt"])
        self.demos.append(record)
        width = out.get("metadata", {}).get("image/png", {}).get("width", 950)
        figure = static_figure(info["caption"], info["description"], out["data"]["image/png"], recording, width)
        return nbformat.v4.new_output("display_data", data={"text/html": figure})


def is_stream(out, name: str | None = None) -> bool:
    """Whether the output ``out`` is printed text (of the stream ``name``, if given)."""
    return out.get("output_type") == "stream" and (name is None or out.get("name") == name)


def recording_alt(last_frame: str) -> str:
    """The alt text of a run's recording: what it is, and what its last picture shows."""
    return f"Recording of the demo's run, from its first step to its last. At the end: {last_frame}"


def static_figure(
    caption: str, description: str, png_base64: str, recording: tuple[str, str] | None, width: int
) -> str:
    """A demo on a page without a kernel, shown ``width`` CSS px wide.

    Its picture, with the description as its alt text; for a demo with Run/Pause
    (``recording`` is the file of its run and that file's alt text) a "Play the run" toggle
    under it that shows the recording in the still's place; then the description, the
    caption and a note.  Both pictures get the still's shape (``width`` and ``height``), so
    the page does not move when one replaces the other.
    """
    if not description.strip():
        raise ValueError("description must say what the demo's picture shows, got an empty text")
    png = base64.b64decode(png_base64)
    with Image.open(io.BytesIO(png)) as image:
        height = round(width * image.height / image.width)
    size = f"width='{width}' height='{height}'"
    src = f"data:image/png;base64,{png_base64}"
    pictures = f"<img class='kf-demo-picture' {size} alt='{html.escape(description)}' src='{src}'>"
    if recording is not None:
        run, alt = recording
        pictures += (
            f"<img class='kf-demo-animation' {size} alt='{html.escape(alt)}' data-src='{html.escape(run)}' hidden>"
            "<div class='kf-run'><button type='button' class='kf-play' aria-pressed='false'>"
            "<span class='kf-icon' aria-hidden='true'></span>Play the run</button>"
            "<p class='kf-note'>A recording of the run, as Run shows it; press again to stop it.</p></div>"
        )
    return (
        f"<div class='kf-demo-static' style='max-width:{width}px'><figure class='kf-demo-still'>{pictures}"
        f"<figcaption><p class='kf-description'>{html.escape(description)}</p>"
        f"<div class='kf-caption'>{caption}</div>"
        "<p class='kf-note'>A picture of the demo. Open this notebook in JupyterLab to use its controls.</p>"
        "</figcaption></figure></div>"
    )


def without_nbval_markers(nb) -> None:
    """Drop the first line of every code cell that only tells nbval what to check."""
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.source = NBVAL_MARKER.sub("", cell.source, count=1)


def nav(pages: list[dict], i: int, bottom: bool = False) -> str:
    """The links to the previous chapter, the index and the next chapter; ``bottom``: the copy at the page's end."""
    prev = (
        f'<a href="{pages[i - 1]["href"]}">&larr; {html.escape(pages[i - 1]["title"])}</a>'
        if i > 0
        else "<span></span>"
    )
    up = '<a href="index.html">All chapters</a>'
    nxt = (
        f'<a href="{pages[i + 1]["href"]}">{html.escape(pages[i + 1]["title"])} &rarr;</a>'
        if i + 1 < len(pages)
        else "<span></span>"
    )
    if bottom:
        return f'<nav class="kf-nav kf-bottom" aria-label="Chapters, at the end">{prev}{up}{nxt}</nav>'
    return f'<nav class="kf-nav" aria-label="Chapters">{prev}{up}{nxt}</nav>'


def link_pages(body: str) -> str:
    """Links between notebooks point at their pages."""
    return re.sub(r'href="([^":/?#]+)\.ipynb(#[^"]*)?"', lambda m: f'href="{m[1]}.html{m[2] or ""}"', body)


def start_order(paths: list[Path]) -> list[int]:
    """The order in which the pages are started: the chapters from the last to the first (the later
    ones run longer: chapter 11's experiments, chapter 10's two recordings), then the notation table and
    the solutions.  With two at a time, the longest starts first and the short ones fill in."""
    numbered = [i for i, p in enumerate(paths) if CHAPTER.fullmatch(p.name)]
    return numbered[::-1] + [i for i in range(len(paths)) if i not in numbered]


def build(out: Path, folder: Path, jobs: int = JOBS) -> list[dict]:
    """Every page of the site into ``out``, ``jobs`` chapters executed at once (each in its own kernel)."""
    t_start = time.monotonic()
    paths = chapters(folder)
    if not paths:
        sys.exit(f"no chapter notebooks in {folder}")
    out.mkdir(parents=True, exist_ok=True)
    for old in [*out.glob("*.html"), out / "demos.json"]:
        old.unlink(missing_ok=True)
    shutil.rmtree(out / "media", ignore_errors=True)
    (out / "media").mkdir()
    mathjax = out / "_static" / "mathjax"
    t0 = time.monotonic()
    if not (mathjax / "MathJax.js").exists():
        shutil.copytree(mathjax_folder(), mathjax, ignore=shutil.ignore_patterns("localization", "*.py"))
        print(f"_static/mathjax: copied in {time.monotonic() - t0:.1f} s", flush=True)

    notebooks = [nbformat.read(p, as_version=4) for p in paths]
    pages = [
        {"href": p.stem + ".html", "title": title_of(nb), "notebook": p.name}
        for p, nb in zip(paths, notebooks, strict=True)
    ]
    exporter = HTMLExporter(
        template_name="lab",
        template_file="kfsite.html.j2",
        extra_loaders=[jinja2.DictLoader({"kfsite.html.j2": TEMPLATE})],
        mathjax_url=MATHJAX_URL,
    )

    def export(i: int) -> None:
        """The executed notebook ``i`` as its page."""
        nb = notebooks[i]
        without_nbval_markers(nb)
        nb.metadata.pop("widgets", None)
        nb.metadata["title"] = pages[i]["title"]  # the page's <title>
        extra = {"kf_nav": nav(pages, i), "kf_nav_bottom": nav(pages, i, bottom=True)}
        extra |= {"kf_css": SITE_CSS, "kf_script": SITE_SCRIPT}
        body, _ = exporter.from_notebook_node(nb, resources=extra)
        (out / pages[i]["href"]).write_text(link_pages(body), encoding="utf-8")

    exporting = asyncio.Lock()  # one page at a time through the exporter

    async def make_page(i: int) -> None:
        path = paths[i]
        t0 = time.monotonic()
        client = SiteClient(
            notebooks[i],
            media=out / "media",
            stem=path.stem,
            timeout=CELL_TIMEOUT_S,
            kernel_name="python3",
            store_widget_state=False,
            resources={"metadata": {"path": str(path.parent)}},
            config=kernel_config(),
        )
        with tempfile.TemporaryFile(mode="w+", encoding="utf-8") as kernel_log:
            await client.async_execute(stderr=kernel_log)  # the kernel process's own log, apart from the cells'
            kernel_log.seek(0)
            said = [line for line in kernel_log.read().splitlines() if line.strip() and SHUTDOWN_NOISE not in line]
        if said:  # anything the kernel logged but the interrupt its shutdown sends it
            print(f"{pages[i]['href']}: the kernel logged\n  " + "\n  ".join(said), flush=True)
        t1 = time.monotonic()
        async with exporting:  # in a thread: meanwhile the other kernel's messages are still read
            await asyncio.to_thread(export, i)
        pages[i]["demos"] = client.demos
        print(
            f"{pages[i]['href']}: {len(client.demos)} demo(s), {time.monotonic() - t0:.1f} s"
            f" (run {t1 - t0 - client.demo_seconds:.1f} s, demos' pictures and recordings"
            f" {client.demo_seconds:.1f} s, page {time.monotonic() - t1:.1f} s)",
            flush=True,
        )

    async def make_pages() -> None:
        waiting = start_order(paths)

        async def worker() -> None:
            while waiting:
                try:
                    await make_page(waiting.pop(0))
                except BaseException:
                    waiting.clear()  # the other worker starts nothing new
                    raise

        await asyncio.gather(*(worker() for _ in range(max(1, jobs))))

    asyncio.run(make_pages())
    items = "\n".join(f'<li><a href="{p["href"]}">{html.escape(p["title"])}</a></li>' for p in pages)
    (out / "index.html").write_text(INDEX.format(items=items), encoding="utf-8")
    (out / "demos.json").write_text(json.dumps({"pages": pages}, indent=2) + "\n", encoding="utf-8")
    print(f"{len(pages)} pages in {time.monotonic() - t_start:.1f} s, {max(1, jobs)} at a time", flush=True)
    return pages


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "site", help="output folder (default: site/)")
    parser.add_argument("--notebooks", type=Path, default=ROOT / "notebooks", help="the chapters (default: notebooks/)")
    parser.add_argument(
        "--jobs", type=int, default=JOBS, help=f"chapters executed at once, each in its own kernel (default: {JOBS})"
    )
    args = parser.parse_args()
    pages = build(args.out.resolve(), args.notebooks.resolve(), args.jobs)
    print(f"{len(pages)} pages: {args.out / 'index.html'}")


if __name__ == "__main__":
    main()
