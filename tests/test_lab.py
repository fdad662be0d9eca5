"""`make lab`, `make restore` and the student's working copy.

The working copy is made once and never overwritten; `make restore` brings back an
original and keeps the student's version.  Then the real `make lab` is started on a free
port (in this test environment's own venv, which make is told not to rebuild) and
checked as a student meets it: the address is printed only once the server answers, it
holds a token and the server refuses requests without it, it listens on 127.0.0.1 only,
JupyterLab's news pop-up is off, widget state is saved with a notebook by default, and
saving a notebook (what autosave does) writes the working copy, never the tracked notebooks.
Its terminal shows no warning while a kernel starts and a chapter opens.  On a port that
another server already holds, `make lab` and `make app` refuse to start, say how to pick
another port, and print no address.
"""

from __future__ import annotations

import http.server
import json
import os
import re
import shutil
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.parse
import urllib.request
import uuid
from contextlib import contextmanager
from pathlib import Path

import pytest

from tests.servers import ALARMING, Served, free_port, get, tracked_hashes
from tools import course
from tools.course import NoRedirect

ROOT = Path(__file__).resolve().parents[1]
START_TIMEOUT_S = 120


# --------------------------------------------------------------------------- the working copy


def fake_originals(folder: Path, names=("00_start", "01_next", "solutions")) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    for name in names:
        (folder / f"{name}.ipynb").write_text(f'{{"original": "{name}"}}\n', encoding="utf-8")
    return folder


def test_working_copy_is_made_once_and_never_overwritten(tmp_path):
    originals = fake_originals(tmp_path / "notebooks")
    work = tmp_path / "my-notebooks"
    copied = course.make_working_copy(originals, work)
    assert [p.name for p in copied] == ["00_start.ipynb", "01_next.ipynb", "solutions.ipynb"]
    assert (work / "00_start.ipynb").read_bytes() == (originals / "00_start.ipynb").read_bytes()

    (work / "00_start.ipynb").write_text("the student's own work", encoding="utf-8")
    assert course.make_working_copy(originals, work) == []
    assert (work / "00_start.ipynb").read_text(encoding="utf-8") == "the student's own work"

    fake_originals(originals, ["02_later"])  # a chapter that lands after the first run
    assert [p.name for p in course.make_working_copy(originals, work)] == ["02_later.ipynb"]
    assert (work / "00_start.ipynb").read_text(encoding="utf-8") == "the student's own work"


def test_restore_one_chapter_keeps_the_students_version(tmp_path):
    originals = fake_originals(tmp_path / "notebooks")
    work = tmp_path / "my-notebooks"
    course.make_working_copy(originals, work)
    for name in ("00_start.ipynb", "01_next.ipynb"):
        (work / name).write_text(f"changed {name}", encoding="utf-8")

    restored = course.restore(originals, work, chapter="1")
    assert [p.name for p in restored] == ["01_next.ipynb"]
    assert (work / "01_next.ipynb").read_bytes() == (originals / "01_next.ipynb").read_bytes()
    assert (work / "00_start.ipynb").read_text(encoding="utf-8") == "changed 00_start.ipynb"
    backups = list((work / "backup").glob("01_next-*.ipynb"))
    assert len(backups) == 1 and backups[0].read_text(encoding="utf-8") == "changed 01_next.ipynb"

    assert len(course.restore(originals, work)) == 3  # every notebook
    assert (work / "00_start.ipynb").read_bytes() == (originals / "00_start.ipynb").read_bytes()
    # 01 was already the original: nothing new to keep
    assert len(list((work / "backup").glob("01_next-*.ipynb"))) == 1


@pytest.mark.parametrize("chapter", ["x", "3a", "99"])
def test_unknown_chapter_is_refused(tmp_path, chapter):
    originals = fake_originals(tmp_path / "notebooks")
    with pytest.raises(ValueError, match="chapter"):
        course.restore(originals, tmp_path / "work", chapter=chapter)


# --------------------------------------------------------------------------- through make


def make_command() -> str:
    found = shutil.which("make")
    if found is None:
        message = "`make` is missing; the make targets cannot be tested"
        if os.environ.get("CI") == "true":
            pytest.fail(message, pytrace=False)
        pytest.skip(message)
    return found


def make_env(tmp_path: Path) -> dict[str, str]:
    """No make flags from an outer `make test`, no token or Jupyter state of the user's."""
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "JUPYTER_TOKEN")}
    for name, sub in [
        ("JUPYTER_RUNTIME_DIR", "runtime"),
        ("JUPYTER_CONFIG_DIR", "config"),
        ("JUPYTERLAB_SETTINGS_DIR", "settings"),
        ("JUPYTERLAB_WORKSPACES_DIR", "workspaces"),
    ]:
        (tmp_path / sub).mkdir(parents=True, exist_ok=True)
        env[name] = str(tmp_path / sub)
    return env


def this_venv() -> list[str]:
    """make variables that run the targets in this test's own environment, never rebuilding it."""
    venv = Path(sys.prefix)
    return [f"--assume-old={venv / '.kfcourse-installed'}", f"VENV={venv}"]


def test_make_restore_brings_back_one_chapter(tmp_path):
    make = make_command()
    work = tmp_path / "my-notebooks"
    course.make_working_copy(ROOT / "notebooks", work)
    original = course.find_chapter(ROOT / "notebooks", "3")
    (work / original.name).write_text("{}", encoding="utf-8")
    result = subprocess.run(
        [make, "--no-print-directory", "restore", f"WORK={work}", "CH=03"],
        cwd=ROOT,
        env=make_env(tmp_path),
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert (work / original.name).read_bytes() == original.read_bytes()
    assert [p.read_text(encoding="utf-8") for p in (work / "backup").iterdir()] == ["{}"]


# --------------------------------------------------------------------------- the real server


def listening_addresses(group: int, port: int) -> set[str]:
    """The local addresses the processes of a process group listen on at ``port``."""
    import psutil

    found = set()
    for proc in psutil.process_iter():
        try:
            if os.getpgid(proc.pid) != group:
                continue
            for conn in proc.net_connections(kind="inet"):
                if conn.status == psutil.CONN_LISTEN and conn.laddr.port == port:
                    found.add(conn.laddr.ip)
        except (psutil.Error, ProcessLookupError, PermissionError):
            continue
    return found


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    make = make_command()
    base = tmp_path_factory.mktemp("make-lab")
    work = base / "my-notebooks"
    port = free_port()
    before = tracked_hashes()
    started = Served(
        [make, "--no-print-directory", *this_venv(), "lab", f"PORT={port}", f"WORK={work}"],
        ROOT,
        make_env(base),
        rf"http://127\.0\.0\.1:{port}/\S*\?token=[0-9a-f]{{16,}}",
        try_at_once=True,  # the address must answer the moment it is printed
    )
    try:
        url = started.wait_for_url(START_TIMEOUT_S)
        token = re.search(r"\?token=([0-9a-f]+)", url)[1]
        printed = open_a_chapter(f"http://127.0.0.1:{port}/", token)
        shown = list(started.lines)  # the terminal after a kernel started and a chapter opened
        yield {
            "started": started,
            "url": url,
            "token": token,
            "port": port,
            "work": work,
            "before": before,
            "printed": printed,
            "shown": shown,
        }
    finally:
        started.stop()
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        assert s.connect_ex(("127.0.0.1", port)) != 0, "the server still answers after `make lab` was stopped"


def open_a_chapter(base: str, token: str) -> str:
    """What a student does first: open a chapter, start its kernel and run a cell. Returns what the cell printed."""
    import websocket  # websocket-client, of the pinned set (jupyter_server's)

    auth = {"Authorization": f"token {token}", "Content-Type": "application/json"}
    assert get(f"{base}api/contents/03_kalman_1d.ipynb?content=1", auth)[0] == 200
    request = urllib.request.Request(f"{base}api/kernels", data=b'{"name": "python3"}', method="POST", headers=auth)
    with urllib.request.urlopen(request, timeout=30) as response:
        kernel = json.loads(response.read())["id"]
    channels = base.replace("http://", "ws://") + f"api/kernels/{kernel}/channels?session_id={uuid.uuid4().hex}"
    ws = websocket.create_connection(channels, header=[f"Authorization: token {token}"], timeout=60)
    try:
        msg_id = uuid.uuid4().hex
        header = {"msg_id": msg_id, "session": uuid.uuid4().hex, "username": "student", "version": "5.3"}
        content = {"code": "print(6 * 7)", "silent": False, "store_history": False, "user_expressions": {}}
        request = {"header": {**header, "msg_type": "execute_request"}, "parent_header": {}, "metadata": {}}
        ws.send(json.dumps({**request, "content": content, "channel": "shell"}))
        printed = ""
        while True:  # until the kernel is idle again after the cell
            msg = json.loads(ws.recv())
            if msg.get("parent_header", {}).get("msg_id") != msg_id:
                continue
            if msg["msg_type"] == "stream":
                printed += msg["content"]["text"]
            if msg["msg_type"] == "status" and msg["content"]["execution_state"] == "idle":
                break
    finally:
        ws.close()
    time.sleep(1.0)  # for anything the server or the kernel would still write
    request = urllib.request.Request(f"{base}api/kernels/{kernel}", method="DELETE", headers=auth)
    urllib.request.urlopen(request, timeout=30).close()
    return printed


def test_lab_terminal_shows_no_warning(lab):
    assert lab["printed"] == "42\n", "the kernel did not run a cell"
    alarming = [line for line in lab["shown"] if ALARMING.search(line)]
    assert not alarming, "the student's terminal shows:\n" + "\n".join(alarming)


def test_lab_prints_the_address_once_the_server_answers(lab):
    started = lab["started"]
    assert lab["url"].startswith(f"http://127.0.0.1:{lab['port']}/lab/tree/00_the_problem.ipynb?token=")
    first = started.first_try
    assert isinstance(first, tuple), f"the printed address did not answer when it was printed: {first}"
    assert first[0] == 200, f"the printed address answered {first[0]}"
    printed = [line for line in started.lines if "?token=" in line and lab["token"] in line]
    assert len(printed) == 1, "the address with the token is printed once"


def test_lab_requires_the_token(lab):
    base = f"http://127.0.0.1:{lab['port']}/"
    assert get(base + "api/status")[0] == 403
    assert get(base + "api/contents")[0] == 403
    assert get(base + "api/status", {"Authorization": "token wrong" + lab["token"]})[0] == 403
    assert get(base + "api/status", {"Authorization": f"token {lab['token']}"})[0] == 200
    opener = urllib.request.build_opener(NoRedirect)
    with pytest.raises(urllib.error.HTTPError) as page:
        opener.open(base + "lab", timeout=30)
    with page.value:
        assert page.value.code == 302 and "/login" in page.value.headers["Location"]


def test_lab_listens_on_loopback_only(lab):
    assert listening_addresses(lab["started"].proc.pid, lab["port"]) == {"127.0.0.1"}


def test_lab_news_popup_is_off(lab):
    status, html = get(f"http://127.0.0.1:{lab['port']}/lab?token={lab['token']}")
    assert status == 200
    config = re.search(rb'<script id="jupyter-config-data" type="application/json">(.*?)</script>', html, re.S)
    assert config, "no page config in the JupyterLab page"
    disabled = json.loads(config[1])["disabledExtensions"]
    assert "@jupyterlab/apputils-extension:announcements" in disabled


def test_lab_saves_widget_state_with_the_notebook(lab):
    """A demo run and saved keeps its picture for the next time (tests/browser/test_saved_notebook.py)."""
    status, body = get(
        f"http://127.0.0.1:{lab['port']}/lab/api/settings/@jupyter-widgets/jupyterlab-manager:plugin",
        {"Authorization": f"token {lab['token']}"},
    )
    assert status == 200
    plugin = json.loads(body)
    # The course's setting is a default (the schema's), which a student's own settings may still change.
    assert plugin["schema"]["properties"]["saveState"]["default"] is True
    assert "saveState" not in plugin["settings"]


def test_lab_serves_the_working_copy_and_saving_never_touches_the_tracked_notebooks(lab):
    base = f"http://127.0.0.1:{lab['port']}/api/contents"
    auth = {"Authorization": f"token {lab['token']}"}
    status, body = get(base, auth)
    assert status == 200
    served = sorted(item["name"] for item in json.loads(body)["content"] if item["type"] == "notebook")
    assert served == sorted(lab["before"]), "the server does not serve the working copy of every notebook"

    # What JupyterLab's autosave does after a student ran a cell: PUT the notebook with outputs.
    name = "00_the_problem.ipynb"
    status, body = get(f"{base}/{name}?content=1", auth)
    model = json.loads(body)["content"]
    cell = next(c for c in model["cells"] if c["cell_type"] == "code")
    cell["execution_count"] = 1
    cell["outputs"] = [{"output_type": "stream", "name": "stdout", "text": "a student's run\n"}]
    payload = json.dumps({"type": "notebook", "format": "json", "content": model}).encode()
    request = urllib.request.Request(f"{base}/{name}", data=payload, method="PUT", headers=auth)
    with urllib.request.urlopen(request, timeout=30) as response:
        assert response.status == 200
    assert "a student's run" in (lab["work"] / name).read_text(encoding="utf-8")
    assert tracked_hashes() == lab["before"], "the tracked notebooks changed while the course was used"


def test_binder_gets_the_same_jupyterlab_settings():
    """Binder (and a hub image built with repo2docker) install the lab config files `make lab` uses."""
    labconfig = course.JUPYTER_CONFIG / "labconfig"
    config = json.loads((labconfig / "page_config.json").read_text(encoding="utf-8"))
    assert config["disabledExtensions"] == {"@jupyterlab/apputils-extension:announcements": True}
    defaults = json.loads((labconfig / "default_setting_overrides.json").read_text(encoding="utf-8"))
    assert defaults == {"@jupyter-widgets/jupyterlab-manager:plugin": {"saveState": True}}
    post = (ROOT / "binder" / "postBuild").read_text(encoding="utf-8")
    assert sorted(p.name for p in labconfig.iterdir()) == ["default_setting_overrides.json", "page_config.json"]
    for path in labconfig.iterdir():
        assert f"cp binder/jupyter-config/labconfig/{path.name}" in post


# --------------------------------------------------------------------------- someone else's server


class Foreign(http.server.BaseHTTPRequestHandler):
    """A server of someone else's. ``everyone``: its login lets any token in; else it answers 200 to all."""

    everyone = False

    def do_GET(self):
        url = urllib.parse.urlsplit(self.path)
        nxt = urllib.parse.parse_qs(url.query).get("next")
        if self.everyone and url.path == "/login" and nxt:
            self.send_response(302)
            self.send_header("Location", nxt[0])
        else:
            self.send_response(200)
        self.end_headers()
        self.wfile.write(b"someone else's page")

    def log_message(self, *args):
        pass


@contextmanager
def foreign_server(everyone: bool = False):
    """Someone else's HTTP server on a free port of 127.0.0.1: yields the port."""
    handler = type("Handler", (Foreign,), {"everyone": everyone})
    with http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler) as server:
        thread = threading.Thread(target=server.serve_forever, daemon=True)
        thread.start()
        try:
            yield server.server_address[1]
        finally:
            server.shutdown()


@pytest.mark.parametrize("everyone", [False, True])
def test_a_foreign_server_does_not_pass_for_ours(everyone):
    with foreign_server(everyone) as port:
        assert course.port_taken(port)
        assert course.next_free_port(port) > port and not course.port_taken(course.next_free_port(port))
        assert not course.knows_token(f"http://127.0.0.1:{port}/", "0123456789abcdef")


@pytest.mark.parametrize("target", ["lab", "app"])
def test_make_refuses_a_port_that_is_taken(tmp_path, target):
    make = make_command()
    with foreign_server() as port:
        args = [f"PORT={port}", f"WORK={tmp_path / 'work'}"] if target == "lab" else ["CH=03", f"APP_PORT={port}"]
        result = subprocess.run(
            [make, "--no-print-directory", *this_venv(), target, *args],
            cwd=ROOT,
            env=make_env(tmp_path),
            capture_output=True,
            text=True,
            timeout=120,
        )
    said = result.stdout + result.stderr
    assert result.returncode != 0, said
    assert f"port {port} is already in use" in said
    fix = "make lab PORT=" if target == "lab" else "make app CH=03 APP_PORT="
    assert re.search(rf"Pick another: {re.escape(fix)}\d+", said), said
    assert "http://" not in said and "is ready" not in said, "an address was printed:\n" + said
