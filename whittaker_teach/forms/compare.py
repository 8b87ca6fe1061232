"""Every form against every other: the accelerations of the independent coordinates at
random admissible points, in 40-digit arithmetic.

:func:`agree` builds each form of a system (a form that does not apply is listed
with the reason: its ModelError), evaluates each one's accelerations at the same
random admissible points (coordinates in (0.1, 1.2), independent velocities of
modulus in (0.2, 1.5), parameters in (0.5, 2)) with the checks' evaluator
(:func:`whittaker_teach.verify.values_at`, mpmath at 40 digits), and, with
``reference=True``, sympy.physics.mechanics' ``LagrangesMethod`` (the constraints as
``nonhol_coneqs``; its ``mass_matrix_full`` and ``forcing_full`` solved at each point),
an independent derivation.  The record prints a table: each form's largest relative
difference from the first one, and whether all agree.

>>> from whittaker_teach.forms import examples, agree
>>> rec = agree(examples.sledge(), forms=["RouthVoss", "Maggi", "GibbsAppell"])
>>> rec.ok, rec.points
(True, 6)
>>> print(rec)                                      # doctest: +ELLIPSIS +NORMALIZE_WHITESPACE
sledge: the accelerations of x, theta at 6 random admissible points, 40 digits
form             eqs  multipliers  quasi-velocities  largest difference  agrees
RouthVoss        4    yes          no                0 (reference)       yes
Maggi            2    no           no                ...
GibbsAppell      2    no           no                ...
LagrangesMethod  4    yes          no                ...
all agree (tolerance 1e-25)
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field

import mpmath
import sympy as sp

from ..errors import ModelError, ModelTypeError
from ..verify import DPS, TOLERANCE, At, Unevaluable, values_at

__all__ = ["agree", "Agreement", "FORMS", "form_class", "lagranges_method_accelerations"]

#: The forms, in the course's order (name: module).
FORMS = {"RouthVoss": "routh_voss", "Voronets": "voronets", "Maggi": "maggi",
         "GibbsAppell": "gibbs_appell", "BoltzmannHamel": "boltzmann_hamel",
         "Nielsen": "nielsen", "Tzenoff": "nielsen", "Kane": "kane"}


def form_class(name):
    """The class of the form called ``name`` (one of :data:`FORMS`)."""
    from importlib import import_module
    if isinstance(name, type):
        return name
    if name not in FORMS:
        raise ModelTypeError(f"no form {name!r}; the forms are {', '.join(FORMS)}")
    return getattr(import_module(f".{FORMS[name]}", __package__), name)


@dataclass
class Agreement:
    """The outcome of :func:`agree`: ``rows`` (one per form: name, number of equations,
    multipliers, quasi-velocities, largest relative difference from the first form or
    None, and the reason where the form did not apply), the number of points, and the
    pairwise largest differences ``pairs`` {(a, b): difference}."""

    system: str
    coordinates: list
    rows: list = field(default_factory=list)
    pairs: dict = field(default_factory=dict)
    points: int = 0
    tolerance: float = TOLERANCE

    @property
    def ok(self) -> bool:
        """Every applicable form agrees with every other (and there were points)."""
        return self.points > 0 and all(d <= self.tolerance for d in self.pairs.values())

    @property
    def largest(self) -> float:
        return max(self.pairs.values(), default=0.0)

    def to_text(self) -> str:
        head = ["form", "eqs", "multipliers", "quasi-velocities", "largest difference",
                "agrees"]
        body = []
        for r in self.rows:
            if r["reason"]:
                body.append([r["name"], "-", "-", "-", "does not apply", r["reason"]])
                continue
            d = r["difference"]
            shown = "0 (reference)" if r is self.rows[0] else f"{d:.1e}"
            body.append([r["name"], str(r["equations"]), "yes" if r["multipliers"] else "no",
                         "yes" if r["quasi"] else "no", shown,
                         "yes" if d <= self.tolerance else "NO"])
        widths = [max(len(row[i]) for row in [head] + body if i < len(row))
                  for i in range(len(head))]
        lines = [f"{self.system}: the accelerations of {', '.join(self.coordinates)} at "
                 f"{self.points} random admissible points, {DPS} digits"]
        for row in [head] + body:
            lines.append("  ".join(v.ljust(w) for v, w in zip(row, widths)).rstrip())
        lines.append(f"all agree (tolerance {self.tolerance:.0e})" if self.ok else
                     f"NOT ALL AGREE: largest pairwise difference {self.largest:.1e}")
        return "\n".join(lines)

    def __str__(self):
        return self.to_text()

    def _repr_html_(self):
        from html import escape
        return "<pre>" + escape(self.to_text()) + "</pre>"


def _points(system, n, seed):
    """``n`` random admissible points where the model's expressions are finite."""
    rng = random.Random(seed)
    return [system.sample(rng) for _ in range(n)]


def _values(exprs, pts):
    """[[value of expr at point i] for expr]: 40 digits, nan where not evaluable."""
    return [values_at(e, pts) for e in exprs]


def lagranges_method_accelerations(system, points):
    """The independent accelerations of ``sympy.physics.mechanics.LagrangesMethod`` (the
    system's Lagrangian, its constraints as ``nonhol_coneqs`` as given) at each point (a
    dict of the system's internal symbols): ``mass_matrix_full`` and ``forcing_full``
    evaluated at 40 digits and solved by mpmath; a list (per point) of lists (per
    independent coordinate)."""
    from sympy.physics.mechanics import LagrangesMethod
    S = system
    coneqs = [S.to_public(f) for f in S._f]
    lm = LagrangesMethod(S.lagrangian, S.coordinates, nonhol_coneqs=coneqs or None)
    lm.form_lagranges_equations()
    lam = list(lm.lam_vec) if coneqs else []
    mapping = dict(S._to_internal)
    for i, l in enumerate(lam):
        mapping[l] = sp.Symbol(f"_lam{i}")
    M = [[S.to_internal(lm.mass_matrix_full[i, j]) for j in range(lm.mass_matrix_full.cols)]
         for i in range(lm.mass_matrix_full.rows)]
    F = [S.to_internal(f) for f in lm.forcing_full]
    n = len(S.coordinates)
    idx = [n + S.coordinates.index(c) for c in S.sigma]     # state: q, qdot; then qddot, lam
    out = []
    with mpmath.workdps(DPS):
        for pt in points:
            pt = dict(pt)
            for c, phi in S._phi.items():          # the dependent velocities on the constraints
                pt[S.qd[c]] = At(pt)(phi)
            at = At(pt)
            try:
                Mn = mpmath.matrix([[at(e) for e in row] for row in M])
                Fn = mpmath.matrix([at(e) for e in F])
                x = mpmath.lu_solve(Mn, Fn)
            except (ZeroDivisionError, ValueError, Unevaluable) as err:
                raise ModelError(f"LagrangesMethod's equations cannot be evaluated: {err}") \
                    from err
            out.append([x[i] for i in idx])
    return out


def agree(system, forms=None, points=6, seed=2024, reference=True):
    """Check that the forms give the same accelerations for ``system``.

    ``forms``: names (keys of :data:`FORMS`), classes or built forms; default every
    form.  A form whose preconditions fail is listed with the reason.  ``reference``
    adds ``LagrangesMethod``.  Returns an :class:`Agreement`."""
    from .model import NonholonomicSystem
    if not isinstance(system, NonholonomicSystem):
        raise ModelTypeError("agree takes a NonholonomicSystem")
    forms = list(FORMS) if forms is None else list(forms)
    S = system
    rec = Agreement(S.name, [str(S.q[c]) for c in S.sigma])
    pts = _points(S, points, seed)
    results = []
    for f in forms:
        try:
            form = f if not isinstance(f, (str, type)) else form_class(f)(S)
            acc = form._accelerations()
            exprs = [acc[S.qdd[c]] for c in S.sigma]
            vals = _values(exprs, pts)
            n_eq = len(form._equations())
            results.append((form.name, vals))
            rec.rows.append(dict(name=form.name, equations=n_eq,
                                 multipliers=getattr(form, "multipliers_used", False),
                                 quasi=getattr(form, "quasi_velocities", False),
                                 difference=0.0, reason=""))
        except ModelError as err:
            name = f if isinstance(f, str) else getattr(f, "__name__", type(f).__name__)
            rec.rows.append(dict(name=name, equations=0, multipliers=False, quasi=False,
                                 difference=None, reason=str(err)))
    if reference:
        ref = lagranges_method_accelerations(S, pts)
        vals = [[ref[i][k] for i in range(len(pts))] for k in range(len(S.sigma))]
        results.append(("LagrangesMethod", vals))
        rec.rows.append(dict(name="LagrangesMethod", equations=len(S.coordinates) + len(S.beta),
                             multipliers=True, quasi=False, difference=0.0, reason=""))
    # the points where every result is finite
    good = [i for i in range(len(pts))
            if all(mpmath.isfinite(v[k][i]) for _, v in results for k in range(len(v)))]
    rec.points = len(good)
    with mpmath.workdps(DPS):
        def diff(a, b):
            worst = mpmath.mpf(0)
            for k in range(len(a)):
                for i in good:
                    x, y = a[k][i], b[k][i]
                    worst = max(worst, abs(x - y) / max(1, abs(x), abs(y)))
            return float(worst)
        for i, (na, va) in enumerate(results):
            for nb, vb in results[i + 1:]:
                rec.pairs[(na, nb)] = diff(va, vb)
        first = results[0][0] if results else None
        for r in rec.rows:
            if r["reason"] == "" and first is not None:
                r["difference"] = 0.0 if r["name"] == first else rec.pairs[(first, r["name"])]
    return rec
