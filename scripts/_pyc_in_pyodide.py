"""Run INSIDE Pyodide by scripts/pyc_lite.mjs (not importable on the host).

JOB = {"wheels": [[src, dst, drop_tests], ...], "stdlib": [src, dst] or None}
(host paths; the host's / is mounted at /host).

Each wheel is rewritten with, next to every ``.py`` module, the checked-hash
``__pycache__/<name>.cpython-3XY.pyc`` that this interpreter's import system
looks for (magic number and cache tag are this CPython's); the ``.py`` files stay
(tracebacks show source lines; a stale .pyc is never used: its source hash is
checked at import). ``drop_tests``: members under a ``tests/`` directory are left
out (as Pyodide's own distribution "unvendors" them). The stdlib zip gets a
checked-hash ``.pyc`` beside every ``.py`` (where zipimport looks). Member order,
dates and compression are kept, so the output is a function of the input.
"""
import base64
import hashlib
import importlib._bootstrap_external as bx
import importlib.util
import json
import site
import sys
import warnings
import zipfile

MAGIC = importlib.util.MAGIC_NUMBER
SITE = site.getsitepackages()[0]
STDLIB_ZIP = f"/lib/python{sys.version_info[0]}{sys.version_info[1]}.zip"


def host(p):
    return "/host" + p


def pyc(source: bytes, filename: str) -> bytes:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # SyntaxWarnings of library code
        code = compile(source, filename, "exec", dont_inherit=True)
    return bytes(bx._code_to_hash_pyc(code, importlib.util.source_hash(source), checked=True))


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def _is_test(name):
    return "/tests/" in name or name.startswith("tests/")


def _add_pyc(zout, info, data, path, cached, failed):
    """Compile one .py member (``path``: where Pyodide will see it) and write its .pyc
    as ``cached`` beside it, with the member's date, compression and mode; the .pyc's
    bytes, or None (the error appended to ``failed``)."""
    try:
        out = pyc(data, path)
    except (SyntaxError, ValueError) as err:
        failed.append(f"{info.filename}: {err}")
        return None
    pinfo = zipfile.ZipInfo(cached, date_time=info.date_time)
    pinfo.compress_type = info.compress_type
    pinfo.external_attr = info.external_attr
    zout.writestr(pinfo, out)
    return out


def wheel(src, dst, drop_tests):
    done, failed = 0, []
    with zipfile.ZipFile(host(src)) as zin, zipfile.ZipFile(host(dst), "w") as zout:
        infos = [i for i in zin.infolist() if not (drop_tests and _is_test(i.filename))]
        record = next(i for i in infos if i.filename.endswith(".dist-info/RECORD"))
        dist_info = record.filename.rsplit("/", 1)[0]
        kept, added = [], []
        for info in infos:
            if info is record:
                continue
            data = zin.read(info)
            zout.writestr(info, data)
            kept.append(info.filename)
            name = info.filename
            top = name.split("/", 1)[0]
            if not name.endswith(".py") or top.endswith((".dist-info", ".data")):
                continue
            cached = importlib.util.cache_from_source(name)
            out = _add_pyc(zout, info, data, f"{SITE}/{name}", cached, failed)
            if out is not None:
                added.append((cached, out))
                done += 1
        # RECORD: the kept files' lines, and one per added .pyc
        kept = set(kept)
        lines = [ln for ln in zin.read(record).decode().splitlines()
                 if ln and ln.split(",", 1)[0] in kept]
        lines += [_record_line(n, d) for n, d in added] + [f"{dist_info}/RECORD,,"]
        zout.writestr(record, "\n".join(lines) + "\n")
    return {"src": src, "dst": dst, "compiled": done, "failed": failed,
            "dropped": sum(1 for i in zipfile.ZipFile(host(src)).infolist()
                           if drop_tests and _is_test(i.filename))}


def stdlib(src, dst):
    done, failed = 0, []
    with zipfile.ZipFile(host(src)) as zin, zipfile.ZipFile(host(dst), "w") as zout:
        names = set(zin.namelist())
        for info in zin.infolist():
            data = zin.read(info)
            zout.writestr(info, data)
            name = info.filename
            if not name.endswith(".py") or name + "c" in names:
                continue
            if _add_pyc(zout, info, data, f"{STDLIB_ZIP}/{name}", name + "c", failed) is not None:
                done += 1
    return {"src": src, "dst": dst, "compiled": done, "failed": failed}


results = {"magic": MAGIC.hex(), "cache_tag": sys.implementation.cache_tag,
           "version": sys.version.split()[0], "wheels": [], "stdlib": None}
for src, dst, drop in JOB.get("wheels") or []:  # noqa: F821 (set by pyc_lite.mjs)
    results["wheels"].append(wheel(src, dst, drop))
if JOB.get("stdlib"):  # noqa: F821
    results["stdlib"] = stdlib(*JOB["stdlib"])  # noqa: F821
print("PYC_LITE " + json.dumps(results))
