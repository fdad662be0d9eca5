"""Build the static HTML edition of the course: every chapter executed, with pictures of the demos.

    python tools/build_site.py            # -> site/index.html and one page per chapter
    python tools/build_site.py --out DIR --notebooks DIR

Every ``notebooks/NN_*.ipynb`` becomes ``NN_*.html``; the notation table (``notation.ipynb``)
and the solutions (``solutions.ipynb``), where there are, come last.  The notebooks are stored
clean, so each one is executed here, with nbclient and the course's own kernel.  nbconvert's
JupyterLab template turns it into HTML; equations are typeset in the reader's browser by a copy
of MathJax 2.7 from the ``jupyter-server-mathjax`` package (requirements-dev.txt), served from
``_static/mathjax`` beside the pages: no CDN.

A page has no kernel, so a demo's live widget cannot show there.  A demo shown as the last
value of a cell also hands the notebook a PNG of the picture it shows at first
(``Demo._repr_mimebundle_``); the page shows that picture with the demo's caption under it,
and for a demo with Run/Pause also a short recording of its run (``tools/recording.py``, run
in the same kernel, saved as a ``.webp`` file in ``media/``), as many pixels wide as the
still and shown as wide.  ``site/demos.json`` lists the pages and their demo pictures.

The ``# NBVAL_CHECK_OUTPUT`` line that opens the cells whose printed numbers the tests check
is left out of the pages: it speaks to the test runner, not to a reader.
"""

from __future__ import annotations

import argparse
import base64
import html
import json
import re
import shutil
import sys
import time
from importlib import resources
from pathlib import Path

import jinja2
import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter

ROOT = Path(__file__).resolve().parents[1]
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
PROBE_MIME = "application/vnd.kfcourse.demo+json"
CHAPTER = re.compile(r"\d\d_[a-z0-9_]+\.ipynb")
CELL_TIMEOUT_S = 600
MATHJAX_URL = "_static/mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full,Safe"
RECORDING = ROOT / "tools" / "recording.py"
NBVAL_MARKER = re.compile(r"\A# NBVAL_[A-Z_]+[ \t]*\r?(\n|\Z)")  # a first line that speaks to nbval alone

# Run in the notebook's kernel after a cell that showed a demo: its caption (the first of the
# demo's rows), and for a demo with Run/Pause a recording of its run, made by tools/recording.py
# loaded from its file.  The widget is found by the model id of its view.
PROBE = """\
import base64 as _b64, importlib.util as _iu, ipywidgets as _w
from IPython.display import display as _display
_demo = _w.widget_serialization["from_json"]("IPY_MODEL_{model_id}", None)
_spec = _iu.spec_from_file_location("kfsite_recording", {recording!r})
_recording = _iu.module_from_spec(_spec)
_spec.loader.exec_module(_recording)
_display({{"{mime}": {{
    "caption": _demo.children[0].value,
    "recording": _b64.b64encode(_recording.record_run(_demo)).decode() if "frame" in _demo.controls else None,
}}}}, raw=True)
del _demo, _spec, _recording
"""

TEMPLATE = r"""{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{%- block jupyter_widgets -%}{%- endblock jupyter_widgets -%}
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
</script>
<script src="{{ resources.mathjax_url }}"></script>
{%- endblock html_head_js_mathjax -%}
{%- block extra_css -%}
<style type="text/css">
  nav.kf-nav { display: flex; justify-content: space-between; gap: 1em; padding: 0.6em 1em;
    font: 14px/1.4 var(--jp-ui-font-family, sans-serif); border-bottom: 1px solid #ddd; }
  nav.kf-nav.kf-bottom { border-top: 1px solid #ddd; border-bottom: none; margin-top: 2em; }
  div.kf-demo-static { max-width: 950px; }
  div.kf-demo-static figure { margin: 0.5em 0 1em; }
  div.kf-demo-static img { max-width: 100%; height: auto; display: block; margin: 0.4em 0; }
  div.kf-demo-static .kf-note { color: #666; font-size: 12px; font-style: italic; margin-top: 0.3em; }
</style>
{%- endblock extra_css -%}
{%- block body_header -%}
{{ super() }}
{{ resources.kf_nav }}
{%- endblock body_header -%}
{%- block body_footer -%}
{{ resources.kf_nav | replace('class="kf-nav"', 'class="kf-nav kf-bottom"') }}
{{ super() }}
{%- endblock body_footer -%}
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
<h1>kfcourse</h1>
<p class="kf-lead">An interactive course on the Kalman filter family for robotics students. This is the
static edition: every chapter executed, each demo shown as a picture of its first frame (and, where it
has Run/Pause, a short recording of its run). To drag the sliders, open the notebooks in JupyterLab
(<code>make lab</code>).</p>
<ul class="kf-chapters">
{items}
</ul>
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


class SiteClient(NotebookClient):
    """Executes a notebook and, after every cell that showed a demo, asks the kernel for the demo's
    caption and the recording of its run; the demo's output becomes a static figure."""

    def __init__(self, nb, *, media: Path, stem: str, **kwargs):
        super().__init__(nb, **kwargs)
        self.media = media
        self.stem = stem
        self.demos: list[dict] = []

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
            else:
                data.pop(WIDGET_VIEW, None)  # no widget manager on a static page
                outputs.append(out)
        cell.outputs = outputs
        self.nb.cells[cell_index] = cell  # nbclient stored the last cell it ran there: a probe's
        return cell

    async def _static_demo(self, out, cell_index: int):
        model_id = out["data"][WIDGET_VIEW]["model_id"]
        probe = nbformat.v4.new_code_cell(PROBE.format(model_id=model_id, mime=PROBE_MIME, recording=str(RECORDING)))
        await super().async_execute_cell(probe, cell_index, store_history=False)
        found = [o["data"][PROBE_MIME] for o in probe.outputs if PROBE_MIME in o.get("data", {})]
        if not found:
            raise RuntimeError(f"{self.stem}: cell {cell_index}: no answer about demo {model_id}: {probe.outputs}")
        info = found[0]
        record = {"cell": cell_index, "picture": True, "animation": None}
        if info["recording"]:
            name = f"{self.stem}-demo{len(self.demos)}.webp"
            (self.media / name).write_bytes(base64.b64decode(info["recording"]))
            record["animation"] = f"media/{name}"
        self.demos.append(record)
        width = out.get("metadata", {}).get("image/png", {}).get("width", 950)
        figure = static_figure(info["caption"], out["data"]["image/png"], record["animation"], width)
        return nbformat.v4.new_output("display_data", data={"text/html": figure})


def static_figure(caption: str, png_base64: str, recording: str | None, width: int) -> str:
    """A demo on a page without a kernel, shown ``width`` CSS px wide: its picture with the
    caption under it, then the recording of its run (if it has one) with a note under it."""
    still = (
        f"<figure class='kf-demo-still'><img class='kf-demo-picture' width='{width}' alt='the demo as it opens'"
        f" src='data:image/png;base64,{png_base64}'><figcaption>"
        f"<div class='kf-caption' style='color:#333;font-size:13px;line-height:1.4'>{caption}</div>"
        "<div class='kf-note'>A picture of the demo. Open this notebook in JupyterLab to use its controls.</div>"
        "</figcaption></figure>"
    )
    run = (
        f"<figure class='kf-demo-run'><img class='kf-demo-animation' width='{width}' alt='the demo, its run'"
        f" src='{recording}'><figcaption class='kf-note'>Its run, as Run shows it.</figcaption></figure>"
        if recording
        else ""
    )
    return f"<div class='kf-demo-static' style='max-width:{width}px'>{still}{run}</div>"


def without_nbval_markers(nb) -> None:
    """Drop the first line of every code cell that only tells nbval what to check."""
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.source = NBVAL_MARKER.sub("", cell.source, count=1)


def nav(pages: list[dict], i: int) -> str:
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
    return f'<nav class="kf-nav">{prev}{up}{nxt}</nav>'


def link_pages(body: str) -> str:
    """Links between notebooks point at their pages."""
    return re.sub(r'href="([^":/?#]+)\.ipynb(#[^"]*)?"', lambda m: f'href="{m[1]}.html{m[2] or ""}"', body)


def build(out: Path, folder: Path) -> list[dict]:
    paths = chapters(folder)
    if not paths:
        sys.exit(f"no chapter notebooks in {folder}")
    out.mkdir(parents=True, exist_ok=True)
    for old in [*out.glob("*.html"), out / "demos.json"]:
        old.unlink(missing_ok=True)
    shutil.rmtree(out / "media", ignore_errors=True)
    (out / "media").mkdir()
    mathjax = out / "_static" / "mathjax"
    if not (mathjax / "MathJax.js").exists():
        shutil.copytree(mathjax_folder(), mathjax, ignore=shutil.ignore_patterns("localization", "*.py"))

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
    for i, (path, nb) in enumerate(zip(paths, notebooks, strict=True)):
        t0 = time.monotonic()
        client = SiteClient(
            nb,
            media=out / "media",
            stem=path.stem,
            timeout=CELL_TIMEOUT_S,
            kernel_name="python3",
            store_widget_state=False,
            resources={"metadata": {"path": str(path.parent)}},
        )
        client.execute()
        without_nbval_markers(nb)
        nb.metadata.pop("widgets", None)
        nb.metadata["title"] = pages[i]["title"]  # the page's <title>
        body, _ = exporter.from_notebook_node(nb, resources={"kf_nav": nav(pages, i)})
        (out / pages[i]["href"]).write_text(link_pages(body), encoding="utf-8")
        pages[i]["demos"] = client.demos
        print(f"{pages[i]['href']}: {len(client.demos)} demo(s), {time.monotonic() - t0:.1f} s", flush=True)

    items = "\n".join(f'<li><a href="{p["href"]}">{html.escape(p["title"])}</a></li>' for p in pages)
    (out / "index.html").write_text(INDEX.format(items=items), encoding="utf-8")
    (out / "demos.json").write_text(json.dumps({"pages": pages}, indent=2) + "\n", encoding="utf-8")
    return pages


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "site", help="output folder (default: site/)")
    parser.add_argument("--notebooks", type=Path, default=ROOT / "notebooks", help="the chapters (default: notebooks/)")
    args = parser.parse_args()
    pages = build(args.out.resolve(), args.notebooks.resolve())
    print(f"{len(pages)} pages: {args.out / 'index.html'}")


if __name__ == "__main__":
    main()
