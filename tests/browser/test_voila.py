"""A chapter as an app: the real `make app` serves it with Voilà, and its demo responds.

`make app CH=04` runs in this test environment's own venv (make is told not to rebuild
it), on a free port.  The page must show the chapter's prose and its live demo without
any code, and a key press on a slider must change the picture, while the terminal shows no
warning.  The server must refuse a visitor without the token.  The process group of `make app` is stopped at the end.
"""

from __future__ import annotations

import os
import re
import shutil
import sys
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from tests.servers import ALARMING, Served, free_port
from tools.course import NoRedirect

try:
    from playwright.sync_api import TimeoutError as PlaywrightTimeoutError
except ImportError:  # the `browser` fixture skips (fails on CI) with the reason
    PlaywrightTimeoutError = TimeoutError

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
CHAPTER = "04"  # the Kalman gain: a demo made of sliders
START_TIMEOUT_S = 120
RENDER_TIMEOUT_MS = 240_000  # Voilà runs the whole chapter before the demo is live
CHANGE_TIMEOUT_MS = 15_000

JS_IMG_READY = """(img) => /^(data|blob):/.test(img.getAttribute('src') || '')
    && img.complete && img.naturalWidth > 0"""


@pytest.fixture(scope="module")
def app(tmp_path_factory, chromium_executable):
    make = shutil.which("make")
    if make is None:
        if os.environ.get("CI") == "true":
            pytest.fail("`make` is missing; `make app` cannot be tested", pytrace=False)
        pytest.skip("`make` is missing; `make app` cannot be tested")
    base = tmp_path_factory.mktemp("make-app")
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "JUPYTER_TOKEN")}
    env["JUPYTER_RUNTIME_DIR"] = str(base)
    venv = Path(sys.prefix)
    port = free_port()
    command = [
        make,
        "--no-print-directory",
        f"--assume-old={venv / '.kfcourse-installed'}",
        "app",
        f"VENV={venv}",
        f"CH={CHAPTER}",
        f"APP_PORT={port}",
    ]
    server = Served(command, ROOT, env, rf"http://127\.0\.0\.1:{port}/\?token=[0-9a-f]{{16,}}")
    try:
        yield {"url": server.wait_for_url(START_TIMEOUT_S), "port": port, "lines": server.lines}
    finally:
        server.stop()


def test_app_refuses_a_visitor_without_the_token(app):
    opener = urllib.request.build_opener(NoRedirect)
    with pytest.raises(urllib.error.HTTPError) as page:
        opener.open(f"http://127.0.0.1:{app['port']}/", timeout=30)
    with page.value:
        assert page.value.code in (302, 403)
        assert page.value.code == 403 or "/login" in page.value.headers["Location"]


def test_app_shows_prose_and_a_live_demo_without_code(browser, app, report):
    context = browser.new_context(viewport={"width": 1920, "height": 1200})  # a wide screen: nothing stretches
    errors: list[str] = []
    try:
        # Only this machine's server: the badge images and anything else from the web are not fetched.
        local = f"http://127.0.0.1:{app['port']}/"
        context.route("**/*", lambda route: route.continue_() if route.request.url.startswith(local) else route.abort())
        page = context.new_page()
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(app["url"], timeout=RENDER_TIMEOUT_MS)
        demo = page.locator(".kf-demo").first
        img = demo.locator("img.kf-figure").first
        try:
            img.wait_for(timeout=RENDER_TIMEOUT_MS)
            page.wait_for_function(JS_IMG_READY, arg=img.element_handle(), timeout=RENDER_TIMEOUT_MS)
        except PlaywrightTimeoutError:
            pytest.fail(f"no live demo picture in the app view; page errors: {errors}", pytrace=False)

        shown, natural = img.evaluate("i => [i.getBoundingClientRect().width, i.naturalWidth]")
        assert shown <= natural / 2 + 0.5, f"the app shows the picture {shown:.0f} px wide, drawn for {natural / 2:.0f}"

        text = page.inner_text("body")
        assert re.search(r"Chapter 4\b", text), "the chapter's prose is not shown"
        assert "kf.demos" not in text and "import kfcourse" not in text, "the app view shows code"
        assert page.locator(".jp-InputArea-editor, .cm-editor").count() == 0, "the app view shows code editors"
        assert page.locator(".jupyter-widgets-error-widget").count() == 0

        slider = demo.locator(".widget-slider").first
        handle = slider.locator(".noUi-handle").first
        handle.scroll_into_view_if_needed()
        for key in ("End", "Home"):
            before = img.get_attribute("src")
            handle.focus()
            page.keyboard.press(key)
            try:
                page.wait_for_function(
                    "([i, s]) => i.getAttribute('src') !== s",
                    arg=[img.element_handle(), before],
                    timeout=CHANGE_TIMEOUT_MS,
                )
            except PlaywrightTimeoutError:
                pytest.fail(f"{key} on the slider did not change the picture in the app view", pytrace=False)
        page.screenshot(path=str(report.artifacts / f"voila_{CHAPTER}.png"))
    finally:
        context.close()
    alarming = [line for line in app["lines"] if ALARMING.search(line)]
    assert not alarming, "the student's terminal shows:\n" + "\n".join(alarming)
