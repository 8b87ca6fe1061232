"""Serve the built site on 127.0.0.1 (JupyterLite does not work from file://).

    python scripts/serve.py [--port 8000] [--directory _build/html]

The standard library's static server, with the MIME types Pyodide needs set
explicitly (``.mjs`` as JavaScript for module workers, ``.wasm`` for streaming
compilation) rather than taken from the machine's /etc/mime.types.
"""
from __future__ import annotations

import argparse
import functools
import http.server
import threading
from pathlib import Path

EXTRA_TYPES = {".mjs": "text/javascript", ".js": "text/javascript",
               ".wasm": "application/wasm", ".json": "application/json",
               ".whl": "application/zip", ".zip": "application/zip",
               ".ipynb": "application/json", ".svg": "image/svg+xml"}


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **EXTRA_TYPES}

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
