"""Figures for the in-browser site (a benchmark that prints numbers, not a test).

    python scripts/bench_lite.py [--site _build/html]      (`make bench-lite`)

Prints
* the size of the lite part of the site on disk (``_build/html/lite``);
* the bytes served on a first visit (fresh browser profile, empty cache) until
  the kernel is ready, counted by the static server itself;
* page open → kernel ready (the status bar says "Python (Pyodide) | Idle");
* the first derivation cell (import + ``reduce`` + every step as LaTeX, i.e.
  derived and checked, for the sledge) timed inside the cell in the browser and
  in native Python (a fresh process), and their ratio; and the browser's wall
  time from pressing Shift+Enter to the typeset output, which also includes
  loading the SymPy/mpmath/whittaker_teach wheels and MathJax.

Requests not to 127.0.0.1 are blocked by the browser (as in tests/book/test_lite.py)
and counted; the count is printed too. The machine's load average is printed
with the figures: on the shared 2-core machine it changes them a lot.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import serve  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
BLOCK_ARGS = ["--no-sandbox", "--disable-gpu", "--no-first-run",
              "--disable-background-networking", "--disable-component-update",
              "--proxy-server=http://127.0.0.1:9", "--proxy-bypass-list=127.0.0.1",
              "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]
NOTEBOOK = "book/your-own-system.ipynb"
CELL = """import time
_t0 = time.perf_counter()
import whittaker_teach as wt
red = wt.examples.sledge().reduce("x", direction=+1)
_tex = red.steps.to_latex()
_dt = time.perf_counter() - _t0
print(f"BENCH {_dt:.3f} s, {len(red.steps.steps)} steps")"""


def du(path: Path) -> int:
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


class CountingHandler(serve.Handler):
    def copyfile(self, source, outputfile):
        start = source.tell()
        super().copyfile(source, outputfile)
        self.server.bytes_sent += source.tell() - start


def native_cell() -> float:
    env = dict(os.environ, PYTHONHASHSEED="0",
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run([sys.executable, "-c", CELL], env=env, capture_output=True,
                         text=True, check=True).stdout
    return float(re.search(r"BENCH ([\d.]+)", out).group(1))


def browser_figures(site: Path):
    import functools
    import http.server
    import threading

    from playwright.sync_api import sync_playwright

    handler = functools.partial(CountingHandler, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    server.bytes_sent = 0
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    outside = []
    fig = {}
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=BLOCK_ARGS)
            ctx = browser.new_context(viewport={"width": 1280, "height": 900})
            ctx.on("request", lambda r: None if r.url.startswith(
                ("http://127.0.0.1:", "ws://127.0.0.1:", "data:", "blob:")) else outside.append(r.url))
            page = ctx.new_page()
            t0 = time.monotonic()
            page.goto(f"{base}lite/lab/index.html?path={NOTEBOOK}")
            status = page.locator(".jp-StatusBar-TextItem", has_text="Pyodide")
            status.filter(has_text="Idle").wait_for(timeout=300_000)
            fig["kernel_ready_s"] = time.monotonic() - t0
            fig["first_visit_bytes"] = server.bytes_sent

            cell = page.locator(".jp-CodeCell").first
            cell.locator(".cm-content").click()
            page.keyboard.press("Control+A")
            page.keyboard.press("Delete")
            page.keyboard.insert_text(CELL + "\nred.show()")
            t1 = time.monotonic()
            page.keyboard.press("Control+Enter")
            out = cell.locator(".jp-OutputArea")
            try:
                out.get_by_text("BENCH").wait_for(timeout=300_000)
            except Exception:
                sys.exit("bench_lite: the cell printed no BENCH line; its output:\n"
                         + out.inner_text()[:2000])
            out.locator(".jp-RenderedLatex mjx-container").last.wait_for(timeout=120_000)
            status.filter(has_text="Idle").wait_for(timeout=120_000)
            fig["browser_wall_s"] = time.monotonic() - t1
            text = out.inner_text()
            fig["browser_cell_s"] = float(re.search(r"BENCH ([\d.]+)", text).group(1))
            fig["total_bytes"] = server.bytes_sent
            browser.close()
    finally:
        server.shutdown()
    fig["outside_requests"] = len(outside)
    return fig


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--site", type=Path, default=ROOT / "_build" / "html")
    args = ap.parse_args(argv)
    lite = args.site / "lite"
    if not (lite / "jupyter-lite.json").exists():
        sys.exit(f"bench_lite: no lite site in {lite}: run `make book` first")
    load = os.getloadavg()[0]
    size = du(lite)
    fig = browser_figures(args.site)
    native = native_cell()
    print(f"lite site on disk           {size / 1e6:8.1f} MB   (target < 60 MB)")
    print(f"first visit, bytes served   {fig['first_visit_bytes'] / 1e6:8.1f} MB   "
          f"(to kernel ready; {fig['total_bytes'] / 1e6:.1f} MB after the first cell)")
    print(f"page open → kernel ready    {fig['kernel_ready_s']:8.1f} s    (target < 15 s)")
    print(f"first derivation cell       {fig['browser_cell_s']:8.2f} s    in the browser "
          f"(in-cell timer; target < 5 s)")
    print(f"                            {native:8.2f} s    native Python (fresh process)")
    print(f"                            {fig['browser_cell_s'] / native:8.1f} ×    browser / native")
    print(f"  wall time, run → typeset  {fig['browser_wall_s']:8.2f} s    (with loading the "
          f"SymPy/mpmath/whittaker_teach wheels and MathJax)")
    print(f"requests outside 127.0.0.1  {fig['outside_requests']:8d}")
    print(f"load average at start       {load:8.2f}      (2 cores, shared)")


if __name__ == "__main__":
    main()
