"""Build the in-browser site (JupyterLite + Pyodide) into the book's HTML site.

    python scripts/build_lite.py [--out _build/html/lite] [--work build/lite]

1. fetches Pyodide's core files (npm) and the pinned pure-Python wheels (PyPI)
   once (``fetch_lite.py``, stamp files);
2. builds the ``whittaker_teach`` wheel from the tree (``pip wheel --no-deps``);
3. byte-compiles every served wheel and Pyodide's ``python_stdlib.zip`` with the
   served Pyodide's own CPython (``pyc_lite.py``: checked-hash ``.pyc`` beside
   every ``.py``; SymPy's and mpmath's tests left out), so that no module is
   compiled from source in the browser;
4. writes a ``pyodide-lock.json`` that lists exactly the wheels served, each with
   the sha256 of the served file (Pyodide checks it before loading), so that
   ``import whittaker_teach`` (or ``sympy``) loads them with no ``%pip`` cell;
   the kernel's own wheels (piplite, pyodide-kernel, its ipykernel stand-in) are
   served and listed too (IPython with one import made lazy: ``WHEEL_PATCHES``),
   and the kernel loads all of its packages from that lock
   in one parallel ``loadPackage`` while Pyodide starts
   (``loadPyodideOptions.packages``) instead of installing them one by one through
   micropip and piplite; with them a small start-up wheel (``STARTUP``, run as
   PYTHONSTARTUP) that imports SymPy and whittaker_teach in the background once
   the kernel is ready;
5. writes the lite copies of every chapter notebook, every student exercise
   notebook and the "your own system" notebook (``lite_notebooks.py``; they
   exist only in the build, so they are never stale);
6. runs ``jupyter lite build`` with the kernel configured for the local Pyodide
   (``pyodideUrl``) and ``disablePyPIFallback: true``: nothing is fetched from
   outside the site at run time;
7. starts the kernel's worker with the page rather than after JupyterLab has
   started (``lite_early_kernel.py``), so that Pyodide starts while JupyterLab does.

The pages that link here are made by book/_ext/wt_lite_launch.py ("Run in the
browser"); `lite_path(docname)` is the one mapping both use.
"""
from __future__ import annotations

import argparse
import email.parser
import hashlib
import json
import os
import re
import shutil
import sys
import tempfile
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import fetch_lite  # noqa: E402
import lite_early_kernel  # noqa: E402
import lite_notebooks as ln  # noqa: E402
import pyc_lite  # noqa: E402

ROOT = fetch_lite.ROOT
#: the notebook of the "your own system" template (stored with outputs in book/)
OWN_SYSTEM = "book/your-own-system"
#: the JupyterLite application the launch buttons open
LITE_APP = "lab/index.html"
KERNEL_PLUGIN = lite_early_kernel.KERNEL_PLUGIN
#: the kernel's own wheels (shipped in its labextension's pypi/ folder), served
#: from the Pyodide folder and listed in the lock like the others
KERNEL_WHEELS = ("piplite", "pyodide_kernel", "ipykernel")
#: what the kernel's worker installs before ``import pyodide_kernel`` (its
#: initPackageManager / initKernel), under the names it checks
#: ``loadPyodideOptions.packages`` for: listed there, they are loaded from the
#: lock while Pyodide starts, in one parallel loadPackage, and skipped later
KERNEL_PACKAGES = ("micropip", "piplite", "ipykernel", "comm", "pyodide-kernel",
                   "jedi", "ipython")
#: the kernel's start-up file (PYTHONSTARTUP): imports SymPy and whittaker_teach
#: in the background once the kernel is ready (scripts/lite_kernel/), served as a
#: small wheel of its own, preloaded with the kernel's packages
STARTUP = Path(__file__).resolve().parent / "lite_kernel" / "wt_lite_startup.py"
STARTUP_PACKAGE = "wt-lite-startup"
STARTUP_PATH = f"/lib/python{fetch_lite.PYODIDE_PYTHON}/site-packages/wt_lite_startup.py"
PRELOAD = KERNEL_PACKAGES + (STARTUP_PACKAGE,)


def lite_path(docname: str) -> str | None:
    """The lite notebook (path inside the lite site) for a book page, or None.

    Exercise pages are the solution notebooks; their lite copy is the student
    version: ``exercises/solutions/x`` → ``exercises/x.ipynb``.

    >>> lite_path("exercises/solutions/kepler-orbit")
    'exercises/kepler-orbit.ipynb'
    >>> lite_path("book/04-generalized-whittaker")
    'book/04-generalized-whittaker.ipynb'
    """
    m = re.fullmatch(r"exercises/solutions/([\w.-]+)", docname)
    doc = f"exercises/{m.group(1)}" if m else docname
    return doc + ".ipynb" if (ROOT / (doc + ".ipynb")).exists() else None


def toc_docs(root: Path = ROOT) -> list[str]:
    """Every document of _toc.yml, in order (without suffix)."""
    import yaml
    toc = yaml.safe_load((root / "_toc.yml").read_text())
    out = [toc["root"]]

    def walk(node):
        if isinstance(node, dict):
            if "file" in node:
                out.append(node["file"])
            for key in ("parts", "chapters", "sections"):
                for child in node.get(key, []) or []:
                    walk(child)
    walk(toc)
    return out


def lite_docs(root: Path = ROOT) -> list[str]:
    """The notebooks of the lite site (root-relative, without suffix)."""
    docs = []
    for d in toc_docs(root) + [OWN_SYSTEM]:
        p = lite_path(d)
        if p and p[:-6] not in docs:
            docs.append(p[:-6])
    return docs


# ------------------------------------------------------------------ notebooks
def write_notebooks(files: Path, root: Path = ROOT) -> list[str]:
    docs = lite_docs(root)
    index = ln.Index.from_notebooks([root / f"{d}.ipynb" for d in docs], root=root)
    for d in docs:
        nb = json.loads((root / f"{d}.ipynb").read_text(encoding="utf-8"))
        out = files / f"{d}.ipynb"
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(json.dumps(ln.lite_notebook(nb, d, index), indent=1,
                                  ensure_ascii=False) + "\n", encoding="utf-8")
        for fig in ln.figure_paths(nb):
            src = (root / d).parent / fig
            if src.exists():
                dst = out.parent / fig
                dst.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, dst)
    # the exercises' answer data is package data: the served wheel carries it
    return docs


# ------------------------------------------------------------------ wheels, lock
def build_package_wheel(dest: Path, withhold=()) -> Path:
    """``pip wheel --no-deps`` of this tree into ``dest`` (emptied first).

    ``withhold``: exercise ids whose answer data is replaced by the statement's
    (``answers.withheld``; the student edition's graded exercises)."""
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    with tempfile.TemporaryDirectory() as tmp:
        # build from a copy of the package sources only (no build/ or egg-info
        # in the working tree, and no stale files from an earlier build)
        src = Path(tmp) / "src"
        src.mkdir()
        for name in ("pyproject.toml", "README.md"):
            shutil.copy2(ROOT / name, src / name)
        shutil.copytree(ROOT / "whittaker_teach", src / "whittaker_teach",
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        if withhold:
            from whittaker_teach.exercises.answers import read_data, withheld
            data = src / "whittaker_teach" / "exercises" / "data"
            for ex in withhold:
                (data / f"{ex}.json").write_text(
                    json.dumps(withheld(read_data(data / f"{ex}.json")), indent=1,
                               ensure_ascii=False, sort_keys=True) + "\n", encoding="utf-8")
        # the installed setuptools if there is one (no download), else pip's
        # isolated build environment (setuptools from PyPI)
        try:
            import setuptools  # noqa: F401
            import wheel  # noqa: F401
            isolation = ["--no-build-isolation"]
        except ImportError:
            isolation = []
        fetch_lite._run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps",
                         *isolation, "-w", dest, src])
    (whl,) = dest.glob("whittaker_teach-*.whl")
    return whl


_norm, _sha256 = pyc_lite._norm, pyc_lite._sha256     # a wheel's name, a file's digest


def _wheel_meta(whl: Path):
    """(name, version, requires (names, no extras), top-level imports) of a wheel."""
    with zipfile.ZipFile(whl) as z:
        names = z.namelist()
        meta_name = next(n for n in names if n.endswith(".dist-info/METADATA"))
        meta = email.parser.Parser().parsestr(z.read(meta_name).decode())
        top = next((n for n in names if n.endswith(".dist-info/top_level.txt")), None)
        if top:
            imports = [s for s in z.read(top).decode().split() if s]
        else:
            imports = sorted({n.split("/")[0].removesuffix(".py") for n in names
                              if not n.split("/")[0].endswith((".dist-info", ".data"))})
    requires = []
    for req in meta.get_all("Requires-Dist") or []:
        if ";" in req and "extra" in req.split(";", 1)[1]:
            continue
        requires.append(_norm(re.match(r"[A-Za-z0-9_.-]+", req).group(0)))
    return meta["Name"], meta["Version"], requires, imports


def write_lock(upstream_lock: Path, wheels: list[Path], dest: Path) -> dict:
    """A pyodide-lock.json listing exactly ``wheels`` (copied into ``dest``)."""
    upstream = json.loads(upstream_lock.read_text())
    served = {}
    for whl in wheels:
        shutil.copy2(whl, dest / whl.name)
        name, version, requires, imports = _wheel_meta(whl)
        key = _norm(name)
        entry = dict(upstream["packages"].get(key) or {
            "name": name, "install_dir": "site", "package_type": "package",
            "unvendored_tests": False, "imports": imports, "depends": requires})
        entry.update(name=name, version=version, file_name=whl.name,
                     sha256=_sha256(dest / whl.name), unvendored_tests=False)
        if key not in upstream["packages"]:
            entry["depends"] = requires
        served[key] = entry
    for key, entry in served.items():
        # a dependency that is not served (e.g. a platform-specific one of
        # the PyPI wheel) would make loading fail: only served ones are kept
        entry["depends"] = [d for d in entry["depends"] if _norm(d) in served]
    lock = {"info": upstream["info"], "packages": dict(sorted(served.items()))}
    (dest / "pyodide-lock.json").write_text(json.dumps(lock, indent=1) + "\n")
    return lock


# ------------------------------------------------------------------ the build
#: source patches of served third-party wheels: {wheel name: [(member, old, new)]}.
#: ``import IPython`` imports ``IPython.terminal.embed`` for its ``embed``, which
#: pulls in the terminal shell and all of prompt_toolkit, for a terminal the
#: browser kernel never has: IPython + pyodide_kernel took 1.4 s to import in
#: Pyodide under node, 1.0 s without it (2-core machine at load 6; see
#: scripts/profile_lite_node.mjs). ``embed`` becomes a function that imports it
#: when called. The build fails if the text is not found.
WHEEL_PATCHES = {
    "ipython": [("IPython/__init__.py",
                 "from .terminal.embed import embed\n",
                 "def embed(**kwargs):\n"
                 "    # (whittaker-teach's lite site: imported when called, see\n"
                 "    # scripts/build_lite.py WHEEL_PATCHES)\n"
                 "    from .terminal.embed import embed as _embed\n"
                 "    return _embed(**kwargs)\n")],
}


def patch_wheel(whl: Path, patches, dest: Path) -> Path:
    """A copy of ``whl`` in ``dest`` with ``patches`` applied (RECORD updated)."""
    import base64
    dest.mkdir(parents=True, exist_ok=True)
    out = dest / whl.name
    changed = {}
    with zipfile.ZipFile(whl) as zin, zipfile.ZipFile(out, "w") as zout:
        for member, old, new in patches:
            text = zin.read(member).decode("utf-8")
            if text.count(old) != 1:
                sys.exit(f"build_lite: {whl.name}: the patch of {member} does not apply "
                         f"(WHEEL_PATCHES; a new version?)")
            changed[member] = text.replace(old, new).encode("utf-8")
        for info in zin.infolist():
            data = changed.get(info.filename)
            if data is None:
                data = zin.read(info)
                if info.filename.endswith(".dist-info/RECORD"):
                    lines = data.decode().splitlines()
                    for i, line in enumerate(lines):
                        name = line.split(",", 1)[0]
                        if name in changed:
                            digest = base64.urlsafe_b64encode(
                                hashlib.sha256(changed[name]).digest()).rstrip(b"=").decode()
                            lines[i] = f"{name},sha256={digest},{len(changed[name])}"
                    data = ("\n".join(lines) + "\n").encode()
            zout.writestr(info, data)
    return out


def patched(wheels: list[Path], dest: Path) -> list[Path]:
    """``wheels``, with those named in WHEEL_PATCHES replaced by patched copies."""
    if dest.exists():
        shutil.rmtree(dest)
    return [patch_wheel(w, WHEEL_PATCHES[_norm(w.name.split("-", 1)[0])], dest)
            if _norm(w.name.split("-", 1)[0]) in WHEEL_PATCHES else w for w in wheels]


def build_startup_wheel(dest: Path) -> Path:
    """The wheel of the kernel's start-up module (``STARTUP``), reproducibly."""
    import base64
    name, version = "wt_lite_startup", "1.0"
    dist = f"{name}-{version}.dist-info"
    files = {
        f"{name}.py": STARTUP.read_bytes(),
        f"{dist}/METADATA": (f"Metadata-Version: 2.1\nName: {STARTUP_PACKAGE}\n"
                             f"Version: {version}\nSummary: the start-up file of "
                             f"whittaker-teach's in-browser kernel\n").encode(),
        f"{dist}/WHEEL": b"Wheel-Version: 1.0\nGenerator: scripts/build_lite.py\n"
                         b"Root-Is-Purelib: true\nTag: py3-none-any\n",
        f"{dist}/top_level.txt": f"{name}\n".encode(),
    }
    record = "".join(
        f"{n},sha256={base64.urlsafe_b64encode(hashlib.sha256(d).digest()).rstrip(b'=').decode()},"
        f"{len(d)}\n" for n, d in files.items()) + f"{dist}/RECORD,,\n"
    files[f"{dist}/RECORD"] = record.encode()
    dest.mkdir(parents=True, exist_ok=True)
    whl = dest / f"{name}-{version}-py3-none-any.whl"
    with zipfile.ZipFile(whl, "w", zipfile.ZIP_DEFLATED) as z:
        for n, d in files.items():
            info = zipfile.ZipInfo(n, date_time=(2020, 2, 2, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, d)
    return whl


def kernel_wheels() -> list[Path]:
    """The kernel's own wheels (piplite, pyodide-kernel, ipykernel stand-in)."""
    pypi = Path(_kernel_labextensions()) / "@jupyterlite" / "pyodide-kernel-extension" \
        / "static" / "pypi"
    found = []
    for name in KERNEL_WHEELS:
        hits = sorted(pypi.glob(f"{name}-*.whl"))
        if len(hits) != 1:
            sys.exit(f"build_lite: expected one {name} wheel in {pypi}, found {hits}")
        found.append(hits[0])
    return found


def lite_config() -> dict:
    return {
        "jupyter-lite-schema-version": 0,
        "jupyter-config-data": {
            "appName": "Whittaker equations, live",
            "disabledExtensions": ["@jupyterlab/apputils-extension:announcements"],
            "litePluginSettings": {
                KERNEL_PLUGIN: {
                    # the local copy, through the loader that hands over the
                    # Pyodide started with the page (lite_early_kernel.py)
                    "pyodideUrl": lite_early_kernel.PYODIDE_URL,
                    "disablePyPIFallback": True,
                    "loadPyodideOptions": {"packages": list(PRELOAD),
                                           "env": {"PYTHONSTARTUP": STARTUP_PATH}},
                },
            },
        },
    }


#: JupyterLab settings of the lite site: every cell rendered (no windowing, so
#: the page can be searched and every output is there), no update check
SETTINGS_OVERRIDES = {
    "@jupyterlab/notebook-extension:tracker": {"windowingMode": "none"},
    "@jupyterlab/apputils-extension:notification": {"fetchNews": "false",
                                                     "checkForUpdates": False},
}


def build(out: Path, work: Path, pyodide_version: str = fetch_lite.PYODIDE_VERSION,
          root: Path = ROOT, edition: str = "", withhold=()):
    """The lite site of the course whose sources are in ``root`` into ``out``;
    ``edition`` names the work folders (``dist-<edition>``, ``src-<edition>``) so
    that two editions can be built side by side."""
    _kernel_labextensions()
    from jupyterlite_pyodide_kernel.constants import PYODIDE_VERSION as kernel_pyodide
    if kernel_pyodide != pyodide_version:
        sys.exit(f"build_lite: jupyterlite-pyodide-kernel is built for pyodide "
                 f"{kernel_pyodide}, not {pyodide_version} (PYODIDE_VERSION in the Makefile)")
    pyodide_dir = fetch_lite.fetch_pyodide(work, pyodide_version)
    wheels_dir = fetch_lite.fetch_wheels(work)
    suffix = f"-{edition}" if edition else ""
    pkg = build_package_wheel(work / f"dist{suffix}", withhold)

    src = work / f"src{suffix}"
    if src.exists():
        shutil.rmtree(src)
    static = src / "static" / "pyodide"
    static.mkdir(parents=True)
    wheels, stdlib = pyc_lite.precompile(
        pyodide_dir, patched(sorted(wheels_dir.glob("*.whl")), work / f"patched{suffix}")
        + kernel_wheels() + [build_startup_wheel(work / f"startup{suffix}"), pkg],
        work / f"pyc{suffix}", pyodide_dir / "python_stdlib.zip")
    for name in fetch_lite.CORE_FILES:
        if name == "python_stdlib.zip":
            shutil.copy2(stdlib, static / name)
        elif name != "pyodide-lock.json":
            shutil.copy2(pyodide_dir / name, static / name)
    lock = write_lock(pyodide_dir / "pyodide-lock.json", wheels, static)
    missing = [p for p in PRELOAD if _norm(p) not in lock["packages"]]
    if missing:
        sys.exit(f"build_lite: the kernel preloads {missing}, which the lock does not list")
    docs = write_notebooks(src / "files", root)
    (src / "jupyter-lite.json").write_text(json.dumps(lite_config(), indent=2) + "\n")
    (src / "overrides.json").write_text(json.dumps(SETTINGS_OVERRIDES, indent=2) + "\n")

    if out.exists():
        shutil.rmtree(out)
    # a fresh build every time: doit's task database would skip steps (such as
    # merging jupyter-lite.json) whose inputs look unchanged
    for db in list(work.glob(".jupyterlite.doit.db*")) + list(src.glob(".jupyterlite.doit.db*")):
        db.unlink()
    shutil.rmtree(work / "cache", ignore_errors=True)
    env = dict(os.environ, JUPYTERLITE_NO_LIBARCHIVE="1")
    env.pop("JUPYTERLITE_PYODIDE_URL", None)
    fetch_lite._run([sys.executable, "-m", "jupyterlite_core", "build",
                     "--lite-dir", src, "--output-dir", out,
                     "--apps", "lab", "--no-sourcemaps", "--no-unused-shared-packages"],
                    cwd=work, env=env)
    for stray in out.glob(".jupyterlite.doit.db*"):
        stray.unlink()
    lite_early_kernel.install(out, lite_config()["jupyter-config-data"]["litePluginSettings"]
                              [KERNEL_PLUGIN]["loadPyodideOptions"])
    check_config(out)
    print(f"build_lite: {len(docs)} notebooks, {len(lock['packages'])} wheels → {out}")
    return docs


def check_config(out: Path) -> None:
    """Fail the build if the kernel is not set to the local Pyodide without PyPI."""
    config = json.loads((out / "jupyter-lite.json").read_text())["jupyter-config-data"]
    kernel = config.get("litePluginSettings", {}).get(KERNEL_PLUGIN, {})
    if kernel.get("pyodideUrl") != lite_early_kernel.PYODIDE_URL \
            or kernel.get("disablePyPIFallback") is not True \
            or kernel.get("loadPyodideOptions", {}).get("packages") != list(PRELOAD):
        sys.exit(f"build_lite: {out}/jupyter-lite.json does not point the kernel at the "
                 f"local Pyodide with the PyPI fallback off: {kernel}")


def _kernel_labextensions() -> str:
    """The labextensions folder holding the Pyodide kernel (only that extension)."""
    prefix = Path(sys.prefix) / "share" / "jupyter" / "labextensions"
    if not (prefix / "@jupyterlite" / "pyodide-kernel-extension").exists():
        sys.exit("build_lite: jupyterlite-pyodide-kernel is not installed "
                 "(pip install -e \".[lite]\" or `make setup`)")
    return str(prefix)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "_build" / "html" / "lite")
    ap.add_argument("--work", type=Path, default=ROOT / "build" / "lite")
    ap.add_argument("--pyodide", default=fetch_lite.PYODIDE_VERSION)
    ap.add_argument("--root", type=Path, default=ROOT,
                    help="the course's sources (_toc.yml, book/, exercises/)")
    ap.add_argument("--edition", default="", help="names the work folders (e.g. student)")
    ap.add_argument("--withhold", action="append", default=[], metavar="ID",
                    help="an exercise whose answer data the wheel carries as statement only")
    args = ap.parse_args(argv)
    build(args.out.resolve(), args.work.resolve(), args.pyodide, args.root.resolve(),
          args.edition, args.withhold)


if __name__ == "__main__":
    main()
