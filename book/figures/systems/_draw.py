"""What the drawing scripts of this folder share (not a figure script itself).

Each ``<name>.py`` here draws one system and writes ``<name>.svg`` beside itself,
deterministically: the SVG backend, a fixed hash salt (the script's name), glyphs
as paths, no date in the metadata.  A script does::

    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parent))
    import _draw  # noqa: E402

    _draw.style("sledge")
    ...
    _draw.save(fig, __file__)

Importing this module selects the SVG backend before pyplot is imported.
"""

from pathlib import Path

import matplotlib

matplotlib.use("svg")
import matplotlib.pyplot as plt  # noqa: E402

__all__ = ["style", "arrow", "plane", "coordinates", "save", "panels"]


def style(name, size=22):
    """Set the rcParams every figure uses; ``name`` salts the SVG ids."""
    plt.rcParams["svg.hashsalt"] = name
    plt.rcParams["svg.fonttype"] = "path"
    plt.rcParams["font.size"] = size
    plt.rcParams["mathtext.fontset"] = "dejavuserif"


def arrow(ax, A, B, color="k", lw=2.0, ms=22, style="-|>", ls=None, zorder=5):
    """An arrow from A to B with a filled head (``style="<|-|>"``: a dimension line).

    ``ls`` is the line style of the shaft (matplotlib's default when None);
    ``zorder=None`` leaves the annotation's default drawing order.
    """
    props = dict(arrowstyle=style, color=color, lw=lw, mutation_scale=ms)
    if ls is not None:
        props["ls"] = ls
    kw = {} if zorder is None else {"zorder": zorder}
    ax.annotate("", xy=B, xytext=A, annotation_clip=False,
                arrowprops=dict(props, shrinkA=0, shrinkB=0), **kw)


def plane(ax, xmax, ymax):
    """The axes x and y of the plane, to ``xmax`` and ``ymax``, with the origin O."""
    arrow(ax, (0, 0), (xmax, 0))
    arrow(ax, (0, 0), (0, ymax))
    ax.text(xmax + 0.1, 0, "$x$", va="center")
    ax.text(0, ymax + 0.1, "$y$", ha="center", va="bottom")
    ax.text(-0.12, -0.12, "$O$", ha="right", va="top")


def coordinates(ax, P, color="#44546a"):
    """The coordinates x, y of the point P: dotted lines to the axes, labelled there."""
    ax.plot([P[0], P[0]], [0, P[1]], ":", color=color, lw=1.4)
    ax.plot([0, P[0]], [P[1], P[1]], ":", color=color, lw=1.4)
    ax.text(P[0], -0.15, "$x$", ha="center", va="top", color=color)
    ax.text(-0.15, P[1], "$y$", ha="right", va="center", color=color)


def save(fig, script_file):
    """Write ``<script name>.svg`` beside ``script_file``, close ``fig``, return the path."""
    out = Path(script_file).with_suffix(".svg")
    fig.savefig(out, metadata={"Date": None}, bbox_inches="tight")
    plt.close(fig)
    return out


def panels(script_file, drawers, figsize, ratios):
    """One figure of side-by-side views, each drawn by one function of ``drawers`` on an
    equal-aspect axes without frame, written by :func:`save`; the path."""
    fig, axes = plt.subplots(1, len(drawers), figsize=figsize,
                             gridspec_kw={"width_ratios": list(ratios)})
    for ax, draw in zip(axes, drawers):
        ax.set_aspect("equal")
        ax.axis("off")
        draw(ax)
    return save(fig, script_file)

