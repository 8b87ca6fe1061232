"""Exact random points and 40-digit evaluation, shared by the integration tests."""

import mpmath
import sympy as sp

DPS = 30
TOL = mpmath.mpf("1e-20")


def rat(rng, lo, hi):
    """A random rational in (lo, hi), exact so that evalf can reach any precision."""
    return sp.Rational(round(rng.uniform(lo, hi) * 10**6), 10**6)


def num(expr, subs):
    """Evaluate expr at subs (symbols -> exact numbers) to DPS + 10 digits."""
    val = sp.sympify(expr).xreplace(subs).evalf(DPS + 10)
    assert not val.free_symbols, f"unsubstituted symbols {val.free_symbols} in {expr}"
    re, im = val.as_real_imag()
    assert abs(im) < 1e-30, f"complex value {val}"
    return mpmath.mpf(sp.Float(re, DPS + 10)._mpf_)


def close(a, b, tol=TOL):
    """a equals b to the relative tolerance tol (absolute below 1)."""
    return abs(a - b) <= tol * max(1, abs(a), abs(b))
