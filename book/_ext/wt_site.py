"""The course website's own styles and script, and theme settings (loaded from _config.yml).

* ``wt_static/wt-site.css``: display maths and text outputs are never cut off.
  The theme (pydata-sphinx-theme) lays a display equation out as a
  ``row-reverse`` flex box with ``overflow: hidden``, so an equation wider than
  the column loses its *left* part without a scroll bar; here every display
  scrolls horizontally from its left edge, with a visible scroll bar and a
  shade at the edge that hides more; in-line maths scroll too instead of
  being clipped; text outputs wrap; long literals break.
* ``wt_static/wt-site.js``: after MathJax has typeset the page, marks every
  equation that is wider than its column (``wt-wide``, and which edges hide
  more of it), and gives it a keyboard focus stop and a label so that it can
  be scrolled without a mouse.
* ``wt_static/wt-print.css``: the print style of ``make pdf``
  (``scripts/make_pdf.py`` inlines it into its one-document edition).
* the bibliography style ``wt_author_year``: the chapters cite author-year
  ("Mei (1983)", sphinxcontrib-bibtex ``author_year`` reference style), so the
  reference list is labelled the same way ("[Mei 1983]") and sorted by author
  and year, instead of pybtex's numbered ``plain`` labels ("[1]"), which no
  citation in the text uses.
* ``html_context["default_mode"]``: pydata-sphinx-theme 0.17 writes
  ``data-default-mode=""`` when it is unset and its script then logs "Got invalid theme mode: .
  Resetting to auto." as a console error on every page. The site's figures
  are drawn for a light background, so the default is ``light`` (the theme's
  switch still offers dark).
"""
from __future__ import annotations

from pathlib import Path

STATIC = Path(__file__).with_name("wt_static")


def _configure(app, config):
    config.html_static_path = [*config.html_static_path, str(STATIC)]
    # a template variable of pydata-sphinx-theme (html_context), not a theme option
    context = dict(config.html_context or {})
    context.setdefault("default_mode", "light")
    config.html_context = context


def _register_bib_style():
    from pybtex.plugin import register_plugin
    from pybtex.style.formatting.unsrt import Style as UnsrtStyle
    from pybtex.style.labels import BaseLabelStyle

    class AuthorYearLabels(BaseLabelStyle):
        """"Mei 1983", "Neimark and Fufaev 1972", "Meurer et al. 2017";
        a, b, ... after the year when two entries would share a label."""

        def format_labels(self, sorted_entries):
            labels = [self._label(e) for e in sorted_entries]
            seen: dict[str, int] = {}
            for label in labels:
                if labels.count(label) > 1:
                    seen[label] = seen.get(label, 0) + 1
                    yield label + "abcdefghijklmnopqrstuvwxyz"[seen[label] - 1]
                else:
                    yield label

        @staticmethod
        def _label(entry):
            persons = entry.persons.get("author") or entry.persons.get("editor") or []
            names = [" ".join(p.last_names) for p in persons]
            if not names:
                who = entry.fields.get("title", entry.key).split()[0]
            elif len(names) == 1:
                who = names[0]
            elif len(names) == 2:
                who = f"{names[0]} and {names[1]}"
            else:
                who = f"{names[0]} et al."
            return f"{who} {entry.fields.get('year', '')}".strip()

    class AuthorYearStyle(UnsrtStyle):
        default_label_style = AuthorYearLabels
        default_sorting_style = "author_year_title"

    try:
        register_plugin("pybtex.style.formatting", "wt_author_year", AuthorYearStyle)
    except Exception:  # registered already (a second build in the same process)
        pass


def _copy_static(app, exception):
    """Sphinx copies static files only when some page is rebuilt; an edit of
    the CSS/JS alone must reach the site too."""
    if exception is None and app.builder.format == "html":
        out = Path(app.outdir, "_static")
        out.mkdir(parents=True, exist_ok=True)
        for f in STATIC.iterdir():
            if f.is_file():
                (out / f.name).write_bytes(f.read_bytes())


def setup(app):
    _register_bib_style()
    app.connect("config-inited", _configure)
    app.connect("build-finished", _copy_static)
    app.add_css_file("wt-site.css", priority=900)
    app.add_js_file("wt-site.js", priority=900)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
