"""Reading an answer: safe, bounded parsing of strings, and one notation for every form.

A student may answer with a SymPy expression (built by hand, or taken from
the library, e.g. ``red.L_star`` with ``theta(x)`` and
``Derivative(theta(x), x)``), with a number of any common kind (Python,
``fractions``, SymPy, numpy and mpmath scalars), or with a string such as
``"sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)"``.

Strings are never evaluated as Python.  SymPy's tokenizer turns the text
into code (names become ``Symbol('...')``, numbers ``Integer``/``Float``),
Python's :mod:`ast` parses that code, and :class:`_Builder` walks the tree,
building the expression node by node: only arithmetic, the maths functions
of ``ALLOWED_FUNCTIONS`` and coordinates such as ``theta(x)`` are accepted,
and the limits of :mod:`.limits` (digits of integers and Floats, size of
powers, order of derivatives, nesting depth, size) are enforced *before*
each node is built, so that ``Pow(9, 387420489)`` or
``diff(sin(theta), theta, 100000000)`` are refused at once.  Every answer is
then rewritten in plain symbols: ``theta(x)`` -> ``theta``,
``Derivative(theta(x), x)`` -> ``thetaprime``, ``Derivative(x(t), t)`` ->
``xdot``; ``theta'`` in a string is ``thetaprime``.

>>> read_answer("sqrt(2*h - k^2*theta^2)")
sqrt(2*h - k**2*theta**2)
>>> read_answer("J*theta'^2")
J*thetaprime**2
>>> for text in ["__import__('os')", "exec('1')", "(a + b", "9^9^9"]:
...     try:
...         read_answer(text)
...     except AnswerError as err:
...         print(str(err)[:94] + ("..." if len(str(err)) > 94 else ""))
the answer contains '__', which is not allowed in a formula
the answer calls exec(...): calls of functions other than the maths functions (sqrt, exp, ...
the parenthesis opened at position 1 is never closed
the answer contains a power 9**387420489 too large to evaluate (a number beyond 1e300)
>>> import numpy as np
>>> read_answer(np.int64(7)), read_answer(np.float64(0.5))
(7, 0.500000000000000)
"""

from __future__ import annotations

import ast
import keyword
import math
import numbers
import re

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.core.relational import Relational
from sympy.logic.boolalg import Boolean
from sympy.parsing.sympy_parser import auto_number, auto_symbol, convert_xor, stringify_expr

from .notation import to_ascii
from .limits import (MAX_DEPTH, MAX_DERIVATIVE_ORDER, MAX_DIGITS, MAX_EXPONENT,
                     MAX_FLOAT_DIGITS, MAX_LENGTH, MAX_MAGNITUDE, MAX_NODES, TooExpensive)

__all__ = ["AnswerError", "Context", "read_answer", "plain_symbols", "describe", "article",
           "ALLOWED_FUNCTIONS"]

ALLOWED_FUNCTIONS = {
    "sqrt": sp.sqrt, "cbrt": sp.cbrt, "exp": sp.exp, "log": sp.log, "ln": sp.log,
    "sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sec": sp.sec, "csc": sp.csc, "cot": sp.cot,
    "asin": sp.asin, "acos": sp.acos, "atan": sp.atan, "atan2": sp.atan2,
    "arcsin": sp.asin, "arccos": sp.acos, "arctan": sp.atan,
    "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
    "Abs": sp.Abs, "abs": sp.Abs, "sign": sp.sign,
    "Rational": sp.Rational, "Derivative": sp.Derivative, "diff": sp.diff,
    "Integral": sp.Integral, "Sum": sp.Sum,
}
CONSTANTS = {"pi": sp.pi, "E": sp.E, "I": sp.I}
MAX_INTEGRALS = 3            # Integral/Sum nodes in one answer (each evaluated by quadrature)
MAX_SUM_TERMS = 10000        # terms of a finite Sum


class Context:
    """What an exercise declares: its symbols (name -> Symbol, with assumptions and
    aliases), the names that are functions (coordinates, as in ``theta(x)``), and
    symbols defined by the statement (name -> expression, e.g. omega = k/sqrt(J))."""

    def __init__(self, symbols=None, functions=(), definitions=None):
        self.symbols = dict(symbols or {})
        self.functions = set(functions)
        self.definitions = dict(definitions or {})

    def symbol(self, name):
        if name in self.definitions:
            return self.definitions[name]
        return self.symbols.get(name) or sp.Symbol(name)

# the names the tokenizer's own code refers to, each checked by _Builder
_GLOBALS = {"Symbol": sp.Symbol, "Function": sp.Function, "Integer": sp.Integer,
            "Float": sp.Float}
_LOCALS = {**ALLOWED_FUNCTIONS, **CONSTANTS}
_TRANSFORMATIONS = (auto_symbol, auto_number, convert_xor)

_GREEK = {"θ": "theta", "φ": "phi", "ϕ": "phi", "α": "alpha", "β": "beta", "μ": "mu",
          "ω": "omega", "ε": "epsilon", "ψ": "psi", "ρ": "rho", "σ": "sigma", "τ": "tau",
          "ν": "nu", "λ": "lambda_", "κ": "kappa", "γ": "gamma", "δ": "delta"}

_SOME_FUNCTIONS = "sqrt, exp, log, sin, cos, tan, ..."


class AnswerError(ValueError):
    """The answer cannot be read as a formula; the message says what was expected."""


def article(word):
    """'an int64', 'a float': the indefinite article for a word.

    >>> article("int64"), article("float"), article("Ellipsis")
    ('an int64', 'a float', 'an Ellipsis')
    """
    return ("an " if word[:1].lower() in "aeiou" else "a ") + word


def describe(value):
    """A short description of any value, never its memory address.

    >>> describe(object())
    'an object'
    >>> describe(3.5)
    'a float 3.5'
    """
    name = type(value).__name__
    if isinstance(value, (numbers.Number, str)) and not isinstance(value, bool):
        text = repr(value) if not isinstance(value, int) or value.bit_length() < 200 else \
            f"of {len(str(abs(value))) if value.bit_length() < 10000 else 'many'} digits"
        if " at 0x" not in text:
            return f"{article(name)} {text[:40]}{'...' if len(text) > 40 else ''}"
    return article(name)


# ---------------------------------------------------------------- strings
def _balance(text):
    """Unbalanced parentheses, in plain words (positions counted from 1)."""
    stack = []
    for i, c in enumerate(text, 1):
        if c == "(":
            stack.append(i)
            if len(stack) > MAX_DEPTH:
                raise AnswerError(f"the answer is nested more than {MAX_DEPTH} levels deep; "
                                  "simplify it")
        elif c == ")":
            if not stack:
                raise AnswerError(f"the parenthesis closed at position {i} was never opened")
            stack.pop()
    if stack:
        raise AnswerError(f"the parenthesis opened at position {stack[-1]} is never closed")


def _calls(text, context=None):
    """Refuse calls of anything but the maths functions and coordinates such as theta(x).

    (With a context, other names followed by '(' were made products by the notation.)
    """
    for m in re.finditer(r"([^\W\d]\w*)\s*\(", text):
        name = m.group(1)
        if name in ALLOWED_FUNCTIONS:
            continue
        depth, j = 1, m.end()
        while j < len(text) and depth:
            depth += {"(": 1, ")": -1}.get(text[j], 0)
            j += 1
        inside = text[m.end():j - 1].strip()
        if not re.fullmatch(r"[^\W\d]\w*", inside) or name in _GLOBALS or name in CONSTANTS:
            raise AnswerError(f"the answer calls {name}(...): calls of functions other than the "
                              f"maths functions ({_SOME_FUNCTIONS}) are not allowed; a "
                              "coordinate may be written theta(x)")


def _check_string(text, max_length, context=None):
    if len(text) > max_length:
        raise AnswerError(f"the answer is {len(text)} characters long; a formula of at most "
                          f"{max_length} characters is expected")
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
        shown = " ".join(repr(c) for c in bad[:8])
        raise AnswerError(f"the answer contains {shown}, which cannot appear in a formula here "
                          "(use + - * / ^ ** ( ) and names)")
    _balance(text)
    _calls(text, context)


def _primes(text):
    """theta'' -> thetaprimeprime, theta' -> thetaprime."""
    def repl(m):
        return m.group(1) + "prime" * len(m.group(2))
    out = re.sub(r"([^\W\d]\w*)('+)", repl, text)
    if "'" in out:
        pos = text.index("'", max(0, len(text) - len(out))) + 1 if "'" in text else 0
        raise AnswerError(f"a prime ' must follow a name, as in theta' (d theta / dx); "
                          f"the one at position {pos} does not")
    return out


def _syntax(text):
    """A plain-words reason why text is not a formula (after the checks above)."""
    m = re.search(r"(?<![\w.])\d+(\.\d*)?\s*(?![eE][+-]?\d)[^\W\d]", text)
    if m:
        return (f"a number is followed by a name at position {m.start() + 1} ({m.group(0)!r}): "
                "write products with *, as in 2*x")
    m = re.search(r"[+\-*/^]\s*[*/^]", text)
    if m and m.group(0).replace(" ", "") not in ("**",):
        return f"two operators in a row at position {m.start() + 1} ({m.group(0)!r})"
    m = re.search(r"[+\-*/^]\s*$", text)
    if m:
        return f"the formula ends with the operator {m.group(0).strip()!r}"
    m = re.search(r"\(\s*\)", text)
    if m:
        return f"empty parentheses at position {m.start() + 1}"
    m = re.search(r"[\w)]\s+[\w(]", text)
    if m:
        return (f"two terms side by side at position {m.start() + 1} ({m.group(0)!r}): "
                "write products with *")
    return "write products with *, powers with ** or ^, e.g. '2*m*g*y'"


_INVERSE_LOOKALIKE = re.compile(
    r"\b(a?(?:sin|cos|tan|sec|csc|cot)h?)\s*(?:\^|\*\*)\s*\(?\s*[-\u2212]\s*1\b"
    r"|\b(a?(?:sin|cos|tan|sec|csc|cot)h?)\u207b\u00b9")


def _inverse_lookalike(text):
    """``sin^-1(x)`` is read by some as arcsin, by others as 1/sin: refuse it."""
    m = _INVERSE_LOOKALIKE.search(text)
    if m:
        f = m.group(1) or m.group(2)
        raise AnswerError(f"{f}^-1 is ambiguous: write a{f}(x) for the inverse function, or "
                          f"1/{f}(x) for the reciprocal")


_TOKEN = re.compile(r"(?P<num>\d+(?:\.\d*)?(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?)"
                    r"|(?P<name>[^\W\d]\w*)|(?P<open>\()|(?P<close>\))|(?P<space>\s+)"
                    r"|(?P<other>.)")


def implicit_products(text, functions=None):
    """``text`` with ``*`` put where two operands stand side by side, and whether any was.

    Only where the reading is unambiguous: a number before a name or a bracket
    (``2h``, ``2(x+1)``), a closing bracket before a name, a number or a bracket
    (``(a+b)c``), two names apart (``C cos(theta)``, ``J theta'``), a name before
    a bracket that is not a call (a maths function or a coordinate ``functions``
    is called; without ``functions``, any name before a bracket is).  Two numbers
    apart (``2 3``) are left as they are: an error.

    >>> implicit_products("2h - k^2 theta^2")
    ('2*h - k^2*theta^2', True)
    >>> implicit_products("C cos(theta) + (a+b)(a-b) + 2(x) + sqrt (2)", functions=())
    ('C*cos(theta) + (a+b)*(a-b) + 2*(x) + sqrt (2)', True)
    >>> implicit_products("theta(x) + 2e5 + v0*g_0", functions={"theta"})
    ('theta(x) + 2e5 + v0*g_0', False)
    """
    out, prev, changed = [], None, False       # prev: the kind of the last operand token
    for m in _TOKEN.finditer(text):
        kind, tok = m.lastgroup, m.group()
        if kind == "space":
            out.append(tok)
            continue
        starts = kind in ("num", "name", "open")
        if starts and prev is not None:
            p_kind, p_tok = prev
            call = kind == "open" and p_kind == "name" and (
                functions is None or p_tok in ALLOWED_FUNCTIONS or p_tok in functions
                or p_tok in _GLOBALS)
            if not call and not (p_kind == "num" and kind == "num"):
                while out and out[-1].isspace():
                    out.pop()
                out.append("*")
                changed = True
        out.append(tok)
        prev = (kind, tok) if kind in ("num", "name", "close") else None
    return "".join(out), changed


def parse_string(text, max_length=MAX_LENGTH, context=None):
    """Parse a formula string safely, without evaluating it; AnswerError says what is wrong.

    ``context`` (:class:`Context`): the exercise's symbols, functions and definitions;
    without it every ``name(symbol)`` is read as a coordinate.
    """
    if len(text) > max_length:
        raise AnswerError(f"the answer is {len(text)} characters long; a formula of at most "
                          f"{max_length} characters is expected")
    if not text.isascii():
        _balance(text)        # positions in the text as typed, before it is rewritten
        if re.search(r"√(?![\s(\w.])|√\s*$", text):
            raise AnswerError("√ must be followed by a bracket, a name or a number, as in "
                              "√(2*h) or √J")
    _inverse_lookalike(text)
    text = to_ascii(text, None if context is None else context.functions)
    _inverse_lookalike(text)
    _check_string(text, 4 * max_length, context)
    text = _primes(text)
    text, _ = implicit_products(text, None if context is None else context.functions)
    try:
        code = stringify_expr(text, dict(_LOCALS), dict(_GLOBALS), _TRANSFORMATIONS)
        tree = ast.parse(code, mode="eval")
    except (SyntaxError, ValueError, TypeError, MemoryError, RecursionError, Exception):
        # not TooExpensive: a BaseException
        shown = text if len(text) <= 30 else text[:27] + "..."
        raise AnswerError(f"could not read {shown!r} as a formula: {_syntax(text)}") \
            from None
    try:
        return _Builder(context).build(tree.body)
    except (OverflowError, ValueError) as exc:
        if isinstance(exc, AnswerError):
            raise
        raise _too_large("a number") from None


def _too_large(what):
    return AnswerError(f"the answer contains {what} too large to evaluate (a number beyond "
                       "1e300)")


class _Builder:
    """Build a SymPy expression from the parsed tree, refusing what is too costly."""

    def __init__(self, context=None):
        self.nodes = 0
        self.integrals = 0
        self.context = context

    def build(self, node, depth=0):
        self.nodes += 1
        if depth > MAX_DEPTH:
            raise AnswerError(f"the answer is nested more than {MAX_DEPTH} levels deep; "
                              "simplify it")
        if self.nodes > MAX_NODES:
            raise TooExpensive()
        if isinstance(node, ast.BinOp):
            return self._binop(node, depth)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            arg = self.build(node.operand, depth + 1)
            return -arg if isinstance(node.op, ast.USub) else arg
        if isinstance(node, ast.Name):
            if node.id in CONSTANTS:
                return CONSTANTS[node.id]
            if node.id in ALLOWED_FUNCTIONS:
                raise AnswerError(f"{node.id} is a function: write {node.id}(...) with its "
                                  "argument")
            raise AnswerError(f"the name {node.id} cannot be used here")
        if isinstance(node, ast.Call):
            return self._call(node, depth)
        if isinstance(node, (ast.Tuple, ast.List, ast.Set, ast.Dict)):
            raise AnswerError(f"the answer is a {type(node).__name__.lower()} of several "
                              "items; one expression is expected (check one part at a time)")
        raise AnswerError("the answer is not a formula (only + - * / ** and the maths functions "
                          "are allowed)")

    def _chain(self, node, depth, ops):
        """The operands of a left-nested chain a + b - c + ... (or a*b/c...), signed."""
        items = []
        while isinstance(node, ast.BinOp) and isinstance(node.op, ops):
            items.append((node.op, node.right))
            node = node.left
            self.nodes += 1
            if self.nodes > MAX_NODES:
                raise TooExpensive()
        items.append((None, node))
        return [(op, self.build(n, depth + 1)) for op, n in reversed(items)]

    def _binop(self, node, depth):
        if isinstance(node.op, (ast.Add, ast.Sub)):     # one Add for the whole chain: linear
            terms = self._chain(node, depth, (ast.Add, ast.Sub))
            return _bounded_number(sp.Add(*[-t if isinstance(op, ast.Sub) else t
                                            for op, t in terms]))
        if isinstance(node.op, (ast.Mult, ast.Div)):
            factors = self._chain(node, depth, (ast.Mult, ast.Div))
            if any(isinstance(op, ast.Div) and f.is_zero for op, f in factors):
                raise AnswerError("the answer divides by zero")
            return _bounded_number(sp.Mul(*[1 / f if isinstance(op, ast.Div) else f
                                            for op, f in factors]))
        a = self.build(node.left, depth + 1)
        b = self.build(node.right, depth + 1)
        op = node.op
        if isinstance(op, ast.Add):
            return a + b
        if isinstance(op, ast.Sub):
            return a - b
        if isinstance(op, ast.Mult):
            out = a * b
        elif isinstance(op, ast.Div):
            if b.is_zero:
                raise AnswerError("the answer divides by zero")
            out = a / b
        elif isinstance(op, ast.Pow):
            out = power(a, b)
        else:
            raise AnswerError("only + - * / and ** (or ^) are allowed between terms")
        return _bounded_number(out)

    def _call(self, node, depth):
        func = node.func
        if node.keywords:
            raise AnswerError("keyword arguments (name=value) are not allowed in a formula")
        if isinstance(func, ast.Call):             # Function('theta')(Symbol('x'))
            f = self._call(func, depth + 1)
            args = [self.build(a, depth + 1) for a in node.args]
            if not isinstance(f, sp.FunctionClass):
                raise AnswerError("a number or a bracket is followed by '(': write products "
                                  "with *, as in 2*(x + 1)")
            if not (len(args) == 1 and args[0].is_Symbol):
                raise AnswerError("a coordinate function takes one symbol, as in theta(x)")
            if self.context is not None and f.__name__ not in self.context.functions:
                return self.context.symbol(f.__name__) * args[0]
            return f(args[0])
        if not isinstance(func, ast.Name):
            raise AnswerError("only the maths functions may be called")
        name = func.id
        if name in ("Symbol", "Function", "Float", "Integer"):
            return self._atom(name, node)
        if name not in ALLOWED_FUNCTIONS:
            raise AnswerError(f"the answer calls {name}(...): calls of functions other than the "
                              f"maths functions ({_SOME_FUNCTIONS}) are not allowed")
        if name in ("Derivative", "diff"):       # Derivative(f, (x, 2)) as SymPy prints it
            args = [tuple(self.build(b, depth + 2) for b in a.elts)
                    if isinstance(a, ast.Tuple) and len(a.elts) == 2 else self.build(a, depth + 1)
                    for a in node.args]
            return _derivative(name, args)
        if name in ("Integral", "Sum"):
            return self._integral(name, node, depth)
        args = [self.build(a, depth + 1) for a in node.args]
        if name == "Rational":
            if len(args) != 2 or not all(a.is_Integer for a in args) or args[1] == 0:
                raise AnswerError("Rational(p, q) takes two integers, q not 0")
            return sp.Rational(*args)
        try:
            return _bounded_number(ALLOWED_FUNCTIONS[name](*args))
        except TypeError:
            wanted = "two arguments" if name == "atan2" else "one argument"
            raise AnswerError(f"{name} takes {wanted}, not {len(args)}") from None

    def _integral(self, name, node, depth):
        """Integral(f, (s, a, b)) / Sum(f, (n, a, b)), left unevaluated (numbers only)."""
        self.integrals += 1
        if self.integrals > MAX_INTEGRALS:
            raise AnswerError(f"the answer contains more than {MAX_INTEGRALS} integrals or sums")
        if len(node.args) != 2 or not (isinstance(node.args[1], ast.Tuple)
                                       and len(node.args[1].elts) == 3):
            raise AnswerError(f"{name}(f, (s, a, b)) takes an expression and a tuple "
                              "(variable, lower limit, upper limit)")
        f = self.build(node.args[0], depth + 1)
        s, a, b = (self.build(e, depth + 2) for e in node.args[1].elts)
        if not s.is_Symbol:
            raise AnswerError(f"{name}(f, (s, a, b)): s must be a name")
        if f.has(sp.Integral, sp.Sum):
            raise AnswerError(f"the answer contains an {name} inside an integral or a sum; "
                              "evaluate the inner one first")
        return (sp.Integral if name == "Integral" else sp.Sum)(f, (s, a, b))

    def _atom(self, name, node):
        (arg,) = node.args if len(node.args) == 1 else (None,)
        value = arg.value if isinstance(arg, ast.Constant) else None
        if name in ("Symbol", "Function") and isinstance(value, str):
            if name == "Symbol":
                return self.context.symbol(value) if self.context else sp.Symbol(value)
            return sp.Function(value)
        if name == "Integer" and isinstance(value, int):
            return integer(value)
        if name == "Float" and isinstance(value, str):
            return float_from_text(value)
        raise AnswerError(f"the answer calls {name}(...): calls of functions other than the "
                          f"maths functions ({_SOME_FUNCTIONS}) are not allowed")


def integer(n):
    """An int as a SymPy Integer, refusing more than MAX_DIGITS digits."""
    if abs(n) >= 10**MAX_DIGITS:
        raise AnswerError(f"the answer contains an integer of more than {MAX_DIGITS} digits")
    return sp.Integer(n)


def float_from_text(text):
    """A decimal number (as text) as a SymPy Float of at most MAX_FLOAT_DIGITS digits."""
    mantissa = re.split(r"[eE]", text)[0]
    digits = len(re.sub(r"\D", "", mantissa).lstrip("0"))
    if digits > MAX_FLOAT_DIGITS:
        raise AnswerError(f"the answer contains a number with {digits} digits; at most "
                          f"{MAX_FLOAT_DIGITS} significant digits are used")
    try:
        value = float(text)
    except (ValueError, OverflowError):
        value = math.inf
    if not math.isfinite(value) or abs(value) > MAX_MAGNITUDE:
        raise AnswerError("the answer contains a number larger than 1e300")
    return sp.Float(text, max(15, digits))


def power(a, b):
    """a**b, refusing exponents beyond MAX_EXPONENT and numbers beyond 1e300 before building."""
    if b.is_Number and abs(b) > MAX_EXPONENT:
        if a.is_Number and a in (0, 1, -1):
            return a ** b
        raise _too_large(f"a power {_short(a)}**{_short(b)}") if a.is_Number else \
            AnswerError(f"the answer contains a power with the exponent {_short(b)}; "
                        f"exponents up to {MAX_EXPONENT} are accepted")
    if a.is_Number and a.is_zero and b.is_Number and b.is_negative:
        raise AnswerError("the answer divides by zero (0 to a negative power)")
    if a.is_Number and b.is_Number and not a.is_zero:
        size = float(b) * math.log10(abs(float(a))) if abs(a) < 10**300 else math.inf
        if size > 300:
            raise _too_large(f"a power {_short(a)}**{_short(b)}")
    return a ** b


def _short(e):
    text = sp.sstr(e) if sp.count_ops(e) < 20 else "(...)"
    return text if len(text) <= 20 else text[:17] + "..."


def _bounded_number(e):
    if e.is_Number and e.is_finite and e != 0:
        if e.is_Rational and (abs(e.p).bit_length() > 1000 or e.q.bit_length() > 1000):
            raise _too_large("a number")
        if abs(e) > MAX_MAGNITUDE:
            raise _too_large("a number")
    return e


def _derivative(name, args):
    """Derivative(f, x[, n]) / diff(f, x, ...), of order at most MAX_DERIVATIVE_ORDER."""
    if len(args) < 2 or isinstance(args[0], tuple):
        raise AnswerError(f"{name}(f, x) takes an expression and a variable")
    f, rest = args[0], args[1:]
    spec, order = [], 0
    for a in rest:
        if isinstance(a, tuple):
            s, n = a
            if not (s.is_Symbol and n.is_Integer and n > 0):
                raise AnswerError(f"{name}(f, (x, n)): x must be a symbol and n a positive "
                                  "integer")
            order += int(min(n, 10**6))
            spec.append([s, int(min(n, 10**6))])
        elif a.is_Symbol:
            spec.append([a, 1])
            order += 1
        elif a.is_Integer and spec and a > 0:
            order += int(min(a, 10**6)) - 1
            spec[-1][1] = int(min(a, 10**6))
        else:
            raise AnswerError(f"{name}(f, x, n): the variables must be symbols and n a positive "
                              "integer")
        if order > MAX_DERIVATIVE_ORDER:
            raise AnswerError(f"the answer contains a derivative of order above "
                              f"{MAX_DERIVATIVE_ORDER}; only first and second derivatives "
                              "are expected")
    flat = [tuple(s) for s in spec]
    if name == "diff" and not f.has(AppliedUndef):
        return sp.diff(f, *flat)
    return sp.Derivative(f, *flat)


# ---------------------------------------------------------------- objects
def read_number(answer):
    """A number of any common kind (int, float, Fraction, Decimal, numpy, mpmath) as SymPy.

    >>> from fractions import Fraction
    >>> read_number(Fraction(1, 3)), read_number(2**10)
    (1/3, 1024)
    """
    kind = type(answer).__module__.split(".")[0]
    if kind == "numpy" and hasattr(answer, "item") and getattr(answer, "ndim", 0) == 0:
        answer = answer.item()
    elif kind == "mpmath":
        import mpmath
        if isinstance(answer, mpmath.mpc):
            answer = complex(answer)
        else:
            answer = mpmath.nstr(answer, MAX_FLOAT_DIGITS) if mpmath.isfinite(answer) else \
                float(answer)
            return number_from_text_or_float(answer)
    if isinstance(answer, bool):
        raise AnswerError(f"the answer is {answer}, a truth value; a formula is expected")
    if isinstance(answer, numbers.Integral):
        return integer(int(answer))
    if isinstance(answer, numbers.Rational):
        return sp.Rational(integer(int(answer.numerator)), integer(int(answer.denominator)))
    if isinstance(answer, numbers.Real):
        return number_from_text_or_float(answer)
    if isinstance(answer, numbers.Complex):
        z = complex(answer)
        return number_from_text_or_float(z.real) + sp.I * number_from_text_or_float(z.imag)
    if isinstance(answer, numbers.Number):          # decimal.Decimal
        return number_from_text_or_float(str(answer))
    return None


def number_from_text_or_float(x):
    """A float, Decimal or numeral text as a SymPy Float (finite, at most 1e300)."""
    try:
        value = float(x)
    except (OverflowError, ValueError):
        value = math.inf
    if math.isnan(value):
        raise AnswerError("the answer is not a number (nan)")
    if not math.isfinite(value):
        raise AnswerError("the answer is infinite; a finite number is expected")
    text = str(x)
    return float_from_text(text) if re.fullmatch(r"[+-]?[\d.]+([eE][+-]?\d+)?", text) else \
        sp.Float(value)


def _bounded_tree(expr):
    """Refuse a SymPy object too costly to handle, before anything is evaluated."""
    count = 0
    stack = [(expr, 0)]
    while stack:
        e, depth = stack.pop()
        count += 1
        if count > MAX_NODES or depth > 4 * MAX_DEPTH:
            raise TooExpensive()
        if isinstance(e, sp.Integer) and e.p.bit_length() > 1000:
            raise _too_large("a number")
        if isinstance(e, sp.Rational) and (e.p.bit_length() > 1000 or e.q.bit_length() > 1000):
            raise _too_large("a number")
        if isinstance(e, sp.Float):
            if e._prec > 4 * MAX_FLOAT_DIGITS:
                raise AnswerError(f"the answer contains a Float with about {int(e._prec * 0.30103)}"
                                  f" digits; at most {MAX_FLOAT_DIGITS} digits are used")
            if e.is_finite and e != 0 and not abs(e._mpf_[2] + e._mpf_[3]) < 1000:
                raise _too_large("a number")
        if isinstance(e, sp.Derivative):
            if sum(int(min(c, 10**6)) if c.is_Integer else 10**6
                   for _, c in e.variable_count) > MAX_DERIVATIVE_ORDER:
                raise AnswerError(f"the answer contains a derivative of order above "
                                  f"{MAX_DERIVATIVE_ORDER}; only first and second derivatives "
                                  "are expected")
        if isinstance(e, sp.Pow) and e.exp.is_Number and abs(e.exp) > MAX_EXPONENT \
                and not e.base.is_Number:
            raise AnswerError(f"the answer contains a power with an exponent beyond "
                              f"{MAX_EXPONENT}")
        stack.extend((a, depth + 1) for a in e.args)


def read_answer(answer, max_length=MAX_LENGTH, context=None):
    """An answer (expression, number or string) as a SymPy expression in plain symbols.

    Raises :class:`AnswerError` with a message saying what was expected, or
    :class:`~whittaker_teach.exercises.limits.TooExpensive`.
    """
    if isinstance(answer, str):
        expr = parse_string(answer, max_length, context)
    elif isinstance(answer, sp.Basic):
        _bounded_tree(answer)
        expr = answer
    else:
        expr = read_number(answer)
        if expr is None:
            _refuse_object(answer)
    if isinstance(expr, sp.Equality):
        raise AnswerError("the answer is an equation (Eq); give only the expression: for "
                          "Eq(lhs, rhs), the right-hand side rhs (or lhs - rhs where the "
                          "exercise asks for an expression that vanishes)")
    if isinstance(expr, Relational) or (isinstance(expr, Boolean)
                                        and not isinstance(expr, sp.Expr)):
        raise AnswerError(f"the answer is a relation or truth value ({type(expr).__name__}); "
                          "a formula is expected")
    if isinstance(expr, sp.MatrixBase) or not isinstance(expr, sp.Expr):
        raise AnswerError(f"the answer is {article(type(expr).__name__)}; one expression is "
                          "expected")
    if expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
        raise AnswerError("the answer contains infinity or an undefined value (a division "
                          "by zero?)")
    return plain_symbols(expr)


def _refuse_object(answer):
    if isinstance(answer, (list, tuple, set, frozenset)):
        raise AnswerError(f"the answer is {article(type(answer).__name__)} of {len(answer)} "
                          "items; one expression is expected (check one part at a time)")
    if isinstance(answer, dict):
        raise AnswerError("the answer is a dict; one expression is expected (for a dict such "
                          "as red.accelerations(), take its value: list(d.values())[0])")
    if type(answer).__module__.split(".")[0] == "numpy" and hasattr(answer, "shape"):
        raise AnswerError(f"the answer is a numpy array of shape {tuple(answer.shape)}; one "
                          "number is expected (take one element)")
    raise AnswerError(f"the answer is {describe(answer)}; a SymPy expression, a number or a "
                      "string such as 'sqrt(2*h)' is expected")


def plain_symbols(expr):
    """Rewrite functions of one variable and their derivatives as plain symbols."""
    if expr.has(sp.Derivative):
        try:
            expr = expr.replace(
                lambda e: isinstance(e, sp.Derivative) and not isinstance(e.expr, AppliedUndef),
                lambda e: e.doit())
        except TooExpensive:
            raise
        except Exception:  # noqa: BLE001 - an odd derivative is reported below
            pass
    subs = {}
    for d in sorted(expr.atoms(sp.Derivative), key=sp.default_sort_key):
        f = d.expr
        if not (isinstance(f, AppliedUndef) and len(f.args) == 1 and f.args[0].is_Symbol):
            raise AnswerError(f"the answer contains the derivative {_short(d)}, which is not "
                              "the derivative of a coordinate such as Derivative(theta(x), x): "
                              "evaluate it first (.doit())")
        var = f.args[0]
        n = sum(int(c) for v, c in d.variable_count if v == var)
        if any(v != var for v, _ in d.variable_count) or n > 2:
            raise AnswerError(f"the answer contains {_short(d)}: only first and second "
                              "derivatives of a coordinate are expected")
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
            raise AnswerError(f"the answer contains {_short(f)}, an unknown function: use the "
                              "names of the exercise, such as theta or theta(x)")
    expr = expr.xreplace(subs) if subs else expr
    return expr
