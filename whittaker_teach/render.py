"""Rendering steps: Unicode for the terminal, LaTeX for the book.

Each step is tagged with the number of its equation in the paper: in LaTeX
with ``\\tag{1.16}`` (MathJax shows it at the right margin), in Unicode with
the label in front.  Nothing here computes; it only reads steps.

Long equations are broken over several lines, at the top-level ``+``/``-``
(and, for a single wide term, inside its widest sum, with ``\\left(`` ...
``\\right.`` continuation), so that they fit a column:

* LaTeX: an ``aligned`` block, rows ending with ``\\cr`` (Sphinx wraps any
  display containing ``\\\\`` in a ``split`` where MathJax refuses ``\\tag``),
  one tag for the whole block.  The width is estimated by :func:`tex_width`
  (in em of MathJax's font; the body and two tag widths fit :data:`PAGE_WIDTH`,
  the book's 688 px column, see :func:`math_latex`);
* Unicode: SymPy's 2-D pictures joined term by term, every line at most the
  terminal's width (100 columns when the output is not a terminal).

>>> import sympy as sp

from .labels import is_paper_number, shown_label
>>> a, b, c = sp.symbols("a b c")
>>> print(equation_unicode(sp.Eq(sp.Symbol("y"), a + b + c), width=12))
y = a + b
    + c
>>> print(equation_latex(sp.Eq(sp.Symbol("y"), a + b + c), width=5))
\\begin{aligned}y &= a + b \\cr &\\quad {} + c\\end{aligned}
"""

from __future__ import annotations

import re
import shutil
import textwrap

import sympy as sp

from .labels import is_paper_number, shown_label

__all__ = ["step_unicode", "step_latex", "derivation_unicode", "derivation_latex", "show",
           "equation_latex", "equation_unicode", "tex_width", "display_width", "tag_width",
           "PAGE_WIDTH", "terminal_width", "math_latex",
           "text_unicode", "text_markdown", "check_markdown", "show_equation", "html_maths",
           "check_html", "LATEX_WIDTH", "MARK"]

MARK = {"verified": "✓", "FAILED": "✗", "not verified": "?", "derived": ""}

#: Width (em of MathJax's default font, :func:`tex_width`) of the body of a display
#: equation without a tag.
LATEX_WIDTH = 28.0
#: Width, in the same em, of the book's column: measured in Chromium on the built site
#: (Jupyter Book theme at 1280 px: a 688 px column, MathJax at 20.4 px per em; the
#: estimate is within 10 % for 80 % of the rows of the examples), less 1 em of margin.
#: MathJax centres a tagged display between two tag-wide margins, so the body of a
#: display tagged (1.26) may be ``PAGE_WIDTH - 2 * tag width`` wide.
PAGE_WIDTH = 32.5


def tag_width(label) -> float:
    """Estimated width, in em, of the tag ``(label)`` that MathJax sets at the margin."""
    return 0.55 * (len(str(label)) + 2) if label else 0.0


#: Columns of the terminal output when it is not a terminal.
DEFAULT_COLUMNS = 100


def terminal_width():
    """The terminal's width in columns, or 100 when the output is not a terminal."""
    import sys
    if sys.stdout is not None and hasattr(sys.stdout, "isatty") and sys.stdout.isatty():
        return max(40, shutil.get_terminal_size((DEFAULT_COLUMNS, 24)).columns)
    return DEFAULT_COLUMNS


# ----- width of LaTeX, in em ---------------------------------------------
_FUNCS = {"sin", "cos", "tan", "cot", "sec", "csc", "log", "ln", "exp", "sinh", "cosh",
          "tanh", "asin", "acos", "atan", "arcsin", "arccos", "arctan", "operatorname"}
_ZERO = {"left", "right", "displaystyle", "limits", "nonumber", "cr", "begin", "end",
         "mathrm", "mathit", "mathbf", "text", "textrm", "boldsymbol", "Big", "big",
         "bigg", "Bigg"}
_SPACE = {",": 0.17, ":": 0.22, ";": 0.28, " ": 0.25, "!": -0.17, "quad": 1.0, "qquad": 2.0}
_ACCENT = {"dot", "ddot", "tilde", "hat", "bar", "overline", "mathring", "vec", "widetilde"}


def _group(s, i):
    """The braced group (or single token) at s[i:]: (content, index after it)."""
    while i < len(s) and s[i] == " ":
        i += 1
    if i >= len(s):
        return "", i
    if s[i] == "{":
        depth, j = 0, i
        while j < len(s):
            if s[j] == "\\":
                j += 2
                continue
            depth += {"{": 1, "}": -1}.get(s[j], 0)
            if depth == 0:
                return s[i + 1:j], j + 1
            j += 1
        return s[i + 1:], len(s)
    if s[i] == "\\":
        m = re.match(r"\\([A-Za-z]+|.)", s[i:])
        return m.group(0), i + len(m.group(0))
    return s[i], i + 1


def tex_width(tex: str) -> float:
    """Estimated width, in em, of ``tex`` typeset by MathJax in display style.

    A box model: fractions are as wide as their wider part, scripts are 0.72 as
    wide as their text, operators carry their spacing; the tag is not counted.

    >>> tex_width(r"\\frac{a + b}{c}") == tex_width("a + b") + 0.3
    True
    """
    tex = re.sub(r"\\tag\*?\{[^}]*\}", "", tex)
    w, i, n = 0.0, 0, len(tex)
    while i < n:
        c = tex[i]
        if c == "\\":
            m = re.match(r"\\([A-Za-z]+|.)", tex[i:])
            name, i = m.group(1), i + len(m.group(0))
            if name in ("frac", "dfrac", "tfrac"):
                a, i = _group(tex, i)
                b, i = _group(tex, i)
                w += max(tex_width(a), tex_width(b)) + 0.3
            elif name == "sqrt":
                if i < n and tex[i] == "[":
                    j = tex.index("]", i)
                    w += 0.5 * tex_width(tex[i + 1:j])
                    i = j + 1
                a, i = _group(tex, i)
                w += tex_width(a) + 1.0
            elif name in ("left", "right"):
                d, i = _group(tex, i)
                w += 0.0 if d == "." else 0.7
            elif name in ("begin", "end", "tag"):
                _, i = _group(tex, i)
            elif name in ("text", "mathrm", "textrm", "operatorname"):
                a, i = _group(tex, i)
                w += 0.5 * len(re.sub(r"\\[A-Za-z]+|[{}]", "x", a))
            elif name in _ACCENT:
                a, i = _group(tex, i)
                w += tex_width(a)
            elif name in _SPACE:
                w += _SPACE[name]
            elif name in _FUNCS:
                w += 0.5 * len(name) + 0.17
            elif name in ("cdot", "times", "pm", "mp"):
                w += 1.22
            elif name in _ZERO:
                pass
            else:                               # Greek letters, \partial, ...
                w += 0.6
        elif c in "^_":
            a, i = _group(tex, i + 1)
            w += 0.72 * tex_width(a)
        elif c == "{":
            a, i = _group(tex, i)
            w += tex_width(a)
            continue
        else:
            i += 1
            if c in "+-":
                w += 1.22
            elif c in "=<>":
                w += 1.34
            elif c in "()[]|":
                w += 0.39
            elif c == ",":
                w += 0.45
            elif c == "'":
                w += 0.28
            elif c.isdigit() or c == ".":
                w += 0.5
            elif c.isalpha() or c in "*/!?":
                w += 0.55
            # spaces, &, } and the like take no room
    return w


def display_width(tex: str) -> float:
    r"""Estimated width, in em, of a display: :func:`tex_width`, and for an ``aligned``
    block its widest left part (before ``&``) plus its widest right part.

    >>> display_width(r"\begin{aligned}a &= b + c \cr &\quad {} + d\end{aligned}") > 0
    True
    """
    tex = re.sub(r"\\tag\*?\{[^}]*\}", "", tex)
    if r"\begin{aligned}" not in tex:
        return tex_width(tex)
    inner = tex[tex.index(r"\begin{aligned}") + 15:tex.rindex(r"\end{aligned}")]
    rows = inner.split(r"\cr")
    left = max(tex_width(r.split("&", 1)[0]) if "&" in r else 0.0 for r in rows)
    right = max(tex_width(r.split("&", 1)[1]) if "&" in r else tex_width(r) for r in rows)
    return left + right


# ----- splitting an equation into terms -----------------------------------
def _ordered_terms(expr):
    from sympy.printing.latex import LatexPrinter
    return LatexPrinter()._as_ordered_terms(expr)


def _signed(term):
    """(sign, |term|) with the sign the printer would show."""
    c, _ = term.as_coeff_Mul()
    if c.is_extended_negative or (c.is_Number and c < 0):
        return "-", -term
    return "+", term


def _inner(term):
    """For a term too wide to fit: (outside, sum) where term = outside * sum, or None.

    The widest sum among the factors (numerator first); a Derivative is split
    inside its argument.  ``outside`` is None for a Derivative (shown as d/dx).
    """
    if getattr(term, "is_total_derivative", False) and isinstance(term.args[0], sp.Add):
        return ("d", term.args[1]), term.args[0]
    if isinstance(term, sp.Derivative) and isinstance(term.expr, sp.Add) and \
            len(term.variables) == 1:
        return ("d", term.variables[0]), term.expr
    if not isinstance(term, sp.Mul):
        return None
    num, den = sp.fraction(term)
    if isinstance(num, sp.Add):
        return ("frac", 1 / den), num
    adds = [f for f in sp.Mul.make_args(num) if isinstance(f, sp.Add)]
    if not adds:
        return None
    big = max(adds, key=sp.count_ops)
    return ("mul", sp.Mul(*[f for f in sp.Mul.make_args(num) if f is not big]) / den), big


class _Layout:
    """Break ``lhs = rhs`` into rows of at most ``width`` units.

    A row is a list of items: ("term", sign, expr), ("open", sign, prefix),
    ("close",).  ``measure(items)`` gives the width of a row of items.
    """

    def __init__(self, measure, width):
        self.measure, self.width = measure, width
        self.tail = []      # what ends the last row ("= 0"): a term must fit with it

    def items(self, expr, sign, depth=0):
        """The items of a signed term, split inside when it is alone too wide."""
        whole = [("term", sign, expr)]
        # measured as it would stand: on a continuation row, before what ends the last row
        if depth >= 2 or self.measure([("cont",)] + whole + self.tail) <= self.width:
            return whole
        inner = _inner(expr)
        if inner is None:
            return whole
        outside, total = inner
        out = [("open", sign, outside)]
        for k, t in enumerate(_ordered_terms(total)):
            s, a = _signed(t)
            out += self.items(a, s if k or s == "-" else "", depth + 1)
        return out + [("close",)]

    def rows(self, first, items, last):
        """Pack items greedily into rows; ``first`` starts the first row, ``last`` ends
        the last one (it is counted in every trial, so the last row fits too)."""
        rows, row, filled = [], list(first), False
        for it in items:
            trial = row + [it]
            if filled and it[0] != "close" and self.measure(trial + list(last)) > self.width:
                rows.append(row)
                row, filled = [("cont",), it], True
            else:
                row, filled = trial, True
        rows.append(row + list(last))
        return rows


def _split_sides(e):
    """(lhs items source, rhs, 'lhs'|'rhs'): which side of an equation to break."""
    lhs, rhs = (e.lhs, e.rhs) if isinstance(e, sp.Equality) else (e, None)
    return lhs, rhs


def _terms_items(layout, expr):
    out = []
    for k, t in enumerate(_ordered_terms(expr) if isinstance(expr, sp.Add) else [expr]):
        s, a = _signed(t)
        out += layout.items(a, s if (k or s == "-") else "")
    return out


def _plan(e, layout):
    """The rows of an equation (or expression), as item lists."""
    lhs, rhs = _split_sides(e)
    if rhs is None:
        return layout.rows([], _terms_items(layout, lhs), [])
    if rhs == 0 or (layout.measure([("term", "", lhs)]) > layout.measure([("term", "", rhs)])
                    and not isinstance(lhs, (sp.Symbol, sp.Function))):
        layout.tail = [("eq", rhs)]
        return layout.rows([], _terms_items(layout, lhs), [("eq", rhs)])
    return layout.rows([("lhs", lhs)], _terms_items(layout, rhs), [])


# ----- LaTeX --------------------------------------------------------------
def _item_tex(it, tex):
    kind = it[0]
    if kind == "lhs":
        return tex(it[1]) + " &="
    if kind == "eq":
        return "= " + tex(it[1])
    if kind == "cont":
        return r"&\quad {}"
    if kind == "close":
        return r"\right)"
    op = {"-": "- ", "+": "+ ", "": ""}[it[1]]
    if kind == "term":
        return op + tex(it[2])
    o = it[2]                                           # open
    if o[0] == "d":
        pre = rf"\frac{{d}}{{d {tex(o[1])}}}"
    elif o[1] == 1:
        pre = ""
    else:
        pre = tex(o[1]) if not isinstance(o[1], sp.Add) else r"\left(" + tex(o[1]) + r"\right)"
        a, b = sp.symbols("A B")
        pre += tex(a * b)[1:-1]                     # the printer's multiplication sign
    return op + pre + r"\left("


def _row_tex(row, depth_in, tex):
    r"""One row of an aligned block; brackets left open at the end of a row close with
    ``\right.`` and reopen with ``\left.`` after the next row's ``&``."""
    parts, depth = [], depth_in
    for it in row:
        parts.append(_item_tex(it, tex))
        if it[0] == "cont":
            parts += [r"\left."] * depth_in
        depth += {"open": 1, "close": -1}.get(it[0], 0)
    parts += [r"\right."] * max(depth, 0)
    return " ".join(parts).replace(r"\left( ", r"\left("), depth


def _tex_rows(rows, tex=sp.latex):
    out, depth = [], 0
    for r in rows:
        text, depth = _row_tex(r, depth, tex)
        out.append(text)
    return out


_VARPHI = re.compile(r"\\phi(?![A-Za-z])")


def equation_latex(e, width=LATEX_WIDTH, **settings) -> str:
    """``e`` (an ``Eq`` or an expression) as LaTeX, broken at top-level + and - into an
    ``aligned`` block when wider than ``width`` em (:func:`tex_width`); ``settings`` go
    to ``sympy.latex`` (e.g. ``mul_symbol="dot"``).  SymPy's ``\\phi`` is set as
    ``\\varphi``: the φ of the Unicode output and of the book's prose."""
    def tex(x):
        return _VARPHI.sub(r"\\varphi", sp.latex(x, **settings))
    whole = tex(e)
    if tex_width(whole) <= width:
        return whole
    layout = _Layout(lambda items: tex_width(_tex_rows([items], tex)[0]), width)
    rows = _tex_rows(_plan(e, layout), tex)
    if len(rows) == 1:
        return whole
    if "&" not in rows[0]:
        rows[0] = "& " + rows[0]
    return r"\begin{aligned}" + r" \cr ".join(rows) + r"\end{aligned}"


# ----- Unicode ------------------------------------------------------------
def _pf(expr):
    from sympy.printing.pretty.pretty import PrettyPrinter
    return PrettyPrinter({"use_unicode": True, "wrap_line": False})._print(expr)


def _text_pf(text):
    from sympy.printing.pretty.stringpict import prettyForm
    return prettyForm(text)


def _row_pictures(row, depth_in):
    """The row as one prettyForm, with open brackets drawn to the row's height."""
    from sympy.printing.pretty.stringpict import prettyForm
    segs, stack = [[]], []    # segs[-1]: pictures at the current depth
    if depth_in:
        for _ in range(depth_in):
            segs.append([])
            stack.append(None)

    def add(p):
        segs[-1].append(p)

    for it in row:
        kind = it[0]
        if kind == "lhs":
            add(_pf(it[1]))
            add(_text_pf(" = "))
        elif kind == "eq":
            add(_text_pf(" = "))
            add(_pf(it[1]))
        elif kind == "cont":
            add(_text_pf("   "))
        elif kind == "close":
            if not stack:                   # opened on an earlier row
                segs.insert(0, [])
                stack.append(None)
            inner = _join(segs.pop())
            pre = stack.pop()
            pic = prettyForm(*inner.parens("(" if pre is not None else "", ")"))
            add(pre if pre is not None else _text_pf(""))
            add(pic)
        else:
            sign = it[1]
            op = {"-": " - ", "+": " + ", "": ""}[sign]
            if sign == "-" and not segs[-1]:
                op = "-"
            if op:
                add(_text_pf(op))
            if kind == "term":
                add(_pf(it[2]))
            else:
                o = it[2]
                if o[0] == "d":
                    pre = _pf(sp.Symbol(f"d/d{sp.pretty(o[1])}"))
                elif o[1] == 1:
                    pre = _text_pf("")
                else:
                    body = _pf(o[1])
                    if isinstance(o[1], sp.Add):
                        body = prettyForm(*body.parens())
                    pre = _join([body, _text_pf("⋅")])
                stack.append(pre)
                segs.append([])
    depth = len(stack)
    while stack:                          # unclosed at the end of the row
        inner = _join(segs.pop())
        pre = stack.pop()
        parts = [pre] if pre is not None else []
        parts.append(prettyForm(*inner.parens("(" if pre is not None else "", "")))
        segs[-1].extend(parts)
    pic = _join(segs[0])
    return pic, depth


def _join(pics):
    from sympy.printing.pretty.stringpict import prettyForm
    pics = [p for p in pics if p is not None]
    if not pics:
        return prettyForm("")
    out = pics[0]
    for p in pics[1:]:
        out = prettyForm(*out.right(p))
    return out


def _render(pic):
    return "\n".join(line.rstrip() for line in pic.render(wrap_line=False).splitlines())


def _uni_rows(rows):
    out, depth = [], 0
    for r in rows:
        pic, depth = _row_pictures(r, depth)
        out.append(pic)
    return out


def equation_unicode(e, width=None) -> str:
    """``e`` as SymPy's 2-D Unicode picture, every line at most ``width`` columns
    (default: :func:`terminal_width`): broken at top-level + and -, then inside the
    widest sum of a wide term, and as a last resort cut into column blocks."""
    width = width or terminal_width()
    whole = _render(_pf(e))
    if max(map(len, whole.splitlines() or [""])) <= width:
        return whole
    layout = _Layout(lambda items: _uni_rows([items])[0].width(), width)
    pics = _uni_rows(_plan(e, layout))
    blocks = []
    for p in pics:
        text = _render(p)
        if max(map(len, text.splitlines() or [""])) > width:
            text = _cut(text, width)
        blocks.append(text)
    return "\n".join(blocks)


def _cut(text, width):
    """Last resort: cut a picture into blocks of ``width`` columns, one under another."""
    lines = text.splitlines()
    n = max(map(len, lines))
    out = []
    for start in range(0, n, width - 1):
        block = [ln[start:start + width - 1].rstrip() for ln in lines]
        more = start + width - 1 < n
        block = [b + ("↩" if more and k == len(block) // 2 else "") for k, b in enumerate(block)]
        out.append("\n".join(b for b in block if b.strip()))
    return "\n".join(out)


# ----- captions: $...$ maths in text ---------------------------------------
_UNI = [(r"\varepsilon", "ε"), (r"\epsilon", "ε"), (r"\partial", "∂"), (r"\Omega", "Ω"),
        (r"\omega", "ω"), (r"\theta", "θ"), (r"\sigma", "σ"), (r"\beta", "β"), (r"\nu", "ν"),
        (r"\varphi", "φ"), (r"\phi", "φ"), (r"\alpha", "α"), (r"\mu", "μ"), (r"\times", "×"),
        (r"\psi", "ψ"), (r"\tau", "τ"), (r"\lambda", "λ"), (r"\delta", "δ"), (r"\gamma", "γ"),
        (r"\cdot", "⋅"), (r"\pm", "±"), (r"\sqrt", "√"), (r"\to", "→"), (r"\,", " "),
        (r"\quad", "  "), (r"\ne", "≠"), (r"\le", "≤"), (r"\ge", "≥"), (r"\sum", "Σ")]
_COMB = {"dot": "\u0307", "ddot": "\u0308", "tilde": "\u0303"}
_SUP = str.maketrans("0123456789+-*", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻*")


_FUNCTIONS = "sinh|cosh|tanh|sin|cos|tan|cot|sec|csc|exp|log|ln"


def _function_name(m):
    """``\\cos`` as `` cos``: apart from what stands before it, and from its argument
    unless that is a power or a parenthesis (C cos θ, cos²θ, sin(φ))."""
    name, after = m.group(1), m.group(2)
    return f" {name}" + ("" if after[:1] in ("^", "(", "") else " ")


def _tex_to_unicode(tex):
    s = re.sub(r"\\operatorname\{([^{}]*)\}\s*", r"\1 ", tex)
    s = re.sub(r"\\(mathrm|text)\{([^{}]*)\}", r"\2", s)
    s = re.sub(r"\\frac\{([^{}]*)\}\{([^{}]*)\}", r"\1/\2", s)
    s = re.sub(r"\\(" + _FUNCTIONS + r")(?![A-Za-z])\s*(?=(.?))", _function_name, s)
    s = re.sub(r"(_\\?[A-Za-z]+)(?=\\dot)", r"\1 ", s)     # q_ε q̇_ε: two symbols, apart
    for a, b in _UNI:           # a letter after a control word is part of another word
        s = re.sub(re.escape(a) + (r"(?![A-Za-z])" if a[-1].isalpha() else ""), b, s)
    for name, mark in _COMB.items():
        s = re.sub(r"\\" + name + r"\s*\{?(\w)\}?", lambda m: m.group(1) + mark, s)
    s = re.sub(r"\^\{?([0-9+\-*]+)\}?", lambda m: m.group(1).translate(_SUP), s)
    s = re.sub(r"\\(dots|ldots)(?![A-Za-z])", "…", s)
    s = re.sub(r"\\([A-Za-z]+)", r"\1", s)
    s = re.sub(r"_\{([(\[][^{}]*[)\]])\}", r"_\1", s)   # _{[1.26b]}: its own brackets
    s = re.sub(r"_\{([^{}]{2,})\}", r"_(\1)", s)
    s = re.sub(r"([∂√])\s+", r"\1", s)
    s = re.sub(r"([(\[]) +", r"\1", s)
    s = s.replace("{", "").replace("}", "").replace("\\", "").replace("  ", " ")
    return s.strip()


def text_unicode(text: str) -> str:
    """A caption with ``$...$`` maths, for the terminal: the maths as Unicode.

    >>> text_unicode(r"$\\partial\\Omega/\\partial\\dot q_\\varepsilon$ and $\\tilde L$")
    '∂Ω/∂q̇_ε and L̃'
    >>> text_unicode(r"$\\dot x\\tan\\theta = -C\\sin\\theta$, $F'(\\theta)\\,F$, $J\\cos^2\\theta$")
    "ẋ tan θ = -C sin θ, F'(θ) F, J cos²θ"
    >>> text_unicode(r"$\\Omega_{\\dot q_\\varepsilon\\dot q_\\varepsilon}$")
    'Ω_(q̇_ε q̇_ε)'
    """
    return re.sub(r"\$([^$]+)\$", lambda m: _tex_to_unicode(m.group(1)), text)


def text_markdown(text: str) -> str:
    """A caption with ``$...$`` maths, for a notebook's Markdown: the maths is kept for
    MathJax, and Markdown's emphasis characters outside it are escaped."""
    parts = re.split(r"(\$[^$]+\$)", text)
    return "".join(p if p.startswith("$") else re.sub(r"([*_`])", r"\\\1", p) for p in parts)


# ----- steps --------------------------------------------------------------
def step_unicode(step, width=None) -> str:
    """The step as text: its label and title, its equations, its check, at most
    ``width`` columns (default :func:`terminal_width`) wide."""
    width = width or terminal_width()
    lines = textwrap.wrap(f"{text_unicode(step.shown_label)} {text_unicode(step.title)}", width,
                          subsequent_indent="    ")
    for e in step.equations:     # an equation, or a str: a line of text between them
        shown = text_unicode(e) if isinstance(e, str) else equation_unicode(e, width - 4)
        lines.append(textwrap.indent(shown, "    "))
    if step.check is not None:
        lines += textwrap.wrap(f"{MARK[step.status]} {step.check.describe()}", width,
                               initial_indent="    ", subsequent_indent="      ")
    if step.note:
        lines += textwrap.wrap("note: " + text_unicode(step.note), width,
                               initial_indent="    ", subsequent_indent="    ")
    return "\n".join(lines)


def _shown(label):
    return label if label[:1] in "[(" else shown_label(label)


def _tag(label):
    """``\\tag{1.16}`` for the paper's numbers, ``\\tag*{[1.26b]}`` for the book's own
    labels (see :mod:`.labels`); a label already in brackets is set as it is."""
    if is_paper_number(label):
        return rf"\tag{{{label}}}"
    return rf"\tag*{{{_shown(label)}}}"


def math_latex(equations, label=None, width=LATEX_WIDTH) -> str:
    """Equations (``Eq`` or expressions) as one LaTeX display body: a single equation
    broken to ``width`` em (at most ``PAGE_WIDTH`` less two tag widths), several in an
    ``aligned`` block, one ``\\tag`` for all.  A ``str`` among them is a line of text
    (``$...$`` maths allowed) set between the equations.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> print(math_latex([sp.Eq(x, 1), "and, cleared:", sp.Eq(x - 1, 0)], "1.26b"))
    \\begin{aligned}&x = 1 \\cr &\\text{and, cleared:} \\cr &x - 1 = 0\\end{aligned} \\tag*{[1.26b]}
    """
    width = min(width, PAGE_WIDTH - 2 * tag_width(label))
    body = [r"\text{" + e + "}" if isinstance(e, str) else equation_latex(e, width)
            for e in equations]
    # align at "=" only when every left side is short: a long one (or a broken
    # equation, aligned at its own "&") would widen the left column of every row
    at_equals = all(isinstance(e, sp.Equality) and tex_width(sp.latex(e.lhs)) <= 8
                    for e in equations)
    rows = []
    for b in body:
        if b.startswith(r"\begin{aligned}"):
            rows.append(b[len(r"\begin{aligned}"):-len(r"\end{aligned}")])
        elif len(body) > 1:
            rows.append(b.replace("=", "&=", 1) if at_equals else "&" + b)
        else:
            rows.append(b)
    if len(rows) == 1 and not body[0].startswith(r"\begin{aligned}"):
        inner = rows[0]
    else:
        inner = r"\begin{aligned}" + r" \cr ".join(rows) + r"\end{aligned}"
    return inner + (" " + _tag(label) if label else "")


def step_latex(step) -> str:
    """The step's equations as one LaTeX display, tagged with the paper's number."""
    return math_latex(step.equations, step.tag or step.label)


def _check_line(step):
    return f"{MARK[step.status]} {step.check.describe()}" if step.check else ""


def derivation_unicode(derivation, width=None) -> str:
    width = width or terminal_width()
    title = text_unicode(derivation.title)
    head = "\n".join(textwrap.wrap(title, width))
    head += "\n" + "=" * min(width, len(title))
    return "\n\n".join([head] + [step_unicode(s, width) for s in derivation.steps])


def derivation_latex(derivation, width=None) -> str:
    """Every step as a LaTeX ``equation``, one row of a broken equation per line, with the
    title and the check as comments wrapped at ``width`` columns (default the terminal's)."""
    width = width or terminal_width()

    def comment(text):
        return "\n".join(textwrap.wrap(text, width, initial_indent="% ",
                                        subsequent_indent="%   "))
    out = [comment(derivation.title)]
    for s in derivation.steps:
        out.append(comment(f"{s.shown_label} {s.title}"))
        if s.equations:
            body = step_latex(s).replace(r" \cr ", " \\cr\n    ")
            out.append(r"\begin{equation}" + body + r"\end{equation}")
        if s.check:
            out.append(comment(_check_line(s)))
    return "\n".join(out)


def check_markdown(check) -> str:
    """``check.describe()`` for a notebook: the claim's maths typeset by MathJax."""
    from dataclasses import replace
    mark = "\x00CLAIM\x00"
    return replace(check, claim=mark).describe().replace(mark, text_markdown(check.claim))


def show_equation(e, label=None, lhs=None):
    """Show one equation (or expression; with ``lhs``, ``lhs = e``) as the steps are shown:
    in a notebook a MathJax display broken to fit the column (tag ``label`` if given), in
    a terminal Unicode at its width.  For a chapter's own displays, e.g.
    ``show_equation(red.L_star, "1.16", lhs=sp.Symbol("L^*"))``."""
    if lhs is not None:
        e = sp.Eq(lhs, e, evaluate=False)
    if _in_notebook():
        from IPython.display import Math, display
        display(Math(math_latex([e], label)))
        return None
    text = equation_unicode(e)
    print(f"{_shown(label)}\n" + textwrap.indent(text, "    ") if label else text)
    return None


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


def html_maths(text: str) -> str:
    """Text with ``$...$`` maths as HTML: the maths in ``span.math`` with ``\\(...\\)``, as
    Sphinx writes inline maths (MathJax typesets it on the site and in JupyterLab), the
    rest escaped.  (A Markdown output would not do: myst-nb renders it as CommonMark,
    without dollar maths, and curls the primes.)

    >>> print(html_maths("the form of $L^*$ & more"))
    the form of <span class="math notranslate nohighlight">\\(L^*\\)</span> &amp; more
    """
    from html import escape
    out = []
    for p in re.split(r"(\$[^$]+\$)", text):
        if len(p) > 1 and p.startswith("$") and p.endswith("$"):
            out.append(rf'<span class="math notranslate nohighlight">\({escape(p[1:-1])}\)</span>')
        else:
            out.append(escape(p))
    return "".join(out)


def check_html(check) -> str:
    """``check.describe()`` as HTML, the claim's maths typeset."""
    from dataclasses import replace
    from html import escape
    mark = "\x00CLAIM\x00"
    return escape(replace(check, claim=mark).describe()).replace(mark, html_maths(check.claim))


def _caption(s):
    """The caption of a step for a notebook: HTML (typeset maths), Markdown and text."""
    lab = s.shown_label
    html = [f"<strong>{html_maths(lab)}</strong> {html_maths(s.title)}"]
    md = [f"**{text_markdown(lab)}** {text_markdown(s.title)}"]
    text = [f"{text_unicode(lab)} {text_unicode(s.title)}"]
    if s.check:
        html.append(f"{MARK[s.status]} {check_html(s.check)}")
        md.append(f"{MARK[s.status]} {check_markdown(s.check)}")
        text.append(f"{MARK[s.status]} {s.check.describe()}")
    if s.note:
        html.append(f"<em>{html_maths(s.note)}</em>")
        md.append(f"*{text_markdown(s.note)}*")
        text.append(text_unicode(s.note))
    return {"text/html": '<div class="wt-step">' + "<br>".join(html) + "</div>",
            "text/markdown": "  \n".join(md), "text/plain": "\n".join(text)}


def show(derivation, latex=False):
    """Show every step: rendered maths in a notebook, Unicode (or LaTeX) in a terminal."""
    if _in_notebook():
        from IPython.display import Math, display
        t = derivation.title
        display({"text/html": f"<strong>{html_maths(t)}</strong>",
                 "text/markdown": f"**{text_markdown(t)}**",
                 "text/plain": text_unicode(t)}, raw=True)
        for s in derivation.steps:
            display(_caption(s), raw=True)
            if s.equations:
                display(Math(step_latex(s)))
        return None
    print(derivation.to_latex() if latex else derivation.to_unicode())
    return None
