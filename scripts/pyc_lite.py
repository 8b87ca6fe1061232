"""Byte-compile what the lite site serves, with the served Pyodide's own CPython.

Pyodide imports a pure-Python wheel by compiling every module it imports from
source, on every page load (it never writes ``__pycache__``: its
``sys.dont_write_bytecode`` is true, and its file system is in memory anyway),
and the npm ``python_stdlib.zip`` holds ``.py`` files only. This module rewrites
the served wheels and stdlib zip so that each ``.py`` has beside it the
checked-hash ``.pyc`` that Pyodide's import system uses instead:

* compiled inside that Pyodide (``node scripts/pyc_lite.mjs``), so the magic
  number and cache tag are exactly its CPython's, whatever Python runs the build;
* checked-hash pycs: the import system hashes the ``.py`` and ignores a ``.pyc``
  whose hash differs, so a stale one can only cost time, never run old code;
* the ``.py`` files stay (tracebacks show source lines); SymPy's and mpmath's
  ``tests/`` packages are left out of their wheels (as Pyodide's own
  distribution does), which halves what is unpacked for SymPy.

Results are cached in ``build/lite/pyc/<key>/`` (the key: the input's sha256,
the Pyodide directory's name and this tool's sources), so only a changed input
is compiled again. ``check_wheel`` / ``check_stdlib`` are what the tests use.

    python scripts/pyc_lite.py --pyodide DIR WHEEL_OR_ZIP...   (check: magic, hashes)
"""
from __future__ import annotations

import _imp
import hashlib
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
RUNNER = HERE / "pyc_lite.mjs"
IN_PYODIDE = HERE / "_pyc_in_pyodide.py"
#: wheels whose ``tests/`` packages are not served (Pyodide unvendors them too)
DROP_TESTS = ("sympy", "mpmath")


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def _tool_digest() -> str:
    h = hashlib.sha256()
    for f in (RUNNER, IN_PYODIDE):
        h.update(f.read_bytes())
    return h.hexdigest()


def _node() -> str:
    node = shutil.which("node")
    if node is None:
        sys.exit("pyc_lite: node is needed to byte-compile for Pyodide (apt-get install nodejs)")
    return node


def run_in_pyodide(pyodide_dir: Path, script: Path, job: dict, timeout: float = 1800) -> dict:
    """Run ``script`` in Pyodide (node) with ``JOB = job``; its ``PYC_LITE {json}`` line."""
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(job, f)
    try:
        proc = subprocess.run([_node(), str(RUNNER), str(pyodide_dir), str(script), f.name],
                              capture_output=True, text=True, timeout=timeout)
    finally:
        os.unlink(f.name)
    m = re.search(r"^PYC_LITE (.*)$", proc.stdout, re.M)
    if proc.returncode != 0 or m is None:
        raise RuntimeError(f"pyc_lite: Pyodide (node) failed ({proc.returncode}):\n"
                           f"{proc.stdout[-2000:]}\n{proc.stderr[-4000:]}")
    return json.loads(m.group(1))


def pyodide_info(pyodide_dir: Path) -> dict:
    """{"magic": hex, "cache_tag": ..., "version": ...} of the Pyodide in ``pyodide_dir``."""
    return run_in_pyodide(pyodide_dir, IN_PYODIDE, {"wheels": [], "stdlib": None})


def precompile(pyodide_dir: Path, wheels: list[Path], cache: Path,
               stdlib: Path | None = None) -> tuple[list[Path], Path | None]:
    """The compiled copies of ``wheels`` (and of the ``stdlib`` zip), from ``cache``.

    Compiles what the cache lacks in one Pyodide run; drops cache entries that
    are no longer used."""
    tool = _tool_digest()

    def key(path: Path) -> str:
        return hashlib.sha256(f"{_sha256(path)} {pyodide_dir.name} {tool}".encode()
                              ).hexdigest()[:24]

    cache.mkdir(parents=True, exist_ok=True)
    jobs = {"wheels": [], "stdlib": None}
    staged = []
    out_wheels = []
    for whl in wheels:
        dst = cache / key(whl) / whl.name
        out_wheels.append(dst)
        if not dst.exists():
            dst.parent.mkdir(parents=True, exist_ok=True)
            tmp = dst.with_name(dst.name + ".part")
            drop = _norm(whl.name.split("-", 1)[0]) in DROP_TESTS
            jobs["wheels"].append([str(whl.resolve()), str(tmp.resolve()), drop])
            staged.append((tmp, dst))
    out_stdlib = None
    if stdlib is not None:
        out_stdlib = cache / key(stdlib) / stdlib.name
        if not out_stdlib.exists():
            out_stdlib.parent.mkdir(parents=True, exist_ok=True)
            tmp = out_stdlib.with_name(out_stdlib.name + ".part")
            jobs["stdlib"] = [str(stdlib.resolve()), str(tmp.resolve())]
            staged.append((tmp, out_stdlib))
    if staged:
        names = ", ".join(Path(d).name for _, d in staged)
        print(f"pyc_lite: byte-compiling in Pyodide (node): {names}", flush=True)
        result = run_in_pyodide(pyodide_dir, IN_PYODIDE, jobs)
        for r in result["wheels"] + ([result["stdlib"]] if result["stdlib"] else []):
            if r["failed"]:
                print(f"pyc_lite: {Path(r['src']).name}: {len(r['failed'])} modules left "
                      f"as source: {r['failed'][:3]}", flush=True)
        for tmp, dst in staged:
            tmp.rename(dst)
    used = {p.parent.name for p in out_wheels} | ({out_stdlib.parent.name} if out_stdlib else set())
    for d in cache.iterdir():
        if d.is_dir() and d.name not in used:
            shutil.rmtree(d)
    return out_wheels, out_stdlib


# ------------------------------------------------------------------ checks
def _check_pyc(name: str, data: bytes, source: bytes, magic: bytes) -> str | None:
    if data[:4] != magic:
        return f"{name}: magic {data[:4].hex()}, not {magic.hex()}"
    flags = int.from_bytes(data[4:8], "little")
    if flags != 0b11:
        return f"{name}: flags {flags:#b}, not a checked-hash pyc"
    if data[8:16] != _imp.source_hash(int.from_bytes(magic, "little"), source):
        return f"{name}: compiled from another source"
    return None


def check_wheel(whl: Path, magic: bytes, cache_tag: str) -> list[str]:
    """Problems of a served wheel: a module without its checked-hash .pyc for
    ``magic`` / ``cache_tag``, or one compiled from another source."""
    problems = []
    with zipfile.ZipFile(whl) as z:
        names = set(z.namelist())
        for name in sorted(names):
            top = name.split("/", 1)[0]
            if not name.endswith(".py") or top.endswith((".dist-info", ".data")):
                continue
            head, _, base = name.rpartition("/")
            cached = (f"{head}/" if head else "") + \
                f"__pycache__/{base[:-3]}.{cache_tag}.pyc"
            if cached not in names:
                problems.append(f"{whl.name}: {name} has no {cached}")
                continue
            p = _check_pyc(cached, z.read(cached), z.read(name), magic)
            if p:
                problems.append(f"{whl.name}: {p}")
    return problems


def check_stdlib(zip_path: Path, magic: bytes) -> list[str]:
    """Problems of the served stdlib zip: a .py without a valid checked-hash .pyc beside it."""
    problems = []
    with zipfile.ZipFile(zip_path) as z:
        names = set(z.namelist())
        for name in sorted(n for n in names if n.endswith(".py")):
            if name + "c" not in names:
                problems.append(f"{name} has no {name}c")
                continue
            p = _check_pyc(name + "c", z.read(name + "c"), z.read(name), magic)
            if p:
                problems.append(p)
    return problems


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+", type=Path)
    ap.add_argument("--pyodide", type=Path, required=True, help="the Pyodide directory")
    args = ap.parse_args(argv)
    info = pyodide_info(args.pyodide)
    magic = bytes.fromhex(info["magic"])
    bad = 0
    for f in args.files:
        problems = (check_wheel(f, magic, info["cache_tag"]) if f.suffix == ".whl"
                    else check_stdlib(f, magic))
        bad += bool(problems)
        print(f"{f.name}: {'ok' if not problems else f'{len(problems)} problems'}")
        for p in problems[:5]:
            print("   ", p)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
