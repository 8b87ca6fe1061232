"""scripts/pyc_lite.py's checks (what tests/book/test_lite.py applies to the served
files) find each way a served .pyc can be wrong: missing, another interpreter's
magic number, not checked-hash, compiled from another source."""
from __future__ import annotations

import importlib._bootstrap_external as bx
import importlib.util
import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

import pyc_lite  # noqa: E402

MAGIC = importlib.util.MAGIC_NUMBER
TAG = sys.implementation.cache_tag
SRC = b"x = 1\n"


def _pyc(source, checked=True):
    code = compile(source, "m.py", "exec")
    return bytes(bx._code_to_hash_pyc(code, importlib.util.source_hash(source), checked))


def _wheel(path, members):
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("pkg-1.0.dist-info/METADATA", "Name: pkg\n")
        z.writestr("pkg-1.0.dist-info/RECORD", "")
        for name, data in members.items():
            z.writestr(name, data)
    return path


def test_a_wheel_compiled_right_passes(tmp_path):
    whl = _wheel(tmp_path / "pkg-1.0-py3-none-any.whl", {
        "pkg/__init__.py": SRC, f"pkg/__pycache__/__init__.{TAG}.pyc": _pyc(SRC),
        "top.py": SRC, f"__pycache__/top.{TAG}.pyc": _pyc(SRC)})
    assert pyc_lite.check_wheel(whl, MAGIC, TAG) == []


def test_each_fault_is_found(tmp_path):
    whl = _wheel(tmp_path / "pkg-1.0-py3-none-any.whl", {
        "pkg/__init__.py": SRC,                                     # no .pyc
        "pkg/a.py": SRC, f"pkg/__pycache__/a.{TAG}.pyc": _pyc(b"x = 2\n"),
        "pkg/b.py": SRC, f"pkg/__pycache__/b.{TAG}.pyc": _pyc(SRC, checked=False)})
    problems = "\n".join(pyc_lite.check_wheel(whl, MAGIC, TAG))
    assert "pkg/__init__.py has no" in problems
    assert "a." in problems and "another source" in problems
    assert "b." in problems and "not a checked-hash" in problems
    other = (int.from_bytes(MAGIC[:2], "little") + 1).to_bytes(2, "little") + MAGIC[2:]
    ok = _wheel(tmp_path / "ok-1.0-py3-none-any.whl", {
        "ok.py": SRC, f"__pycache__/ok.{TAG}.pyc": _pyc(SRC)})
    assert "magic" in pyc_lite.check_wheel(ok, other, TAG)[0]
    assert "has no" in pyc_lite.check_wheel(ok, MAGIC, "cpython-399")[0]


def test_stdlib_zip_check(tmp_path):
    good = tmp_path / "good.zip"
    with zipfile.ZipFile(good, "w") as z:
        z.writestr("m.py", SRC)
        z.writestr("m.pyc", _pyc(SRC))
    assert pyc_lite.check_stdlib(good, MAGIC) == []
    bad = tmp_path / "bad.zip"
    with zipfile.ZipFile(bad, "w") as z:
        z.writestr("m.py", SRC)
        z.writestr("n.py", SRC)
        z.writestr("n.pyc", _pyc(b"y = 0\n"))
    problems = "\n".join(pyc_lite.check_stdlib(bad, MAGIC))
    assert "m.py has no m.pyc" in problems and "another source" in problems
