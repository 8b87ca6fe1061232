"""nbval: compare stored SVG figures up to a drawing tolerance.

matplotlib writes SVG coordinates with six decimals and names clip paths by a
hash of their full-precision corner coordinates. The same notebook run on
another processor (other SIMD paths in numpy and libm) moves points by about
1e-6 pt, which changes those digits and every clip-path name although the
figure is the same. nbval compares strings, so every figure would "differ".

Here a stored and a fresh SVG are equal when they have the same tokens, in
the same order, with numbers within ``SVG_TOLERANCE_PT`` of each other and
hash-named ids (``p0123456789``) renamed in order of first appearance. Every
other output (text, LaTeX, HTML) is still compared exactly.

Also: under pytest 9, pytest-xdist's ``--dist loadgroup`` no longer groups anything
(xdist 3.8 renames a test by setting ``item._nodeid``, which pytest 9 no longer reads:
it keeps a structured ``item._id``).  The hook below gives each test marked
``xdist_group(name)`` the id ``...@name`` that xdist's scheduler groups by, so that
the tests that grade in the sandbox do run in one worker, one at a time.

And: a test's figures meant for the log (a benchmark table, recorded with
``record_property("printed", text)``) are printed at the end of the run, by the
main process: under pytest-xdist a worker's own prints never reach the terminal.
"""
from __future__ import annotations

import re

import pytest

SVG_TOLERANCE_PT = 0.05          # 1/1440 inch: invisible at any zoom a reader uses

_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")
_HASH_ID = re.compile(r"\b([pm])[0-9a-f]{10}\b")


def _normalise_ids(svg: str) -> str:
    names: dict[str, str] = {}

    def rename(match: re.Match) -> str:
        return names.setdefault(match.group(0), f"{match.group(1)}ID{len(names)}")

    return _HASH_ID.sub(rename, svg)


def _split(svg: str) -> tuple[list[str], list[float]]:
    """The SVG's text with numbers cut out, and the numbers."""
    svg = _normalise_ids(svg)
    return _NUMBER.split(svg), [float(n) for n in _NUMBER.findall(svg)]


class SVGOutput(str):
    """An SVG string whose ``==`` allows ``SVG_TOLERANCE_PT`` on every number."""

    def __eq__(self, other):
        if not isinstance(other, str):
            return NotImplemented
        text_a, nums_a = _split(self)
        text_b, nums_b = _split(other)
        return text_a == text_b and len(nums_a) == len(nums_b) and all(
            abs(a - b) <= SVG_TOLERANCE_PT for a, b in zip(nums_a, nums_b))

    def __ne__(self, other):
        equal = self.__eq__(other)
        return equal if equal is NotImplemented else not equal

    __hash__ = str.__hash__


def _is_svg(value) -> bool:
    return isinstance(value, str) and "<svg" in value[:1000]


def pytest_configure(config):
    """Wrap nbval's sanitizer so that SVG outputs compare with a tolerance."""
    if not getattr(config.option, "nbval", False):
        return
    from nbval.plugin import IPyNbCell

    if getattr(IPyNbCell, "_wt_svg_tolerance", False):
        return
    sanitize = IPyNbCell.sanitize

    def sanitize_with_svg_tolerance(self, s):
        s = sanitize(self, s)
        return SVGOutput(s) if _is_svg(s) else s

    IPyNbCell.sanitize = sanitize_with_svg_tolerance
    IPyNbCell._wt_svg_tolerance = True


def pytest_terminal_summary(terminalreporter):
    """Print what the tests recorded as ``("printed", text)`` (see the module docstring)."""
    for key in ("passed", "failed"):
        for report in terminalreporter.stats.get(key, []):
            for name, value in getattr(report, "user_properties", ()):
                if name == "printed" and report.when == "call":
                    terminalreporter.write_line(str(value))


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config, items):
    """``--dist loadgroup``: the ``@group`` suffix xdist adds to a grouped test's id, in the
    form pytest 9 reads (see the module docstring); nothing where xdist's own works."""
    if not getattr(config.option, "loadgroup", False):     # set in xdist's workers
        return
    try:
        from _pytest.nodeid import NodeId
    except ImportError:             # pytest before 9: xdist's own suffix works
        return
    for item in items:
        names = {str(m.args[0] if m.args else m.kwargs.get("name", "default"))
                 for m in item.iter_markers("xdist_group")}
        if names and "@" not in item.nodeid and hasattr(item, "_id"):
            item._id = NodeId.parse(f"{item.nodeid}@{'_'.join(sorted(names))}")
