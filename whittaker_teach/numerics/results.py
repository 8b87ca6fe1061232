"""What a simulation returns: a :class:`Trajectory` (in t) or a :class:`Path` (in q_eps).

Both hold plain numpy arrays keyed by coordinate; a key may be the
dynamicsymbol ``x(t)``, its name ``"x"`` or the reduced function ``x(s)``.

>>> from sympy.physics.mechanics import dynamicsymbols
>>> x = dynamicsymbols("x")
>>> d = CoordDict({x: 1.5})
>>> d["x"], d[x]
(1.5, 1.5)
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import ModelError

__all__ = ["CoordDict", "Trajectory", "Path", "Switch", "Choice"]


def _key_name(key):
    if isinstance(key, str):
        return key
    func = getattr(key, "func", None)
    if func is not None and hasattr(key, "args") and getattr(key, "is_Function", False):
        return func.__name__
    name = getattr(key, "name", None)
    if name is not None:
        return name
    expr = getattr(key, "expr", None)          # x.diff(t) names the coordinate x
    return _key_name(expr) if expr is not None else None


class CoordDict(dict):
    """A dict keyed by coordinates that also accepts a coordinate's name."""

    def _resolve(self, key):
        if dict.__contains__(self, key):
            return key
        name = _key_name(key)
        for k in self:
            if _key_name(k) == name:
                return k
        raise KeyError(key)

    def __getitem__(self, key):
        return dict.__getitem__(self, self._resolve(key))

    def __contains__(self, key):
        try:
            self._resolve(key)
        except KeyError:
            return False
        return True

    def get(self, key, default=None):
        return self[key] if key in self else default


@dataclass
class Choice:
    """Which model and method ``simulate(..., tol=...)`` picked, and why.

    ``model`` ('exact', 'full' or 'reduced'), ``method``, ``rtol`` (None for the
    closed form), ``tol`` (the relative error asked for), ``error`` (the estimated
    relative error: for an integration, the difference between the runs at ten
    times ``rtol`` and at ``rtol``, the error of the looser one; the run returned, at
    ``rtol``, is normally more accurate still; for the closed form, its rounding
    error), ``why`` (plain words),
    ``tried``: every run made on the way, as (model, method, rtol, estimated
    error, evaluations); ``check_nfev``: the evaluations of the other run of the
    accepted pair; ``stiffness``: the :class:`~.scene.Stiffness` test of a full-model
    integration (None otherwise); ``nfev_all``: every evaluation the choice made.  ``str(choice)`` is the explanation.
    """

    model: str
    method: str
    rtol: object
    tol: float
    error: float
    why: str
    tried: list = field(default_factory=list)
    check_nfev: int = 0
    stiffness: object = None
    nfev_all: int = 0

    def __str__(self):
        import textwrap
        head = (f"{self.model} model, " + (f"{self.method} at rtol {self.rtol:.1e}"
                                           if self.rtol else self.method)
                + f": estimated relative error {self.error:.1e} <= tol {self.tol:g}")
        lines = [head] + textwrap.wrap("why: " + self.why, 78, subsequent_indent="  ")
        for model, method, rtol, err, nfev in self.tried:
            est = "" if err is None else f", estimated error {err:.1e}"
            lines.append(f"  tried {model} {method} rtol {rtol:.1e}{est} ({nfev} evaluations)")
        return "\n".join(lines)


def _explain(obj):
    if obj.choice is None:
        return (f"{obj.method}: chosen by the caller (simulate without tol); pass "
                "tol=... to let the package choose the model and the method")
    return str(obj.choice)


@dataclass
class Trajectory:
    """A motion integrated in time by :meth:`ChaplyginSystem.simulate`.

    ``t`` (array), ``q[c]`` and ``qdot[c]`` (arrays, every coordinate, the
    dependent ones included), ``energy`` (the energy integral 1.11 along the
    motion; ``h`` is its initial value), ``nfev`` (right-hand-side
    evaluations), ``njev`` (Jacobian evaluations).  Calling it, ``traj(t)``,
    interpolates the coordinates (dense output) and returns ``{coordinate:
    value}`` (arrays for an array ``t``).
    """

    t: object
    q: CoordDict
    qdot: CoordDict
    energy: object
    h: float
    nfev: int
    njev: int
    method: str
    formulation: str
    coordinates: list
    _dense: object = field(default=None, repr=False)
    choice: object = None       # a Choice when simulate(..., tol=...) picked the model

    def explain(self):
        """Which model and method made this trajectory, and why (see :class:`Choice`)."""
        return _explain(self)

    def __call__(self, t):
        if self._dense is None:
            raise ModelError("this trajectory was computed with dense=False: no "
                             "interpolation; simulate again with dense=True")
        import numpy as np
        t = np.asarray(t, dtype=float)
        lo, hi = sorted((self.t[0], self.t[-1]))
        if np.any((t < lo - 1e-12 * max(1, abs(lo))) | (t > hi + 1e-12 * max(1, abs(hi)))):
            raise ModelError(f"t outside the simulated interval [{lo}, {hi}]")
        vals = self._dense(t)
        out = CoordDict()
        for i, c in enumerate(self.coordinates):
            v = vals[i]
            out[c] = float(v) if np.ndim(v) == 0 else v
        return out

    @property
    def energy_error(self):
        """max |E(t) - h| / max(|h|, 1e-300): the relative drift of the energy integral."""
        import numpy as np
        return float(np.max(np.abs(self.energy - self.h)) / max(abs(self.h), 1e-300))

    def __repr__(self):
        return (f"<Trajectory: {len(self.t)} points, t in [{self.t[0]:g}, {self.t[-1]:g}], "
                f"{self.method} ({self.formulation}), nfev={self.nfev}>")


@dataclass
class Switch:
    """One change of chart along a :class:`Path`: where, from what, to what, and why."""

    s: float                  # q_eps (the original independent coordinate) at the switch
    t: float
    frm: str
    to: str
    reason: str


@dataclass
class Path:
    """A motion integrated in q_eps by :meth:`Reduction.simulate`.

    ``s`` (the values of q_eps), ``t`` (time recovered by quadrature of
    dt/dq_eps = 1/qdot_eps), ``q[c]`` (every coordinate: q_eps itself, the
    q_nu and the dependent ones), ``qp[c]`` (q'_nu = dq_nu/dq_eps), ``nfev``.
    Calling it, ``path(s)``, interpolates (dense output): ``{coordinate:
    value, "t": time}``.

    When the path met a turning point of q_eps and was continued
    (``on_turning_point="switch"``), ``switches`` lists where, and
    ``turning_points`` the (q_eps, t) where qdot_eps vanished; such a path is
    not a function of q_eps, so ``path(s)`` refuses (use the arrays).
    """

    s: object
    t: object
    q: CoordDict
    qp: CoordDict
    h: float
    nfev: int
    njev: int
    method: str
    independent: str
    direction: int
    coordinates: list
    switches: list = field(default_factory=list)
    turning_points: list = field(default_factory=list)
    segments: list = field(default_factory=list)
    _dense: object = field(default=None, repr=False)
    choice: object = None       # a Choice when simulate(..., tol=...) picked the model

    def explain(self):
        """Which model and method made this path, and why (see :class:`Choice`)."""
        return _explain(self)

    def __call__(self, s):
        import numpy as np
        if self.switches:
            raise ModelError(f"this path switched chart {len(self.switches)} time(s) (first "
                             f"at {self.independent} = {self.switches[0].s:.6g}): it is not a "
                             f"function of {self.independent}; use path.s, path.t, path.q")
        if self._dense is None:
            raise ModelError("this path was computed with dense=False: no interpolation")
        s = np.asarray(s, dtype=float)
        lo, hi = sorted((self.s[0], self.s[-1]))
        if np.any((s < lo - 1e-12 * max(1, abs(lo))) | (s > hi + 1e-12 * max(1, abs(hi)))):
            raise ModelError(f"{self.independent} outside the integrated span [{lo}, {hi}]")
        return self._dense(s)

    def __repr__(self):
        return (f"<Path in {self.independent}: {len(self.s)} points, {self.independent} in "
                f"[{self.s[0]:g}, {self.s[-1]:g}], t in [{self.t[0]:g}, {self.t[-1]:g}], "
                f"{self.method}, nfev={self.nfev}, {len(self.switches)} switch(es)>")
