"""One call at the top of every notebook of the book and the exercises.

``setup()`` makes SymPy print MathJax (not PNG: myst-nb would show images)
and makes matplotlib figures SVG with no date and a fixed hash salt, so that
re-running a notebook stores the same outputs (nbval re-checks them).

>>> from whittaker_teach.notebook import setup
>>> setup()      # outside IPython only the printing and matplotlib settings apply
"""

__all__ = ["setup"]


def setup():
    """SymPy → MathJax; matplotlib → deterministic inline SVG."""
    import sympy as sp
    sp.init_printing(use_latex="mathjax")
    try:
        import matplotlib as mpl
    except ImportError:
        return
    mpl.rcParams["svg.hashsalt"] = "whittaker-teach"
    mpl.rcParams["svg.fonttype"] = "path"
    mpl.rcParams["figure.dpi"] = 100
    try:
        from IPython import get_ipython
    except ImportError:
        return
    ip = get_ipython()
    if ip is not None:
        ip.run_line_magic("config", "InlineBackend.figure_formats = ['svg']")
        ip.run_line_magic("config", "InlineBackend.print_figure_kwargs = "
                          "{'metadata': {'Date': None}, 'bbox_inches': 'tight'}")
