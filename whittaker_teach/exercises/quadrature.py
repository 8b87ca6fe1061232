"""Unevaluated integrals and sums in a numeric answer, evaluated at a bounded cost.

``sp.integrate`` returns an unevaluated ``Integral`` when it finds no
antiderivative; a student who passes it (or types ``Integral(...)``) to a
part whose answer is a number gets it evaluated here: Gauss-Legendre
quadrature of mpmath (``mpmath.quad``) with a fixed maximal degree, so that
the number of evaluations of the integrand is bounded (a few hundred), each
evaluation guarded as in :mod:`.compare` (no value beyond 1e300); a finite
``Sum`` of at most ``MAX_SUM_TERMS`` terms is added term by term.

>>> import sympy as sp
>>> s = sp.Symbol("s")
>>> float(numeric_value(sp.Integral(sp.cos(s), (s, 0, sp.pi / 2))))
1.0
>>> round(float(numeric_value(sp.Sum(1 / s**2, (s, 1, 100)) + 1)), 12)
2.634983900185
"""

from __future__ import annotations

import mpmath
import sympy as sp

from .compare import _Fn
from .parsing import MAX_SUM_TERMS, AnswerError

__all__ = ["numeric_value", "QUAD_DEGREE"]

QUAD_DEGREE = 6          # mpmath.quad's maxdegree: at most ~ 3 * 2**7 evaluations per interval
MAX_WORK = 200_000       # evaluations x nodes of the integrand or summand (no timer in Pyodide)
QUAD_EVALUATIONS = 400   # about what QUAD_DEGREE allows


def _bounded_work(f, evaluations):
    nodes = sum(1 for _ in zip(range(MAX_WORK + 1), sp.preorder_traversal(f)))
    if nodes * evaluations > MAX_WORK:
        raise AnswerError("the integral or sum of your answer is too costly to evaluate "
                          "(a long integrand, or many terms): give its value")


def _number(e):
    fn = _Fn(e, [])
    value = fn({})
    if value is None:
        raise AnswerError(f"the limit {sp.sstr(e)[:30]} of an integral or sum is not a finite "
                          "number")
    return value


def _integral(node):
    (s, a, b), = node.limits if len(node.limits) == 1 else (None,)
    if s is None or a is None or b is None:
        raise AnswerError("an integral of the answer needs one variable with both limits, "
                          "Integral(f, (s, a, b))")
    extra = node.function.free_symbols - {s}
    if extra or a.free_symbols or b.free_symbols:
        raise AnswerError("an integral in a numeric answer may contain no symbol but its "
                          "variable")
    lo, hi = _number(a), _number(b)
    if mpmath.im(lo) or mpmath.im(hi) or not (mpmath.isfinite(lo) and mpmath.isfinite(hi)):
        raise AnswerError("the limits of an integral must be finite real numbers")
    _bounded_work(node.function, QUAD_EVALUATIONS)
    fn = _Fn(node.function, [s])

    def f(t):
        v = fn({s: t})
        if v is None:
            raise ValueError("undefined")
        return v
    with mpmath.workdps(20):
        try:
            value, err = mpmath.quad(f, [mpmath.re(lo), mpmath.re(hi)], maxdegree=QUAD_DEGREE,
                                     error=True)
        except (ValueError, ZeroDivisionError, OverflowError, TypeError):
            raise AnswerError("the integrand of your integral is undefined or too large "
                              "somewhere between its limits") from None
    if err > 1e-9 * max(1, abs(value)):
        raise AnswerError("the integral of your answer cannot be evaluated accurately enough "
                          "(a singular or oscillating integrand?): give its value")
    return sp.Float(mpmath.nstr(mpmath.re(value), 18)) + \
        sp.I * sp.Float(mpmath.nstr(mpmath.im(value), 18))


def _sum(node):
    (n, a, b), = node.limits if len(node.limits) == 1 else (None,)
    if not (a is not None and b is not None and a.is_Integer and b.is_Integer):
        raise AnswerError("a sum in a numeric answer needs integer limits, Sum(f, (n, 1, 10))")
    if b - a + 1 > MAX_SUM_TERMS:
        raise AnswerError(f"the answer contains a sum of more than {MAX_SUM_TERMS} terms; "
                          "give its value")
    if node.function.free_symbols - {n}:
        raise AnswerError("a sum in a numeric answer may contain no symbol but its index")
    _bounded_work(node.function, int(b - a + 1))
    fn = _Fn(node.function, [n])
    total = mpmath.mpf(0)
    with mpmath.workdps(20):
        for k in range(int(a), int(b) + 1):
            v = fn({n: mpmath.mpf(k)})
            if v is None:
                raise AnswerError(f"the term {k} of your sum is undefined or too large")
            total += v
    return sp.Float(mpmath.nstr(mpmath.re(total), 18)) + \
        sp.I * sp.Float(mpmath.nstr(mpmath.im(total), 18))


def numeric_value(expr):
    """expr with every Integral and Sum replaced by its value (bounded cost)."""
    sub = {}
    for node in expr.atoms(sp.Integral, sp.Sum):
        if node.function.has(sp.Integral, sp.Sum):
            raise AnswerError("an integral or sum inside another one: evaluate the inner one")
        sub[node] = _integral(node) if isinstance(node, sp.Integral) else _sum(node)
    return expr.xreplace(sub) if sub else expr
