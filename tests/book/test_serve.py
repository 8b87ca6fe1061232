"""scripts/serve.py: the static server of the built site (tests, bench, `make serve`).

Its caching headers are what make a second visit to the in-browser site re-use
the browser's copies (no download; for Pyodide's content-named folder, no
request at all, so that V8 re-uses its compilation of the wasm) while never
serving a stale copy of a rebuilt file (a stale wheel would fail Pyodide's
sha256 check against the new pyodide-lock.json).
"""
from __future__ import annotations

import os
import sys
import urllib.error
import urllib.request
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

import serve  # noqa: E402


@pytest.fixture
def site(tmp_path):
    (tmp_path / "lite").mkdir()
    (tmp_path / "lite" / "index.html").write_text("<p>lite</p>")
    (tmp_path / "a.whl").write_bytes(b"wheel one")
    (tmp_path / "m.wasm").write_bytes(b"\0asm")
    server, base = serve.serve_in_thread(tmp_path)
    yield tmp_path, base
    server.shutdown()


def _get(url, headers=None):
    req = urllib.request.Request(url, headers=headers or {})
    try:
        with urllib.request.urlopen(req) as r:
            return r.status, r.headers, r.read()
    except urllib.error.HTTPError as err:
        return err.code, err.headers, b""


def test_files_are_sent_with_no_cache_and_a_content_etag(site):
    root, base = site
    status, headers, body = _get(base + "a.whl")
    assert status == 200 and body == b"wheel one"
    assert headers["Cache-Control"] == "no-cache"
    assert headers["ETag"].startswith('"') and len(headers["ETag"]) > 10
    assert headers["Content-Type"] == "application/zip"
    assert _get(base + "m.wasm")[1]["Content-Type"] == "application/wasm"
    assert _get(base + "lite/")[1]["Cache-Control"] == "no-cache"


def test_only_content_named_files_are_kept_for_good(site):
    root, base = site
    core = root / "lite" / "static" / "pyodide-core-0123456789ab"
    core.mkdir(parents=True)
    (core / "pyodide.asm.wasm").write_bytes(b"\0asm")
    (root / "lite" / "static" / "pyodide").mkdir()
    (root / "lite" / "static" / "pyodide" / "pyodide-lock.json").write_text("{}")
    (root / "lite" / "static" / "pyodide-core-old").mkdir()
    (root / "lite" / "static" / "pyodide-core-old" / "x.js").write_text("")
    ext = root / "lite" / "extensions" / "@jupyterlite" / "kernel" / "static"
    ext.mkdir(parents=True)
    (root / "lite" / "build").mkdir()
    for name in ("1031.b91a70b.js", "bundle.js", "1031.js"):
        (root / "lite" / "build" / name).write_text("")
    for name in ("393.d0cf8b3e64df6b99.js", "style.js"):
        (ext / name).write_text("")
    for rel in ("lite/static/pyodide-core-0123456789ab/pyodide.asm.wasm",
                "lite/build/1031.b91a70b.js",
                "lite/extensions/@jupyterlite/kernel/static/393.d0cf8b3e64df6b99.js"):
        headers = _get(base + rel)[1]
        assert headers["Cache-Control"] == "max-age=31536000, immutable", rel
        assert headers["ETag"]
    for rel in ("lite/static/pyodide/pyodide-lock.json", "lite/static/pyodide-core-old/x.js",
                "m.wasm", "lite/build/bundle.js", "lite/build/1031.js",
                "lite/extensions/@jupyterlite/kernel/static/style.js"):
        assert _get(base + rel)[1]["Cache-Control"] == "no-cache", rel


def test_the_server_speaks_http_1_1(site):
    """Chromium revalidates a cached response only when it came over HTTP/1.1 (an
    HTTP/1.0 one is fetched again whole, measured: bench_lite.py's second visit)."""
    import http.client
    root, base = site
    host, port = base.split("//")[1].rstrip("/").split(":")
    conn = http.client.HTTPConnection(host, int(port))
    for _ in range(2):                                  # one connection, kept alive
        conn.request("GET", "/a.whl")
        r = conn.getresponse()
        assert r.version == 11 and r.read() == b"wheel one"
    conn.request("GET", "/a.whl", headers={"If-None-Match": r.headers["ETag"]})
    r = conn.getresponse()
    assert r.status == 304 and r.read() == b""
    conn.close()


def test_a_matching_etag_is_answered_304_without_a_body(site):
    root, base = site
    tag = _get(base + "a.whl")[1]["ETag"]
    status, headers, body = _get(base + "a.whl", {"If-None-Match": tag})
    assert status == 304 and body == b"" and headers["ETag"] == tag
    assert _get(base + "a.whl", {"If-None-Match": '"other", ' + tag})[0] == 304
    assert _get(base + "a.whl", {"If-None-Match": '"other"'})[0] == 200


def test_a_changed_file_with_the_same_date_and_size_is_sent_again(site):
    """JupyterLite dates its files 1985-10-26 and the build copies files with their
    dates: neither the date nor the size may decide that a file is unchanged."""
    root, base = site
    f = root / "a.whl"
    st = f.stat()
    status, headers, _ = _get(base + "a.whl")
    tag = headers["ETag"]
    f.write_bytes(b"wheel two")                      # same size
    os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))  # same date
    assert f.stat().st_mtime_ns == st.st_mtime_ns and f.stat().st_size == st.st_size
    since = headers["Last-Modified"]
    status, headers, body = _get(base + "a.whl",
                                 {"If-None-Match": tag, "If-Modified-Since": since})
    assert status == 200 and body == b"wheel two" and headers["ETag"] != tag
    # an older file in place of a newer cached one: not 304 by date either
    os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns - 10**12))
    assert _get(base + "a.whl", {"If-Modified-Since": since})[0] == 200


def test_missing_files_and_directory_redirects_still_work(site):
    root, base = site
    assert _get(base + "nothere.whl")[0] == 404
    status, headers, body = _get(base + "lite")      # redirected to lite/
    assert status == 200 and body == b"<p>lite</p>"
