"""What every form shares: built on a :class:`~.model.NonholonomicSystem`, asked for its
equations, steps and the accelerations of the independent coordinates."""

from __future__ import annotations

from ..dag import substitute
from ..errors import ModelTypeError, guarded
from ..rewrite import rational
from ..steps import Derivation, Report, Step, eq
from ..verify import check_zero, shared_points
from .model import NonholonomicSystem

__all__ = ["Form"]


class Shown:
    """What every object with ``steps`` (a Derivation kept in ``_cache``) offers."""

    def verify(self):
        """The checks of the steps, re-run: a :class:`~whittaker_teach.steps.Report`."""
        self._cache.pop("steps", None)
        return Report(s.check for s in self.steps if s.check)

    def show(self, latex=False):
        """Show the steps (notebook: rendered; terminal: Unicode)."""
        return self.steps.show(latex=latex)


class Form(Shown):
    """A classical form of the equations of motion of one system (subclasses say which).

    Subclasses set ``label`` (printed in square brackets), ``title``, ``source``
    and ``needs`` (one line: what the form needs and gives), and implement
    ``_equations()`` (expressions = 0 in the internal symbols, linear in
    ``_unknowns()``) and ``_steps_before()`` (the steps that lead to them).
    """

    label = "?"
    title = "?"
    source = "?"
    needs = ""
    multipliers_used = False
    quasi_velocities = False

    def __init__(self, system):
        if not isinstance(system, NonholonomicSystem):
            raise ModelTypeError(f"{type(self).__name__} takes a NonholonomicSystem "
                                 f"(whittaker_teach.forms.NonholonomicSystem), got "
                                 f"{type(system).__name__}")
        self.system = system
        self._cache = {}
        self._require()

    def _require(self):
        """Raise ModelError when the form does not apply to the system."""

    # ----- to implement ---------------------------------------------------
    def _equations(self):
        raise NotImplementedError

    def _unknowns(self):
        """The symbols the equations are solved for (default: the independent q_sigma'')."""
        S = self.system
        return [S.qdd[c] for c in S.sigma]

    def _solution(self):
        """{unknown: expression}, solved from ``_equations()``."""
        if "sol" not in self._cache:
            unknowns = self._unknowns()
            sol = self.system.solve_linear(self._equations(), unknowns,
                                           f"the matrix of {self.name}'s equations")
            self._cache["sol"] = dict(zip(unknowns, sol))
        return self._cache["sol"]

    def _accelerations(self):
        """{qddot_sigma: expression in q and qdot_sigma}, internal symbols."""
        sol = self._solution()
        S = self.system
        return {S.qdd[c]: sol[S.qdd[c]] for c in S.sigma}

    def _steps_before(self):
        return []

    # ----- public ---------------------------------------------------------
    @property
    def name(self):
        return type(self).__name__

    @property
    @guarded("deriving the equations")
    def equations(self):
        """The equations of this form, expressions (= 0) in dynamicsymbols."""
        return [self.system.to_public(e) for e in self._equations()]

    @guarded("solving for the accelerations")
    def accelerations(self, dependent=False):
        """{q_sigma.diff(t, 2): expression} of the independent coordinates (with
        ``dependent=True`` also the dependent ones, from the constraints at acceleration
        level), in the coordinates and the independent velocities."""
        S = self.system
        acc = self._accelerations()
        sig = [S.qd[c] for c in S.sigma]
        out = {S.to_public(k): S.to_public(rational(v, sig)) for k, v in acc.items()}
        if dependent:
            memo = {}
            for c in S.beta:
                out[c.diff(S._t, 2)] = S.to_public(substitute(S.on_constraints[S.qdd[c]],
                                                              acc, memo))
        return out

    def _acceleration_step(self):
        S, acc = self.system, self._accelerations()
        sig = [S.qd[c] for c in S.sigma]
        chk = check_zero(self.label, f"the accelerations solved satisfy [{self.label}]",
                         self._equations(), S.sample, seed=5, at=self._solution())
        return Step(self.label + "a", "the accelerations of the independent coordinates",
                    lambda: [eq(k, rational(v, sig)) for k, v in acc.items()], chk)

    @property
    @guarded("deriving the steps")
    def steps(self):
        """The steps of this form: a :class:`~whittaker_teach.steps.Derivation`."""
        if "steps" not in self._cache:
            with shared_points():
                st = self._steps_before() + [self._acceleration_step()]
            self._cache["steps"] = Derivation(f"{self.system.name}: {self.title}", st)
        return self._cache["steps"]

    def __repr__(self):
        return f"<{self.name} [{self.label}] of {self.system.name!r}>"

