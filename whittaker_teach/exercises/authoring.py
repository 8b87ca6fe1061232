"""From a lecturer's exercise source to answer data, and from answer data to an exercise.

An exercise source ``exercises/src/<id>.py`` holds one cell marked
``# %% exercise``: a dictionary (Python literals only, read with
:func:`ast.literal_eval`, never run) that says what the exercise is::

    EXERCISE = {
        "title": "The sledge's reduced Lagrangian",
        "equations": "3.5, 3.6, 3.7",
        "solvers": False,               # may a graded notebook use the library's solvers?
        "symbols": "x xdot+ theta thetadot thetaprime h m+ J+ k+",   # + : positive
        "domain": {"theta": "angle", "xdot": "speed", "h": "energy"},
        "conditions": ["2*h - k^2*theta^2"],          # positive where answers are compared
        "definitions": {},                            # e.g. {"omega": "k/sqrt(J)"}
        "parts": {
            "L_star": {"what": "L* (3.7)", "points": 2, "sign_note": "...",
                       "why_not": {"xdot": "put xdot from (3.5)"}, "success": "..."},
        },
    }

The expected answers are not written there: ``make exercises`` runs the
solution, and each ``check(id, answer, part=...)`` of the solution gives
that part's expected answer (:func:`collecting`).  :func:`make_data` then
writes everything to ``whittaker_teach/exercises/data/<id>.json`` (:mod:`.answers`), from
which :func:`exercise_from_data` builds the :class:`~.specs.Exercise` that
``check`` uses.

``notes`` ({name: what to write instead}) is said when an answer uses a name
that is not a symbol of the exercise (``{"g": "gravity is g_0"}``).

A domain entry is a range ``[low, high]`` (``None`` for no bound on that
side: ``[1.5708, None]`` is s > 1.5708) or one of the names of
:data:`PRESETS` (``positive`` and ``speed`` are 0 < s, ``slope``, ``energy``
and ``real`` every real value, ``angle`` |s| < pi/2, ``turn`` |s| < pi,
``unit`` |s| < 1); a symbol without an entry is on ``positive`` when declared
positive (``m+``), else on ``real``.  It is the statement's domain: answers
are compared on the whole of it (:class:`~.compare.Domain`), an infinite
range over many decades.  The answer data keeps a preset by its name.  A part is an expression
(its answer a SymPy expression or a number) unless it has ``choices``
(``{key: [[other spellings], message]}``): then the solution's answer is
the right key.  Optional keys of a part: ``points`` (default 1),
``variables`` (the symbols the answer may contain; default: those of the
expected answer), ``why_not`` ({symbol: why the answer should not contain
it}), ``sign_note``, ``success``, ``wrong`` ([[answer, message], ...]: known
wrong answers, e.g. a misprint of the paper), ``rtol`` (for a number),
``form`` (the expected answer written as the hints should see it, e.g.
``"sqrt(2*h - k^2*theta^2)/sqrt(m*sec(theta)^2 + J*theta'^2)"`` where the
solution's own result is ``sqrt((2*h - ...)/(...))``: ``make exercises``
checks it equal to the solution's answer on the domain, and stops if not).
"""

from __future__ import annotations

import ast
import json
import math
import os

import sympy as sp

from .answers import FORMAT, from_srepr, to_srepr

__all__ = ["PRESETS", "read_spec", "make_data", "exercise_from_data", "collecting",
           "record_expected", "SpecError"]

_INF = float("inf")
_HALF_PI = 1.5707963267948966
#: the named domains (open ranges; an infinite end is sampled over many decades)
PRESETS = {
    "positive": (0.0, _INF),          # masses, moments of inertia, lengths, constants
    "angle": (-_HALF_PI, _HALF_PI),   # |theta| < pi/2
    "turn": (-2 * _HALF_PI, 2 * _HALF_PI),   # an angle over a whole turn
    "slope": (-_INF, _INF),           # q' = dq/dq_eps, any real value
    "speed": (0.0, _INF),             # qdot_eps > 0, the direction of travel
    "energy": (-_INF, _INF),          # an energy constant: any value the conditions allow
    "real": (-_INF, _INF),            # any real value (a symbol not declared positive)
    "unit": (-1.0, 1.0),
}
PART_KEYS = {"what", "points", "variables", "why_not", "sign_note", "success", "wrong", "rtol",
             "choices", "form"}
SPEC_KEYS = {"title", "equations", "solvers", "symbols", "functions", "domain", "conditions",
             "definitions", "notes", "parts"}
COLLECT = "WHITTAKER_TEACH_COLLECT"


class SpecError(ValueError):
    """The exercise cell of a source is not what it should be: the message says where."""


# ---------------------------------------------------------------- the source's cell
def read_spec(code, where="<source>"):
    """The dictionary of an ``# %% exercise`` cell (``EXERCISE = {...}``), checked."""
    try:
        tree = ast.parse(code)
    except SyntaxError as exc:
        raise SpecError(f"{where}: the exercise cell is not Python ({exc.msg}, line "
                        f"{exc.lineno})") from None
    if len(tree.body) != 1 or not isinstance(tree.body[0], ast.Assign) or \
            [getattr(t, "id", None) for t in tree.body[0].targets] != ["EXERCISE"]:
        raise SpecError(f"{where}: the exercise cell must be one assignment EXERCISE = {{...}}")
    try:
        spec = ast.literal_eval(tree.body[0].value)
    except ValueError:
        raise SpecError(f"{where}: EXERCISE may contain only literals (strings, numbers, "
                        "lists, dicts, True/False)") from None
    _check_spec(spec, where)
    return spec


def _check_spec(spec, where):
    if not isinstance(spec, dict):
        raise SpecError(f"{where}: EXERCISE must be a dict")
    unknown = set(spec) - SPEC_KEYS
    if unknown:
        raise SpecError(f"{where}: unknown keys {sorted(unknown)}; allowed: {sorted(SPEC_KEYS)}")
    for key in ("title", "parts"):
        if not spec.get(key):
            raise SpecError(f"{where}: EXERCISE needs {key!r}")
    if not isinstance(spec.get("symbols"), str):
        raise SpecError(f"{where}: EXERCISE needs 'symbols', a string of names ('m+ theta': "
                        "+ for positive; '' for none)")
    if not isinstance(spec.get("solvers", False), bool):
        raise SpecError(f"{where}: 'solvers' is True or False")
    names = _symbol_names(spec["symbols"])
    positive = {t.rstrip("+") for t in _split(spec["symbols"]) if t.endswith("+")}
    for name, rng in spec.get("domain", {}).items():
        if name not in names:
            raise SpecError(f"{where}: the domain names {name!r}, which is not in 'symbols'")
        if not ((isinstance(rng, str) and rng in PRESETS) or (
                isinstance(rng, (list, tuple)) and len(rng) == 2
                and all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)
                                      and math.isfinite(v)) for v in rng)
                and (None in rng or rng[0] < rng[1]))):
            raise SpecError(f"{where}: the domain of {name} must be [low, high] (finite "
                            "numbers, low < high; None for no bound: [0, None] is s > 0) "
                            f"or one of {', '.join(PRESETS)}")
        low = domain_range(rng)[0]
        if name in positive and low < 0:
            raise SpecError(f"{where}: {name} is declared positive ({name}+) but its domain "
                            f"{rng!r} reaches below 0")
    for name, part in spec["parts"].items():
        if not isinstance(part, dict) or not part.get("what"):
            raise SpecError(f"{where}: part {name!r} needs a dict with 'what'")
        unknown = set(part) - PART_KEYS
        if unknown:
            raise SpecError(f"{where}: part {name!r} has unknown keys {sorted(unknown)}; "
                            f"allowed: {sorted(PART_KEYS)}")
        pts = part.get("points", 1)
        if isinstance(pts, bool) or not isinstance(pts, (int, float)) or pts < 0:
            raise SpecError(f"{where}: the points of part {name!r} must be a number >= 0")
        for sym in list(part.get("why_not", {})) + _split(part.get("variables", "")):
            if sym not in names:
                raise SpecError(f"{where}: part {name!r} names {sym!r}, which is not in "
                                "'symbols'")


def _split(text):
    return text.split() if isinstance(text, str) else list(text)


def _symbol_names(spec_symbols):
    return [t.rstrip("+") for t in _split(spec_symbols)]


def _symbols(spec_symbols):
    return [sp.Symbol(t.rstrip("+"), positive=True) if t.endswith("+") else sp.Symbol(t)
            for t in _split(spec_symbols)]


# ---------------------------------------------------------------- collecting the solution's answers
def collecting():
    """Is this kernel run by ``make exercises`` to collect the solution's answers?"""
    return bool(os.environ.get(COLLECT))


def record_expected(exercise_id, part, answer):
    """Append the solution's answer to a part to the file named by $WHITTAKER_TEACH_COLLECT."""
    from .parsing import read_answer
    rec = {"exercise": exercise_id, "part": part}
    if isinstance(answer, type) and issubclass(answer, BaseException):
        answer = answer.__name__
    if isinstance(answer, str):
        rec["text"] = answer
    else:
        rec["srepr"] = to_srepr(read_answer(answer))
    with open(os.environ[COLLECT], "a", encoding="utf-8") as out:
        out.write(json.dumps(rec) + "\n")


# ---------------------------------------------------------------- the answer data
def _norm(text):
    return "".join(c for c in text.lower() if c.isalnum())


def make_data(ex_id, spec, collected, source_sha256=""):
    """The answer data (a JSON-able dict) of one exercise from its spec and the solution's
    answers (``collected``: the records written by :func:`record_expected`)."""
    from .parsing import Context, read_answer
    from .specs import Names
    symbols = _symbols(spec["symbols"])
    names = Names(symbols, spec.get("functions"))
    by_name = {s.name: s for s in symbols}
    ctx = Context(names.alias, names.functions)
    answers = {}
    for rec in collected:
        if rec.get("exercise") == ex_id:
            answers[rec["part"]] = rec
    unknown = sorted(set(answers) - set(spec["parts"]))
    if unknown:
        raise SpecError(f"{ex_id}: the solution checks parts {unknown}, which EXERCISE does "
                        "not list")

    def expr(text, what):
        try:
            e = read_answer(text, context=ctx)
        except Exception as exc:  # noqa: BLE001
            raise SpecError(f"{ex_id}: {what} {text!r} cannot be read: {exc}") from None
        return _resolve(e, by_name, ex_id, what)

    definitions = {k: expr(v, f"the definition of {k}")
                   for k, v in spec.get("definitions", {}).items()}
    domain = domain_data(spec)
    conditions = [expr(c, "the condition") for c in spec.get("conditions", [])]
    parts = []
    for name, p in spec["parts"].items():
        rec = answers.get(name)
        if rec is None:
            raise SpecError(f"{ex_id}: the solution never calls check(..., part={name!r}), so "
                            "that part has no expected answer")
        out = {"name": name, "what": p["what"], "points": p.get("points", 1),
               "why_not": dict(p.get("why_not", {})), "sign_note": p.get("sign_note", ""),
               "success": p.get("success", ""), "rtol": p.get("rtol")}
        if "choices" in p:
            choices = {k: [list(v[0]), v[1]] for k, v in p["choices"].items()}
            given = rec.get("text")
            if given is None:
                raise SpecError(f"{ex_id}: part {name!r} is a choice; the solution must answer "
                                "with a string (or an exception class)")
            keys = [k for k, (aliases, _) in choices.items()
                    if _norm(given) in {_norm(a) for a in (k, *aliases)}
                    or _norm(given.rsplit(".", 1)[-1]) in {_norm(a) for a in (k, *aliases)}]
            if len(keys) != 1:
                raise SpecError(f"{ex_id}: the solution's answer {given!r} to part {name!r} is "
                                f"not one of its choices {list(choices)}")
            out.update(choices=choices, answer_key=keys[0], expected=None, variables=[],
                       wrong=[])
        else:
            if "srepr" in rec:
                e = _resolve(from_srepr(rec["srepr"]), by_name, ex_id, f"the answer to {name}")
            else:
                e = expr(rec["text"], f"the solution's answer to part {name!r}")
            e = e.xreplace({by_name[k]: v for k, v in definitions.items() if k in by_name})
            if "form" in p:
                e = _same_form(ex_id, name, expr(p["form"], f"the form of part {name!r}"), e,
                               domain, by_name, conditions)
            variables = _split(p["variables"]) if "variables" in p else \
                sorted(s.name for s in e.free_symbols)
            wrong = [(expr(w, f"the wrong answer of part {name!r}"), msg)
                     for w, msg in p.get("wrong", [])]
            _wrong_is_wrong(ex_id, name, wrong, e, domain, by_name, conditions, p.get("rtol"))
            out.update(expected=to_srepr(e), variables=variables,
                       wrong=[[to_srepr(w), msg] for w, msg in wrong])
        parts.append(out)
    return {"format": FORMAT, "id": ex_id, "title": spec["title"],
            "equations": spec.get("equations", ""), "solvers": spec.get("solvers", False),
            "source_sha256": source_sha256,
            "symbols": [[s.name, bool(s.is_positive)] for s in symbols],
            "functions": sorted(names.functions),
            "definitions": {k: to_srepr(v) for k, v in definitions.items()},
            "notes": {str(k): str(v) for k, v in spec.get("notes", {}).items()},
            "domain": domain,
            "conditions": [to_srepr(c) for c in conditions],
            "parts": parts}


def _wrong_is_wrong(ex_id, name, wrong, answer, domain, by_name, conditions, rtol=None):
    """Refuse a ``wrong`` entry equal to the right answer: its message would tell a
    student with the right answer that it is wrong (review C, gap 7)."""
    from .compare import Domain, equal
    dom = Domain({by_name[k]: domain_range(v) for k, v in domain.items()}, tuple(conditions))
    for w, _ in wrong:
        if not w.free_symbols and not answer.free_symbols:
            same = abs(complex(w) - complex(answer)) <= (1e-10 if rtol is None else rtol) \
                * max(abs(complex(answer)), 1e-300)
        else:
            same = equal(w, answer, dom, 0)
        if same:
            raise SpecError(f"{ex_id}: the 'wrong' answer {sp.sstr(w)[:60]} of part {name!r} "
                            "equals the right answer on the domain: a student who gives it "
                            "would be told it is wrong")


def _same_form(ex_id, name, form, answer, domain, by_name, conditions):
    """The lecturer's form of a part's answer, once shown equal to the solution's."""
    from .compare import Domain, equal
    dom = Domain({by_name[k]: domain_range(v) for k, v in domain.items()}, tuple(conditions))
    if not equal(form, answer, dom, 0):
        raise SpecError(f"{ex_id}: the 'form' of part {name!r}, {sp.sstr(form)[:60]}, is not "
                        f"equal to the solution's answer {sp.sstr(answer)[:60]} on the domain")
    return form


def domain_data(spec):
    """The stored domain of a spec: {symbol name: preset name or [low, high]} for every
    symbol (``positive`` for one declared positive and not named, else ``real``)."""
    domain = {}
    for s in _symbols(spec["symbols"]):
        rng = spec.get("domain", {}).get(s.name)
        if rng is None:
            rng = "positive" if s.is_positive else "real"
        domain[s.name] = rng if isinstance(rng, str) else \
            [None if v is None else float(v) for v in rng]
    return domain


def domain_range(entry):
    """(low, high) of a stored domain entry: a name of :data:`PRESETS` or [low, high]
    (None: no bound on that side).

    >>> domain_range("angle")[1], domain_range([0, None]), domain_range([None, 2])
    (1.5707963267948966, (0.0, inf), (-inf, 2.0))
    """
    if isinstance(entry, str):
        if entry not in PRESETS:
            raise ValueError(f"answer data: unknown domain {entry!r}")
        return PRESETS[entry]
    low, high = entry
    return (-_INF if low is None else float(low), _INF if high is None else float(high))


def _resolve(e, by_name, ex_id, what):
    sub = {}
    for s in e.free_symbols:
        if s.name not in by_name:
            raise SpecError(f"{ex_id}: {what} uses the symbol {s.name}, which is not in "
                            "EXERCISE['symbols']")
        sub[s] = by_name[s.name]
    return e.xreplace(sub)


def exercise_from_data(data):
    """The :class:`~.specs.Exercise` of one exercise's answer data."""
    from .compare import Domain
    from .specs import Exercise, Names, Part
    symbols = [sp.Symbol(n, positive=True) if pos else sp.Symbol(n) for n, pos in
               data["symbols"]]
    by_name = {s.name: s for s in symbols}

    def read(text):
        return _resolve(from_srepr(text), by_name, data["id"], "the answer data")

    def builder():
        definitions = {k: read(v) for k, v in data.get("definitions", {}).items()}
        names = Names(symbols, data.get("functions"), definitions, data.get("notes"))
        dom = Domain({by_name[k]: domain_range(v) for k, v in data["domain"].items()},
                     conditions=tuple(read(c) for c in data.get("conditions", [])))
        parts = []
        for p in data["parts"]:
            kw = dict(name=p["name"], what=p["what"], points=p.get("points", 1),
                      why_not=p.get("why_not", {}), sign_note=p.get("sign_note", ""),
                      success=p.get("success", ""), rtol=p.get("rtol"))
            if data.get("withheld"):            # the student edition: the statement only
                if p.get("choices"):
                    kw.update(choices={k: (tuple(v[0]), "") for k, v in p["choices"].items()})
            elif p.get("choices"):
                kw.update(choices={k: (tuple(v[0]), v[1]) for k, v in p["choices"].items()},
                          answer_key=p["answer_key"])
            else:
                kw.update(expected=read(p["expected"]),
                          variables=tuple(by_name[v] for v in p["variables"]),
                          wrong=[(read(w), msg) for w, msg in p.get("wrong", [])])
            parts.append(Part(**kw))
        return names, dom, parts

    ex = Exercise(data["id"], data["title"], data.get("equations", ""), builder,
                  solvers=bool(data.get("solvers", False)))
    ex.part_points = {p["name"]: p.get("points", 1) for p in data["parts"]}
    ex.withheld = bool(data.get("withheld"))
    return ex
