"""The forms' cost on the chain of spring-coupled Chaplygin sleighs, against
sympy.physics.mechanics (printed, never asserted).

``python -m whittaker_teach.forms.bench [n ...]`` (default n = 3 6 9): for the chain
with n coordinates (:func:`whittaker_teach.bench.chain`, g = n // 3 constraints), the
CPU time of each form to derive its equations and solve them for the accelerations
(a fresh model each, built from the mechanics user's Lagrangian and constraints; the
model's checks included, the building of the mechanics model not),
and of LagrangesMethod (forming the equations and ``rhs()``) and KanesMethod
(``kanes_equations`` and ``rhs()``), in this process, one run each, SymPy's cache
cleared before each: figures to compare orders of magnitude, not a timing test.
What is timed differs a little: the forms' accelerations are solved but not tidied;
the peers' ``rhs()`` solves the full mass matrix (every coordinate and, for
LagrangesMethod, the multipliers).

>>> rows = rows_for([3], forms=["Maggi"], peers=False)
>>> sorted(rows[0])
['Maggi', 'n']
"""

from __future__ import annotations

import sys
import time

__all__ = ["rows_for", "table", "main"]

PEERS = ("LagrangesMethod", "KanesMethod")


def _time(fn):
    from sympy.core.cache import clear_cache
    clear_cache()           # each run starts with SymPy's cache empty
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def rows_for(ns, forms=None, peers=True):
    """[{"n": n, form: seconds, ..., peer: seconds}] for each n."""
    from ..bench import chain, run_kane_chain, run_lagrange_chain
    from .compare import FORMS, form_class
    from .model import NonholonomicSystem
    forms = list(FORMS) if forms is None else list(forms)
    rows = []
    for n in ns:
        row = {"n": n}
        F = chain(n)            # the mechanics user's model, built once (not timed)
        for name in forms:
            def run():
                S = NonholonomicSystem(F["L"], F["q"], constraints=F["coneqs"],
                                       dependent=F["dependent"])
                form_class(name)(S)._accelerations()
            row[name] = _time(run)
        if peers:
            from sympy.core.cache import clear_cache
            clear_cache()
            row["LagrangesMethod"] = run_lagrange_chain(n)["peer"]
            clear_cache()
            row["KanesMethod"] = run_kane_chain(n)["peer"]
        rows.append(row)
    return rows


def table(rows):
    """The rows as a text table, seconds with two significant figures."""
    names = [k for k in rows[0] if k != "n"]
    w = max(len(k) for k in names)
    lines = ["CPU seconds to the accelerations, chain of sleighs (g = n // 3)",
             "form".ljust(w) + "".join(f"  n={r['n']:<6}" for r in rows)]
    for k in names:
        lines.append(k.ljust(w) + "".join(f"  {r[k]:<8.2g}" for r in rows))
    return "\n".join(lines)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ns = [int(a) for a in argv] or [3, 6, 9]
    print(table(rows_for(ns)))


if __name__ == "__main__":
    main()
