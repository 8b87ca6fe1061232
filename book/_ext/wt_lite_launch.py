""""Run in the browser": a launch button that opens the page's notebook in the
in-browser site (JupyterLite, built into ``<site>/lite/`` by scripts/build_lite.py).

sphinx-book-theme's own JupyterLite button (``launch_buttons.jupyterlite_url``)
needs a repository address and builds one absolute-looking URL for every page;
here the link is made relative to each page, so the site works from any address
(and offline), and an exercise page (the solution notebook) opens the student
version. The theme's Binder/Colab/repository buttons are not used: the project
has no public address yet.

``_config.yml``::

    launch_buttons:
      jupyterlite_url: lite/lab/index.html   # relative to the site root
"""
from __future__ import annotations

import re
from pathlib import Path

from sphinx.util import logging

LOGGER = logging.getLogger(__name__)
DEFAULT_APP = "lite/lab/index.html"


def lite_path(srcdir: Path, docname: str) -> str | None:
    """The notebook (path inside the lite site) for a page, or None.

    Same mapping as scripts/build_lite.py: ``exercises/solutions/x`` opens the
    student notebook ``exercises/x.ipynb``.
    """
    m = re.fullmatch(r"exercises/solutions/([\w.-]+)", docname)
    doc = f"exercises/{m.group(1)}" if m else docname
    return doc + ".ipynb" if (Path(srcdir) / (doc + ".ipynb")).exists() else None


def _app_url(app) -> str:
    options = getattr(app.config, "html_theme_options", None) or {}
    url = (options.get("launch_buttons") or {}).get("jupyterlite_url") or DEFAULT_APP
    return url.strip("/")


def launch_url(app, pagename: str) -> str | None:
    """The page-relative URL of its "Run in the browser" link, or None."""
    path = lite_path(app.srcdir, pagename)
    if path is None:
        return None
    depth = pagename.count("/")
    return "../" * depth + f"{_app_url(app)}?path={path}"


def add_button(app, pagename, templatename, context, doctree):
    buttons = context.get("header_buttons")
    if buttons is None:
        return
    # the theme's launch group (Binder/Colab/JupyterLite at absolute addresses)
    buttons[:] = [b for b in buttons if b.get("label") != "launch-buttons"]
    url = launch_url(app, pagename)
    if url is None:
        return
    buttons.insert(0, {
        "type": "link",
        "url": url,
        "tooltip": "Run this notebook in the browser (JupyterLite: Python in the "
                   "page, nothing to install; your edits stay in this browser)",
        "icon": "fas fa-play",
        "text": "Run in the browser",
        "label": "run-in-browser",
    })
    context["wt_lite_url"] = url
    if pagename.startswith("exercises/solutions/"):
        body = context.get("body", "")
        end = body.find("</h1>")      # after the page title
        cut = body.find("\n", end) + 1 if end >= 0 else 0
        context["body"] = body[:cut] + _exercise_note(url) + body[cut:]


def _exercise_note(url: str) -> str:
    """How to work on the exercise in the browser and hand it in."""
    return (
        '<div class="admonition tip wt-run-in-browser">\n'
        '<p class="admonition-title">Work on this exercise in your browser</p>\n'
        f'<p><a class="reference external" href="{url}" target="_blank">Run in the '
        'browser</a> opens the student version of this notebook (the solutions '
        'below removed) in JupyterLite: Python runs in the page, nothing is '
        'installed, and <code>check(...)</code> gives its feedback there. Your '
        'work is saved in this browser&#8217;s storage only (not on a server, '
        'and not in another browser or a private window). To hand it in, use '
        '<em>File &#9656; Download</em> in JupyterLite, which saves the '
        '<code>.ipynb</code> file to your computer.</p>\n'
        '</div>\n')


def _add_static(app, config):
    config.html_static_path = [*config.html_static_path, str(Path(__file__).parent / "static")]


def setup(app):
    app.connect("config-inited", _add_static)
    app.add_css_file("wt_lite_launch.css")
    # after sphinx-book-theme's own buttons (priority 501)
    app.connect("html-page-context", add_button, priority=502)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
