"""Build the in-browser site (JupyterLite + Pyodide) into the book's HTML site.

    python scripts/build_lite.py [--out _build/html/lite] [--work build/lite]

1. fetches Pyodide's core files (npm) and the pinned pure-Python wheels (PyPI)
   once (``fetch_lite.py``, stamp files);
2. builds the ``whittaker_teach`` wheel from the tree (``pip wheel --no-deps``);
3. writes a ``pyodide-lock.json`` that lists exactly the wheels served, each with
   the sha256 of the served file (Pyodide checks it before loading), so that
   ``import whittaker_teach`` (or ``sympy``) loads them with no ``%pip`` cell;
4. writes the lite copies of every chapter notebook, every student exercise
   notebook and the "your own system" notebook (``lite_notebooks.py``; they
   exist only in the build, so they are never stale);
5. runs ``jupyter lite build`` with the kernel configured for the local Pyodide
   (``pyodideUrl``) and ``disablePyPIFallback: true``: nothing is fetched from
   outside the site at run time.

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
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import fetch_lite  # noqa: E402
import lite_notebooks as ln  # noqa: E402

ROOT = fetch_lite.ROOT
#: the notebook of the "your own system" template (stored with outputs in book/)
OWN_SYSTEM = "book/your-own-system"
#: the JupyterLite application the launch buttons open
LITE_APP = "lab/index.html"
KERNEL_PLUGIN = "@jupyterlite/pyodide-kernel-extension:kernel"


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


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


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
def lite_config() -> dict:
    return {
        "jupyter-lite-schema-version": 0,
        "jupyter-config-data": {
            "appName": "Whittaker equations, live",
            "disabledExtensions": ["@jupyterlab/apputils-extension:announcements"],
            "litePluginSettings": {
                KERNEL_PLUGIN: {
                    # the local copy (the build's pyodide addon sets the same)
                    "pyodideUrl": "./static/pyodide/pyodide.mjs",
                    "disablePyPIFallback": True,
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
    for name in fetch_lite.CORE_FILES:
        if name != "pyodide-lock.json":
            shutil.copy2(pyodide_dir / name, static / name)
    lock = write_lock(pyodide_dir / "pyodide-lock.json",
                      sorted(wheels_dir.glob("*.whl")) + [pkg], static)
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
    check_config(out)
    print(f"build_lite: {len(docs)} notebooks, {len(lock['packages'])} wheels → {out}")
    return docs


def check_config(out: Path) -> None:
    """Fail the build if the kernel is not set to the local Pyodide without PyPI."""
    config = json.loads((out / "jupyter-lite.json").read_text())["jupyter-config-data"]
    kernel = config.get("litePluginSettings", {}).get(KERNEL_PLUGIN, {})
    if kernel.get("pyodideUrl") != "./static/pyodide/pyodide.mjs" \
            or kernel.get("disablePyPIFallback") is not True:
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
