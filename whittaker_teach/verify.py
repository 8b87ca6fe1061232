"""Checking the identities the paper claims, for the system at hand.

An identity ``lhs = rhs`` is first tried exactly, by a cheap targeted
rewrite (the difference is identically zero as built, or ``expand`` makes it
zero), and otherwise by evaluating both sides in high precision (mpmath, 40
significant digits) at random admissible points.  A :class:`Check` records
which method decided, at how many points, and the largest relative residual,
so that a reader sees how each claim was shown.

>>> import sympy as sp
>>> x = sp.Symbol("x", positive=True)
>>> check_identity("demo", "sec^2 = 1 + tan^2", 1/sp.cos(x)**2, 1 + sp.tan(x)**2,
...                sample=lambda rng: {x: rng.uniform(0.1, 1.2)})
Check('demo', holds=True, method='numeric', points=6, max_residual<1e-30)
"""

from __future__ import annotations

import random
from dataclasses import dataclass

import mpmath
import sympy as sp

__all__ = ["Check", "check_identity", "check_zero", "DPS", "TOLERANCE"]

#: Working precision (decimal digits) of the numeric checks.
DPS = 40
#: Largest relative residual accepted by a numeric check.
TOLERANCE = 1e-25
#: Number of random admissible points of a numeric check.
POINTS = 6
#: Above this operation count, the exact attempt is skipped (it would cost more
#: than the numeric check).
EXACT_OPS_LIMIT = 250


@dataclass(frozen=True)
class Check:
    """The outcome of checking one identity.

    ``holds`` is True or False when the check decided, None when it could not
    (for example no point could be evaluated); ``method`` is ``"exact"`` or
    ``"numeric"``; ``detail`` says which rewrite or which precision was used.
    """

    label: str
    claim: str
    holds: bool | None
    method: str
    detail: str
    points: int = 0
    max_residual: float = 0.0

    @property
    def status(self) -> str:
        """``"verified"``, ``"FAILED"`` or ``"not verified"``."""
        return {True: "verified", False: "FAILED", None: "not verified"}[self.holds]

    def describe(self) -> str:
        """One line: the claim, whether it held, and how it was shown.

        >>> Check("1.9", "dOmega/dq = dL~/dq", True, "exact", "expand").describe()
        '(1.9) dOmega/dq = dL~/dq: verified exactly (expand)'
        """
        from .render import text_unicode     # the claim's $...$ maths as Unicode
        head = f"({self.label}) {text_unicode(self.claim)}: {self.status}"
        if self.method == "exact":
            return f"{head} exactly ({self.detail})"
        if self.method == "numeric":
            return (f"{head} numerically at {self.points} random admissible points, "
                    f"{self.detail}, largest relative residual {self.max_residual:.1e}")
        return f"{head} ({self.detail})"

    def __repr__(self) -> str:
        res = "" if self.method != "numeric" else (
            ", max_residual<1e-30" if self.max_residual < 1e-30
            else f", max_residual={self.max_residual:.1e}")
        pts = f", points={self.points}" if self.method == "numeric" else ""
        return f"Check({self.label!r}, holds={self.holds}, method={self.method!r}{pts}{res})"


def _as_list(x):
    return list(x) if isinstance(x, (list, tuple)) else [x]


def _exactly_zero(diff):
    """Return the name of the rewrite that shows ``diff == 0``, or None."""
    if diff == 0:
        return "identical as built"
    if sp.count_ops(diff) > EXACT_OPS_LIMIT:
        return None
    if sp.expand(diff) == 0:
        return "expand"
    return None


def _numeric(lhs, rhs, sample, points, seed):
    """Largest relative residual of lhs - rhs over random points, and the count."""
    symbols = sorted(set().union(*(e.free_symbols for e in lhs + rhs)), key=str)
    fn = sp.lambdify(symbols, [*lhs, *rhs], modules="mpmath", docstring_limit=0)
    rng = random.Random(seed)
    worst, used, attempts = 0.0, 0, 0
    n = len(lhs)
    with mpmath.workdps(DPS):
        while used < points and attempts < 4 * points:
            attempts += 1
            point = sample(rng)
            missing = [s for s in symbols if s not in point]
            if missing:
                raise KeyError(f"no sample value for {missing}")
            try:
                vals = fn(*[mpmath.mpf(point[s]) for s in symbols])
            except (ZeroDivisionError, ValueError, OverflowError):
                continue
            if not all(mpmath.isfinite(v) for v in vals):
                continue
            for a, b in zip(vals[:n], vals[n:]):
                scale = max(1, abs(a), abs(b))
                worst = max(worst, float(abs(a - b) / scale))
            used += 1
    return worst, used


def check_identity(label, claim, lhs, rhs, sample, *, exact=True, points=POINTS, seed=0):
    """Check ``lhs == rhs`` (expressions or equal-length lists of them).

    ``sample(rng)`` returns a dict {Symbol: float} of one random admissible
    point; it must give a value for every free symbol.
    """
    lhs, rhs = _as_list(lhs), _as_list(rhs)
    if len(lhs) != len(rhs):
        return Check(label, claim, False, "exact", f"{len(lhs)} left sides, {len(rhs)} right sides")
    if exact:
        ways = [_exactly_zero(sp.sympify(a - b)) for a, b in zip(lhs, rhs)]
        if all(ways):
            return Check(label, claim, True, "exact", ", ".join(sorted(set(ways))))
    worst, used = _numeric(lhs, rhs, sample, points, seed)
    detail = f"mpmath at {DPS} digits"
    if used == 0:
        return Check(label, claim, None, "unverified", "no admissible point could be evaluated")
    return Check(label, claim, worst <= TOLERANCE, "numeric", detail, used, worst)


def check_zero(label, claim, expr, sample, **kw):
    """Check that ``expr`` (or each of a list) vanishes: ``check_identity(expr, 0)``."""
    exprs = _as_list(expr)
    return check_identity(label, claim, exprs, [sp.S.Zero] * len(exprs), sample, **kw)
