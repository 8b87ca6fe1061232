"""Reading an answer: safe parsing of strings, and one notation for every form.

A student may answer with a SymPy expression (built by hand, or taken from
the library, e.g. ``red.L_star`` with ``theta(x)`` and
``Derivative(theta(x), x)``) or with a string such as
``"sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)"``.

Strings are parsed by SymPy's ``parse_expr`` with no builtins, a short list
of allowed functions, no attribute access (``.`` before a letter), no
dunder names, a length limit and a bound on the size of numbers, so that no
arbitrary code runs.  Every answer is then rewritten in plain symbols:
``theta(x)`` -> ``theta``, ``Derivative(theta(x), x)`` -> ``thetaprime``,
``Derivative(x(t), t)`` -> ``xdot``; ``theta'`` in a string is
``thetaprime``.

>>> read_answer("sqrt(2*h - k^2*theta^2)")
sqrt(2*h - k**2*theta**2)
>>> read_answer("J*theta'^2")
J*thetaprime**2
>>> try:
...     read_answer("__import__('os')")
... except AnswerError as err:
...     print(err)
the answer contains '__', which is not allowed in a formula
"""

from __future__ import annotations

import keyword
import re

import mpmath
import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.core.relational import Relational
from sympy.logic.boolalg import Boolean
from sympy.parsing.sympy_parser import auto_number, auto_symbol, convert_xor, parse_expr

__all__ = ["AnswerError", "read_answer", "plain_symbols", "ALLOWED_FUNCTIONS"]

MAX_LENGTH = 2000

ALLOWED_FUNCTIONS = {
    "sqrt": sp.sqrt, "cbrt": sp.cbrt, "exp": sp.exp, "log": sp.log, "ln": sp.log,
    "sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sec": sp.sec, "csc": sp.csc, "cot": sp.cot,
    "asin": sp.asin, "acos": sp.acos, "atan": sp.atan, "atan2": sp.atan2,
    "arcsin": sp.asin, "arccos": sp.acos, "arctan": sp.atan,
    "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
    "Abs": sp.Abs, "abs": sp.Abs, "sign": sp.sign, "pi": sp.pi,
    "Rational": sp.Rational, "Derivative": sp.Derivative, "diff": sp.diff,
}

# what the parser's own transformations refer to, and nothing else
_GLOBALS = {"__builtins__": {}, "Symbol": sp.Symbol, "Function": sp.Function,
            "Integer": sp.Integer, "Float": sp.Float, "Rational": sp.Rational,
            "Add": sp.Add, "Mul": sp.Mul, "Pow": sp.Pow}

_TRANSFORMATIONS = (auto_symbol, auto_number, convert_xor)

_GREEK = {"θ": "theta", "φ": "phi", "ϕ": "phi", "α": "alpha", "β": "beta", "μ": "mu",
          "ω": "omega", "ε": "epsilon", "ψ": "psi", "ρ": "rho", "σ": "sigma", "τ": "tau",
          "ν": "nu", "λ": "lambda_", "κ": "kappa", "γ": "gamma", "δ": "delta"}


class AnswerError(ValueError):
    """The answer cannot be read as a formula; the message says what was expected."""


def _check_string(text):
    if len(text) > MAX_LENGTH:
        raise AnswerError(f"the answer is {len(text)} characters long; a formula of at most "
                          f"{MAX_LENGTH} characters is expected")
    if not text.strip():
        raise AnswerError("the answer is an empty string; write a formula such as "
                          "'sqrt(2*h - k^2*theta^2)'")
    if "__" in text:
        raise AnswerError("the answer contains '__', which is not allowed in a formula")
    if re.search(r"\.\s*[^\W\d]", text):
        raise AnswerError("the answer contains '.' before a name (attribute access), which is "
                          "not allowed in a formula; write numbers as 0.5, functions as sin(x)")
    if re.search(r"(?<![<>=!])=(?!=)", text) or "==" in text:
        raise AnswerError("the answer is an equation; give only the expression (the right-hand "
                          "side), e.g. 'sqrt(2*h)' instead of 'xdot = sqrt(2*h)'")
    word = re.search(r"\b(" + "|".join(keyword.kwlist) + r")\b", text)
    if word:
        raise AnswerError(f"the answer contains the Python keyword {word.group(1)!r}; a formula "
                          "is expected")
    bad = sorted({c for c in text if not (c.isalnum() or c == "_" or c.isspace()
                                          or c in "+-*/^().,'")})
    if bad:
        raise AnswerError(f"the answer contains {' '.join(repr(c) for c in bad)}, which cannot "
                          "appear in a formula here (use + - * / ^ ** ( ) and names)")


def _primes(text):
    """theta'' -> thetaprimeprime, theta' -> thetaprime."""
    def repl(m):
        return m.group(1) + "prime" * len(m.group(2))
    out = re.sub(r"([^\W\d]\w*)('+)", repl, text)
    if "'" in out:
        raise AnswerError("a prime ' must follow a name, as in theta' (d theta / dx)")
    return out


def _size_check(expr):
    """Refuse numbers too large to handle (9**9**9) before SymPy evaluates them."""
    def value(e):
        if e.free_symbols:
            for a in e.args:
                value(a)
            return None
        if isinstance(e, sp.Integer):
            if abs(int(e)) > 10**30:
                raise AnswerError("the answer contains a number larger than 1e30")
            return mpmath.mpf(int(e))
        if isinstance(e, (sp.Rational, sp.Float)):
            return mpmath.mpf(float(e))
        if isinstance(e, (sp.Add, sp.Mul, sp.Pow)):
            vals = [value(a) for a in e.args]
            if any(v is None for v in vals):
                if isinstance(e, sp.Pow) and vals[1] is not None and abs(vals[1]) > 1000:
                    raise AnswerError("the answer contains a power with an exponent larger "
                                      "than 1000")
                return None
            if isinstance(e, sp.Pow) and abs(vals[1]) > 1000:
                raise AnswerError("the answer contains a power with an exponent larger than "
                                  "1000")
            try:
                if isinstance(e, sp.Add):
                    v = mpmath.fsum(vals)
                elif isinstance(e, sp.Mul):
                    v = mpmath.fprod(vals)
                else:
                    v = mpmath.power(vals[0], vals[1]) if vals[0] else mpmath.mpf(0)
            except (ZeroDivisionError, ValueError, OverflowError):
                return None
            if abs(v) > mpmath.mpf(10) ** 300:
                raise AnswerError("the answer contains a number larger than 1e300")
            return v
        for a in e.args:
            value(a)
        return None

    with mpmath.workdps(15):
        value(expr)
    for p in expr.atoms(sp.Pow):
        ex = p.exp
        if ex.is_Number and abs(float(ex)) > 1000:
            raise AnswerError("the answer contains a power with an exponent larger than 1000")


def _rebuild(e):
    """Evaluate an expression parsed with evaluate=False."""
    if not e.args or isinstance(e, (sp.Symbol, sp.Number)):
        return e
    return e.func(*[_rebuild(a) for a in e.args])


def parse_string(text):
    """Parse a formula string safely; AnswerError says what is wrong with it."""
    _check_string(text)
    for g, name in _GREEK.items():
        text = text.replace(g, name)
    text = _primes(text)
    try:
        with mpmath.workdps(15):
            expr = parse_expr(text, local_dict=dict(ALLOWED_FUNCTIONS), global_dict=dict(_GLOBALS),
                              transformations=_TRANSFORMATIONS, evaluate=False)
    except AnswerError:
        raise
    except SyntaxError:
        raise AnswerError(f"could not read {text!r} as a formula (write products with *, "
                          "powers with ** or ^, e.g. '2*m*g*y')") from None
    except Exception as exc:  # the parser can raise nearly anything on odd input
        raise AnswerError(f"could not read {text!r} as a formula ({type(exc).__name__})") \
            from None
    if not isinstance(expr, sp.Basic):
        raise AnswerError(f"could not read {text!r} as one formula (it reads as a "
                          f"{type(expr).__name__})")
    _size_check(expr)
    try:
        return _rebuild(expr)
    except Exception as exc:
        raise AnswerError(f"could not read {text!r} as a formula ({type(exc).__name__}: "
                          f"{exc})") from None


def _describe(value):
    if value is None:
        return "None"
    text = repr(value)
    return f"{type(value).__name__} {text[:40]}{'...' if len(text) > 40 else ''}"


def read_answer(answer):
    """An answer (expression, number or string) as a SymPy expression in plain symbols.

    Raises :class:`AnswerError` with a message saying what was expected.
    """
    if isinstance(answer, bool):
        raise AnswerError(f"the answer is {answer}, a truth value; a formula is expected")
    if isinstance(answer, str):
        expr = parse_string(answer)
    elif isinstance(answer, (int, float)) and not isinstance(answer, bool):
        expr = sp.sympify(answer)
    elif isinstance(answer, sp.Basic):
        expr = answer
    elif isinstance(answer, (list, tuple, set, frozenset)):
        raise AnswerError(f"the answer is a {type(answer).__name__} of {len(answer)} items; "
                          "one expression is expected (check one part at a time)")
    elif isinstance(answer, dict):
        raise AnswerError("the answer is a dict; one expression is expected (for a dict such "
                          "as red.accelerations(), take its value: list(d.values())[0])")
    else:
        raise AnswerError(f"the answer is a {_describe(answer)}; a SymPy expression or a "
                          "string such as 'sqrt(2*h)' is expected")
    if isinstance(expr, sp.Equality):
        raise AnswerError("the answer is an equation (Eq); give only the expression: for "
                          "Eq(lhs, rhs), the right-hand side rhs (or lhs - rhs where the "
                          "exercise asks for an expression that vanishes)")
    if isinstance(expr, Relational) or (isinstance(expr, Boolean)
                                        and not isinstance(expr, sp.Expr)):
        raise AnswerError(f"the answer is a relation or truth value ({type(expr).__name__}); "
                          "a formula is expected")
    if isinstance(expr, sp.MatrixBase) or not isinstance(expr, sp.Expr):
        raise AnswerError(f"the answer is a {type(expr).__name__}; one expression is expected")
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        raise AnswerError("the answer contains infinity or an undefined value (a division "
                          "by zero?)")
    if any(abs(n) > 10**300 for n in expr.atoms(sp.Number)):
        raise AnswerError("the answer contains a number larger than 1e300")
    return plain_symbols(expr)


def plain_symbols(expr):
    """Rewrite functions of one variable and their derivatives as plain symbols."""
    if expr.has(sp.Derivative):
        try:
            expr = expr.replace(
                lambda e: isinstance(e, sp.Derivative) and not isinstance(e.expr, AppliedUndef),
                lambda e: e.doit())
        except Exception:  # noqa: BLE001 - an odd derivative is reported below
            pass
    subs = {}
    for d in sorted(expr.atoms(sp.Derivative), key=sp.default_sort_key):
        f = d.expr
        if not (isinstance(f, AppliedUndef) and len(f.args) == 1 and f.args[0].is_Symbol):
            raise AnswerError(f"the answer contains the derivative {d}, which is not the "
                              "derivative of a coordinate such as Derivative(theta(x), x): "
                              "evaluate it first (.doit())")
        var = f.args[0]
        n = sum(c for v, c in d.variable_count if v == var)
        if any(v != var for v, _ in d.variable_count) or n > 2:
            raise AnswerError(f"the answer contains {d}: only first and second derivatives "
                              "of a coordinate are expected")
        name = f.func.__name__
        if var.name == "t":
            suffix = "dot" if n == 1 else "ddot"
        else:
            suffix = "prime" * n
        subs[d] = sp.Symbol(name + suffix)
    expr = expr.xreplace(subs) if subs else expr
    subs = {}
    for f in expr.atoms(AppliedUndef):
        if len(f.args) == 1 and f.args[0].is_Symbol:
            subs[f] = sp.Symbol(f.func.__name__)
        else:
            raise AnswerError(f"the answer contains {f}, an unknown function: use the names "
                              "of the exercise, such as theta or theta(x)")
    expr = expr.xreplace(subs) if subs else expr
    return expr
