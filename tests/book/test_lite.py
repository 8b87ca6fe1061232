"""The in-browser site (JupyterLite + Pyodide) inside the built book.

Built by ``make site`` (scripts/build_lite.py) into ``_build/html/lite``. The
static checks read the files; the browser test serves the site from 127.0.0.1,
blocks and counts every request to any other address, opens chapter 4 through
its page's "Run in the browser" button, runs every cell in Pyodide, then opens a
student exercise the same way and checks the checker's feedback for a right and
a wrong answer.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import sys
import tempfile
import time
import zipfile
from pathlib import Path
from urllib.parse import parse_qs, urljoin, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[2]
SITE = ROOT / "_build" / "html"
LITE = SITE / "lite"
sys.path.insert(0, str(ROOT / "scripts"))

import build_lite  # noqa: E402
import lite_early_kernel  # noqa: E402
import lite_notebooks  # noqa: E402
import pyc_lite  # noqa: E402

if not (LITE / "jupyter-lite.json").is_file():
    _msg = f"no lite site at {LITE}: run `make site` (or `make lite`) first"
    if os.environ.get("WT_REQUIRE_SITE") == "1":
        raise RuntimeError(_msg)
    pytest.skip(_msg, allow_module_level=True)

PYODIDE = LITE / "static" / "pyodide"
KERNEL_READY_S = 180       # Pyodide start-up took 12-45 s on the shared 2-core machine
RUN_ALL_S = 600
_LAUNCH_RE = re.compile(r'<a href="([^"]*lite/[^"]*)"[^>]*class="[^"]*btn-run-in-browser')


def _config():
    return json.loads((LITE / "jupyter-lite.json").read_text())["jupyter-config-data"]


def _launch_links(rel: str) -> list[str]:
    return _LAUNCH_RE.findall((SITE / rel).read_text(encoding="utf-8"))


def _page_of(doc: str) -> str:
    return doc + ".html"


# ------------------------------------------------------------------ static checks
def test_kernel_uses_the_local_pyodide_and_no_pypi():
    settings = _config()["litePluginSettings"][build_lite.KERNEL_PLUGIN]
    # the local Pyodide, through the loader that hands over the early one
    assert settings["pyodideUrl"] == "./static/pyodide/wt-pyodide.mjs"
    core = lite_early_kernel.core_dir(LITE)
    assert f'from "../{core.name}/pyodide.mjs"' in (PYODIDE / "wt-pyodide.mjs").read_text()
    assert settings["disablePyPIFallback"] is True
    for url in settings.get("pipliteUrls", []):
        assert url.startswith("./"), url
    # Pyodide's own files in their content-named folder, the lock and wheels beside
    # the loader (scripts/lite_early_kernel.py)
    for name in ("pyodide.mjs", "pyodide.asm.mjs", "pyodide.asm.wasm", "python_stdlib.zip"):
        assert (core / name).is_file(), name
        assert not (PYODIDE / name).exists(), name
    assert core.name == lite_early_kernel.core_name(
        [core / n for n in lite_early_kernel.CORE_FILES])


def test_lock_lists_exactly_the_served_wheels_with_their_sha256():
    lock = json.loads((PYODIDE / "pyodide-lock.json").read_text())
    served = sorted(p.name for p in PYODIDE.glob("*.whl"))
    listed = sorted(e["file_name"] for e in lock["packages"].values())
    assert listed == served
    for entry in lock["packages"].values():
        digest = hashlib.sha256((PYODIDE / entry["file_name"]).read_bytes()).hexdigest()
        assert entry["sha256"] == digest, entry["file_name"]
        for dep in entry["depends"]:
            assert dep.lower().replace("_", "-") in lock["packages"], (entry["name"], dep)
    pkg = lock["packages"]["whittaker-teach"]
    assert pkg["imports"] == ["whittaker_teach"]
    assert sorted(pkg["depends"]) == ["mpmath", "sympy"]
    for name in ("sympy", "mpmath", "ipython", "jedi", "comm", "micropip"):
        assert name in lock["packages"], name
    assert not [k for k in lock["packages"] if k in ("numpy", "scipy", "matplotlib")]


def test_kernel_loads_its_packages_from_the_lock_while_pyodide_starts():
    """The kernel's packages (micropip, piplite, pyodide-kernel, ipykernel, IPython,
    jedi, comm) are preloaded by loadPyodide from the site's lock, under the names
    the kernel's worker checks (it then skips installing them through piplite)."""
    settings = _config()["litePluginSettings"][build_lite.KERNEL_PLUGIN]
    preload = settings["loadPyodideOptions"]["packages"]
    assert preload == list(build_lite.PRELOAD)
    assert {"micropip", "piplite", "ipykernel", "comm", "pyodide-kernel", "jedi",
            "ipython"} <= set(preload)
    lock = json.loads((PYODIDE / "pyodide-lock.json").read_text())["packages"]
    for name in preload:
        entry = lock[name]
        assert (PYODIDE / entry["file_name"]).is_file(), name
        for dep in entry["depends"]:                   # and what they need
            assert dep.lower().replace("_", "-") in lock, (name, dep)
    assert lock["pyodide-kernel"]["imports"] == ["pyodide_kernel"]


def test_the_kernel_start_up_file_is_served_and_set():
    """PYTHONSTARTUP names the start-up module's path in Pyodide's site-packages;
    its wheel is preloaded and carries the current scripts/lite_kernel/ source; as
    a start-up file (not a module) it only starts the background import."""
    options = _config()["litePluginSettings"][build_lite.KERNEL_PLUGIN]["loadPyodideOptions"]
    assert options["env"]["PYTHONSTARTUP"] == build_lite.STARTUP_PATH
    assert build_lite.STARTUP_PACKAGE in options["packages"]
    lock = json.loads((PYODIDE / "pyodide-lock.json").read_text())["packages"]
    entry = lock[build_lite.STARTUP_PACKAGE]
    site = f"/lib/python{build_lite.fetch_lite.PYODIDE_PYTHON}/site-packages/"
    with zipfile.ZipFile(PYODIDE / entry["file_name"]) as z:
        member = build_lite.STARTUP_PATH.removeprefix(site)
        assert z.read(member) == build_lite.STARTUP.read_bytes()
    # run as a start-up file: defines nothing in the user's namespace, calls start()
    calls = []
    fake = type(sys)("wt_lite_startup")
    fake.start = lambda: calls.append(1)
    ns = {"__name__": "__main__"}
    saved = sys.modules.get("wt_lite_startup")
    sys.modules["wt_lite_startup"] = fake
    try:
        exec(compile(build_lite.STARTUP.read_text(), "startup", "exec"), ns)
    finally:
        if saved is None:
            sys.modules.pop("wt_lite_startup")
        else:
            sys.modules["wt_lite_startup"] = saved
    assert calls == [1] and set(ns) == {"__name__", "__builtins__"}


def test_the_kernel_worker_is_started_with_the_page():
    """lab/index.html loads wt-early-kernel.js before JupyterLab; it starts
    wt-kernel.worker.mjs, which imports the kernel's own (comlink) worker file as
    served and starts Pyodide with exactly the kernel's loadPyodideOptions; the
    kernel's loader (wt-pyodide.mjs) hands that Pyodide over only if the options
    match (scripts/lite_early_kernel.py)."""
    html = (LITE / "lab" / "index.html").read_text()
    # (before the inline script that imports config-utils.js, which starts JupyterLab)
    assert html.index(lite_early_kernel.TAG) < html.index("jupyter-config-data") \
        < html.index("config-utils.js")
    worker = lite_early_kernel.kernel_worker(LITE)
    assert (LITE / lite_early_kernel.KERNEL_STATIC / worker).is_file()
    early = (PYODIDE / "wt-kernel.worker.mjs").read_text()
    imported = re.search(r'^import "([^"]+)";', early, re.M).group(1)
    assert (PYODIDE / imported).resolve() == (LITE / lite_early_kernel.KERNEL_STATIC
                                              / worker).resolve()
    options = json.loads(re.search(r"^const OPTIONS = (.*);$", early, re.M).group(1))
    assert options == _config()["litePluginSettings"][build_lite.KERNEL_PLUGIN][
        "loadPyodideOptions"]
    page_script = (LITE / lite_early_kernel.PAGE_SCRIPT).read_text()
    assert f"/static/{worker}" in page_script and "wt-kernel.worker.mjs" in page_script
    for path in (LITE / lite_early_kernel.PAGE_SCRIPT, PYODIDE / "wt-kernel.worker.mjs",
                 PYODIDE / "wt-pyodide.mjs"):
        assert "__KERNEL_WORKER__" not in path.read_text()
        assert "__OPTIONS__" not in path.read_text()


def test_the_served_ipython_imports_its_terminal_only_when_asked():
    """The served IPython's ``embed`` imports IPython.terminal when called (the
    kernel never starts a terminal; WHEEL_PATCHES in scripts/build_lite.py)."""
    lock = json.loads((PYODIDE / "pyodide-lock.json").read_text())["packages"]
    with zipfile.ZipFile(PYODIDE / lock["ipython"]["file_name"]) as z:
        init = z.read("IPython/__init__.py").decode()
    assert "\nfrom .terminal.embed import embed\n" not in init
    assert "def embed(**kwargs):" in init and "from .terminal.embed import embed as _embed" in init


def test_served_modules_are_precompiled_for_the_served_pyodide():
    """Every module of every served wheel and of the served stdlib zip has the
    checked-hash .pyc of its own source, for the magic number and cache tag of the
    Pyodide that the site serves (asked from that Pyodide itself, under node)."""
    if not shutil.which("node"):
        pytest.skip("node is needed to start the served Pyodide outside a browser")
    core = lite_early_kernel.core_dir(LITE)
    with tempfile.TemporaryDirectory() as tmp:     # Pyodide's files and the site's lock
        for f in [*core.iterdir(), PYODIDE / "pyodide-lock.json"]:
            os.symlink(f, Path(tmp) / f.name)
        info = pyc_lite.pyodide_info(Path(tmp))
    magic = bytes.fromhex(info["magic"])
    lock = json.loads((PYODIDE / "pyodide-lock.json").read_text())
    problems = []
    for entry in lock["packages"].values():
        problems += pyc_lite.check_wheel(PYODIDE / entry["file_name"], magic,
                                         info["cache_tag"])
    problems += pyc_lite.check_stdlib(core / "python_stdlib.zip", magic)
    assert problems == [], problems[:10]
    # SymPy's and mpmath's own test suites are not served
    for name in ("sympy", "mpmath"):
        with zipfile.ZipFile(PYODIDE / lock["packages"][name]["file_name"]) as z:
            assert not [n for n in z.namelist() if "/tests/" in n], name


def test_every_chapter_and_exercise_is_in_the_lite_site():
    docs = build_lite.lite_docs()
    chapters = sorted(p.relative_to(ROOT).with_suffix("").as_posix()
                      for p in (ROOT / "book").glob("[0-9]*.ipynb"))
    students = sorted(p.relative_to(ROOT).with_suffix("").as_posix()
                      for p in (ROOT / "exercises").glob("*.ipynb"))
    assert set(chapters) <= set(docs) and set(students) <= set(docs)
    assert build_lite.OWN_SYSTEM in docs
    for d in docs:
        assert (LITE / "files" / f"{d}.ipynb").is_file(), d
    assert not (LITE / "files" / "exercises" / "solutions").exists()


def test_lite_copies_are_the_current_conversion_of_the_sources():
    """Each lite notebook is what the converter makes from its source now."""
    docs = build_lite.lite_docs()
    index = lite_notebooks.Index.from_notebooks([ROOT / f"{d}.ipynb" for d in docs])
    for d in docs:
        source = json.loads((ROOT / f"{d}.ipynb").read_text(encoding="utf-8"))
        built = json.loads((LITE / "files" / f"{d}.ipynb").read_text(encoding="utf-8"))
        expected = lite_notebooks.lite_notebook(source, d, index)
        assert [c["source"] for c in built["cells"]] == \
            [c["source"] for c in expected["cells"]], f"{d}: stale, run `make lite`"


def test_no_myst_syntax_left_in_the_lite_notebooks():
    myst = re.compile(r"^(`{3,}|:{3,})\{[\w:-]+\}|\{(doc|ref|term|cite:[pt]|eq|numref)\}`"
                      r"|^\([\w:.-]+\)=\s*$", re.M)
    for nb_path in (LITE / "files").rglob("*.ipynb"):
        nb = json.loads(nb_path.read_text(encoding="utf-8"))
        for cell in nb["cells"]:
            if cell["cell_type"] == "markdown":
                src = "".join(cell["source"])
                assert not myst.search(src), (nb_path.name, myst.search(src).group(0))


def test_native_only_notebooks_say_so_and_the_others_run_here():
    for nb_path in (LITE / "files").rglob("*.ipynb"):
        nb = json.loads(nb_path.read_text(encoding="utf-8"))
        meta = nb["metadata"]["whittaker_teach"]
        first = "".join(nb["cells"][0]["source"])
        if meta["runs_in_browser"]:
            assert "runs locally" not in first
            outputs = [o for c in nb["cells"] if c["cell_type"] == "code" for o in c["outputs"]]
            assert outputs == [], f"{nb_path.name}: stored outputs in a live notebook"
        else:
            assert "runs locally, not in the browser" in first, nb_path.name
            assert "make book" in first
    assert json.loads((LITE / "files/book/04-generalized-whittaker.ipynb").read_text())[
        "metadata"]["whittaker_teach"]["runs_in_browser"]


def test_every_chapter_and_exercise_page_has_a_launch_link_that_resolves():
    pages = {}
    for doc in build_lite.toc_docs():
        target = build_lite.lite_path(doc)
        if target is not None:
            pages[_page_of(doc)] = target
    assert "book/04-generalized-whittaker.html" in pages
    assert pages["exercises/solutions/kepler-orbit.html"] == "exercises/kepler-orbit.ipynb"
    base = "http://127.0.0.1/"
    for rel, target in pages.items():
        links = _launch_links(rel)
        assert links, f"{rel}: no 'Run in the browser' button"
        for href in links:
            url = urlsplit(urljoin(base + rel, href.replace("&amp;", "&")))
            assert not href.startswith(("http:", "https:", "/")), href   # relative
            assert (SITE / url.path.lstrip("/")).is_file(), href
            (path,) = parse_qs(url.query)["path"]
            assert path == target, (rel, href)
            assert (LITE / "files" / path).is_file(), href


def test_no_placeholder_buttons():
    for rel in ("book/04-generalized-whittaker.html", "exercises/solutions/kepler-orbit.html"):
        html = (SITE / rel).read_text(encoding="utf-8")
        for host in ("mybinder.org", "colab.research.google.com", "github.com/whittaker-teach"):
            assert host not in html, (rel, host)


def test_exercise_pages_say_how_to_hand_in():
    html = (SITE / "exercises/solutions/kepler-orbit.html").read_text(encoding="utf-8")
    assert "browser&#8217;s storage" in html and "Download" in html


# ------------------------------------------------------------------ the browser test
CHROMIUM = "/usr/bin/chromium"
# Every request not to 127.0.0.1 is blocked by the browser itself (a dead proxy
# for everything but 127.0.0.1, and no name resolution), which covers the page,
# its workers and the service worker alike, and is counted from the request
# events. (Routing every request through Playwright would block too, but costs
# about a second per request with Pyodide's many files.)
BLOCK_ARGS = ["--no-sandbox", "--disable-gpu", "--no-first-run",
              "--disable-background-networking", "--disable-component-update",
              "--proxy-server=http://127.0.0.1:9", "--proxy-bypass-list=127.0.0.1",
              "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]
_LOCAL = ("http://127.0.0.1:", "ws://127.0.0.1:", "data:", "blob:", "about:")


class Lite:
    """One browser context on the served site, counting requests that leave it."""

    def __init__(self, browser, base_url):
        self.browser = browser
        self.base_url = base_url
        self.outside = []
        self.context = None

    def _on_request(self, request):
        if not request.url.startswith(_LOCAL):
            self.outside.append(request.url)

    def launch(self, page_rel):
        """Open a book page and press its "Run in the browser" button.

        Each launch gets a fresh browser profile (no JupyterLab workspace or
        kernel restored from an earlier test)."""
        if self.context is not None:
            self.context.close()
        self.context = self.browser.new_context(viewport={"width": 1280, "height": 900})
        self.context.on("request", self._on_request)
        page = self.context.new_page()
        page.goto(self.base_url + page_rel)
        button = page.locator("a.btn-run-in-browser")
        assert button.count() == 1, f"{page_rel}: no launch button"
        with self.context.expect_page() as new:
            button.click()
        lab = new.value
        lab.wait_for_load_state()
        return lab


def _kernel_status(lab):
    return lab.locator(".jp-StatusBar-TextItem", has_text="Pyodide")


def wait_kernel_idle(lab, timeout_s=KERNEL_READY_S):
    _kernel_status(lab).filter(has_text="Idle").wait_for(timeout=timeout_s * 1000)


def _notebook(lab):
    return lab.locator(".jp-Notebook:visible").first


def wait_notebook(lab, min_code_cells=2):
    """Wait until the notebook is shown with its code cells' editors."""
    _notebook(lab).wait_for(timeout=60_000)
    _notebook(lab).locator(".jp-CodeCell .cm-content").nth(min_code_cells - 1).wait_for(
        timeout=60_000)


def run_all(lab, timeout_s=RUN_ALL_S):
    _notebook(lab).click(position={"x": 5, "y": 5})
    lab.locator(".lm-MenuBar-itemLabel", has_text="Run").first.click()
    lab.locator(".lm-Menu-itemLabel").get_by_text("Run All Cells", exact=True).click()
    deadline = time.monotonic() + timeout_s
    lab.wait_for_timeout(1000)
    while time.monotonic() < deadline:
        busy = lab.locator(".jp-InputPrompt", has_text="[*]").count()
        if busy == 0 and "Idle" in _kernel_status(lab).inner_text():
            return
        lab.wait_for_timeout(500)
    raise AssertionError("the cells did not finish running")


def _code_cell(lab, source_start):
    cells = _notebook(lab).locator(".jp-CodeCell")
    # the first line of each cell's source (a collapsed input has no editor: "")
    firsts = cells.evaluate_all(
        "els => els.map(e => { const l = e.querySelector('.cm-content .cm-line');"
        " return l ? l.textContent : ''; })")
    for i, text in enumerate(firsts):
        if text.lstrip().startswith(source_start):
            return cells.nth(i), i
    raise AssertionError(f"no code cell starts with {source_start!r}: {firsts}")


def _errors(lab):
    return lab.locator(".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr']")


@pytest.fixture(scope="module")
def lite():
    playwright = pytest.importorskip("playwright.sync_api")
    if not os.path.exists(CHROMIUM):
        pytest.skip(f"{CHROMIUM} not installed")
    import serve
    server, base_url = serve.serve_in_thread(SITE)
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=BLOCK_ARGS)
        try:
            yield Lite(browser, base_url)
        finally:
            browser.close()
            server.shutdown()


@pytest.mark.browser
@pytest.mark.slow
def test_chapter_4_runs_in_the_browser(lite):
    lab = lite.launch("book/04-generalized-whittaker.html")
    assert "path=book/04-generalized-whittaker.ipynb" in lab.url
    wait_notebook(lab)
    assert lab.locator(".jp-OutputArea-output").count() == 0   # nothing stored: it runs here
    wait_kernel_idle(lab)
    run_all(lab)
    errors = _errors(lab)
    assert errors.count() == 0, errors.all_inner_texts()[:3]
    # every code cell ran: [n], not [ ] (a collapsed input, hide-input, shows no prompt)
    nb = json.loads((LITE / "files/book/04-generalized-whittaker.ipynb").read_text())
    code = [c for c in nb["cells"] if c["cell_type"] == "code"]
    hidden = sum(bool(c["metadata"].get("jupyter", {}).get("source_hidden")) for c in code)
    prompts = [p.strip() for p in
               _notebook(lab).locator(".jp-CodeCell .jp-InputPrompt").all_inner_texts()]
    assert len(prompts) == len(code)
    ran = [p for p in prompts if re.fullmatch(r"\[\d+\]:", p)]
    assert len(ran) == len(code) - hidden and prompts.count("") == hidden, prompts
    # the reduced equation (1.26) for the sledge, typeset by MathJax
    cell, _ = _code_cell(lab, 'red.steps.only("1.26"')
    out = cell.locator(".jp-OutputArea")
    assert "(1.26)" in out.inner_text() and "generalized Whittaker equations" in out.inner_text()
    # JupyterLab typesets lazily, when an output comes into view
    latex = out.locator(".jp-RenderedLatex")
    assert latex.count() >= 1
    latex.last.scroll_into_view_if_needed()
    latex.last.locator("mjx-container").first.wait_for(timeout=60_000)
    assert out.locator("mjx-merror").count() == 0
    assert lite.outside == [], lite.outside


_WORKER_MARKS_JS = ("() => performance.getEntriesByType('mark')"
                    ".filter(m => m.name.startsWith('wt:')).map(m => m.name.slice(3))")


def _kernel_workers(lab):
    return [w for w in lab.workers
            if "wt-kernel.worker" in w.url or "comlink.worker" in w.url]


@pytest.mark.browser
@pytest.mark.slow
def test_the_kernel_takes_the_worker_started_with_the_page(lite):
    """The kernel's worker is the one wt-early-kernel.js started with the page: one
    Pyodide worker, not two; its early steps ran and the kernel took that Pyodide
    with no "starting again" warning; a cell runs. After a restart the new kernel
    gets a worker of its own (the early one is given once) and runs a cell too."""
    messages = []
    lab = lite.launch("book/04-generalized-whittaker.html")
    lab.on("console", lambda m: messages.append(m.text))
    wait_notebook(lab)
    wait_kernel_idle(lab)
    workers = _kernel_workers(lab)
    assert [w.url.rsplit("/", 1)[-1] for w in workers] == ["wt-kernel.worker.mjs"]
    marks = workers[0].evaluate(_WORKER_MARKS_JS)
    for step in ("early: loadPyodide, with the kernel's packages end",
                 "early: import piplite, pyodide_kernel (IPython) end",
                 "kernel asks for Pyodide end"):
        assert step in marks, marks
    assert marks.index("early: import piplite, pyodide_kernel (IPython) end") \
        < marks.index("kernel asks for Pyodide end")

    def run_first_cell(code, expect):
        cell = _notebook(lab).locator(".jp-CodeCell").first
        cell.locator(".cm-content").click()
        lab.keyboard.press("Control+A")
        lab.keyboard.insert_text(code)
        lab.keyboard.press("Control+Enter")
        cell.locator(".jp-OutputArea").get_by_text(expect).wait_for(timeout=120_000)

    run_first_cell("import sys; print('RAN', 'pyodide_kernel' in sys.modules)", "RAN True")
    lab.locator(".jp-Toolbar-item[data-jp-item-name='restart'] button, "
                "button[data-command='notebook:restart-kernel'], "
                "jp-button[data-command='notebook:restart-kernel']").first.click()
    lab.locator(".jp-Dialog .jp-mod-accept").click()
    # the early worker is ended with the old kernel; the new one is the kernel's own
    def kinds():
        return [w.url.rsplit("/", 1)[-1].split(".")[0] for w in _kernel_workers(lab)]

    deadline = time.monotonic() + KERNEL_READY_S
    while time.monotonic() < deadline and kinds() != ["comlink"]:
        lab.wait_for_timeout(200)
    assert kinds() == ["comlink"], [w.url for w in lab.workers]
    wait_kernel_idle(lab)
    run_first_cell("print('AGAIN', 6 * 7)", "AGAIN 42")
    assert not [m for m in messages if m.startswith("whittaker-teach:")], messages
    assert lite.outside == [], lite.outside


@pytest.mark.browser
@pytest.mark.slow
def test_chapter_11_every_form_runs_in_the_browser(lite):
    """The forms room (whittaker_teach.forms) in Pyodide: every cell of chapter 11 runs
    without an error, and the three systems' forms are shown equal there too."""
    lab = lite.launch("book/11-every-form.html")
    assert "path=book/11-every-form.ipynb" in lab.url
    wait_notebook(lab)
    wait_kernel_idle(lab)
    run_all(lab, timeout_s=1800)
    errors = _errors(lab)
    assert errors.count() == 0, errors.all_inner_texts()[:3]
    for start in ("report(agree(disk))", "report(agree(weight))"):
        cell, _ = _code_cell(lab, start)
        assert "all agree" in cell.locator(".jp-OutputArea").inner_text(), start
    assert lite.outside == [], lite.outside


@pytest.mark.browser
@pytest.mark.slow
def test_geometry_and_rolling_rooms_run_in_the_browser(lite):
    """Chapters 13 and 14 keep their stored outputs in the browser (their figures need
    matplotlib), but their symbolic parts run there: the sledge's non-holonomic bracket
    and its Jacobiator (chapter 13), and the Chaplygin ball taken in through the
    mechanics input with x and y dependent (chapter 14), in Pyodide. Every module
    imported on the way (SymPy, whittaker_teach, stdlib) is loaded from its served
    .pyc: none is compiled from source in the browser."""
    lab = lite.launch("book/your-own-system.html")
    wait_notebook(lab)
    wait_kernel_idle(lab)
    cell = _notebook(lab).locator(".jp-CodeCell").first
    cell.locator(".cm-content").click()
    lab.keyboard.press("Control+A")
    lab.keyboard.press("Delete")
    lab.keyboard.insert_text(
        # count the modules compiled from source (no usable .pyc) while importing
        "import importlib._bootstrap_external as _bx, zipimport as _zi\n"
        "_src = []\n"
        "_s2c = _bx.SourceLoader.source_to_code\n"
        "_bx.SourceLoader.source_to_code = lambda self, data, path, **kw: "
        "(_src.append(path), _s2c(self, data, path, **kw))[1]\n"
        "_cs = _zi._compile_source\n"
        "_zi._compile_source = lambda path, source: (_src.append(path), _cs(path, source))[1]\n"
        "import whittaker_teach as wt\n"
        "from whittaker_teach import geometry as geo, rolling\n"
        "nb = geo.nonholonomic_bracket(wt.examples.sledge())\n"
        "print('JAC', nb.structure.jacobiator(*nb.symbols('x', 'p_x', 'p_theta')))\n"
        "ball = rolling.chaplygin_ball()\n"
        "print('BALL', ball.name, ball.dependent_coordinates)\n"
        "import tomllib, wave\n"               # stdlib modules not imported before
        "print('FROM_SOURCE', len(_src), _src[:5])\n"
        "import sys, wt_lite_startup\n"
        "await wt_lite_startup.task\n"
        "print('WARM', wt_lite_startup.error, [m in sys.modules for m in "
        "('sympy', 'whittaker_teach', 'IPython.terminal.embed', 'prompt_toolkit')])\n")
    lab.keyboard.press("Control+Enter")
    out = cell.locator(".jp-OutputArea")
    out.get_by_text("WARM").wait_for(timeout=RUN_ALL_S * 1000)
    text = out.inner_text()
    assert "JAC tan(theta)" in text, text
    assert "BALL chaplygin_ball [x(t), y(t)]" in text, text
    # SymPy, whittaker_teach and the stdlib came from their precompiled .pyc files
    assert "FROM_SOURCE 0 []" in text, text
    # the start-up file imported SymPy and whittaker_teach; the kernel no terminal
    assert "WARM None [True, True, False, False]" in text, text
    assert _errors(lab).count() == 0, _errors(lab).all_inner_texts()[:3]
    assert lite.outside == [], lite.outside


def _answer(lab, source_start, new_source):
    """Replace a cell's code, run it and the next cell (the check); the check's output."""
    cell, _ = _code_cell(lab, source_start)
    check_cell, _ = _code_cell(lab, 'check("sledge-L-star", Omega')
    before = check_cell.locator(".jp-InputPrompt").inner_text().strip()
    editor = cell.locator(".cm-content")
    editor.click()
    lab.keyboard.press("Control+A")
    lab.keyboard.press("Delete")
    lab.keyboard.insert_text(new_source)
    lab.keyboard.press("Shift+Enter")      # runs the answer, selects the check cell
    lab.keyboard.press("Shift+Enter")      # runs the check
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:      # the check cell ran again
        prompt = check_cell.locator(".jp-InputPrompt").inner_text().strip()
        if prompt != before and re.fullmatch(r"\[\d+\]:", prompt):
            break
        lab.wait_for_timeout(250)
    else:
        raise AssertionError("the check cell did not run")
    check_cell.locator(".wt-feedback").first.wait_for(timeout=30_000)
    return check_cell


@pytest.mark.browser
@pytest.mark.slow
def test_student_exercise_feedback_in_the_browser(lite):
    lab = lite.launch("exercises/solutions/sledge-L-star.html")
    assert "path=exercises/sledge-L-star.ipynb" in lab.url
    wait_notebook(lab)
    # the student version: the answers are None, no solution in it
    _code_cell(lab, "Omega = None")
    assert "solution" not in _notebook(lab).inner_text().lower()
    wait_kernel_idle(lab)
    run_all(lab)
    assert _errors(lab).count() == 0, _errors(lab).all_inner_texts()[:3]

    right = "Omega = m/2*xdot**2*(1 + sp.tan(theta)**2) + J/2*(xdot*thetaprime)**2 - k**2*theta**2/2"
    check = _answer(lab, "Omega = ", right)
    assert check.locator(".wt-feedback-correct").count() == 1, check.inner_text()
    assert "Correct." in check.locator(".wt-feedback").inner_text()

    wrong = "Omega = m/2*xdot**2 + J/2*(xdot*thetaprime)**2 - k**2*theta**2/2"
    check = _answer(lab, "Omega = ", wrong)
    assert check.locator(".wt-feedback-wrong").count() == 1, check.inner_text()
    assert "Not yet right." in check.locator(".wt-feedback").inner_text()
    assert _errors(lab).count() == 0, _errors(lab).all_inner_texts()[:3]
    assert lite.outside == [], lite.outside
