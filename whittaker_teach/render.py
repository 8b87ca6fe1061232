"""Rendering steps: Unicode for the terminal, LaTeX for the book.

Each step is tagged with the number of its equation in the paper: in LaTeX
with ``\\tag{1.16}`` (MathJax shows it at the right margin), in Unicode with
the label in front.  Nothing here computes; it only reads steps.
"""

from __future__ import annotations

import textwrap

import sympy as sp

__all__ = ["step_unicode", "step_latex", "derivation_unicode", "derivation_latex", "show"]

MARK = {"verified": "✓", "FAILED": "✗", "not verified": "?", "derived": ""}


def _pretty(eq):
    text = sp.pretty(eq, use_unicode=True, wrap_line=False)
    return "\n".join(line.rstrip() for line in text.splitlines())


def step_unicode(step) -> str:
    """The step as text: its label and title, its equations, its check."""
    lines = [f"({step.label}) {step.title}"]
    for eq in step.equations:
        lines.append(textwrap.indent(_pretty(eq), "    "))
    if step.check is not None:
        lines.append(f"    {MARK[step.status]} {step.check.describe()}")
    if step.note:
        lines.append(textwrap.indent(textwrap.fill("note: " + step.note, 72), "    "))
    return "\n".join(lines)


def _tag(label):
    return rf"\tag{{{label}}}" if label[0].isdigit() else rf"\tag*{{{label}}}"


def step_latex(step) -> str:
    """The step's equations as one LaTeX display, tagged with the paper's number."""
    body = [sp.latex(eq) for eq in step.equations]
    if len(body) == 1:
        inner = body[0]
    else:
        rows = [b.replace("=", "&=", 1) if "=" in b else "&" + b for b in body]
        # rows end with \cr, not \\: Sphinx wraps any display containing \\ in a
        # split environment, where MathJax refuses \tag
        inner = r"\begin{aligned}" + r" \cr ".join(rows) + r"\end{aligned}"
    return inner + " " + _tag(step.label)


def _check_line(step):
    return f"{MARK[step.status]} {step.check.describe()}" if step.check else ""


def derivation_unicode(derivation) -> str:
    head = f"{derivation.title}\n{'=' * len(derivation.title)}"
    return "\n\n".join([head] + [step_unicode(s) for s in derivation.steps])


def derivation_latex(derivation) -> str:
    out = [f"% {derivation.title}"]
    for s in derivation.steps:
        out.append(f"% ({s.label}) {s.title}")
        out.append(r"\begin{equation}" + step_latex(s) + r"\end{equation}")
        if s.check:
            out.append(f"% {_check_line(s)}")
    return "\n".join(out)


def _in_notebook():
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    ip = get_ipython()
    if ip is None:
        return False
    # Jupyter's kernel, or the Pyodide kernel of the in-browser site (JupyterLite)
    kind = type(ip)
    return kind.__name__ == "ZMQInteractiveShell" or kind.__module__.startswith("pyodide_kernel")


def show(derivation, latex=False):
    """Show every step: rendered maths in a notebook, Unicode (or LaTeX) in a terminal."""
    if _in_notebook():
        from IPython.display import Markdown, Math, display
        display(Markdown(f"**{derivation.title}**"))
        for s in derivation.steps:
            text = f"**({s.label})** {s.title}"
            if s.check:
                text += f"  \n{_check_line(s)}"
            if s.note:
                text += f"  \n*{s.note}*"
            display(Markdown(text))
            if s.equations:
                display(Math(step_latex(s)))
        return None
    print(derivation.to_latex() if latex else derivation.to_unicode())
    return None
