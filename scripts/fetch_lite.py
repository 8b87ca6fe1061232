"""Fetch what the in-browser site serves, from the package registries.

    python scripts/fetch_lite.py [--pyodide 314.0.6] [--dest build/lite]

* ``npm pack pyodide@VERSION``: the Pyodide core files (``pyodide.mjs``,
  ``pyodide.asm.mjs``, ``pyodide.asm.wasm``, ``python_stdlib.zip`` and the
  upstream ``pyodide-lock.json``) into ``DEST/pyodide-VERSION/``;
* ``pip download --no-deps --only-binary=:all:`` of the pure-Python wheels pinned
  in ``requirements/lite-wheels.txt`` (for Pyodide's Python 3.14) into
  ``DEST/wheels/``.

Idempotent: each part writes a stamp file recording what it fetched and is
skipped while the stamp matches (the wheels' stamp is the requirements file's
sha256). Nothing is fetched from anywhere but the npm registry and PyPI, through
their ordinary clients.
"""
from __future__ import annotations

import argparse
import hashlib
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PYODIDE_VERSION = "314.0.6"
#: Pyodide's Python, for which the wheels are chosen
PYODIDE_PYTHON = "3.14"
CORE_FILES = ("pyodide.mjs", "pyodide.asm.mjs", "pyodide.asm.wasm",
              "python_stdlib.zip", "pyodide-lock.json")
WHEELS_REQUIREMENTS = ROOT / "requirements" / "lite-wheels.txt"


def _run(cmd, **kw):
    print("fetch_lite:", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True, **kw)


def fetch_pyodide(dest: Path, version: str) -> Path:
    """The Pyodide core files of npm ``pyodide@version`` in ``dest/pyodide-version``."""
    out = dest / f"pyodide-{version}"
    stamp = out / ".stamp"
    if stamp.exists() and all((out / f).exists() for f in CORE_FILES):
        return out
    npm = shutil.which("npm")
    if npm is None:
        sys.exit("fetch_lite: npm is needed to fetch pyodide (apt-get install npm)")
    with tempfile.TemporaryDirectory() as tmp:
        _run([npm, "pack", f"pyodide@{version}", "--silent"], cwd=tmp,
             stdout=subprocess.DEVNULL)
        (tgz,) = Path(tmp).glob("pyodide-*.tgz")
        out.mkdir(parents=True, exist_ok=True)
        with tarfile.open(tgz) as tar:
            for name in CORE_FILES:
                member = tar.getmember(f"package/{name}")
                with tar.extractfile(member) as src, open(out / name, "wb") as dst:
                    shutil.copyfileobj(src, dst)
    stamp.write_text(f"pyodide@{version}\n")
    return out


def fetch_wheels(dest: Path, requirements: Path = WHEELS_REQUIREMENTS) -> Path:
    """The pinned pure-Python wheels for Pyodide in ``dest/wheels``."""
    out = dest / "wheels"
    stamp = out / ".stamp"
    digest = hashlib.sha256(requirements.read_bytes()).hexdigest()
    if stamp.exists() and stamp.read_text().strip() == digest:
        return out
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    _run([sys.executable, "-m", "pip", "download", "-q", "--no-deps",
          "--only-binary=:all:", "--python-version", PYODIDE_PYTHON,
          "--implementation", "py", "--abi", "none", "--platform", "any",
          "-d", out, "-r", requirements])
    stamp.write_text(digest + "\n")
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pyodide", default=PYODIDE_VERSION, help="npm pyodide version")
    ap.add_argument("--dest", type=Path, default=ROOT / "build" / "lite")
    args = ap.parse_args(argv)
    fetch_pyodide(args.dest, args.pyodide)
    fetch_wheels(args.dest)


if __name__ == "__main__":
    main()
