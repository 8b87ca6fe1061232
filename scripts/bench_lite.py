"""Figures for the in-browser site (a benchmark that prints numbers, not a test).

    python scripts/bench_lite.py [--site _build/html] [--visits 2] [--server plain]
                                                                   (`make bench-lite`)

Prints
* the size of the lite part of the site on disk (``_build/html/lite``);
* for a first visit (fresh browser profile, empty HTTP and code caches) and a
  second visit (the same profile directory again, in a new browser process, so
  that the HTTP cache and V8's wasm code cache are warm):
  - the bytes served until the kernel is ready, counted by the static server
    itself, and how many requests it answered (200 / 304);
  - page open → kernel ready (the status bar says "Python (Pyodide) | Idle");
  - where that time went, as a timeline: the kernel's worker, started with the
    page (scripts/lite_early_kernel.py), starting Pyodide and importing IPython
    while JupyterLab starts, until the kernel asks for Pyodide, then the kernel's
    own steps (below); and the worker's fetches (its Resource Timing entries:
    start, end, MB over the wire / body);
  - the first derivation cell (import + ``reduce`` + every step as LaTeX, i.e.
    derived and checked, for the sledge), run right after "Idle", timed inside
    the cell and split into ``import sympy``, ``import whittaker_teach``,
    ``reduce`` and ``to_latex`` (the imports are ~0 when the kernel's start-up
    file has already imported them in the background: scripts/lite_kernel/), and
    the browser's wall time from pressing Ctrl+Enter to the printed and to the
    typeset output, which also includes loading the SymPy/mpmath/whittaker_teach
    wheels and importing them (or waiting for the start-up file to) and MathJax;
  - the kernel worker's own steps (loadPyodide with the kernel's packages, the
    kernel's imports; during the cell, loading packages), from performance marks
    left by the worker started with the page and by a timing wrapper of the
    site's loader that only the benchmark's server serves (``TIMED_PYODIDE``;
    the built site is not changed);
* the same cell in native Python (a fresh process), and the browser/native ratio.

Requests not to 127.0.0.1 are blocked by the browser (as in tests/book/test_lite.py)
and counted; the count is printed too. The machine's load average is printed
with the figures: on the shared 2-core machine it changes them a lot.
"""
from __future__ import annotations

import argparse
import http.server
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from urllib.parse import urlsplit

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
_t = [time.perf_counter()]
import sympy
_t.append(time.perf_counter())
import whittaker_teach as wt
_t.append(time.perf_counter())
red = wt.examples.sledge().reduce("x", direction=+1)
_t.append(time.perf_counter())
_tex = red.steps.to_latex()
_t.append(time.perf_counter())
print(f"BENCH {_t[-1] - _t[0]:.3f} s, {len(red.steps.steps)} steps")
print("PARTS " + " ".join(f"{b - a:.3f}" for a, b in zip(_t, _t[1:])))"""
PARTS = ("import sympy", "import whittaker_teach", "reduce", "steps.to_latex")


def du(path: Path) -> int:
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


class PlainHandler(http.server.SimpleHTTPRequestHandler):
    """The standard library's static server with only the site's MIME types (what
    scripts/serve.py was before it sent cache headers): ``--server plain``."""
    extensions_map = serve.Handler.extensions_map

    def log_message(self, fmt, *args):
        pass


class CountingMixin:
    """Counts bytes and logs (time, path, status) per request."""

    def copyfile(self, source, outputfile):
        start = source.tell()
        super().copyfile(source, outputfile)
        self.server.bytes_sent += source.tell() - start

    def send_response(self, code, message=None):
        self.server.log.append((time.monotonic(), urlsplit(self.path).path, code,
                                "If-None-Match" in self.headers
                                or "If-Modified-Since" in self.headers))
        super().send_response(code, message)


class InstrumentMixin:
    """Serves the site with the kernel pointed at ``TIMED_PYODIDE`` (a wrapper of
    the site's loader, static/pyodide/wt-pyodide.mjs, that leaves performance marks
    in the kernel's worker). Only the benchmark's server does this; the built site
    is not changed. With ``--no-warm-up``, the kernel's options and those of the
    worker started with the page (static/pyodide/wt-kernel.worker.mjs) both lose
    the start-up file, so that the early Pyodide is still the kernel's."""

    def do_GET(self):
        path = urlsplit(self.path).path
        no_warm_up = getattr(self.server, "no_warm_up", False)
        if path.endswith("/lite/jupyter-lite.json"):
            data = json.loads((Path(self.directory) / path.lstrip("/")).read_text())
            kernel = data["jupyter-config-data"]["litePluginSettings"][KERNEL_PLUGIN]
            kernel["pyodideUrl"] = kernel["pyodideUrl"].rsplit("/", 1)[0] + "/" + TIMED_NAME
            if no_warm_up:
                kernel.get("loadPyodideOptions", {}).get("env", {}).pop("PYTHONSTARTUP", None)
            return self._send_bytes(json.dumps(data).encode(), "application/json")
        if path.endswith("/static/pyodide/" + TIMED_NAME):
            return self._send_bytes(TIMED_PYODIDE.encode(), "text/javascript")
        if no_warm_up and path.endswith("/static/pyodide/wt-kernel.worker.mjs"):
            text = (Path(self.directory) / path.lstrip("/")).read_text()
            text = re.sub(r'"PYTHONSTARTUP": "[^"]*"', "", text)
            return self._send_bytes(text.encode(), "text/javascript")
        return super().do_GET()

    def _send_bytes(self, body: bytes, ctype: str):
        self.send_response(200)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)
        self.server.bytes_sent += len(body)


class CountingHandler(InstrumentMixin, CountingMixin, serve.Handler):
    pass


class PlainCountingHandler(InstrumentMixin, CountingMixin, PlainHandler):
    pass


KERNEL_PLUGIN = "@jupyterlite/pyodide-kernel-extension:kernel"
TIMED_NAME = "bench-timed-pyodide.mjs"
#: the kernel's worker imports this instead of wt-pyodide.mjs: the same
#: loadPyodide (which hands over the Pyodide started with the page, whose own
#: steps are marked by wt-kernel.worker.mjs), then the kernel's own steps
#: (runPythonAsync: micropip / piplite set-up, ``import pyodide_kernel``) and the
#: cells' package loads, each between two performance marks ("wt:<label>")
TIMED_PYODIDE = """import { loadPyodide as load } from "./wt-pyodide.mjs";
const mark = (label) => performance.mark("wt:" + label);
export async function loadPyodide(options) {
  const py = await load(options);
  for (const name of ["runPythonAsync", "loadPackagesFromImports", "loadPackage"]) {
    const orig = py[name].bind(py);
    py[name] = async (arg, ...rest) => {
      const what = typeof arg === "string" ? arg.trim().split("\\n")[0].slice(0, 60)
                                           : JSON.stringify(arg).slice(0, 60);
      mark("kernel: " + name + ": " + what);
      try { return await orig(arg, ...rest); } finally { mark("kernel: " + name + ": " + what + " end"); }
    };
  }
  return py;
}
"""


def native_cell() -> tuple[float, list[float]]:
    env = dict(os.environ, PYTHONHASHSEED="0",
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run([sys.executable, "-c", CELL], env=env, capture_output=True,
                         text=True, check=True).stdout
    return (float(re.search(r"BENCH ([\d.]+)", out).group(1)),
            [float(x) for x in re.search(r"PARTS ([\d. ]+)", out).group(1).split()])


# ------------------------------------------------------------------ the worker's timeline
#: the kernel worker's fetches, from its own Resource Timing entries (ms since the
#: worker's time origin) and the time origin itself (ms since the epoch)
_WORKER_TIMING_JS = """() => ({
  origin: performance.timeOrigin,
  now: performance.now(),
  marks: performance.getEntriesByType('mark').filter(m => m.name.startsWith('wt:'))
    .map(m => ({name: m.name.slice(3), t: m.startTime})),
  entries: performance.getEntriesByType('resource').map(e => ({
    name: e.name, start: e.startTime, end: e.responseEnd,
    transfer: e.transferSize, body: e.encodedBodySize, decoded: e.decodedBodySize}))
})"""


def _short(url: str) -> str:
    path = urlsplit(url).path
    return path.rsplit("/", 1)[-1] or path


def _intervals(marks: list[dict]) -> list[tuple[str, float, float, int]]:
    """(label, start ms, end ms, depth) from "label" … "label end" mark pairs, in
    the order they start; depth 1 for a step inside another (e.g. a loadPackage
    inside a runPythonAsync). Steps of the worker started with the page and of the
    kernel may overlap: they are paired by label, not by order."""
    out, open_ = [], {}
    for m in marks:
        name = m["name"]
        if name.endswith(" end") and open_.get(name[:-4]):
            label = name[:-4]
            out.append((label, open_[label].pop(), m["t"]))
        else:
            open_.setdefault(name, []).append(m["t"])
    out.sort(key=lambda x: (x[1], -x[2]))
    return [(label, a, b, int(any(a2 <= a and b <= b2 and (a2, b2) != (a, b)
                                  for _, a2, b2 in out)))
            for label, a, b in out]


def phases(timing: dict, t_open_ms: float, t_ready_ms: float) -> list[tuple]:
    """The kernel's start as a timeline: (label, start s, end s, depth), seconds
    since the page was opened, from the marks left in the kernel's worker by the
    worker itself (wt-kernel.worker.mjs, started with the page), the site's loader
    (wt-pyodide.mjs: "kernel asks for Pyodide") and the benchmark's wrapper of it
    (``TIMED_PYODIDE``: the kernel's own steps).

    The worker started with the page: loadPyodide (fetch and compile the wasm,
    python_stdlib.zip, start Python, and load the kernel's packages: fetch, check
    and unpack wheels) → ``import piplite, pyodide_kernel`` (IPython, jedi, …).
    Meanwhile JupyterLab starts and opens the notebook, then starts the kernel,
    which asks for Pyodide (and waits for the early one if it is not yet ready),
    runs its own set-up steps (quick: their imports are done) and is ready; the
    page shows "Idle" once the kernel answers.
    """
    origin = timing["origin"]
    since_open = lambda ms: (origin + ms - t_open_ms) / 1000   # noqa: E731
    out = [("the kernel's worker starts", 0.0, (origin - t_open_ms) / 1000, 0)]
    marks = [m for m in timing.get("marks", []) if origin + m["t"] <= t_ready_ms]
    asked = None
    for label, a, b, depth in _intervals(marks):
        out.append((label, since_open(a), since_open(b), depth))
        if label == "kernel asks for Pyodide" and asked is None:
            asked = since_open(a)
    if asked is not None:
        out.append(("JupyterLab's own start, until the kernel asks for Pyodide",
                    0.0, asked, 0))
    out.append(("kernel ready (\"Idle\" on the page)", (t_ready_ms - t_open_ms) / 1000,
                (t_ready_ms - t_open_ms) / 1000, 0))
    return sorted(out, key=lambda x: (x[2], x[1]))


def cell_marks(timing: dict, t_from_ms: float) -> list[tuple[str, float]]:
    """(label, seconds) of the timed kernel steps in the worker after ``t_from_ms``."""
    origin = timing["origin"]
    marks = [m for m in timing.get("marks", []) if origin + m["t"] >= t_from_ms]
    return [(("  " * depth) + name, (b - a) / 1000) for name, a, b, depth in _intervals(marks)]


def fetch_table(timing: dict, t_ready_ms: float) -> list[tuple]:
    """(file, start s, end s, MB over the wire, MB body) per fetch until ready."""
    origin = timing["origin"]
    rows = []
    for e in sorted(timing["entries"], key=lambda e: e["start"]):
        if origin + e["start"] > t_ready_ms or "/api/drive" in e["name"]:
            continue            # (DriveFS's file-system calls: counted apart)
        rows.append((_short(e["name"]), e["start"] / 1000, e["end"] / 1000,
                     e["transfer"] / 1e6, e["body"] / 1e6))
    return rows


def _kernel_worker(page):
    for w in page.workers:
        if any(name in w.url for name in ("wt-kernel.worker", "comlink.worker",
                                          "coincident.worker")):
            return w
    return None


# ------------------------------------------------------------------ one visit
def visit(p, profile: Path, base: str, server, run_cell: bool = True) -> dict:
    """Open the "your own system" notebook in a browser on ``profile``; figures."""
    outside = []
    fig = {}
    ctx = p.chromium.launch_persistent_context(
        str(profile), executable_path=CHROMIUM, args=BLOCK_ARGS, headless=True,
        viewport={"width": 1280, "height": 900})
    try:
        ctx.on("request", lambda r: None if r.url.startswith(
            ("http://127.0.0.1:", "ws://127.0.0.1:", "data:", "blob:", "about:",
             "chrome:", "chrome-extension:")) else outside.append(r.url))
        page = ctx.pages[0] if ctx.pages else ctx.new_page()
        server.bytes_sent = 0
        server.log = []
        t0 = time.monotonic()
        t0_ms = time.time() * 1000
        page.goto(f"{base}lite/lab/index.html?path={NOTEBOOK}")
        status = page.locator(".jp-StatusBar-TextItem", has_text="Pyodide")
        status.filter(has_text="Idle").wait_for(timeout=300_000)
        fig["kernel_ready_s"] = time.monotonic() - t0
        t_ready_ms = t0_ms + fig["kernel_ready_s"] * 1000
        fig["bytes_to_ready"] = server.bytes_sent
        codes = [c for _, _, c, _ in server.log]
        fig["requests_to_ready"] = (len(codes), codes.count(200), codes.count(304),
                                    sum(cond for *_, cond in server.log))
        worker = _kernel_worker(page)
        if worker is not None:
            timing = worker.evaluate(_WORKER_TIMING_JS)
            fig["phases"] = phases(timing, t0_ms, t_ready_ms)
            fig["fetches"] = fetch_table(timing, t_ready_ms)
            fig["drive_calls"] = sum("/api/drive" in e["name"] for e in timing["entries"]
                                     if timing["origin"] + e["start"] <= t_ready_ms)
        if run_cell:
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
            fig["browser_printed_s"] = time.monotonic() - t1
            out.locator(".jp-RenderedLatex mjx-container").last.wait_for(timeout=120_000)
            status.filter(has_text="Idle").wait_for(timeout=120_000)
            fig["browser_wall_s"] = time.monotonic() - t1
            text = out.inner_text()
            fig["browser_cell_s"] = float(re.search(r"BENCH ([\d.]+)", text).group(1))
            fig["browser_parts"] = [float(x) for x in
                                    re.search(r"PARTS ([\d. ]+)", text).group(1).split()]
            if worker is not None:
                fig["cell_steps"] = cell_marks(worker.evaluate(_WORKER_TIMING_JS),
                                               t0_ms + (t1 - t0) * 1000)
            fig["total_bytes"] = server.bytes_sent
    finally:
        ctx.close()
    fig["outside_requests"] = len(outside)
    return fig


def browser_figures(site: Path, visits: int = 2, plain: bool = False,
                    no_warm_up: bool = False) -> list[dict]:
    import functools
    import threading

    from playwright.sync_api import sync_playwright

    handler = functools.partial(PlainCountingHandler if plain else CountingHandler,
                                directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    server.bytes_sent = 0
    server.log = []
    server.no_warm_up = no_warm_up
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    # one server (one origin) for every visit: the HTTP cache is keyed by URL
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    figs = []
    try:
        with tempfile.TemporaryDirectory(prefix="wt-bench-lite-") as profile, \
                sync_playwright() as p:
            for _ in range(visits):
                figs.append(visit(p, Path(profile), base, server))
    finally:
        server.shutdown()
    return figs


def report(fig: dict, name: str, native: tuple[float, list[float]]) -> None:
    n, ok, not_modified, conditional = fig["requests_to_ready"]
    print(f"\n{name} visit")
    print(f"  bytes served to ready     {fig['bytes_to_ready'] / 1e6:8.1f} MB   "
          f"({n} requests, {conditional} conditional: {ok} × 200, {not_modified} × 304;")
    print(f"{'':38s}{fig['total_bytes'] / 1e6:.1f} MB after the first cell)")
    print(f"  page open → kernel ready  {fig['kernel_ready_s']:8.1f} s")
    if fig.get("phases"):
        print("    when each step ended, since the page was opened (and how long it took):")
    for phase, a, b, depth in fig.get("phases", []):
        print(f"    {b:6.2f} s  ({b - a:5.2f} s)  {'  ' * depth}{phase}")
    if fig.get("fetches"):
        print("    the kernel worker's fetches until ready (s since the worker started;\n"
              "    MB over the wire / body):")
        for fname, a, b, transfer, body in fig["fetches"]:
            print(f"      {a:6.2f} → {b:6.2f}  {transfer:6.2f} / {body:6.2f}  {fname}")
        print(f"      (and {fig['drive_calls']} DriveFS calls to /api/drive)")
    cell, parts = fig["browser_cell_s"], fig["browser_parts"]
    native_s, native_parts = native
    warm = parts[0] < 0.05
    print(f"  first derivation cell     {cell:8.2f} s    in the browser (in-cell timer)"
          f" = {cell / native_s:.1f} × native" + (" (*)" if warm else ""))
    if warm:
        print("    (*) not like for like: SymPy and whittaker_teach were already imported by\n"
              "    the kernel's start-up file in the background; the cell, run right after\n"
              "    \"Idle\", waited for that: see Ctrl+Enter → output")
    for label, b, nat in zip(PARTS, parts, native_parts):
        print(f"    {b:6.2f} s  {label:24s} (native {nat:.2f} s)")
    for label, secs in fig.get("cell_steps", []):
        print(f"    {secs:6.2f} s  {label}")
    print(f"  Ctrl+Enter → output       {fig['browser_printed_s']:8.2f} s    "
          f"(with loading and importing SymPy, mpmath and")
    print(f"{'':38s}whittaker_teach, or waiting for the start-up file to)")
    print(f"  Ctrl+Enter → typeset      {fig['browser_wall_s']:8.2f} s    (and MathJax)")
    print(f"  requests outside 127.0.0.1 {fig['outside_requests']:7d}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--site", type=Path, default=ROOT / "_build" / "html")
    ap.add_argument("--visits", type=int, default=2,
                    help="visits with one browser profile (1: the first visit only)")
    ap.add_argument("--server", choices=("site", "plain"), default="site",
                    help="site: scripts/serve.py (ETag, no-cache); plain: the standard "
                         "library's server (Last-Modified only, as before)")
    ap.add_argument("--no-warm-up", action="store_true",
                    help="serve the site's jupyter-lite.json without the kernel's start-up "
                         "file (PYTHONSTARTUP), so the first cell imports SymPy itself")
    args = ap.parse_args(argv)
    lite = args.site / "lite"
    if not (lite / "jupyter-lite.json").exists():
        sys.exit(f"bench_lite: no lite site in {lite}: run `make book` (or `make lite`) first")
    load = os.getloadavg()
    size = du(lite)
    figs = browser_figures(args.site, args.visits, plain=args.server == "plain",
                           no_warm_up=args.no_warm_up)
    native = native_cell()
    load_end = os.getloadavg()
    print(f"lite site on disk           {size / 1e6:8.1f} MB   (target < 60 MB); "
          f"server: {args.server}" + ("; without the start-up file" if args.no_warm_up else ""))
    for i, fig in enumerate(figs):
        report(fig, ("first", "second", "third")[i] if i < 3 else f"#{i + 1}", native)
    print(f"\nnative derivation cell      {native[0]:8.2f} s    (fresh process)")
    print("targets: kernel ready < 10 s on a first visit, < 5 s on a second; "
          "the derivation < 2 s")
    print(f"load average (1 min)        {load[0]:8.2f}      at start, "
          f"{load_end[0]:.2f} at the end (2 cores, shared)")


if __name__ == "__main__":
    main()
