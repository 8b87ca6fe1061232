"""Serve the built site on 127.0.0.1 (JupyterLite does not work from file://).

    python scripts/serve.py [--port 8000] [--directory _build/html]

The standard library's static server, with the MIME types Pyodide needs set
explicitly (``.mjs`` as JavaScript for module workers, ``.wasm`` for streaming
compilation) rather than taken from the machine's /etc/mime.types, and with
caching made explicit: every file is sent with ``Cache-Control: no-cache`` and an
``ETag`` (a hash of its content), and a request whose
``If-None-Match`` names the current ETag is answered ``304 Not Modified`` with no
body, over HTTP/1.1 (Chromium refetches an HTTP/1.0 response whole instead of
revalidating it). So a second visit re-uses the browser's cached copy of every
file after one cheap revalidation each, and a
rebuilt file is never taken from the cache: the served wheels are checked against
the sha256 in pyodide-lock.json, so a stale cached wheel would break the kernel.
The exceptions are files named by their content: the folder of Pyodide's own
files (``static/pyodide-core-<hash>/``, scripts/lite_early_kernel.py) and the
JupyterLite build's chunks (``lite/build/<name>.<hash>.js``, and the
labextensions' ``static/<name>.<hash>.js``): a rebuilt file there has a new
name, so they are sent with ``max-age`` a year and ``immutable`` and the browser
does not ask again (about 120 requests fewer on a second visit, which on a real
network is as many round trips). This matters most for Pyodide: measured in
Chromium, a
revalidated ``pyodide.asm.wasm`` is compiled again on every visit (V8's cached
compilation is not used), about 2-3 s of compiler threads on the 2-core machine.
(The standard server's ``If-Modified-Since`` test is not used: JupyterLite gives
its files a fixed date in 1985 and the build copies files with their original
dates, so a changed file can have the date of the cached one, or an older one.)
"""
from __future__ import annotations

import argparse
import functools
import hashlib
import http.server
import os
import re
import threading
from pathlib import Path

EXTRA_TYPES = {".mjs": "text/javascript", ".js": "text/javascript",
               ".wasm": "application/wasm", ".json": "application/json",
               ".whl": "application/zip", ".zip": "application/zip",
               ".ipynb": "application/json", ".svg": "image/svg+xml"}


CACHE_CONTROL = "no-cache"
#: content-named files (a new name for new content): kept by the browser for good.
#: Pyodide's own files (scripts/lite_early_kernel.py) and the JupyterLite build's
#: chunks, named ``[name].[contenthash:7].js`` by its rspack.config.js (and the
#: labextensions' ``[name].[contenthash].js``)
IMMUTABLE = re.compile(r"/static/pyodide-core-[0-9a-f]{12}/[^/]+$"
                       r"|/lite/build/[^/]+\.[0-9a-f]{7}\.js$"
                       r"|/lite/extensions/.+/static/[^/]+\.[0-9a-f]{16,20}\.js$")
CACHE_CONTROL_IMMUTABLE = "max-age=31536000, immutable"
_ETAGS: dict = {}
_ETAGS_LOCK = threading.Lock()


def etag(path) -> str:
    """The ETag of a file: a hash of its content (memoized per file state).

    Not the modification time: JupyterLite's build gives its application files
    one fixed date (1985-10-26), and the build copies fetched files with their
    original dates, so a changed file can keep the date (and size) of the old one.
    The memo key has the inode change time, which every write updates."""
    st = os.stat(path)
    key = (os.fspath(path), st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns)
    with _ETAGS_LOCK:
        tag = _ETAGS.get(key)
    if tag is None:
        h = hashlib.blake2b(digest_size=12)
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
        tag = f'"{h.hexdigest()}"'
        with _ETAGS_LOCK:
            _ETAGS[key] = tag
    return tag


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **EXTRA_TYPES}
    # HTTP/1.1 (keep-alive; every response has a Content-Length): Chromium does
    # not revalidate a cached HTTP/1.0 response, it fetches the file again whole
    protocol_version = "HTTP/1.1"

    def send_head(self):
        path = self.translate_path(self.path)
        if os.path.isdir(path):
            # the standard server redirects ".../dir" to ".../dir/" (no ETag then)
            slash = self.path.split("?", 1)[0].split("#", 1)[0].endswith("/")
            path = os.path.join(path, "index.html") if slash else ""
        self._etag = etag(path) if os.path.isfile(path) else None
        del self.headers["If-Modified-Since"]          # the ETag alone decides
        if self._etag is not None and self._etag in [
                t.strip() for t in self.headers.get("If-None-Match", "").split(",")]:
            self.send_response(http.HTTPStatus.NOT_MODIFIED)
            self.end_headers()
            return None
        return super().send_head()

    def end_headers(self):
        if getattr(self, "_etag", None) is not None:
            self.send_header("ETag", self._etag)
            path = self.path.split("?", 1)[0].split("#", 1)[0]
            self.send_header("Cache-Control", CACHE_CONTROL_IMMUTABLE
                             if IMMUTABLE.search(path) else CACHE_CONTROL)
        super().end_headers()

    def log_message(self, fmt, *args):  # quiet unless asked
        if getattr(self.server, "verbose", False):
            super().log_message(fmt, *args)


def make_server(directory: Path, port: int = 0, verbose: bool = False):
    """A ThreadingHTTPServer on 127.0.0.1 (port 0: any free port)."""
    handler = functools.partial(Handler, directory=str(directory))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", port), handler)
    server.verbose = verbose
    server.daemon_threads = True
    return server


def serve_in_thread(directory: Path):
    """Start a server in a daemon thread; returns (server, base URL)."""
    server = make_server(directory)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}/"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--directory", type=Path,
                    default=Path(__file__).resolve().parent.parent / "_build" / "html")
    args = ap.parse_args(argv)
    if not (args.directory / "index.html").is_file():
        raise SystemExit(f"serve: no site in {args.directory}: run `make book` first")
    try:
        server = make_server(args.directory, args.port, verbose=True)
    except OSError as err:
        raise SystemExit(f"serve: cannot listen on 127.0.0.1:{args.port} ({err.strerror}); "
                         f"choose another port: make serve SERVE_PORT=8001") from None
    print(f"serving {args.directory} on http://127.0.0.1:{args.port}/ (Ctrl-C stops)",
          flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
