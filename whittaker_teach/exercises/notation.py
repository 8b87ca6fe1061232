"""The notations a student types or copies: Unicode of the rendered statements, keyboard forms.

:func:`to_ascii` rewrites a typed answer into the plain notation that
:mod:`.parsing` reads, one character at a time (linear in the length, so
it adds no cost that the length limit does not already bound):

* the Unicode the statements show when rendered: ``−`` (minus), ``·``
  ``⋅`` ``×`` (times), ``÷``, ``’`` ``′`` (prime), ``″`` (two primes),
  superscripts ``²`` ``³`` ``⁻¹``, subscripts ``g₀`` -> ``g_0``, ``√``,
  ``π``, Greek letters (``θ`` -> ``theta``), dots over a letter (``θ̇``,
  ``ẋ`` -> ``thetadot``, ``xdot``; two dots -> ``ddot``);
* keyboard forms of powers of functions: ``sec^2(x)``, ``sin**2 x`` ->
  ``(sec(x))^2``, ``(sin(x))^2``;
* a name followed by ``(`` that is neither a maths function nor one of the
  exercise's coordinates (its declared functions) is a product:
  ``J(theta')^2`` -> ``J*(theta')^2``.

>>> to_ascii("√(2*h − k²θ²)·√(m*sec²θ + J*θ′²)")
"sqrt(2*h - k^(2)*theta^(2))*sqrt(m*(sec(theta))^(2) + J*theta'^(2))"
>>> to_ascii("ẋ·tan θ"), to_ascii("θ̇"), to_ascii("g₀*x²/2"), to_ascii("2π"), to_ascii("kθ")
('xdot*tan(theta)', 'thetadot', 'g_0*x^(2)/2', '2*pi', 'k*theta')
>>> to_ascii("sec^2(theta) + tan**2 theta")
'(sec(theta))^2 + (tan(theta))^2'
>>> to_ascii("J + m(b)*b^2", functions={"theta"}), to_ascii("theta(x)", functions={"theta"})
('J + m*(b)*b^2', 'theta(x)')
"""

from __future__ import annotations

import builtins
import re
import unicodedata

__all__ = ["to_ascii", "GREEK", "FUNCTION_NAMES"]

GREEK = {"θ": "theta", "ϑ": "theta", "φ": "phi", "ϕ": "phi", "α": "alpha", "β": "beta",
         "μ": "mu", "ω": "omega", "ε": "epsilon", "ϵ": "epsilon", "ψ": "psi", "ρ": "rho",
         "σ": "sigma", "τ": "tau", "ν": "nu", "λ": "lambda_", "κ": "kappa", "γ": "gamma",
         "δ": "delta", "η": "eta", "ξ": "xi", "ζ": "zeta", "χ": "chi", "Ω": "Omega",
         "Λ": "Lambda", "Φ": "Phi", "Ψ": "Psi", "Θ": "Theta", "Δ": "Delta", "Γ": "Gamma"}

# the maths functions of the parser (kept here so that this module needs nothing else)
FUNCTION_NAMES = {"sqrt", "cbrt", "exp", "log", "ln", "sin", "cos", "tan", "sec", "csc", "cot",
                  "asin", "acos", "atan", "atan2", "arcsin", "arccos", "arctan", "sinh",
                  "cosh", "tanh", "Abs", "abs", "sign", "Rational", "Derivative", "diff",
                  "Integral", "Sum"}
_TOKENIZER = {"Symbol", "Function", "Integer", "Float"}

_SIMPLE = {"−": "-", "–": "-", "‐": "-", "‑": "-", "﹣": "-", "－": "-",
           "·": "*", "⋅": "*", "×": "*", "∙": "*", "∗": "*", "÷": "/", "∕": "/",
           "’": "'", "′": "'", "ʹ": "'", "‘": "'", "´": "'", "″": "''", "‴": "'''",
           "\u00a0": " ", "\u2009": " ", "\u202f": " ", "（": "(", "）": ")", "π": " pi "}
_SUPER = {"⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁶": "6", "⁷": "7",
          "⁸": "8", "⁹": "9", "⁻": "-", "⁺": ""}
_SUB = {"₀": "0", "₁": "1", "₂": "2", "₃": "3", "₄": "4", "₅": "5", "₆": "6", "₇": "7",
        "₈": "8", "₉": "9"}
_DOT, _DDOT = "\u0307", "\u0308"
_NAME = r"[^\W\d]\w*'*"
_BUILTINS = set(dir(builtins))


def _characters(text):
    out = []
    i = 0
    while i < len(text):
        c = text[i]
        if c in _SUPER:
            j = i
            while j < len(text) and text[j] in _SUPER:
                j += 1
            out.append("^(" + "".join(_SUPER[d] for d in text[i:j]) + ")")
            i = j
            continue
        if c in _SUB:
            j = i
            while j < len(text) and text[j] in _SUB:
                j += 1
            out.append("_" + "".join(_SUB[d] for d in text[i:j]))
            i = j
            continue
        if c == _DOT:
            out.append("dot")
        elif c == _DDOT:
            out.append("ddot")
        elif c in GREEK:
            # a Greek letter glued to a Latin one is a product: k θ, kθ, θx
            before = "*" if out and (out[-1][-1:].isalnum() or out[-1][-1:] == ")") else ""
            nxt = text[i + 1] if i + 1 < len(text) else ""
            after = "*" if (nxt.isalnum() or nxt in GREEK) and nxt not in _SUB \
                and nxt not in _SUPER and nxt not in _SIMPLE else ""
            out.append(before + GREEK[c] + after)
        else:
            out.append(_SIMPLE.get(c, c))
        i += 1
    return "".join(out)


def _tidy_pi(text):
    """' pi ' (from π) joined to its neighbours: 2π -> 2*pi, πx -> pi*x, (π) -> (pi)."""
    text = re.sub(r"([\w)'])\s*\bpi \s*(?=[\w(])", r"\1*pi*", text)
    text = re.sub(r"([\w)'])\s*\bpi \s*", r"\1*pi", text)
    text = re.sub(r"\s*\bpi \s*(?=[\w(])", "pi*", text)
    text = re.sub(r" ?\bpi ", "pi", text)
    return text


def _matching(text, start):
    """Index just past the parenthesis that closes the one at text[start] (or -1)."""
    depth = 0
    for j in range(start, len(text)):
        depth += {"(": 1, ")": -1}.get(text[j], 0)
        if depth == 0:
            return j + 1
    return -1


def _roots(text):
    """√(…) -> sqrt(…), √x -> sqrt(x), 2√x -> 2*sqrt(x)."""
    while "√" in text:
        i = text.index("√")
        before = "*" if i and re.match(r"[\w)]", text[i - 1]) else ""
        rest = text[i + 1:].lstrip()
        if rest.startswith("("):
            text = text[:i] + before + "sqrt" + rest
            continue
        m = re.match(r"\d+(\.\d+)?|" + _NAME, rest)
        if not m:
            return text          # left for the parser's message
        text = text[:i] + before + f"sqrt({m.group(0)})" + rest[m.end():]
    return text


_FPOW = re.compile(r"\b(" + "|".join(sorted(FUNCTION_NAMES - {"Derivative", "diff", "Rational",
                                                                "Integral", "Sum", "atan2"},
                                            key=len, reverse=True))
                   + r")\s*(?:\^|\*\*)\s*(\(\s*-?\d+\s*\)|-?\d+)\s*")


def _function_powers(text):
    """sec^2(x) -> (sec(x))^2; sin^2 x -> (sin(x))^2 (the argument a name or a number)."""
    pos = 0
    while True:
        m = _FPOW.search(text, pos)
        if not m:
            return text
        name, power = m.group(1), m.group(2).replace(" ", "")
        rest = text[m.end():]
        if rest.startswith("("):
            end = _matching(rest, 0)
            if end < 0:
                return text
            arg = rest[:end]
        else:
            a = re.match(r"\d+(\.\d+)?|" + _NAME, rest)
            if not a:
                pos = m.end()
                continue
            arg = "(" + a.group(0) + ")"
            end = a.end()
        new = f"({name}{arg})^{power}"
        text = text[:m.start()] + new + rest[end:]
        pos = m.start() + len(new)


_FSPACE = re.compile(r"\b(" + "|".join(sorted(FUNCTION_NAMES - {"Derivative", "diff", "Rational",
                                                                  "Integral", "Sum", "atan2"},
                                              key=len, reverse=True))
                     + r")\s+(\d+(\.\d+)?|" + _NAME + r")")


def _function_spaces(text):
    """sin theta -> sin(theta): a function, a space and a name or a number."""
    return _FSPACE.sub(lambda m: f"{m.group(1)}({m.group(2)})", text)


def _products(text, functions):
    """name(…) is a product unless name is a maths function or a declared coordinate."""
    def repl(m):
        name = m.group(1)
        if name in FUNCTION_NAMES or name in functions or name in _TOKENIZER \
                or name in _BUILTINS or name.endswith("'") or _has_comma(text, m.end() - 1):
            return m.group(0)          # a call: the parser accepts it or says why not
        return name + "*("
    return re.sub(r"(?<![\w'])([^\W\d]\w*)\s*\(", repl, text)


def _has_comma(text, start):
    """Does the bracket opened at text[start] hold a comma at its own level?"""
    depth = 0
    for j in range(start, len(text)):
        c = text[j]
        depth += {"(": 1, ")": -1}.get(c, 0)
        if depth == 0:
            return False
        if c == "," and depth == 1:
            return True
    return False


def to_ascii(text, functions=None):
    """The typed answer in the parser's notation (see the module's docstring).

    ``functions``: the names that may be applied as coordinates, as in
    ``theta(x)``; ``None`` leaves every ``name(...)`` to the parser.
    """
    if text.isascii():
        out = text
    else:
        out = _characters(unicodedata.normalize("NFD", text))
        out = unicodedata.normalize("NFC", out)
        out = _tidy_pi(out) if "pi " in out else out
        out = _roots(out)
        # sec²θ: the product sign put before θ belongs to no product
        out = re.sub(r"\b(" + "|".join(sorted(FUNCTION_NAMES)) + r")\^\((-?\d+)\)\*",
                     r"\1^(\2) ", out)
    out = _function_spaces(_function_powers(out))
    if functions is not None:
        out = _products(out, set(functions))
    return out
