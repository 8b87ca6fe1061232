"""Where an exercise's answer data lives, and how it is read back safely.

``make exercises`` runs each exercise's solution and writes
``whittaker_teach/exercises/data/<id>.json``: the statement's symbols with their
assumptions, the domain, the parts (with their points, hints and messages)
and each part's expected answer.  The files are package data (the wheel
carries them, so an installed package checks every exercise from any
folder); this module finds one and reads it.  Nothing in them is code.

Expressions are stored as ``sympy.srepr`` text and read back by
:func:`from_srepr`, a restricted reader: Python's :mod:`ast` parses the
text and only the SymPy constructors of :data:`CONSTRUCTORS` with literal
arguments are built (no ``eval``, no pickle, no attribute access).

>>> import sympy as sp
>>> m = sp.Symbol("m", positive=True)
>>> e = sp.sqrt(2 * m) * sp.sin(sp.Symbol("theta")) + sp.Float("0.25") + sp.pi
>>> from_srepr(sp.srepr(e)) == e and from_srepr(sp.srepr(e)).has(m)
True
>>> from_srepr("__import__('os')")
Traceback (most recent call last):
...
ValueError: answer data: __import__ is not a SymPy constructor allowed here

Search order of :func:`answers_dirs` (the first folder holding
``<id>.json`` wins): the folder named by the environment variable
``WHITTAKER_TEACH_ANSWERS`` (a lecturer's own exercises), then the
package's ``exercises/data``.  Nothing else: in particular not the current
folder, where a student could place a file of their own.
"""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import sympy as sp

__all__ = ["answers_dirs", "answers_path", "read_data", "from_srepr", "to_srepr",
           "withheld", "CONSTRUCTORS", "FORMAT"]

FORMAT = 1
DATA_DIR = Path(__file__).resolve().parent / "data"
MAX_DATA_CHARS = 2_000_000
MAX_NODES = 200_000

CONSTRUCTORS = {
    "Symbol": sp.Symbol, "Dummy": sp.Symbol, "Integer": sp.Integer, "Rational": sp.Rational,
    "Float": sp.Float, "Add": sp.Add, "Mul": sp.Mul, "Pow": sp.Pow, "Tuple": sp.Tuple,
    "sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sec": sp.sec, "csc": sp.csc, "cot": sp.cot,
    "asin": sp.asin, "acos": sp.acos, "atan": sp.atan, "atan2": sp.atan2, "sinh": sp.sinh,
    "cosh": sp.cosh, "tanh": sp.tanh, "exp": sp.exp, "log": sp.log, "Abs": sp.Abs,
    "sign": sp.sign,
}
NAMES = {"pi": sp.pi, "E": sp.E, "I": sp.I, "S": None}
_ASSUMPTIONS = {"positive", "negative", "real", "nonnegative", "nonpositive", "nonzero",
                "integer", "commutative", "finite", "zero"}


def answers_dirs():
    """Every folder that may hold answer data, in search order (existing or not)."""
    out = []
    env = os.environ.get("WHITTAKER_TEACH_ANSWERS")
    if env:
        out.append(Path(env))
    out.append(DATA_DIR)
    return out


def answers_path(exercise_id):
    """The JSON file of ``exercise_id``'s answer data, or None where there is none."""
    if not isinstance(exercise_id, str) or not exercise_id.replace("-", "").replace(
            "_", "").isalnum() or len(exercise_id) > 100:
        return None
    for d in answers_dirs():
        p = d / f"{exercise_id}.json"
        if p.is_file():
            return p
    return None


def available():
    """{exercise id: path} of every answer file found (first folder wins)."""
    found = {}
    for d in answers_dirs():
        if d.is_dir():
            for p in sorted(d.glob("*.json")):
                found.setdefault(p.stem, p)
    return found


def read_data(path):
    """The answer data of one file (a dict), checked for its format."""
    text = Path(path).read_text(encoding="utf-8")
    if len(text) > MAX_DATA_CHARS:
        raise ValueError(f"answer data {path}: larger than {MAX_DATA_CHARS} characters")
    data = json.loads(text)
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise ValueError(f"answer data {path}: not format {FORMAT}; run `make exercises`")
    return data


#: what the student edition keeps of a graded exercise's data: the statement (its
#: symbols, domain and parts as asked), nothing computed from the solution
STATEMENT_KEYS = ("format", "id", "title", "equations", "symbols", "domain", "conditions",
                  "definitions", "functions", "notes", "solvers")
STATEMENT_PART_KEYS = ("name", "what", "points", "why_not")


def withheld(data):
    """The statement-only data of a graded exercise, for the student edition.

    Every expected answer, known wrong answer, success message, sign note, tolerance,
    answer key and the list of symbols an answer depends on is left out; a choice
    keeps its options' names (and their other spellings), not their messages.  With
    it, ``check`` reads an answer back and says that the part is graded.

    >>> data = {"format": 1, "id": "e", "title": "t", "symbols": [["x", False]],
    ...         "domain": {}, "source_sha256": "0" * 64,
    ...         "parts": [{"name": "a", "what": "w", "points": 2, "expected": "Symbol('x')",
    ...                    "variables": ["x"], "success": "x, right", "wrong": []}]}
    >>> withheld(data)["parts"]
    [{'name': 'a', 'what': 'w', 'points': 2}]
    >>> withheld(data)["withheld"], "source_sha256" in withheld(data)
    (True, False)
    """
    out = {k: data[k] for k in STATEMENT_KEYS if k in data}
    out["withheld"] = True
    parts = []
    for p in data["parts"]:
        q = {k: p[k] for k in STATEMENT_PART_KEYS if k in p}
        if p.get("choices"):
            q["choices"] = {k: [list(v[0]), ""] for k, v in p["choices"].items()}
        parts.append(q)
    out["parts"] = parts
    return out


def to_srepr(expr):
    """The stored form of an expression."""
    return sp.srepr(expr)


def from_srepr(text):
    """An expression from its ``srepr`` text, building only :data:`CONSTRUCTORS`."""
    if not isinstance(text, str) or len(text) > MAX_DATA_CHARS:
        raise ValueError("answer data: an expression must be a string")
    tree = ast.parse(text, mode="eval")
    count = [0]

    def build(node):
        count[0] += 1
        if count[0] > MAX_NODES:
            raise ValueError("answer data: expression too large")
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float, str)) \
                and not isinstance(node.value, bool):
            return node.value
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) \
                and isinstance(node.operand, ast.Constant):
            return -node.operand.value
        if isinstance(node, ast.Name) and NAMES.get(node.id) is not None:
            return NAMES[node.id]
        if isinstance(node, ast.Tuple):
            return tuple(build(e) for e in node.elts)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            name = node.func.id
            if name not in CONSTRUCTORS:
                raise ValueError(f"answer data: {name} is not a SymPy constructor allowed here")
            args = [build(a) for a in node.args]
            kwargs = {}
            for kw in node.keywords:
                if kw.arg in _ASSUMPTIONS and isinstance(kw.value, ast.Constant) \
                        and isinstance(kw.value.value, bool):
                    kwargs[kw.arg] = kw.value.value
                elif kw.arg == "precision" and name == "Float" and \
                        isinstance(kw.value, ast.Constant) and isinstance(kw.value.value, int) \
                        and 1 <= kw.value.value <= 400:
                    kwargs[kw.arg] = kw.value.value
                else:
                    raise ValueError(f"answer data: keyword {kw.arg} not allowed in {name}")
            if name in ("Symbol", "Dummy") and not (len(args) == 1 and isinstance(args[0], str)):
                raise ValueError("answer data: Symbol takes a name")
            if name in ("Integer", "Rational") and not all(isinstance(a, int) and
                                                          abs(a) < 10**60 for a in args):
                raise ValueError("answer data: Integer/Rational take small integers")
            if name == "Float" and not (len(args) == 1 and isinstance(args[0], str)):
                raise ValueError("answer data: Float takes its digits as a string")
            if name == "Float":
                return sp.Float(args[0], **({"precision": kwargs["precision"]}
                                            if "precision" in kwargs else {}))
            if name in ("Symbol", "Dummy"):
                return sp.Symbol(args[0], **kwargs)
            if kwargs:
                raise ValueError(f"answer data: {name} takes no keywords")
            return CONSTRUCTORS[name](*args)
        raise ValueError("answer data: not a SymPy expression in srepr form")

    return build(tree.body)
