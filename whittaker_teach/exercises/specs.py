"""What an exercise asks: :class:`Exercise` and :class:`Part`, and the checking of one part.

An exercise has an id, a title, the paper's equations it involves, and a
builder that reads its parts from the exercise's answer data
(:mod:`.authoring`, :mod:`.answers`).  The builder runs on the first check
of that exercise only, and its result is kept.

A :class:`Part` is either an expression (``expected``, compared with
:func:`~whittaker_teach.exercises.compare.compare` on the exercise's
:class:`~whittaker_teach.exercises.compare.Domain`) or a choice among named
options (``choices``).
"""

from __future__ import annotations

import math
import re
import zlib
from dataclasses import dataclass, field, replace

import sympy as sp

from .compare import _Fn, compare, depends_on, equal
from .feedback import Feedback
from .limits import MAX_LENGTH, TOO_EXPENSIVE, TooExpensive, time_budget
from .parsing import _GREEK, AnswerError, Context, article, plain_symbols, read_answer

__all__ = ["Exercise", "Part", "Names", "check_part"]


class Names:
    """The symbols of an exercise, by name, with the aliases a student may use.

    ``thetaprime`` is also ``thetap``, ``theta_p``, ``theta_prime``;
    ``thetaprimeprime`` is ``thetapp``, ``theta_pp``; ``xdot`` is ``x_dot``;
    Greek letters may be written as such (``θ``).
    """

    def __init__(self, symbols, functions=None, definitions=None, notes=None):
        self.symbols = {s.name: s for s in symbols}
        self.notes = dict(notes or {})      # {a name that is not a symbol: what to write}
        # the coordinates: a name with a derivative among the symbols (theta: thetaprime)
        self.functions = set(functions) if functions is not None else {
            n for n in self.symbols if any(n + d in self.symbols for d in ("prime", "dot"))
            and not n.endswith(("prime", "dot"))}
        self.definitions = dict(definitions or {})
        self.alias = {}
        for name, s in self.symbols.items():
            self.alias[name] = s
            for suffix, alts in (("primeprime", ("pp", "_pp", "_primeprime", "''")),
                                 ("prime", ("p", "_p", "_prime", "'")),
                                 ("ddot", ("_ddot", "dd")), ("dot", ("_dot", "d"))):
                if name.endswith(suffix) and len(name) > len(suffix):
                    base = name[:-len(suffix)]
                    for a in alts:
                        self.alias.setdefault(base + a, s)
                    break
        for name, s in self.symbols.items():
            if "_" in name.strip("_"):             # g_0 is also g0 (and g₀, by the notation)
                self.alias.setdefault(name.replace("_", ""), s)
            m = re.fullmatch(r"([^\W\d_]+)(\d+)", name)
            if m:                                  # v0 is also v_0 (and v₀, by the notation)
                self.alias.setdefault(f"{m.group(1)}_{m.group(2)}", s)
        for g, latin in _GREEK.items():
            for name, s in list(self.alias.items()):
                if name.startswith(latin):
                    self.alias.setdefault(g + name[len(latin):], s)

    def __getitem__(self, name):
        return self.symbols[name]

    def context(self):
        """The :class:`~whittaker_teach.exercises.parsing.Context` for reading strings."""
        return Context(self.alias, self.functions, self.definitions)

    def split(self, name, most=4):
        """``name`` as a product of the exercise's symbol names (``mb`` -> m, b), or None.

        >>> Names(sp.symbols("m b J theta")).split("mbtheta")
        ['m', 'b', 'theta']
        """
        if len(name) > 40:
            return None
        best = {0: []}
        for i in range(len(name)):
            if i not in best or len(best[i]) >= most:
                continue
            for j in range(len(name), i, -1):
                if name[i:j] in self.alias and j not in best:
                    best[j] = best[i] + [name[i:j]]
        found = best.get(len(name))
        return found if found and len(found) > 1 else None

    def resolve(self, expr):
        """Map every free symbol of expr (by name) to the exercise's symbol."""
        sub = {}
        for s in sorted(expr.free_symbols, key=str):
            if s.name in self.definitions:
                sub[s] = self.definitions[s.name]
                continue
            canon = self.alias.get(s.name)
            if canon is None:
                note = self.notes.get(s.name)
                split = None if note else self.split(s.name)
                if split:
                    note = f"did you mean {'·'.join(split)}? write products with *"
                raise AnswerError(f"your answer uses the symbol {s.name[:30]}, which is not a "
                                  "symbol of this exercise" + (f" ({note})" if note else ""))
            if canon is not s:
                sub[s] = canon
        return expr.xreplace(sub) if sub else expr


@dataclass
class Part:
    """One question of an exercise.

    name: the ``part=`` argument; what: what is asked (shown in messages);
    expected: the right answer (an expression in the exercise's symbols);
    variables: the symbols the answer may depend on; why_not: {symbol name:
    why the answer should not contain it}; sign_note: said when the sign is
    wrong; wrong: [(expression, message)] for known wrong answers (the
    paper's misprints); success: said when the answer is right.  For a
    choice: choices = {key: (aliases, message)} and answer_key.
    """

    name: str
    what: str
    expected: sp.Expr | None = None
    variables: tuple = ()
    why_not: dict = field(default_factory=dict)
    sign_note: str = ""
    wrong: list = field(default_factory=list)
    success: str = ""
    choices: dict = field(default_factory=dict)
    answer_key: str = ""
    rtol: float | None = None
    points: float = 1

    @property
    def is_choice(self):
        return bool(self.choices)

    def listing(self):
        if self.is_choice:
            return "expected one of " + ", ".join(repr(k) for k in self.choices)
        if not self.variables:
            return f"expected {self.what}, a number"
        names = ", ".join(str(v) for v in self.variables)
        return f"expected {self.what}, an expression in {names}"


@dataclass
class Exercise:
    """An exercise: id, title, equations of the paper, and a builder of its parts.

    solvers: may a graded notebook of it use the library's solvers (the
    grader's sandbox offers only ``check`` and ``setup`` when False).
    """

    id: str
    title: str
    equations: str
    builder: object
    solvers: bool = False
    _built: tuple | None = None
    withheld: bool = False     # the student edition of a graded exercise: no answers here

    def build(self):
        """(names, domain, {part name: Part}), derived once."""
        if self._built is None:
            names, domain, parts = self.builder()
            self._built = (names, domain, {p.name: p for p in parts})
        return self._built

    @property
    def parts(self):
        return self.build()[2]


def _sentence(text):
    return text[:1].upper() + text[1:]


def _lecturer_hint(text):
    """A lecturer's ``wrong`` message as a sentence (capital, final stop)."""
    text = _sentence(text.strip())
    return text if text.endswith((".", "!", "?")) else text + "."


def _norm_choice(text):
    return "".join(c for c in text.lower() if c.isalnum())


MAX_CHOICE_LENGTH = 200


def _check_choice(ex, part, answer):
    if isinstance(answer, type) and issubclass(answer, BaseException):
        answer = answer.__name__                     # wt.ChartError, the class itself
    if isinstance(answer, BaseException):
        answer = type(answer).__name__
    if isinstance(answer, str) and len(answer) > MAX_CHOICE_LENGTH:
        return Feedback(False, f"The answer is {len(answer)} characters long; "
                        f"{part.listing()} (a short string)", ex.id, part.name, "invalid")
    if not isinstance(answer, str):
        return Feedback(False, f"The answer is {article(type(answer).__name__)}; "
                        f"{part.listing()} (a string)", ex.id, part.name, "invalid")
    key = _norm_choice(answer)
    # "wt.ChartError", "whittaker_teach.ChartError": the name after the module (only for
    # a dotted name: in a sentence, the last word after a period is not the answer)
    dotted = re.fullmatch(r"\s*[^\W\d][\w.]*\s*", answer) and "." in answer
    last = _norm_choice(answer.strip().rsplit(".", 1)[-1]) if dotted else key
    for name, (aliases, message) in part.choices.items():
        if {key, last} & {_norm_choice(a) for a in (name, *aliases)}:
            if name == part.answer_key:
                return Feedback(True, message or part.success, ex.id, part.name)
            return Feedback(False, message, ex.id, part.name)
    named = [name for name, (aliases, _) in part.choices.items()
             if any(_norm_choice(a) and _norm_choice(a) in key for a in (name, *aliases))]
    if named:                     # "RK45 rather than DOP853", "not DOP853": read as a whole
        return Feedback(False, f"Your answer names {' and '.join(repr(n) for n in named)} "
                        "among other words: give one option alone; "
                        f"{part.listing()} (a string)", ex.id, part.name, "invalid")
    return Feedback(False, f"{answer[:40]!r} is not one of the options: {part.listing()} "
                    "(a string)", ex.id, part.name, "invalid")


def read_back(ex, part, answer, max_length=None):
    """How ``answer`` was read, for a part whose answers are withheld (a graded exercise
    in the student edition): no verdict, only the answer as the grader will read it."""
    names, _, _ = ex.build()
    if answer is None or answer is Ellipsis:
        what = part.listing() if part.is_choice else f"expected {part.what}"
        return Feedback(False, f"not answered yet: replace None by your answer ({what})",
                        ex.id, part.name, "unanswered")
    graded = ("this part is graded in your course: it is checked when your lecturer "
              "grades the notebook you hand in")
    if part.is_choice:
        key = _norm_choice(answer) if isinstance(answer, str) else None
        for name, (aliases, _) in part.choices.items():
            if key in {_norm_choice(a) for a in (name, *aliases)}:
                return Feedback(False, f"Read as the option {name!r}; {graded}.", ex.id,
                                part.name, "graded")
        return Feedback(False, f"{str(answer)[:40]!r} is not one of the options: "
                        f"{part.listing()} (a string)", ex.id, part.name, "invalid")
    try:
        with time_budget():
            expr = names.resolve(read_answer(answer, max_length or MAX_LENGTH, names.context()))
            shown = sp.sstr(expr)
    except AnswerError as exc:
        return Feedback(False, _sentence(f"{exc}; expected {part.what}"), ex.id, part.name,
                        "invalid")
    except TooExpensive as exc:
        return Feedback(False, _sentence(str(exc) or TOO_EXPENSIVE) + ".", ex.id, part.name,
                        "invalid")
    if len(shown) > 300:
        shown = shown[:300] + " ..."
    return Feedback(False, f"Read as {shown}; {graded}.", ex.id, part.name, "graded")


def check_part(ex, part, answer, max_length=None, graded=False):
    """Check one answer against one part: a :class:`Feedback`.

    ``max_length``: of a string answer (default: the limit for typed answers).
    ``graded``: the hints name the kind of mistake only, never a quantity that
    reveals the right answer (a factor, a constant, a percentage); a practice
    check (the default) keeps the detailed hints.
    """
    names, domain, _ = ex.build()
    if answer is None or answer is Ellipsis:
        what = part.listing() if part.is_choice else f"expected {part.what}"
        return Feedback(False, f"not answered yet: replace None by your answer ({what})",
                        ex.id, part.name, "unanswered")
    if part.is_choice:
        return _check_choice(ex, part, answer)
    try:
        with time_budget():
            return _check_expression(ex, part, answer, names, domain, max_length, graded)
    except TooExpensive as exc:
        return Feedback(False, _sentence(str(exc) or TOO_EXPENSIVE) + ".", ex.id, part.name,
                        "invalid")


def _check_expression(ex, part, answer, names, domain, max_length=None, graded=False):
    """The verdict on an expression answer; a typed one (a string) is read back."""
    read = {}
    feedback = _judge_expression(ex, part, answer, names, domain, max_length, read, graded)
    if isinstance(answer, str) and feedback.status != "invalid" and "expr" in read:
        shown = sp.sstr(read["expr"])
        feedback = replace(feedback, read=shown if len(shown) <= 200 else shown[:197] + "...")
    return feedback


def _judge_expression(ex, part, answer, names, domain, max_length, read, graded=False):
    """The verdict; ``read["expr"]`` is set to the answer as read."""
    try:
        expr = names.resolve(read_answer(answer, max_length or MAX_LENGTH, names.context()))
        if expr.has(sp.Integral, sp.Sum):
            if part.expected.free_symbols:
                raise AnswerError("your answer contains an unevaluated integral or sum: "
                                  "evaluate it (this part's answer is a formula)")
            from .quadrature import numeric_value
            read["expr"] = expr
            expr = numeric_value(expr)
        read.setdefault("expr", expr)
    except AnswerError as exc:
        return Feedback(False, _sentence(f"{exc}; {part.listing()}"), ex.id, part.name,
                        "invalid")
    if not expr.free_symbols and part.expected.free_symbols:
        return Feedback(False, f"Your answer is the number {sp.sstr(expr)[:40]}, but the right "
                        "answer depends on "
                        f"{', '.join(sorted(str(s) for s in part.expected.free_symbols))}",
                        ex.id, part.name)
    seed = zlib.crc32(f"{ex.id}:{part.name}".encode())
    extra = sorted((s for s in expr.free_symbols if s not in part.variables), key=str)
    if extra:
        # the seed's points, then fresh ones: a dependence hidden from known points is seen
        pts = domain.points(seed, 4, core=True)
        fn = _Fn(expr, domain.symbols)
        bad = [s for s in extra if depends_on(fn, s, pts[0], pts, domain)]
        if not bad:
            more = pts[:1] + domain.points(seed) + domain.fresh()
            bad = [s for s in extra if depends_on(fn, s, more[0], more, domain, most=None)]
        if bad:
            why = "; ".join(part.why_not[s.name] for s in bad if s.name in part.why_not)
            return Feedback(False, f"Your answer depends on {', '.join(map(str, bad))}, which it "
                            f"should not" + (f" ({why})" if why else "") + f": {part.listing()}",
                            ex.id, part.name)
        if not part.expected.free_symbols:
            # a number: its value where the symbols it does not depend on take any value
            expr = expr.xreplace({s: pts[0][s] for s in extra})
        # an expression keeps them: the comparison below varies them over the domain too
    if not part.expected.free_symbols and not expr.free_symbols:
        return _check_number(ex, part, expr, graded)
    verdict = compare(expr, part.expected, domain, seed, part.sign_note, part.rtol)
    if verdict.ok:
        return Feedback(True, part.success or f"{part.what} is right.", ex.id, part.name)
    for wrong, message in part.wrong:
        if equal(expr, wrong, domain, seed, fresh=False):
            return Feedback(False, _lecturer_hint(message), ex.id, part.name)
    other = _other_part(ex, part, expr, domain, seed,
                        terms=verdict.hint.startswith("your answer is not equal"))
    if other:
        return Feedback(False, other, ex.id, part.name)
    return Feedback(False, _sentence(verdict.graded_hint if graded else verdict.hint) + ".",
                    ex.id, part.name)


def _other_part(ex, part, expr, domain, seed, terms=True):
    """Is the answer another part's answer, or (terms) does it carry a term of another part's?"""
    try:
        for name, other in ex.parts.items():
            if name == part.name or other.is_choice or not other.expected.free_symbols:
                continue
            if equal(expr, other.expected, domain, seed, fresh=False):
                return (f"That is the answer to part {name!r} ({other.what}), not to this "
                        f"one: {part.what}.")
        if not terms:
            return ""
        diff = expr - part.expected
        for name, other in ex.parts.items():
            if name == part.name or other.is_choice or not other.expected.free_symbols:
                continue
            terms = sp.Add.make_args(other.expected)
            if len(terms) < 2 or len(terms) > 8:
                continue
            for t in terms:
                for sign, what in ((1, "an extra term"), (-1, "a term missing")):
                    if equal(diff, sign * t, domain, seed, fresh=False):
                        return (f"Your answer has {what}, one of the terms of part {name!r} "
                                f"({other.what}): that term does not belong to "
                                f"{part.what}." if sign == 1 else
                                f"Your answer lacks a term (one that also appears in part "
                                f"{name!r}, {other.what}).")
    except (RuntimeError, TooExpensive):
        return ""
    return ""


def _check_number(ex, part, expr, graded=False):
    """A number against a number: equal within part.rtol (default 1e-10) relative to the
    right value at every magnitude, or which way it is off.

    A lecturer's known wrong values (``wrong``) get their own message.  A graded check
    says only "too large" or "too small"; a practice check adds by how much."""
    fn = _Fn(expr, [])
    got, want = fn({}), _Fn(part.expected, [])({})
    if got is None:
        why = " (it is beyond 1e300)" if fn.huge else ""
        return Feedback(False, f"Cannot evaluate your answer as a number{why}; "
                        f"{part.listing()}", ex.id, part.name, "invalid")
    got, want = complex(got), complex(want)
    rtol = 1e-10 if part.rtol is None else part.rtol
    if _within(got, want, rtol):
        return Feedback(True, part.success or f"{part.what} is right.", ex.id, part.name)
    for wrong, message in part.wrong:
        value = _Fn(wrong, [])({})
        if value is not None and _within(got, complex(value), rtol):
            return Feedback(False, _lecturer_hint(message), ex.id, part.name)
    if abs(got.imag) > 1e-12 * max(1.0, abs(got)):
        return Feedback(False, "Your answer is a complex number; the right one is real.",
                        ex.id, part.name)
    if want.real and abs(got.real + want.real) <= rtol * abs(want.real):
        return Feedback(False, "The sign is wrong.", ex.id, part.name)
    side = "too large" if got.real > want.real else "too small"
    if graded:
        return Feedback(False, f"Your number is {side}.", ex.id, part.name)
    if not want.real:
        return Feedback(False, f"Your number is {side}: the right value is 0.", ex.id,
                        part.name)
    tolerance = f"(the tolerance is {rtol:g}, relative)"
    if abs(got.real - want.real) >= 100 * abs(want.real):
        return Feedback(False, f"Your number is {side}: {abs(got.real / want.real):.3g} times "
                        f"the right value {tolerance}.", ex.id, part.name)
    return Feedback(False, f"Your number is {side} by {_percent(got.real, want.real)} of the "
                    f"right value {tolerance}.", ex.id, part.name)


def _within(got, want, rtol):
    """|got - want| <= rtol |want| (relative at every magnitude; absolute only for 0).

    >>> _within(0.5372873646, 0.5372879846, 1e-6), _within(1157.0, 1157.0000001, 1e-9)
    (False, True)
    """
    return abs(got - want) <= rtol * (abs(want) if want else 1.0)


def _percent(got, want):
    """|got - want|/|want| as a percentage with two significant digits (never 0.00%).

    >>> _percent(1.0000001, 1.0), _percent(1.5, 1.0), _percent(1.0123, 1.0)
    ('0.000010%', '50%', '1.2%')
    """
    rel = abs(got - want) / abs(want) * 100
    text = f"{rel:.{max(0, 1 - math.floor(math.log10(rel)))}f}"
    return text + "%"


def plain(expr, names):
    """A library expression in the exercise's symbols (theta(x) -> theta, ...)."""
    return names.resolve(plain_symbols(sp.sympify(expr)))
