"""The reduced model: the generalized Whittaker equations (1.26) integrated in q_eps.

:func:`simulate` is what :meth:`Reduction.simulate` calls.  The state is
(q_nu, q'_nu, t, q_dep) as functions of s = q_eps: q''_nu from (1.26), and
alongside, by quadrature, dt/ds = 1/qdot_eps with qdot_eps from the energy
(1.12) and dq_dep/ds = qdot*_dep (1.23).

>>> import whittaker_teach as wt
>>> red = wt.examples.sledge().reduce("x", +1)
>>> ex = wt.examples.sledge_exact({"m": 1, "J": 1, "k": 1}, a=0.5, C=1.0)
>>> q0, qp0, h = ex.reduced_initial()
>>> path = red.simulate(q0, qp0, h, (0.0, 5.0), {"m": 1, "J": 1, "k": 1}, rtol=1e-10)
>>> end = path(5.0)
>>> abs(end["theta"] - ex(end["t"])["theta"]) < 1e-8
True

**Turning points.**  The chart q_eps fails where qdot_eps vanishes: there
q'_nu = qdot_nu/qdot_eps blows up, or the radicand R = 2(h + A0) of (1.12)
reaches zero.  The integration watches the chart's quality

    rho = min( 1/sqrt(1 + sum q'_nu^2),  sqrt(R / (|2h| + |2 A0|)) )

(the share of qdot_eps in the velocity, and of the kinetic energy left) and
stops when rho falls to ``turning_tol`` (default 1e-3).  From there a short
integration in time tells what happens next.  With
``on_turning_point="raise"`` (default) a :class:`~whittaker_teach.ChartError`
names the coordinate and the value of q_eps where qdot_eps vanished (or, if it
only became small, where the chart became nearly singular).  Whether qdot_eps
vanishes is decided within the integration error: a motion that only comes within
that error of a turning point (the sledge at a = pi/2 - 1e-12, rtol 1e-10) may be
reported as turning, and one that turns back by less than it as not; the message
says so, and a tighter rtol decides (chapter 8).  With
``"switch"`` the path continues in time across the turning point and goes
back to the reduced equations, in the direction q_eps now runs, once rho
exceeds 4 ``turning_tol``; ``path.switches`` and ``path.turning_points`` say
where.  A turning point that falls on the end of the span ends the path.

**Round-off.**  A radicand R within round-off below zero (relative size
:data:`~whittaker_teach.numerics.validate.ROUNDOFF`) is clipped to zero; one
further below means the state is off the energy surface: a ModelError at the
start, a rejected trial step during the integration.  No NaN is produced.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ChartError, ModelError
from . import codegen, validate
from .ivp import ARITHMETIC, roots_within_steps, solve
from .results import CoordDict, Path, Switch

__all__ = ["simulate", "reduced_initial_state", "DEFAULT_TURNING_TOL"]

DEFAULT_TURNING_TOL = 1e-3
RESUME_FACTOR = 4.0
#: A starting slope |q'_nu| beyond this is refused: its square is out of floating point's
#: range (and the chart quality rho < 1e-150 is far below any turning_tol anyway).
MAX_SLOPE = 1e150


def _n(c):
    return c.func.__name__


def _clip(R, scale):
    """R >= 0, with round-off below zero clipped; None if R is truly negative."""
    if R >= 0:
        return R
    return 0.0 if R >= -validate.ROUNDOFF * scale else None


class _Chart:
    """One reduction (q_eps, direction), compiled and bound to the parameters and h."""

    def __init__(self, red, p, h, tau):
        self.red, self.p, self.h, self.tau = red, p, h, tau
        self.m = codegen.reduced_model(red)
        S = red.system
        self.eps = red._eps
        self.nus = list(red._nus)
        self.deps = list(S.dependent_coordinates)
        self.dir = red.direction
        self.nu = len(self.nus)
        self.size = 2 * self.nu + 1 + len(self.deps)
        self.name = f"{_n(self.eps)} ({self.dir:+d})"

    def radicands(self, s, zl):
        R, D, scale = self.m.radicands(*zl, s, self.h, *self.p)
        return float(R), float(D), float(scale)

    def fun(self):
        """f(s, z) for scipy.  A trial state where the chart is worse than half the
        turning tolerance gets infinite slopes: the step is rejected, so no accepted
        step jumps across a turning point (where q' passes through infinity)."""
        core, rad, nu, h, p, d = self.m.core, self.m.radicands, self.nu, self.h, self.p, self.dir
        inf = np.full(self.size, np.inf)
        lim = 4 / self.tau ** 2 - 1                 # 1/sqrt(1 + |q'|^2) < tau/2
        lim_r = self.tau ** 2 / 4                   # sqrt(R/scale) < tau/2

        def f(s, z):
            zl = z.tolist()
            if sum(x * x for x in zl[nu:2 * nu]) > lim:
                return inf
            try:
                R, D, scale = rad(*zl, s, h, *p)
                R = _clip(R, abs(scale))
                if not R or D <= 0 or R < lim_r * scale:
                    return inf
                sR, sD = math.sqrt(R), math.sqrt(D)
                out = core(*zl, s, h, sR, sD, *p)
            except (ZeroDivisionError, ValueError, OverflowError):
                return inf
            return np.array(zl[nu:2 * nu] + out[:nu] + [d * sD / sR] + out[nu:])
        return f

    def jac(self):
        """jac(s, z) for the implicit methods (the unclipped symbolic Jacobian)."""
        raw, h, p, n = self.m.jac, self.h, self.p, self.size

        def j(s, z):
            try:
                return np.array(raw(*z.tolist(), s, h, *p), dtype=float)
            except (ZeroDivisionError, ValueError, OverflowError):
                return np.full((n, n), np.inf)
        return j

    def quality(self, s, zl):
        """rho: min(1/sqrt(1 + |q'|^2), sqrt(R/scale))."""
        qp = zl[self.nu:2 * self.nu]
        R, _D, scale = self.radicands(s, zl)
        R = max(R, 0.0)
        if not scale > 0:                   # h = 0 = A0: no kinetic energy at all
            return 0.0
        return min(1 / math.sqrt(1 + sum(x * x for x in qp)), math.sqrt(R / scale))

    def speed(self, s, zl):
        """qdot_eps = direction sqrt(R/D) (1.12), R clipped at zero."""
        R, D, scale = self.radicands(s, zl)
        R = _clip(R, abs(scale))
        if R is None:
            raise ModelError(f"the state at {_n(self.eps)} = {s:.10g} is off the energy "
                             f"surface: 2(h + A0) = {self.radicands(s, zl)[0]:.3g} < 0 (1.13)")
        return self.dir * math.sqrt(R / D)

    def to_time(self, s, zl):
        """(q of every coordinate in system order, qdot_sigma in system order, t)."""
        S = self.red.system
        v = self.speed(s, zl)
        q = {self.eps: s}
        qd = {self.eps: v}
        for i, c in enumerate(self.nus):
            q[c] = zl[i]
            qd[c] = v * zl[self.nu + i]
        for j, c in enumerate(self.deps):
            q[c] = zl[2 * self.nu + 1 + j]
        return ([q[c] for c in S.coordinates], [qd[c] for c in S.independent_coordinates],
                zl[2 * self.nu])

    def from_time(self, q, v, t):
        """z from the coordinates (system order), independent velocities and t."""
        S = self.red.system
        qm = dict(zip(S.coordinates, q))
        vm = dict(zip(S.independent_coordinates, v))
        ve = vm[self.eps]
        return (qm[self.eps], [qm[c] for c in self.nus] + [vm[c] / ve for c in self.nus]
                + [t] + [qm[c] for c in self.deps])


class _TimeBridge:
    """The full model in t, used across a turning point of q_eps."""

    def __init__(self, system, p, eps):
        self.S, self.p = system, p
        self.fm = codegen.time_model(system, "auto")
        self.form = self.fm.formulation
        self.n = len(system.coordinates)
        self.ie = system.coordinates.index(eps)
        sig = system.independent_coordinates
        self.iv = ([self.n + i for i in range(len(sig))] if self.form == "chaplygin"
                   else [self.n + system.coordinates.index(c) for c in sig])
        self.je = sig.index(eps)

    def state(self, q, v):
        if self.form == "chaplygin":
            return np.array(q + v)
        allv = [float(w) for w in self.fm.from_independent(*q, *v, *self.p)]
        return np.array(q + allv)

    def split(self, y):
        return y[:self.n].tolist(), [y[i] for i in self.iv]


def _reduction(red, direction):
    """The reduction of the same system and q_eps in ``direction`` (``red`` itself, or one
    made once and cached on the system: a path that switches reuses its code)."""
    if direction == red.direction:
        return red
    cache = codegen.cache_of(red.system).setdefault("reductions", {})
    key = (_n(red._eps), direction)
    if key not in cache:
        cache[key] = red.system.reduce(red._eps, direction)
    return cache[key]


def simulate(red, q0, qp0, h, span, params, method="DOP853", rtol=1e-9, atol=None, *,
             on_turning_point="raise", turning_tol=DEFAULT_TURNING_TOL, t0=0.0, dense=True,
             max_switches=1000, max_bridge_time=None):
    """Integrate the reduced model in q_eps; see :meth:`Reduction.simulate`.

    The input is checked once (:func:`.validate.reduced_input`), then the compiled
    model (:func:`.codegen.reduced_model`, cached) and :func:`.ivp.solve` run."""
    try:
        inp = validate.reduced_input(red, q0, qp0, h, span, params, method, rtol, atol,
                                     on_turning_point, turning_tol, t0, max_bridge_time)
        return _simulate(red, inp, dense, max_switches)
    except ARITHMETIC as err:
        raise ModelError(f"{red.system.name}, reduced model in {_n(red._eps)}: the arithmetic "
                         f"failed ({err}); the initial state, h or the parameters are out of "
                         "the range of floating point (a speed or a slope q' too small or too "
                         "large: with qdot_eps near 0 the chart degenerates, use the time "
                         "model)") from None


def _simulate(red, inp, dense, max_switches):
    q, qp, h, (a, b), p, t0 = inp.q, inp.qp, inp.h, inp.span, inp.p, inp.t0
    S, eps = red.system, red._eps
    chart = _Chart(red, p, h, inp.tau)
    z0 = ([q[c] for c in red._nus] + [qp[c] for c in red._nus]
          + [t0] + [q[c] for c in S.dependent_coordinates])
    big = [(_n(c), qp[c]) for c in red._nus if not abs(qp[c]) <= MAX_SLOPE]
    if big:
        e = _n(eps)
        err = ChartError(f"qdot_{e} is (nearly) zero at the start, {e} = {a:.10g}: the slope "
                         f"{big[0][0]}' = d{big[0][0]}/d{e} = {big[0][1]:.3g} is beyond "
                         f"{MAX_SLOPE:.0e} (q' = qdot/qdot_{e}, 1.5); {e} cannot replace time "
                         "here, the reduction degenerates.  Use the time model "
                         "(system.simulate) or another independent coordinate")
        err.coordinate, err.value, err.t = e, a, float(t0)
        raise err
    R0, D0, scale0 = chart.radicands(a, z0)
    if _clip(R0, abs(scale0)) is None:
        raise ModelError(f"the initial state violates the energy integral: with h = {h:g}, "
                         f"2(h + A0) = {R0:.6g} < 0 at the start, so (1.12) gives no real "
                         f"qdot_{_n(eps)} (h is below the potential energy there, 1.13)")
    if not D0 > 0:
        raise ModelError(f"2 A2 = {D0:.6g} <= 0 at the start: the kinetic energy along "
                         f"{_n(eps)} is not positive (1.13)")
    run = _Run(red, chart, p, h, inp.method, inp.rtol, inp.atol, inp.tau,
               inp.on_turning_point, (a, b), max_switches, inp.max_bridge_time, dense)
    return run.go(a, z0)


class _Run:
    """One call of :func:`simulate`: the segments in q_eps (and in t across turning points)."""

    def __init__(self, red, chart, p, h, method, rtol, atol, tau, mode, span, max_switches,
                 max_bridge_time, dense):
        self.red, self.S, self.p, self.h = red, red.system, p, h
        self.method, self.rtol, self.atol, self.tau, self.mode = method, rtol, atol, tau, mode
        self.span, self.max_switches, self.dense = span, max_switches, dense
        self.chart0 = chart
        self.eps = red._eps
        self.segments, self.switches, self.turns = [], [], []
        self.nfev = self.njev = 0
        self.max_bridge_time = max_bridge_time
        self._bridge = None

    # ----- the loop -------------------------------------------------------
    def go(self, s, z):
        chart = self.chart0
        self.t_start = z[2 * chart.nu]
        v0 = abs(chart.speed(s, z))
        self.v0 = v0
        if chart.quality(s, z) <= self.tau:
            if self.mode == "raise":
                self._degenerate_start(chart, s, z)
            y, t = self._to_time(chart, s, z)
            self.switches.append(Switch(s, t, chart.name, "t", "the chart is degenerate at "
                                        "the start (qdot_eps nearly zero)"))
            return self._time_phase(y, t)
        return self._reduced_phase(chart, s, z)

    def _reduced_phase(self, chart, s, z):
        while True:
            ended, s, z = self._reduced_segment(chart, s, z)
            if ended:
                return self._finish()
            y, t = self._to_time(chart, s, z)
            if self.mode == "raise":
                self._look_ahead(chart, s, z, y, t)      # raises, or ends at the span's end
                return self._finish()
            self.switches.append(Switch(s, t, chart.name, "t", f"qdot_{_n(self.eps)} small: "
                                        f"rho = {self.tau:.1e} (turning point ahead?)"))
            return self._time_phase(y, t)

    def _time_phase(self, y, t):
        while True:
            if len(self.switches) > self.max_switches:
                raise ChartError(f"more than {self.max_switches} chart switches before "
                                 f"{_n(self.eps)} reached {self.span[1]}")
            outcome, y, t = self._time_segment(y, t)
            if outcome == "end":
                return self._finish()
            q, v = self.bridge.split(y)
            d = 1 if v[self.bridge.je] > 0 else -1
            chart = _Chart(_reduction(self.red, d), self.p, self.h, self.tau)
            s, z = chart.from_time(q, v, t)
            self.switches.append(Switch(s, t, "t", chart.name, "the chart is regular again"))
            ended, s, z = self._reduced_segment(chart, s, z)
            if ended:
                return self._finish()
            y, t = self._to_time(chart, s, z)
            self.switches.append(Switch(s, t, chart.name, "t", f"qdot_{_n(self.eps)} small"))

    # ----- reduced segments -----------------------------------------------
    def _reduced_segment(self, chart, s, z):
        a, b = self.span
        toward = (b - s) * chart.dir > 0
        bound = b if toward else s + chart.dir * (2 * abs(b - a) + abs(s - a) + 1.0)
        tau = self.tau

        def ev(si, zi):
            return chart.quality(si, zi.tolist()) - tau
        ev.terminal, ev.direction = True, -1
        events = [ev] + _pole_events(chart)
        sol = solve(None, None, (s, bound), list(z), self.p, self.method, self.rtol,
                    self.atol, events=events, dense=self.dense,
                    what=f"{self.S.name}, reduced model in {_n(self.eps)}",
                    fun=chart.fun(), jac_fun=chart.jac())
        self.nfev += sol.nfev
        self.njev += sol.njev
        if sol.status == 1:
            if len(sol.t_events[0]):
                self.segments.append(("reduced", chart, sol, len(sol.t)))
                return False, float(sol.t_events[0][0]), sol.y_events[0][0].tolist()
            # a pole was crossed within the last step: go back to its start
            keep = max(len(sol.t) - 2, 1)
            self.segments.append(("reduced", chart, sol, keep))
            return False, float(sol.t[keep - 1]), sol.y[:, keep - 1].tolist()
        self.segments.append(("reduced", chart, sol, len(sol.t)))
        if not toward:
            raise ChartError(f"the path runs away from {_n(self.eps)} = {b}: after a turning "
                             f"point it went {abs(bound - s):.3g} the other way without "
                             "turning back")
        return True, float(sol.t[-1]), sol.y[:, -1].tolist()

    # ----- time segments --------------------------------------------------
    @property
    def bridge(self):
        if self._bridge is None:
            self._bridge = _TimeBridge(self.S, self.p, self.eps)
        return self._bridge

    def _to_time(self, chart, s, z):
        q, v, t = chart.to_time(s, z)
        return self.bridge.state(q, v), t

    def _time_limit(self, t):
        if self.max_bridge_time is not None:
            return self.max_bridge_time
        a, b = self.span
        return 10 * max(abs(t - self.t_start), abs(b - a) / max(self.v0, 1e-300), 1e-6)

    def _time_events(self, resume):
        B, ie, je, chart = self.bridge, self.bridge.ie, self.bridge.je, self.chart0
        b = self.span[1]
        h, p, nu = self.h, self.p, chart.nu
        zero_qp = [0.0] * nu

        def recover(t, y):
            q, v = B.split(y)
            qm = dict(zip(self.S.coordinates, q))
            zl = [qm[c] for c in chart.nus] + zero_qp + [t] + [qm[c] for c in chart.deps]
            R, _D, scale = chart.m.radicands(*zl, q[ie], h, *p)
            ratio = abs(v[je]) / math.sqrt(sum(w * w for w in v))
            return min(ratio, math.sqrt(max(R, 0.0) / scale)) - resume

        def end(t, y):
            return y[ie] - b
        recover.terminal, recover.direction = True, 1
        end.terminal = True
        return [recover, end]

    def _turns(self, sol):
        """[(q_eps, t)] where qdot_eps vanishes along a time segment, found inside the
        steps too (x may reverse by less than a step and come back within it)."""
        B = self.bridge
        iv = B.iv[B.je]

        def g(t, Y):
            return Y[iv]
        ts = roots_within_steps(sol, g)
        return [(float(sol.sol(t)[B.ie]), float(t)) for t in ts]

    def _time_segment(self, y, t):
        """Integrate in t from a turning region: ('recover' | 'end', y, t)."""
        B = self.bridge
        events = self._time_events(RESUME_FACTOR * self.tau)
        sol = solve(B.fm.rhs, B.fm.jac, (t, t + self._time_limit(t)), y, self.p,
                    self.method, self.rtol, self.atol, events=events, dense=True,
                    what=f"{self.S.name}, time model across a turning point of "
                         f"{_n(self.eps)}")
        self.nfev += sol.nfev
        self.njev += sol.njev
        self.turns.extend(self._turns(sol))
        sol.sol = None                       # the steps are kept; the interpolants are not
        self.segments.append(("time", B, sol, len(sol.t)))
        if len(sol.t_events[1]):
            return "end", sol.y_events[1][0], float(sol.t_events[1][0])
        if len(sol.t_events[0]):
            return "recover", sol.y_events[0][0], float(sol.t_events[0][0])
        raise ChartError(f"{_n(self.eps)} stays (nearly) stationary: in "
                         f"{self._time_limit(t):.3g} time units after t = {t:.6g} the chart "
                         f"{_n(self.eps)} did not become regular again; set max_bridge_time "
                         "or use the time model")

    # ----- raise mode -----------------------------------------------------
    def _degenerate_start(self, chart, s, z):
        rho = chart.quality(s, z)
        e = _n(self.eps)
        R, _D, scale = chart.radicands(s, z)
        turning = ""
        if R <= validate.ROUNDOFF * abs(scale) or not scale > 0:
            turning = (f"the start is a turning point of {e} (h = {self.h:.6g} leaves no "
                       f"kinetic energy: 2(h + A0) = {R:.3g}, 1.12); ")
        err = ChartError(
            f"qdot_{e} is (nearly) zero at the start, {e} = {s:.10g}: {turning}"
            f"the chart quality rho = "
            f"{rho:.2e} <= turning_tol = {self.tau:g} (|q'| = dq/d{e} too large, or almost no "
            f"kinetic energy left); {e} cannot replace time here (1.5), the reduction "
            f"degenerates.  Use the time model (system.simulate), another independent "
            f"coordinate, or on_turning_point='switch'")
        err.coordinate, err.value, err.t = e, s, z[2 * chart.nu]
        raise err

    def _look_ahead(self, chart, s, z, y, t):
        """After the chart degenerated at (s, z): find out why, by a short run in time."""
        B = self.bridge
        e = _n(self.eps)
        events = self._time_events(RESUME_FACTOR * self.tau)
        sol = solve(B.fm.rhs, B.fm.jac, (t, t + self._time_limit(t)), y, self.p,
                    self.method, self.rtol, self.atol, events=events, dense=True,
                    what=f"{self.S.name}, time model after {e} = {s:.6g}")
        b = self.span[1]
        tol = 10 * (self.atol + self.rtol * abs(b))
        turns = self._turns(sol)
        if turns:
            s_t, t_t = turns[0]
            if abs(s_t - b) <= tol:
                _cut(sol, t_t)                   # the path ends at the turning point
                sol.sol = None
                self.nfev += sol.nfev
                self.segments.append(("time", B, sol, len(sol.t)))
                self.turns.append((s_t, t_t))
                self.switches.append(Switch(s, t, chart.name, "t", f"turning point at the "
                                            f"end of the span, {e} = {s_t:.10g}"))
                return
            err = ChartError(
                f"qdot_{e} vanishes, or nearly vanishes, within the integration error at "
                f"{e} = {s_t:.10g} (t = {t_t:.10g}): a turning point of {e}.  Beyond it {e} "
                f"runs backward, so it cannot serve as the independent variable (1.5: "
                f"q' = qdot/qdot_{e} blows up); the reduced model stopped at {e} = {s:.10g}.  "
                f"A motion that only comes within the integration error of a turning point "
                f"(qdot_{e} small but of one sign) cannot be told from one at this "
                f"tolerance: tighten rtol to decide.  Pass on_turning_point='switch' to "
                "continue across it (in time, then in the other direction)")
            err.coordinate, err.value, err.t = e, s_t, t_t
            raise err
        if len(sol.t_events[1]):
            self.nfev += sol.nfev
            self.segments.append(("time", B, sol, len(sol.t)))
            self.switches.append(Switch(s, t, chart.name, "t", "nearly singular chart up to "
                                        "the end of the span"))
            return
        err = ChartError(
            f"the chart {e} is nearly singular at {e} = {s:.10g} (t = {t:.10g}): d{e}/dt "
            f"fell to {self.tau:g} of the speed without vanishing (no turning point); the "
            f"reduced equations divide by it, and the step size collapses there.  Pass "
            f"on_turning_point='switch' to "
            f"cross such a stretch in time, or lower turning_tol")
        err.coordinate, err.value, err.t = e, s, t
        raise err

    # ----- output ---------------------------------------------------------
    def _finish(self):
        S = self.S
        coords = S.coordinates
        s_l, t_l, q_l, qp_l = [], [], {c: [] for c in coords}, {c: [] for c in self.red._nus}
        for k, (kind, obj, sol, keep) in enumerate(self.segments):
            cut = 0 if k == 0 else 1
            if kind == "reduced":
                s_, t_, q_, qp_ = _reduced_arrays(obj, sol)
            else:
                s_, t_, q_, qp_ = _time_arrays(obj, sol, self.eps, self.red._nus)
            s_l.append(s_[cut:keep])
            t_l.append(t_[cut:keep])
            for c in coords:
                q_l[c].append(q_[c][cut:keep])
            for c in self.red._nus:
                qp_l[c].append(qp_[c][cut:keep])
        q = CoordDict((c, np.concatenate(q_l[c])) for c in coords)
        qp = CoordDict((c, np.concatenate(qp_l[c])) for c in self.red._nus)
        dense = None
        if self.dense and len(self.segments) == 1 and self.segments[0][0] == "reduced":
            dense = _dense(self.segments[0][1], self.segments[0][2].sol)
        return Path(np.concatenate(s_l), np.concatenate(t_l), q, qp, self.h, int(self.nfev),
                    int(self.njev), self.method, _n(self.eps), self.red.direction,
                    list(coords), self.switches, self.turns,
                    [(k, getattr(o, "name", "t"), float(sol.t[0]), float(sol.t[keep - 1]))
                     for k, o, sol, keep in self.segments], dense)


def _cut(sol, t_end):
    """Keep the steps of ``sol`` before ``t_end`` and end it there (dense output needed)."""
    keep = (sol.t - t_end) * np.sign(sol.t[-1] - sol.t[0]) < 0
    sol.y = np.column_stack([sol.y[:, keep], sol.sol(t_end)])
    sol.t = np.append(sol.t[keep], t_end)


def _pole_events(chart):
    """Terminal events where a denominator of the reduced equations changes sign: a
    step that crossed a pole is caught even if the quality event missed it."""
    fn, h, p = chart.m.poles, chart.h, chart.p
    if fn is None:
        return []
    events = []
    for i in range(len(chart.m.pole_names)):
        def ev(s, z, i=i):
            vals = fn(*z.tolist(), s, h, *p)
            return vals[i] if isinstance(vals, (list, tuple)) else vals
        ev.terminal = True
        events.append(ev)
    return events


def _reduced_arrays(chart, sol):
    Z, s = sol.y, sol.t
    nu = chart.nu
    S = chart.red.system
    q = {chart.eps: s}
    for i, c in enumerate(chart.nus):
        q[c] = Z[i]
    for j, c in enumerate(chart.deps):
        q[c] = Z[2 * nu + 1 + j]
    qp = {c: Z[nu + i] for i, c in enumerate(chart.nus)}
    return s, Z[2 * nu], {c: q[c] for c in S.coordinates}, qp


def _time_arrays(bridge, sol, eps, nus):
    Y = sol.y
    q = {c: Y[i] for i, c in enumerate(bridge.S.coordinates)}
    sig = bridge.S.independent_coordinates
    v = {c: Y[bridge.iv[i]] for i, c in enumerate(sig)}
    with np.errstate(all="ignore"):
        qp = {c: v[c] / v[eps] for c in nus}
    return q[eps], sol.t, q, qp


def _dense(chart, solution):
    S, nu = chart.red.system, chart.nu

    def f(s):
        Z = solution(s)
        out = CoordDict()
        out[chart.eps] = s
        for i, c in enumerate(chart.nus):
            out[c] = Z[i]
        for j, c in enumerate(chart.deps):
            out[c] = Z[2 * nu + 1 + j]
        ordered = CoordDict((c, _scalar(out[c])) for c in S.coordinates)
        ordered["t"] = _scalar(Z[2 * nu])
        return ordered
    return f


def _scalar(v):
    return float(v) if np.ndim(v) == 0 else np.asarray(v)


def reduced_initial_state(red, q0, qdot0, params):
    """(q0, qp0, h) for :meth:`Reduction.simulate` from a time-domain state.

    ``q0``: every coordinate; ``qdot0``: the independent velocities.  h is the
    energy (1.11) of that state; q'_nu = qdot_nu/qdot_eps (1.5).

    >>> import whittaker_teach as wt
    >>> red = wt.examples.sledge().reduce("x", +1)
    >>> q0, qp0, h = reduced_initial_state(red, {"x": 0, "theta": 0.5, "y": 0},
    ...                                    {"x": 2.0, "theta": 1.0}, {"m": 1, "J": 1, "k": 1})
    >>> qp0, round(h, 12)
    ({'theta': 0.5}, 3.221892820819)
    """
    S, eps = red.system, red._eps
    q, v, p = validate.state_input(S, q0, qdot0, params)
    fm = codegen.time_model(S, "chaplygin")
    y0 = fm.initial_state(q, v, p)
    n = len(S.coordinates)
    h = float(fm.energy(*y0, *p))
    v = dict(zip(S.independent_coordinates, y0[n:]))
    if v[eps] * red.direction <= 0:
        raise ModelError(f"qdot_{_n(eps)} = {v[eps]} does not have the sign "
                         f"{red.direction:+d} of this reduction")
    q = {_n(c): float(x) for c, x in zip(S.coordinates, y0[:n])}
    return q, {_n(c): float(v[c] / v[eps]) for c in red._nus}, h
