"""Run the course on this machine: the student's own copy in JupyterLab, or one chapter as an app.

    python tools/course.py lab [--port 8888] [--work my-notebooks]    (what `make lab` runs)
    python tools/course.py app --chapter 03 [--port 8866]             (what `make app CH=03` runs)
    python tools/course.py restore [--chapter 03] [--work my-notebooks]  (`make restore [CH=03]`)

``lab`` serves a working copy of the chapters (``my-notebooks/``, git-ignored), made on the
first run and never overwritten: a chapter added to ``notebooks/`` later is copied in on the
next run.  So the tracked notebooks in ``notebooks/`` are never written by using the course,
and ``restore`` puts the original of one chapter (or of all) back into the working copy,
keeping the replaced version in ``my-notebooks/backup/``.

``app`` serves one chapter with Voilà: the prose and the live demos, no code.  It reads the
tracked notebook and never writes it.

Both servers listen on 127.0.0.1 only and keep token authentication on (a new random token
each start).  A port that is already taken is refused before anything starts, with the fix
(``make lab PORT=8890``, ``make app CH=03 APP_PORT=8870``), and the address to open is printed
only once the server answering there has shown it knows this start's token: never the address
of someone else's server.  The course's notebooks, as shipped, are signed as trusted.

Both take the course's Jupyter settings from ``binder/jupyter-config``, so that a student's
terminal shows no warning that reads like an error:

- ``jupyter_server_config.json`` and ``voila.json``: kernels talk to the server over encrypted
  transport where the kernel supports it (``KernelManager.transport_encryption = "auto"``,
  CurveZMQ), instead of warning that they run over TCP without encryption;
- ``jupyter_server_config.json``: JupyterLab's ``notebook_shim`` (the bridge for classic
  Notebook server extensions, of which the course has none) is off, since it reads the
  deprecated ``ServerApp.token`` and warns; and no websocket keep-alive pings on this
  loopback server (``ws_ping_interval = 0``), whose default timeout tornado warns about;
- ``labconfig/``: no news pop-up (the announcements plugin), and widget state saved with a
  notebook, so a demo run and saved still shows its picture when the notebook is reopened
  with a new kernel.  Binder gets these two (``binder/postBuild``), not the server settings
  above: its server sits behind Binder's own proxy.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.parse
import urllib.request
from datetime import datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ORIGINALS = ROOT / "notebooks"
WORK = ROOT / "my-notebooks"
# Jupyter configuration the course adds to the user's own: its labconfig/page_config.json
# turns JupyterLab's announcements plugin (the news and update pop-ups) off, and
# labconfig/default_setting_overrides.json makes the widget manager save widget state
# (a default: a student can still switch it off under Settings).
JUPYTER_CONFIG = ROOT / "binder" / "jupyter-config"
START_TIMEOUT_S = 120
STOP_TIMEOUT_S = 15


# --------------------------------------------------------------------------- the working copy


def notebooks(folder: Path) -> list[Path]:
    """Every notebook in ``folder``: the chapters and the others (the solutions)."""
    return sorted(folder.glob("*.ipynb"))


def chapters(folder: Path) -> list[Path]:
    """The chapter notebooks ``NN_name.ipynb`` in ``folder``, in order."""
    return sorted(folder.glob("[0-9][0-9]_*.ipynb"))


def find_chapter(folder: Path, chapter: str) -> Path:
    """The notebook of chapter ``chapter`` ("3" or "03") in ``folder``.

    Raises
    ------
    ValueError
        If ``chapter`` is not a chapter number with a notebook in ``folder``.
    """
    names = ", ".join(p.name[:2] for p in chapters(folder))
    text = str(chapter).strip()
    if not text.isdigit():
        raise ValueError(f"chapter must be a chapter number (one of {names}), got {chapter!r}")
    found = [p for p in chapters(folder) if int(p.name[:2]) == int(text)]
    if not found:
        raise ValueError(f"chapter {chapter!r} has no notebook in {folder} (there are: {names})")
    return found[0]


def make_working_copy(originals: Path = ORIGINALS, work: Path = WORK) -> list[Path]:
    """Copy every notebook that ``work`` lacks from ``originals``; never overwrite one.

    Returns the notebooks copied (none once the copy is complete).
    """
    work.mkdir(parents=True, exist_ok=True)
    copied = []
    for original in notebooks(originals):
        target = work / original.name
        if not target.exists():
            shutil.copyfile(original, target)
            copied.append(target)
    return copied


def restore(originals: Path = ORIGINALS, work: Path = WORK, chapter: str | None = None) -> list[Path]:
    """Put the original of one chapter (or of every notebook) back into the working copy.

    A working notebook that differs from its original is first moved to
    ``work/backup/<name>-<date>-<time>.ipynb``.  Returns the notebooks restored.
    """
    picked = [find_chapter(originals, chapter)] if chapter not in (None, "") else notebooks(originals)
    work.mkdir(parents=True, exist_ok=True)
    stamp = datetime.now().strftime("%Y%m%d-%H%M%S")
    restored = []
    for original in picked:
        target = work / original.name
        if target.exists() and not filecmp.cmp(original, target, shallow=False):
            backup = work / "backup" / f"{original.stem}-{stamp}.ipynb"
            backup.parent.mkdir(exist_ok=True)
            shutil.move(target, backup)
            print(f"  your version of {original.name} is kept as {backup.relative_to(work.parent)}")
        shutil.copyfile(original, target)
        restored.append(target)
    return restored


# --------------------------------------------------------------------------- the servers


def port_taken(port: int) -> bool:
    """True when another program already holds ``port`` on 127.0.0.1."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as the servers bind: a closed port is free
        try:
            probe.bind(("127.0.0.1", port))
        except OSError:
            return True
    return False


def next_free_port(port: int) -> int:
    """The first port after ``port`` that is free on 127.0.0.1 now: the one to suggest."""
    return next(p for p in range(port + 1, 65536) if not port_taken(p))


class NoRedirect(urllib.request.HTTPRedirectHandler):
    """An opener handler that hands a redirect back as an HTTPError instead of following it."""

    def redirect_request(self, *args, **kwargs):
        return None


def logs_in(base: str, token: str) -> bool:
    """True when the Jupyter server at ``base`` logs ``token`` in.

    Its login page, given a token it knows, redirects to the ``next`` page it is asked for
    (here a fresh, random one); given any other token, it shows the login form.
    """
    page = f"/kfcourse-{secrets.token_hex(8)}"
    url = f"{base}login?" + urllib.parse.urlencode({"token": token, "next": page})
    try:
        with urllib.request.build_opener(NoRedirect).open(url, timeout=2):
            return False
    except urllib.error.HTTPError as error:
        with error:
            return error.code == 302 and urllib.parse.urlsplit(error.headers.get("Location", "")).path == page
    except (urllib.error.URLError, OSError):
        return False


def knows_token(base: str, token: str) -> bool:
    """True when the server at ``base`` is the one this start made: it logs this start's token in, and no other.

    A server of someone else's does not know the token; one that lets anybody in (no token
    at all) logs the wrong one in too.
    """
    return logs_in(base, token) and not logs_in(base, f"not-{token}")


def serve(command: list[str], env: dict[str, str], port: int, token: str, banner: list[str], fix: str) -> int:
    """Start a server on ``port``, print ``banner`` once it knows ``token``, stop the server on Ctrl-C.

    A port already taken is refused before anything starts, with ``fix``.  The server shares
    this process's group, so whoever stops the group stops both; its standard input is closed,
    so Ctrl-C stops it at once instead of asking.
    """
    if port_taken(port):
        print(f"\n  kfcourse: port {port} is already in use on 127.0.0.1 (another server?). Pick another: {fix}")
        return 1
    server = subprocess.Popen(command, env=env, stdin=subprocess.DEVNULL)
    signal.signal(signal.SIGTERM, lambda *_: server.terminate())
    try:
        deadline = time.monotonic() + START_TIMEOUT_S
        while not (knows_token(f"http://127.0.0.1:{port}/", token) and server.poll() is None):
            if server.poll() is not None:
                print(f"\n  kfcourse: the server stopped (exit code {server.returncode}); see its messages above.")
                return server.returncode or 1
            if time.monotonic() > deadline:
                print(f"\n  kfcourse: no server of ours answered on port {port} in {START_TIMEOUT_S} s; stopping it.")
                return 1
            time.sleep(0.25)
        print("\n".join(["", *banner, ""]), flush=True)
        return server.wait()
    except KeyboardInterrupt:
        return 0
    finally:
        if server.poll() is None:
            server.terminate()
            try:
                server.wait(timeout=STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                server.kill()
                server.wait()


def trust(paths: list[Path]) -> None:
    """Sign the notebooks as trusted with Jupyter's notary, so the server does not warn that they are not."""
    import nbformat  # of the course's environment (`make restore` runs without it)
    from nbformat.sign import NotebookNotary

    notary = NotebookNotary()
    for path in paths:
        nb = nbformat.read(path, as_version=4)
        if not notary.check_signature(nb):
            notary.sign(nb)


def server_env(token: str) -> dict[str, str]:
    """The environment of a server: the token, and the course's Jupyter configuration added."""
    env = dict(os.environ, JUPYTER_TOKEN=token)
    env.pop("JUPYTER_TOKEN_FILE", None)
    env["JUPYTER_CONFIG_PATH"] = os.pathsep.join(
        filter(None, [str(JUPYTER_CONFIG), os.environ.get("JUPYTER_CONFIG_PATH")])
    )
    return env


def tool(name: str) -> str:
    """A command of this Python's environment (the course's .venv)."""
    return str(Path(sys.executable).with_name(name))


def lab(port: int, work: Path) -> int:
    copied = make_working_copy(ORIGINALS, work)
    if copied:
        print(f"  kfcourse: copied {len(copied)} notebook(s) into {work} (your own copy: edit and save freely)")
    trust([p for p in notebooks(work) if (ORIGINALS / p.name).exists() and filecmp.cmp(p, ORIGINALS / p.name, False)])
    token = secrets.token_hex(24)
    command = [
        tool("jupyter"),
        "lab",
        "--no-browser",
        "--ServerApp.ip=127.0.0.1",
        f"--ServerApp.port={port}",
        "--ServerApp.port_retries=0",
        f"--ServerApp.root_dir={work}",
    ]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        command.append("--allow-root")
    first = chapters(work)[0].name if chapters(work) else ""
    base = f"http://127.0.0.1:{port}/"
    banner = [
        "  kfcourse is ready: open this address in your browser (it holds your access token):",
        f"      {base}lab/tree/{first}?token={token}",
        f"  It serves your own copy of the chapters, {work}; `make restore CH=NN` brings back a chapter's original.",
        "  Ctrl-C here stops the server.",
    ]
    fix = f"make lab PORT={next_free_port(port)}"
    return serve(command, server_env(token), port, token, banner, fix)


def app(port: int, chapter: str) -> int:
    notebook = find_chapter(ORIGINALS, chapter)
    trust([notebook])
    token = secrets.token_hex(24)
    command = [
        tool("voila"),
        str(notebook),
        "--no-browser",
        "--Voila.auto_token=True",  # token authentication on; the token itself comes from JUPYTER_TOKEN
        "--Voila.ip=127.0.0.1",
        f"--Voila.port={port}",
        "--Voila.port_retries=0",
    ]
    base = f"http://127.0.0.1:{port}/"
    banner = [
        f"  kfcourse app view of {notebook.name} is ready: open this address in your browser:",
        f"      {base}?token={token}",
        "  (each visit runs the chapter afresh; Ctrl-C here stops the server)",
    ]
    fix = f"make app CH={notebook.name[:2]} APP_PORT={next_free_port(port)}"
    return serve(command, server_env(token), port, token, banner, fix)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p_lab = sub.add_parser("lab", help="serve your own copy of the chapters in JupyterLab")
    p_lab.add_argument("--port", type=int, default=8888)
    p_lab.add_argument("--work", type=Path, default=WORK, help="the working copy (default: my-notebooks/)")
    p_app = sub.add_parser("app", help="serve one chapter as an app (Voilà)")
    p_app.add_argument("--chapter", required=True, help="chapter number, e.g. 03")
    p_app.add_argument("--port", type=int, default=8866)
    p_restore = sub.add_parser("restore", help="put the originals back into your working copy")
    p_restore.add_argument("--chapter", default=None, help="chapter number, e.g. 03 (default: every chapter)")
    p_restore.add_argument("--work", type=Path, default=WORK, help="the working copy (default: my-notebooks/)")
    args = parser.parse_args(argv)
    try:
        if args.command == "lab":
            return lab(args.port, args.work.resolve())
        if args.command == "app":
            return app(args.port, args.chapter)
        restored = restore(ORIGINALS, args.work.resolve(), args.chapter)
        print(f"  kfcourse: restored {', '.join(p.name for p in restored)} in {args.work}")
        return 0
    except ValueError as error:
        print(f"  kfcourse: {error}", file=sys.stderr)
        if args.command == "app":
            print("  usage: make app CH=NN, e.g. make app CH=03", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
