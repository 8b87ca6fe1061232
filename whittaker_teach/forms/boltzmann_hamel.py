"""The Boltzmann-Hamel equations (Boltzmann 1902, Hamel 1904): quasi-velocities and
Hamel's (transpositional) coefficients.

Quasi-velocities omega_r = sum_s a_rs(q) qdot_s (r = 1..n), chosen so that the
constraints read omega_beta = 0: the user's n - g independent ones, then the
constraints as given, a_beta,s = df_beta/dqdot_s; or by default the natural ones,
omega_sigma = qdot_sigma and omega_beta = qdot_beta - phi_beta (then b is known
without inverting a).  With b = a^(-1) (qdot_s = sum_r b_sr omega_r) [BHb] and L*(q,
omega) = L(q, b omega) [BHL], Hamel's coefficients [BHg] (the transpositional
relations d(delta pi_r) - delta(d pi_r) = sum gamma^r_kl omega_l delta pi_k)

    gamma^r_kl = sum_s,t (da_rs/dq_t - da_rt/dq_s) b_sk b_tl

give, for each independent quasi-velocity k,

    d/dt dL*/domega_k - sum_s b_sk dL*/dq_s + sum_r,l gamma^r_kl omega_l dL*/domega_r = 0   [BH]

taken at omega_beta = 0; the quasi-accelerations omegadot_k are solved and the
accelerations of the coordinates follow (qddot = bdot omega + b omegadot) [BHa].
Only linear constraints (A(q) qdot = 0) have quasi-velocities of this kind: a
nonlinear constraint is a ModelError.

>>> from whittaker_teach.forms import examples, BoltzmannHamel
>>> bh = BoltzmannHamel(examples.sledge())
>>> bh.hamel_coefficients()        # {(r, k, l): gamma}, those not zero, k < l
{(omega_3, omega_1, omega_2): -tan(theta)**2 - 1}
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..dag import along, substitute
from ..errors import ModelError
from ..rewrite import rational
from ..steps import Step, eq, notation
from ._form import Form
from ._print import indexed, tidy

__all__ = ["BoltzmannHamel"]


def _tidy(e):
    """One fraction (``rewrite.rational``, bounded), sin^2 + cos^2 read as 1 where that
    shortens it (:func:`._print.tidy`)."""
    return tidy(e)


class BoltzmannHamel(Form):
    """Boltzmann-Hamel equations in quasi-velocities (Boltzmann 1902, Hamel 1904).

    ``quasi_velocities``: None (the natural ones, omega_sigma = qdot_sigma) or a list
    of n - g expressions linear in the velocities (dynamicsymbols), the independent
    quasi-velocities; with the constraints they must form a regular matrix a(q)."""

    label = "BH"
    title = "Boltzmann-Hamel: quasi-velocities"
    source = "L. Boltzmann (1902), G. Hamel (1904)"
    needs = "n - g equations in quasi-accelerations; the inverse b of a and Hamel's coefficients"
    quasi_velocities = True

    def __init__(self, system, quasi_velocities=None):
        self._given = quasi_velocities
        super().__init__(system)

    @property
    def name(self):
        return "BoltzmannHamel" if self._given is None else "BoltzmannHamel (omega given)"

    def _require(self):
        S = self.system
        if not S.is_linear:
            raise ModelError("Boltzmann-Hamel equations need constraints linear in the "
                             "velocities (quasi-velocities omega = a(q) qdot with omega_beta = "
                             "0 on the constraints); this system has a nonlinear (Chetaev) "
                             "constraint")
        n, g = len(S.coordinates), len(S.beta)
        self.omega = list(sp.symbols(f"omega_1:{n + 1}"))
        self.omegadot = list(sp.symbols(f"omegadot_1:{n + 1}"))
        qd = [S.qd[c] for c in S.coordinates]
        if self._given is None:
            rows = [[sp.S.One if c == s else sp.S.Zero for c in S.coordinates] for s in S.sigma]
        else:
            given = list(self._given)
            if len(given) != n - g:
                raise ModelError(f"{len(given)} quasi-velocities given: give n - g = {n - g}, "
                                 "the independent ones (the constraints are the others)")
            rows = []
            for w in given:
                e = S.to_internal(sp.sympify(w))
                row = [S._d(e, v) for v in qd]
                if any(S._d(r, v) != 0 for r in row for v in qd) or \
                        substitute(e, {v: sp.S.Zero for v in qd}) != 0:
                    raise ModelError(f"the quasi-velocity {w} is not linear and homogeneous "
                                     "in the velocities: omega = a(q) qdot")
                rows.append(row)
        # the constraints: as given with the user's quasi-velocities (the sideways
        # velocity of a sleigh, say); in the solved form, omega_beta = qdot_beta -
        # phi_beta, with the natural ones (then b is known: no inversion)
        fs = S._f if self._given is not None else [S.qd[b] - S._phi[b] for b in S.beta]
        for f in fs:
            rows.append([S._d(f, v) for v in qd])
        self.a = sp.Matrix(rows)
        if self._given is None:
            # natural quasi-velocities: a = [[1, 0], [-B, 1]] in (sigma, beta), so b is
            # [[1, 0], [B, 1]]: qdot_sigma = omega_sigma, qdot_beta = B omega + omega_beta
            cols = {k: c for k, c in enumerate(S.sigma)}
            cols.update({n - g + j: c for j, c in enumerate(S.beta)})
            self.b = sp.Matrix(n, n, lambda i, k: (
                S.C(S.coordinates[i], cols[k]) if k < n - g else
                (sp.S.One if S.coordinates[i] == cols[k] else sp.S.Zero)))
            self._ind = list(range(n - g))
            return
        # b = a^-1, column by column (a regular: checked at a sampled point)
        cols = []
        for k in range(n):
            e = [sp.S.One if i == k else sp.S.Zero for i in range(n)]
            eqs = [add(*[mul(self.a[i, j], sp.Symbol(f"_b{j}")) for j in range(n)], -e[i])
                   for i in range(n)]
            try:
                cols.append(S.solve_linear(eqs, [sp.Symbol(f"_b{j}") for j in range(n)],
                                           "the matrix a of the quasi-velocities"))
            except ModelError as err:
                raise ModelError("the quasi-velocities and the constraints are not "
                                 "independent: their matrix a(q) is singular") from err
        # each entry one fraction (a targeted cancel on a small piece, bounded)
        self.b = sp.Matrix(n, n, lambda i, k: rational(cols[k][i]))
        self._ind = list(range(n - g))       # the indices of the independent omegas

    # ----- pieces ---------------------------------------------------------
    def _Lstar(self):
        if "L*" not in self._cache:
            S = self.system
            n = len(S.coordinates)
            sub = {S.qd[c]: add(*[mul(self.b[i, r], self.omega[r]) for r in range(n)
                                  if self.b[i, r] != 0])
                   for i, c in enumerate(S.coordinates)}
            self._cache["L*"] = substitute(S._L, sub)
        return self._cache["L*"]

    def hamel_coefficients(self):
        """{(omega_r, omega_k, omega_l): gamma^r_kl} for the independent k < l, those not
        zero (gamma^r_lk = -gamma^r_kl), in the internal symbols."""
        if "gamma" not in self._cache:
            S = self.system
            n = len(S.coordinates)
            q = [S.q[c] for c in S.coordinates]
            # the non-zero da_rs/dq_t - da_rt/dq_s, s < t, per r (a sparse a has few)
            curl = []
            for r in range(n):
                nz = {(s, t): self.a[r, s] for s in range(n) if self.a[r, s] != 0
                      for t in range(n) if self.a[r, s].has(q[t])}
                pairs = {}
                for s, t in {tuple(sorted(p)) for p in nz if p[0] != p[1]}:
                    c = add(S._d(self.a[r, s], q[t]), -S._d(self.a[r, t], q[s]))
                    if c != 0:
                        pairs[(s, t)] = c
                curl.append(pairs)
            out = {}
            for r in range(n):
                if not curl[r]:
                    continue
                for i, k in enumerate(self._ind):
                    for l in self._ind[i + 1:]:
                        terms = []
                        for (s, t), c in curl[r].items():
                            # (s, t) and (t, s): c (b_sk b_tl - b_tk b_sl)
                            for u, v, sign in ((s, t, 1), (t, s, -1)):
                                if self.b[u, k] != 0 and self.b[v, l] != 0:
                                    terms.append(mul(sign, c, self.b[u, k], self.b[v, l]))
                        gam = _tidy(add(*terms)) if terms else sp.S.Zero
                        if gam != 0:
                            out[(self.omega[r], self.omega[k], self.omega[l])] = gam
            self._cache["gamma"] = out
        return self._cache["gamma"]

    def _gamma(self, r, k, l):
        g = self.hamel_coefficients()
        if k < l:
            return g.get((self.omega[r], self.omega[k], self.omega[l]), sp.S.Zero)
        if k > l:
            return -g.get((self.omega[r], self.omega[l], self.omega[k]), sp.S.Zero)
        return sp.S.Zero

    def _on(self):
        """omega_beta = 0 and omegadot_beta = 0."""
        return {w: sp.S.Zero for i, w in enumerate(self.omega) if i not in self._ind} | \
            {w: sp.S.Zero for i, w in enumerate(self.omegadot) if i not in self._ind}

    def _rate(self, f):
        """d/dt of f(q, omega) along the motion: qdot = b omega, omega' = omegadot."""
        S = self.system
        rates = {S.q[c]: add(*[mul(self.b[i, r], self.omega[r]) for r in self._ind])
                 for i, c in enumerate(S.coordinates)}
        rates.update({w: wd for w, wd in zip(self.omega, self.omegadot)})
        return along(f, rates, self._cache.setdefault("along", {}))

    def _bh_equations(self):
        """[BH] in q, omega_sigma, omegadot_sigma."""
        if "bh" not in self._cache:
            S, Ls = self.system, self._Lstar()
            n = len(S.coordinates)
            q = [S.q[c] for c in S.coordinates]
            P = [S._d(Ls, w) for w in self.omega]
            dLq = [S._d(Ls, x) for x in q]
            on, memo = self._on(), {}
            out = []
            for k in self._ind:
                terms = [self._rate(P[k])]
                terms += [-mul(self.b[s, k], dLq[s]) for s in range(n)
                          if self.b[s, k] != 0 and dLq[s] != 0]
                for r in range(n):
                    for l in self._ind:
                        gam = self._gamma(r, k, l)
                        if gam != 0 and P[r] != 0:
                            terms.append(mul(gam, self.omega[l], P[r]))
                out.append(substitute(add(*terms), on, memo))
            self._cache["bh"] = out
        return self._cache["bh"]

    def _omega_of_qdot(self):
        """omega_sigma in q and qdot_sigma (the dependent velocities substituted)."""
        S = self.system
        qd = [S.qd[c] for c in S.coordinates]
        return {self.omega[k]: S.constrained(add(*[mul(self.a[k, s], qd[s])
                                                    for s in range(len(qd))]))
                for k in self._ind}

    def _equations(self):
        """[BH] with omega written in the velocities: linear in the omegadot_sigma."""
        if "eqs" not in self._cache:
            w = self._omega_of_qdot()
            memo = {}
            self._cache["eqs"] = [substitute(e, w, memo) for e in self._bh_equations()]
        return self._cache["eqs"]

    def _unknowns(self):
        return [self.omegadot[k] for k in self._ind]

    def _accelerations(self):
        if "acc" not in self._cache:
            S = self.system
            sol = self._solution()
            w = self._omega_of_qdot()
            out = {}
            for i, c in enumerate(S.coordinates):
                if c not in S.sigma:
                    continue
                qd_i = add(*[mul(self.b[i, r], self.omega[r]) for r in self._ind])
                acc = substitute(self._rate(qd_i), sol | w)
                out[S.qdd[c]] = substitute(acc, w)
            self._cache["acc"] = out
        return self._cache["acc"]

    def _steps_before(self):
        S = self.system
        n = len(S.coordinates)
        qd = [S.qd[c] for c in S.coordinates]
        return [
            Step("BHw", r"the quasi-velocities $\omega = a(q)\,\dot q$ (the last are the "
                 r"constraints: $\omega_\beta = 0$)", lambda: [
                     eq(self.omega[r], add(*[mul(self.a[r, s], qd[s]) for s in range(n)]))
                     for r in range(n)]),
            Step("BHb", r"$\dot q = b\,\omega$, $b = a^{-1}$", lambda: [
                eq(qd[i], add(*[mul(self.b[i, r], self.omega[r]) for r in range(n)]))
                for i in range(n)]),
            Step("BHL", r"$L^*(q, \omega) = L(q, b\,\omega)$",
                 lambda: [eq(notation("L*", "L^{*}"), self._Lstar())]),
            Step("BHg", r"Hamel's coefficients $\gamma$ (the transpositional relations), those "
                 r"not zero, for $k < l$", lambda: [
                     eq(indexed("γ", [self.omega.index(k) + 1, self.omega.index(l) + 1],
                                sup=self.omega.index(r) + 1, base_tex=r"\gamma"), g)
                     for (r, k, l), g in self.hamel_coefficients().items()]),
            Step("BH", r"the Boltzmann-Hamel equations at $\omega_\beta = 0$",
                 lambda: [eq(e, 0) for e in self._bh_equations()]),
        ]
