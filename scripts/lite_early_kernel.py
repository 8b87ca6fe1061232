"""Start the in-browser kernel's worker with the page (part of ``build_lite.py``).

JupyterLab starts the Pyodide kernel only once it has itself started and opened
the notebook; the kernel then starts Pyodide, loads its packages and imports
IPython. On a 2-core machine each takes about 3 s, one after the other. This
step makes them run side by side: a small script in ``lab/index.html``
(``wt-early-kernel.js``) starts the kernel's worker with the page, that worker
(``static/pyodide/wt-kernel.worker.mjs``: the kernel's own worker plus an early
``loadPyodide`` with the kernel's options, and the kernel's imports) is handed to
the kernel when it asks for one, and the kernel's ``pyodideUrl`` points at
``static/pyodide/wt-pyodide.mjs``, which returns the Pyodide already started if
its options are the kernel's. The three files are in ``scripts/lite_kernel/``;
this module fills in the kernel worker's file name and the options, and checks
the result.

It also moves Pyodide's own files (``CORE_FILES``) into a folder named by their
content, ``static/pyodide-core-<sha256[:12]>/``, which the loader uses as
Pyodide's index URL (the lock and the wheels, which change with every build, stay
in ``static/pyodide/``). A server may then let the browser keep that folder for
good, without asking again on each visit (scripts/serve.py does): measured on the
2-core machine, a browser that revalidates ``pyodide.asm.wasm`` on every visit
compiles it again (about 2-3 s of compiler threads), and the kernel was ready
about 1 s later on a second visit than with the folder kept.
"""
from __future__ import annotations

import hashlib
import json
import re
import sys
from pathlib import Path

SOURCES = Path(__file__).resolve().parent / "lite_kernel"
PAGE_SCRIPT = "wt-early-kernel.js"
WORKER = "static/pyodide/wt-kernel.worker.mjs"
LOADER = "static/pyodide/wt-pyodide.mjs"
#: the kernel's pyodideUrl in jupyter-lite.json
PYODIDE_URL = "./" + LOADER
KERNEL_STATIC = "extensions/@jupyterlite/pyodide-kernel-extension/static"
TAG = f'<script src="../{PAGE_SCRIPT}"></script>'
APP_PAGES = ("lab/index.html",)
#: Pyodide's own files: the same for every build with this Pyodide and stdlib zip
CORE_FILES = ("pyodide.mjs", "pyodide.asm.mjs", "pyodide.asm.wasm", "python_stdlib.zip")
CORE_PREFIX = "pyodide-core-"
KERNEL_PLUGIN = "@jupyterlite/pyodide-kernel-extension:kernel"


def kernel_worker(out: Path) -> str:
    """The file name of the Pyodide kernel's (comlink) worker in the built site."""
    found = sorted(p.name for p in (out / KERNEL_STATIC).glob("comlink.worker.*.js"))
    if len(found) != 1:
        sys.exit(f"build_lite: expected one comlink.worker.*.js in {out / KERNEL_STATIC}, "
                 f"found {found} (a new jupyterlite-pyodide-kernel?)")
    return found[0]


def core_name(files: list[Path]) -> str:
    """The content-named folder of Pyodide's own ``files``."""
    h = hashlib.sha256()
    for f in sorted(files, key=lambda f: f.name):
        h.update(f"{f.name}\0{f.stat().st_size}\0".encode())
        h.update(f.read_bytes())
    return CORE_PREFIX + h.hexdigest()[:12]


def core_dir(out: Path) -> Path:
    """The built site's content-named folder of Pyodide's own files."""
    found = sorted((out / "static").glob(CORE_PREFIX + "*"))
    if len(found) != 1:
        sys.exit(f"build_lite: expected one {CORE_PREFIX}* folder in {out / 'static'}, "
                 f"found {[f.name for f in found]}")
    return found[0]


def move_core(out: Path) -> Path:
    """Move Pyodide's own files from static/pyodide/ into their content-named folder."""
    pyodide = out / "static" / "pyodide"
    if not all((pyodide / name).is_file() for name in CORE_FILES):
        return core_dir(out)                       # (moved already)
    dest = out / "static" / core_name([pyodide / name for name in CORE_FILES])
    dest.mkdir(exist_ok=True)
    for name in CORE_FILES:
        (pyodide / name).replace(dest / name)
    return dest


def install(out: Path, options: dict) -> None:
    """Write the three files into the built site ``out`` and load the page script
    from each app page; ``options`` are the kernel's ``loadPyodideOptions``."""
    worker = kernel_worker(out)
    core = move_core(out).name
    for name, dest in ((PAGE_SCRIPT, PAGE_SCRIPT), ("wt-kernel.worker.mjs", WORKER),
                       ("wt-pyodide.mjs", LOADER)):
        text = (SOURCES / name).read_text()
        text = text.replace("__KERNEL_WORKER__", worker)
        text = text.replace("__OPTIONS__", json.dumps(options, sort_keys=True))
        text = text.replace("__CORE__", core)
        _write(out / dest, text)
    for page in APP_PAGES:
        path = out / page
        html = path.read_text()
        if TAG not in html:
            html, n = re.subn(r'(\n\s*)(<script id="jupyter-config-data")',
                              lambda m: m.group(1) + TAG + m.group(1) + m.group(2), html,
                              count=1)
            if n != 1:
                sys.exit(f"build_lite: no jupyter-config-data script in {path} to load "
                         f"{PAGE_SCRIPT} before")
        _write(path, html)
    # (jupyterlite's pyodide add-on sets pyodideUrl to its copy of pyodide.mjs)
    config_path = out / "jupyter-lite.json"
    config = json.loads(config_path.read_text())
    config["jupyter-config-data"]["litePluginSettings"][KERNEL_PLUGIN]["pyodideUrl"] = PYODIDE_URL
    _write(config_path, json.dumps(config, indent=2) + "\n")
    check(out, options)


def check(out: Path, options: dict) -> None:
    """Fail the build if the early start is not wired as described above."""
    worker = kernel_worker(out)
    problems = []
    for page in APP_PAGES:
        if TAG not in (out / page).read_text():
            problems.append(f"{page} does not load {PAGE_SCRIPT}")
    for dest in (PAGE_SCRIPT, WORKER, LOADER):
        text = (out / dest).read_text()
        if "__KERNEL_WORKER__" in text or "__OPTIONS__" in text or "__CORE__" in text:
            problems.append(f"{dest} was not filled in")
    if worker not in (out / WORKER).read_text() or worker not in (out / PAGE_SCRIPT).read_text():
        problems.append(f"{WORKER} or {PAGE_SCRIPT} does not name the kernel's worker {worker}")
    if json.dumps(options, sort_keys=True) not in (out / WORKER).read_text():
        problems.append(f"{WORKER} does not start Pyodide with the kernel's options {options}")
    core = core_dir(out)
    files = [core / name for name in CORE_FILES]
    if not all(f.is_file() for f in files) or core_name(files) != core.name:
        problems.append(f"{core.name} does not hold exactly the files its name was made of")
    if [n for n in CORE_FILES if (out / "static" / "pyodide" / n).exists()]:
        problems.append("Pyodide's own files are still in static/pyodide too")
    if f"../{core.name}/pyodide.mjs" not in (out / LOADER).read_text():
        problems.append(f"{LOADER} does not load Pyodide from {core.name}")
    kernel = json.loads((out / "jupyter-lite.json").read_text())["jupyter-config-data"][
        "litePluginSettings"][KERNEL_PLUGIN]
    if kernel.get("pyodideUrl") != PYODIDE_URL:
        problems.append(f"the kernel's pyodideUrl is {kernel.get('pyodideUrl')}, not {PYODIDE_URL}")
    if kernel.get("loadPyodideOptions") != options:
        problems.append(f"the kernel's loadPyodideOptions are not {options}")
    if problems:
        sys.exit("build_lite: the early kernel start is broken: " + "; ".join(problems))


def _write(path: Path, text: str) -> None:
    if path.exists():
        path.unlink()          # (a hard link into another build must not be changed)
    path.write_text(text)
