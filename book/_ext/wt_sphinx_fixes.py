"""Local Sphinx fixes for the course website (loaded from _config.yml).

Sphinx 7.4 adds an inline script registered with ``app.add_js_file(None,
body=...)`` after ``Builder.init()`` twice: once as ``_JavaScript(None)`` when
it is registered, and again as ``_JavaScript('')`` in ``prepare_writing``; the
two do not compare equal, so the page gets the script twice. sphinx-thebe
registers ``const THEBE_JS_URL = ...`` that way, and the second copy is an
uncaught ``SyntaxError: Identifier 'THEBE_JS_URL' has already been declared``
on every page (caught by tests/book/test_site.py). Normalising the filename to
``''`` before writing lets Sphinx's own de-duplication drop the copy.

While Thebe (live code) is off (``launch_buttons.thebe: false``), the
sphinx-thebe assets are dropped as well: they are unused then, and its inline
script names a CDN (``THEBE_JS_URL = "https://unpkg.com/..."``), which this
offline site must not reference.
"""
from __future__ import annotations


def _thebe_enabled(app) -> bool:
    options = getattr(app.config, "html_theme_options", None) or {}
    return bool((options.get("launch_buttons") or {}).get("thebe"))


def _is_thebe_asset(asset) -> bool:
    filename = str(getattr(asset, "filename", "") or "")
    body = str(getattr(asset, "attributes", {}).get("body", ""))
    return filename.endswith(("sphinx-thebe.js", "sphinx-thebe.css")) or "THEBE_JS_URL" in body


def _fix_assets(app, env):
    builder = app.builder
    if not hasattr(builder, "_js_files"):
        return None
    from sphinx.builders.html._assets import _JavaScript

    drop_thebe = not _thebe_enabled(app)
    fixed = []
    for js in builder._js_files:
        if isinstance(js, _JavaScript) and js.filename is None:
            js = _JavaScript("", priority=js.priority, **js.attributes)
        if drop_thebe and _is_thebe_asset(js):
            continue
        if js not in fixed:
            fixed.append(js)
    builder._js_files = fixed
    if drop_thebe:
        builder._css_files = [c for c in builder._css_files if not _is_thebe_asset(c)]
        # prepare_writing re-adds the assets registered with the app
        registry = app.registry
        registry.js_files = [
            (name, attrs) for name, attrs in registry.js_files
            if not _is_thebe_asset(_JavaScript(name or "", **attrs))
        ]
        registry.css_files = [
            (name, attrs) for name, attrs in registry.css_files
            if not str(name).endswith("sphinx-thebe.css")
        ]
    return None


def setup(app):
    app.connect("env-updated", _fix_assets)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
