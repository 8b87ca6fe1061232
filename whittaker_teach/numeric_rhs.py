"""Numeric right-hand sides of the equations, ready for an integrator: no substitution maps.

Like ``lambdify`` of ``LagrangesMethod.rhs()``: one function of (independent
variable, state, parameters) returning the state's derivative, generated once by
``sympy.lambdify`` with common subexpressions (``cse=True``).  The default module is
Python's ``math`` (plain floats, no numpy needed: the core runs without it);
``modules="mpmath"`` gives arbitrary precision, ``modules="numpy"`` arrays.

The order of the arguments is fixed and printed by ``str(f)``:

- ``ChaplyginSystem.lambdify_rhs()``: ``f(t, state, params)`` with
  ``state = [q_1, ..., q_n, qdot_sigma...]`` (every coordinate, then the independent
  velocities) and the result ``[qdot_1, ..., qdot_n, qddot_sigma...]`` (the dependent
  velocities from the constraints (1.3), the accelerations from (1.4));
- ``Reduction.lambdify_rhs()``: ``f(x, state, h, params)`` with
  ``state = [q_nu..., q'_nu..., t, q_dep...]`` and the result
  ``[q'_nu..., q''_nu..., dt/dx, dq_dep/dx...]`` ((1.26), (1.12), (1.23)): the reduced
  equations with time and the dependent coordinates recovered by quadrature.

``params`` is a sequence in the order of ``f.parameters`` (the system's parameters,
sorted by name) or a dict keyed by the parameter symbols or their names.

>>> import whittaker_teach as wt
>>> f = wt.examples.sledge().lambdify_rhs()
>>> f.state, f.parameters
(['x', 'theta', 'y', 'xdot', 'thetadot'], ['J', 'k', 'm'])
>>> [round(v, 6) for v in f(0.0, [0.0, 0.3, 0.0, 1.0, 0.5], {"J": 1, "k": 1, "m": 1})]
[1.0, 0.5, 0.309336, -0.154668, -0.3]
>>> g = wt.examples.sledge().reduce("x").lambdify_rhs()
>>> g
<RhsFunction f(x, state, h, params): state = ['theta', 'thetaprime', 't', 'y'], params = ['J', 'k', 'm'], returns d/dx of the state>
>>> [round(v, 6) for v in g(0.0, [0.3, 0.5, 0.0, 0.0], 2.0, [1, 1, 1])]
[0.5, -0.025916, 0.586657, 0.309336]
"""

from __future__ import annotations

import sympy as sp

from .errors import ModelError, ModelTypeError

__all__ = ["RhsFunction", "system_rhs", "reduction_rhs"]


class RhsFunction:
    """A compiled right-hand side ``f(x, state, [h,] params) -> list``; ``state``,
    ``parameters`` and ``outputs`` name the entries, ``variable`` the independent one."""

    def __init__(self, variable, state, outputs, parameters, exprs, modules, energy=None):
        self.variable = str(variable)
        self.state = [str(s) for s in state]
        self.outputs = list(outputs)
        self.parameters = [str(p) for p in parameters]
        self._params = list(parameters)
        self._energy = energy
        args = [variable, list(state)] + ([energy] if energy is not None else []) \
            + [list(parameters)]
        try:
            self._f = sp.lambdify(args, list(exprs), modules=modules, cse=True)
        except (ImportError, NameError, TypeError) as err:
            raise ModelError(f"lambdify_rhs: cannot generate the function with modules="
                             f"{modules!r}: {err}") from err

    def _param_values(self, params):
        if params is None:
            params = ()
        if isinstance(params, dict):
            by_name = {str(k): v for k, v in params.items()}
            missing = [p for p in self.parameters if p not in by_name]
            if missing:
                raise ModelError(f"no value for the parameter(s) {', '.join(missing)}; "
                                 f"the parameters are {self.parameters}")
            return [by_name[p] for p in self.parameters]
        params = list(params)
        if len(params) != len(self.parameters):
            raise ModelError(f"{len(params)} parameter value(s) for the parameters "
                             f"{self.parameters} (in this order)")
        return params

    def __call__(self, x, state, *rest):
        if len(state) != len(self.state):
            raise ModelError(f"the state has {len(state)} entries, expected "
                             f"{len(self.state)}: {self.state}")
        if self._energy is not None:
            if not rest:
                raise ModelTypeError("call f(x, state, h, params): the energy h is missing")
            h, rest = rest[0], rest[1:]
            return self._f(x, list(state), h, self._param_values(rest[0] if rest else None))
        return self._f(x, list(state), self._param_values(rest[0] if rest else None))

    def __repr__(self):
        h = ", h" if self._energy is not None else ""
        return (f"<RhsFunction f({self.variable}, state{h}, params): state = {self.state}, "
                f"params = {self.parameters}, returns d/d{self.variable} of the state>")


def system_rhs(system, modules="math"):
    """``f(t, state, params)`` of the full model (1.3), (1.4); see the module."""
    S = system
    q = [S.q[c] for c in S.coordinates]
    qd = [S.qd[c] for c in S._sig]
    phi = dict(zip(S.dependent_coordinates, S._phi.values()))
    acc = S._accelerations()
    rates = [phi[c] if c in phi else S.qd[c] for c in S.coordinates]
    exprs = rates + [acc[S.qdd[c]] for c in S._sig]
    f = RhsFunction(sp.Dummy("t"), q + qd, [f"{s}dot" for s in q] + [f"{s}ddot" for s in qd],
                    S.parameters, exprs, modules)
    f.variable = "t"
    return f


def reduction_rhs(red, modules="math"):
    """``f(x, state, h, params)`` of the reduced model (1.26) with t and the dependent
    coordinates by quadrature; see the module."""
    S = red.system
    qn = [S.q[c] for c in red._nus]
    qp = [red._qp[c] for c in red._nus]
    acc = red._accelerations()
    t = sp.Dummy("t")
    dep = [sp.Dummy(S.q[c].name) for c in S.dependent_coordinates]
    exprs = qp + [acc[red._qpp[c]] for c in red._nus] + [1 / red._vstar] + list(red._qdstar)
    state = qn + qp + [t] + dep
    f = RhsFunction(red.independent, state,
                    [f"{s}prime" for s in qn] + [f"{s}primeprime" for s in qn]
                    + ["dt/d" + str(red.independent)]
                    + [f"d{d}/d{red.independent}" for d in dep], S.parameters, exprs, modules,
                    energy=red.h)
    f.state = [str(s) for s in qn + qp] + ["t"] + [d.name for d in dep]
    f.outputs[-len(dep) or len(f.outputs):] = [f"d{d.name}/d{red.independent}" for d in dep]
    return f
