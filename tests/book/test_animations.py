"""Browser test of the offline animation in chapter 14 (``_build/html``): the page is
served from 127.0.0.1 and opened in headless Chromium (as in test_site.py); the
animation's canvas is found, the page has no console error and no uncaught exception,
and pressing Play advances the frames (the container's ``data-frame``), the slider
follows, Pause stops it.  Skipped when the site is not built, unless WT_REQUIRE_SITE=1."""

from __future__ import annotations

import functools
import http.server
import os
import shutil
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SITE = Path(os.environ.get("WT_SITE_DIR", ROOT / "_build" / "html")).resolve()
PAGE = "book/14-rolling-bodies.html"
CHROMIUM = os.environ.get("CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
REQUIRED = os.environ.get("WT_REQUIRE_SITE") == "1"
ANIMATION = "#wt-rattleback-animation"

pytestmark = pytest.mark.browser

if not (SITE / PAGE).is_file():
    _msg = f"no built page {SITE / PAGE}: run `make site` first"
    if REQUIRED:
        raise RuntimeError(_msg)
    pytest.skip(_msg, allow_module_level=True)


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):  # noqa: A002 - stdlib signature
        pass


@pytest.fixture(scope="module")
def base_url():
    handler = functools.partial(_Quiet, directory=str(SITE))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}/"
    server.shutdown()


def _favicon(url):
    # Chromium asks every server for /favicon.ico; the site need not have one
    return url.rstrip("/").endswith("/favicon.ico")


def test_animation_loads_and_advances(base_url):
    if REQUIRED:                     # with the site required, a missing Playwright fails
        from playwright import sync_api
    else:
        sync_api = pytest.importorskip("playwright.sync_api")
    errors, outside = [], []
    with sync_api.sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, headless=True,
                                     args=["--no-sandbox", "--disable-gpu",
                                           "--proxy-server=http://127.0.0.1:9",
                                           "--proxy-bypass-list=127.0.0.1"])
        try:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            page.on("console", lambda m: errors.append(f"{m.text} ({m.location.get('url')})")
                    if m.type == "error" and not _favicon(m.location.get("url", "")) else None)
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.on("request", lambda r: outside.append(r.url)
                    if r.url.startswith("http") and not r.url.startswith(base_url) else None)
            page.goto(base_url + PAGE, wait_until="load", timeout=30_000)
            root = page.locator(ANIMATION)
            assert root.count() == 1, "the animation is not on the page"
            assert root.locator("canvas").count() == 1
            assert root.get_attribute("data-frame") == "0"
            n = int(root.locator(".wt-slider").get_attribute("max"))
            assert n >= 100, f"only {n + 1} frames"
            root.locator(".wt-play").click()
            page.wait_for_timeout(1500)
            root.locator(".wt-play").click()               # pause
            stopped = root.get_attribute("data-frame")
            assert int(stopped) > 5, f"Play did not advance the frames ({stopped})"
            assert root.locator(".wt-slider").input_value() == stopped
            page.wait_for_timeout(400)
            assert root.get_attribute("data-frame") == stopped
            root.locator(".wt-slider").fill("150")         # the slider shows a frame
            assert root.get_attribute("data-frame") == "150"
            lit = page.evaluate("""() => {
                const c = document.querySelector('#wt-rattleback-animation canvas');
                const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
                let k = 0; for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0) k++;
                return k; }""")
            assert lit > 2000, "the canvas is (nearly) empty"
        finally:
            browser.close()
    assert errors == [], errors
    assert outside == [], outside
