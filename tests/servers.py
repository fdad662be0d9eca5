"""Servers the tests start, and how they talk to them.

`make lab` (tests/test_lab.py), `make app` (tests/browser/test_voila.py) and the course's
lab server over a saved copy (tests/browser/test_saved_notebook.py) are each started as a
:class:`Served` command: it runs in its own process group, its output is read line by
line, the address it prints is picked out, and the whole group is stopped at the end.
A lab the course starts must leave the tracked notebooks as they are (:func:`tracked_hashes`).
"""

from __future__ import annotations

import hashlib
import os
import re
import signal
import socket
import subprocess
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from tools import course

ROOT = Path(__file__).resolve().parents[1]
# What a student's terminal must not show: a warning, an error, an untrusted notebook.
ALARMING = re.compile(r"warn|error|deprecat|not trusted|\[W |\[E ", re.I)


def tracked_hashes() -> dict[str, str]:
    """Each tracked notebook's SHA-256, by file name."""
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in course.notebooks(ROOT / "notebooks")}


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def get(url: str, headers: dict[str, str] | None = None) -> tuple[int, bytes]:
    """GET ``url``: the status and the body, an HTTP error included."""
    request = urllib.request.Request(url, headers=headers or {})
    try:
        with urllib.request.urlopen(request, timeout=30) as response:
            return response.status, response.read()
    except urllib.error.HTTPError as error:
        with error:
            return error.code, error.read()


class Served:
    """A command that serves: its output lines, and the first address it prints that matches ``url_pattern``.

    With ``try_at_once``, the address is requested the moment it is printed (``first_try``:
    the status and body, or the error): a server must answer at the address it prints.
    """

    def __init__(self, command, cwd, env, url_pattern: str, try_at_once: bool = False):
        self.lines: list[str] = []
        self.url: str | None = None
        self.first_try: tuple[int, bytes] | str | None = None
        self.pattern = re.compile(url_pattern)
        self.try_at_once = try_at_once
        self.proc = subprocess.Popen(
            command,
            cwd=cwd,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            start_new_session=True,  # its own process group, stopped as a whole
        )
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self) -> None:
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))
            match = self.pattern.search(line)
            if match and self.url is None:
                if self.try_at_once:
                    try:
                        self.first_try = get(match[0])
                    except (urllib.error.URLError, OSError) as error:
                        self.first_try = f"{type(error).__name__}: {error}"
                self.url = match[0]

    def wait_for_url(self, timeout_s: float) -> str:
        """The printed address; the test fails if the command exits or prints none within ``timeout_s``."""
        deadline = time.monotonic() + timeout_s
        while self.url is None:
            if self.proc.poll() is not None:
                self.reader.join(timeout=5)
                if self.url is not None:
                    break
                pytest.fail(f"exited with {self.proc.returncode} before printing an address:\n{self.tail()}")
            if time.monotonic() > deadline:
                pytest.fail(f"no address printed in {timeout_s} s:\n{self.tail()}")
            time.sleep(0.1)
        return self.url

    def tail(self, n: int = 40) -> str:
        return "\n".join(self.lines[-n:])

    def stop(self) -> None:
        """Stop the whole process group: SIGTERM, then SIGKILL if it does not end."""
        for sig, wait_s in ((signal.SIGTERM, 20), (signal.SIGKILL, 10)):
            try:
                os.killpg(self.proc.pid, sig)
            except ProcessLookupError:
                break
            try:
                self.proc.wait(timeout=wait_s)
                break
            except subprocess.TimeoutExpired:
                continue
        self.reader.join(timeout=5)
        self.proc.stdout.close()
