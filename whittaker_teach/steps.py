"""Steps of a derivation: the paper's label, the equations, the check.

A :class:`Step` is a record: the number of the equation in Mei (1983), a
short title, the equations it shows (SymPy ``Eq`` objects, in the paper's
notation: q' for dq/dq_eps, qdot for velocities) and, where the paper claims
an identity, the :class:`~whittaker_teach.verify.Check` that verified it.
A :class:`Derivation` is the ordered list of steps of one system.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from .labels import shown_label
from .verify import Check

__all__ = ["Step", "Derivation", "Report", "eq", "notation", "partial"]


@dataclass(frozen=True)
class Step:
    """One numbered step of the paper, for the system at hand.

    ``equations`` may be given as a list or as a function returning one: the
    readable form of a long result (a targeted rewrite) is then computed only
    when the step is shown, not when it is derived or verified.

    >>> import sympy as sp
    >>> v, u, th = sp.symbols("v u theta")
    >>> s = Step("3.2", "the constraint", [sp.Eq(v, u*sp.tan(th))])
    >>> print(s.to_unicode())
    (3.2) the constraint
        v = u⋅tan(θ)
    """

    label: str
    title: str
    shown: object = field(default_factory=list, repr=False)
    check: Check | None = None
    note: str = ""
    tag: str = ""

    @property
    def shown_label(self) -> str:
        """The label as printed: ``(1.16)`` for one of the paper's equations, in square
        brackets for the book's own forms (``[1.26b]``); ``tag``, when given, instead.

        >>> Step("1.4a", "accelerations").shown_label
        '[1.4a]'
        """
        return self.tag or shown_label(self.label)

    @property
    def equations(self) -> list:
        """The equations of the step (SymPy ``Eq``), in the paper's notation."""
        if callable(self.shown):
            object.__setattr__(self, "shown", list(self.shown()))
        return self.shown

    @property
    def status(self) -> str:
        """``"verified"``, ``"FAILED"``, ``"not verified"`` or ``"derived"`` (no claim to check)."""
        return self.check.status if self.check else "derived"

    def to_unicode(self) -> str:
        from .render import step_unicode
        return step_unicode(self)

    def to_latex(self) -> str:
        from .render import step_latex
        return step_latex(self)

    def _repr_latex_(self):
        return "$$" + self.to_latex() + "$$"

    def __str__(self):
        return self.to_unicode()


#: cell styles of the check table: the label, residual and verdict never break; the claim
#: and "how" columns wrap between words (a formula is never broken)
_TD = {0: ' style="white-space:nowrap"', 1: ' style="min-width:14em"',
       3: ' style="white-space:nowrap"', 4: ' style="white-space:nowrap"'}


class Report(list):
    """The checks of a derivation, re-run: a list of :class:`Check`.

    ``report.ok`` is True when every check held; ``str(report)`` says, for
    each, how it was shown.
    """

    @property
    def ok(self) -> bool:
        return all(c.holds for c in self)

    @property
    def failed(self) -> list:
        return [c for c in self if c.holds is not True]

    def summary(self) -> str:
        """One sentence: how many checks held, how, and the largest residual."""
        n_exact = sum(c.method == "exact" for c in self)
        n_num = sum(c.method == "numeric" for c in self)
        worst = max((c.max_residual for c in self if c.method == "numeric"), default=0.0)
        return (f"{len(self)} checks: {len(self) - len(self.failed)} held "
                f"({n_exact} exactly, {n_num} numerically, largest residual {worst:.1e}); "
                f"{len(self.failed)} did not")

    def to_text(self, width=None) -> str:
        """Every check on its own line(s), wrapped at ``width`` columns (default: the
        terminal's width, 100 when not a terminal), then the summary."""
        import textwrap
        from .render import terminal_width, text_unicode
        width = width or terminal_width()
        lines = []
        for c in self:
            lines += textwrap.wrap(text_unicode(c.describe()), width, subsequent_indent="    ")
        lines += textwrap.wrap(self.summary(), width, subsequent_indent="    ")
        return "\n".join(lines)

    def __str__(self):
        return self.to_text()

    def _repr_html_(self):
        """A table (equation, claim, how, largest residual, held), folded under the summary
        line (open when a check did not hold); its text wraps between words, and in a
        column narrower than its formulas it scrolls sideways."""
        from html import escape

        from .render import html_maths
        rows = []
        for c in self:
            how = {"exact": f"exactly ({c.detail})",
                   "numeric": f"at {c.points} points, {c.detail}"}.get(c.method, c.detail)
            res = f"{c.max_residual:.1e}" if c.method in ("numeric", "refutation") else "0"
            cells = [escape(shown_label(c.label)), html_maths(c.claim), escape(how), res,
                     {True: "yes", False: "NO", None: "not verified"}[c.holds]]
            rows.append("<tr>" + "".join(f"<td{_TD.get(i, '')}>{v}</td>"
                                         for i, v in enumerate(cells)) + "</tr>")
        head = "".join(f"<th>{h}</th>" for h in ("eq.", "claim", "how", "residual", "held"))
        # folded under its one-line summary; open when a check did not hold
        return (f'<details class="wt-report"{"" if self.ok else " open"}>'
                f"<summary>{escape(self.summary())}</summary>"
                '<table class="wt-report" style="table-layout:auto;width:100%">'
                f"<thead><tr>{head}</tr></thead>"
                "<tbody>" + "".join(rows) + "</tbody></table></details>")


class Derivation:
    """An ordered list of steps with rendering and re-verification."""

    def __init__(self, title, steps, checks=None):
        self.title = title
        self.steps = list(steps)
        self._checks = checks  # callables re-running the checks, by label

    def __iter__(self):
        return iter(self.steps)

    def __len__(self):
        return len(self.steps)

    def __getitem__(self, label):
        """The step with a paper label, e.g. ``derivation["1.16"]``."""
        for s in self.steps:
            if s.label == label:
                return s
        raise KeyError(f"no step labelled ({label}) in {self.title}")

    @property
    def labels(self):
        return [s.label for s in self.steps]

    def only(self, *labels, exact=False):
        """The steps with these paper labels, in order, as a smaller Derivation; a label
        also selects its sub-labels ("1.26" selects (1.26a) and (1.26b), "3.10" selects
        (3.10 OCR)), unless ``exact=True``: then only the steps labelled exactly so.

        >>> import whittaker_teach as wt
        >>> wt.examples.sledge().reduce("x").steps.only("1.16", "1.23").labels
        ['1.16', '1.23']
        >>> wt.examples.sledge().reduce("x").steps.only("1.26").labels
        ['1.26', '1.26a', '1.26b']
        >>> wt.examples.sledge().reduce("x").steps.only("1.26", exact=True).labels
        ['1.26']
        """
        def wanted(label):
            if exact:
                return label in labels
            base = label.split(" ")[0]
            return (label in labels or base in labels
                    or (base[-1:].isalpha() and base[:-1] in labels))
        return Derivation(self.title, [s for s in self.steps if wanted(s.label)])

    def show(self, latex=False):
        from .render import show
        return show(self, latex=latex)

    def to_unicode(self):
        from .render import derivation_unicode
        return derivation_unicode(self)

    def to_latex(self):
        from .render import derivation_latex
        return derivation_latex(self)

    def __repr__(self):
        return f"<Derivation {self.title!r}: {len(self.steps)} steps>"


class Notation(sp.Symbol):
    """A symbol that stands for a notation of the paper (dOmega/dq', L*, ...).

    It prints as written: Unicode in a terminal, LaTeX in the book.

    >>> n = notation("L*", "L^{*}")
    >>> print(n, sp.latex(n))
    L* L^{*}
    """

    def _latex(self, printer):
        return _TEX.get(self.name, self.name)

    def _pretty(self, printer):
        from sympy.printing.pretty.stringpict import prettyForm
        return prettyForm(self.name)


_TEX = {}


def notation(text, tex):
    """A :class:`Notation` printed as ``text`` (Unicode) and ``tex`` (LaTeX)."""
    _TEX[text] = tex
    return Notation(text)


_PRINTED = {}


def tex(x):
    """``sp.latex(x)`` of a symbol, remembered: a derivation names the same symbols in
    many steps (the printer costs some 10 microseconds a call).

    >>> print(tex(sp.Symbol("theta_1")))
    \\theta_{1}
    """
    r = _PRINTED.get(("tex", x))
    if r is None:
        if len(_PRINTED) > 10_000:
            _PRINTED.clear()
        r = _PRINTED["tex", x] = sp.latex(x)
    return r


def text(x, use_unicode=None):
    """``sp.pretty(x, use_unicode=...)`` of a symbol, remembered (by the Unicode setting
    in force, where none is given)."""
    from sympy.printing.pretty.pretty_symbology import pretty_use_unicode
    flag = pretty_use_unicode() if use_unicode is None else use_unicode
    r = _PRINTED.get(("text", x, flag))
    if r is None:
        r = _PRINTED["text", x, flag] = sp.pretty(x, use_unicode=flag)
    return r


def partial(f, f_tex, z, w=None):
    """The notation d f / d z (or d^2 f / dz dw, or d^2 f / dz^2 with w = z), to show a
    step in the paper's form for the coordinates at hand."""
    zt, zl = text(z, use_unicode=True), tex(z)
    if w is None:
        return notation(f"∂{f}/∂{zt}", rf"\frac{{\partial {f_tex}}}{{\partial {zl}}}")
    if w == z:
        return notation(f"∂²{f}/∂{zt}²", rf"\frac{{\partial^2 {f_tex}}}{{\partial {zl}^2}}")
    wt, wl = text(w, use_unicode=True), tex(w)
    return notation(f"∂²{f}/∂{zt}∂{wt}",
                    rf"\frac{{\partial^2 {f_tex}}}{{\partial {zl}\,\partial {wl}}}")


def eq(lhs, rhs):
    """An equation for display, ``Eq(lhs, rhs)`` left unevaluated (SymPy would otherwise
    spend time deciding whether the two sides are equal; the checks do that)."""
    return sp.Eq(lhs, rhs, evaluate=False)
