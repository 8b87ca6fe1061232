"""Solving M x = b for expressions: SymPy's LU solve, without its products by zero.

SymPy's ``Matrix.LUsolve`` eliminates with every entry, zero or not.  A product
``0 * y`` asks whether each factor of ``y`` is finite (0 times a pole is not 0): on
a banded mass matrix with large entries, a walk of assumption queries for every
structural zero.  :func:`lu_solve` is the same algorithm (the same pivots, the same
operations in the same order, so the same expressions) that skips a product with a
factor that is ``0`` as built, whose result is known: ``x - 0 * y`` is ``x``.
Valid for finite entries, as the equations of motion are at an admissible point.

>>> import sympy as sp
>>> a, b, c = sp.symbols("a b c", positive=True)
>>> M, rhs = sp.Matrix([[a, 0], [0, b]]), sp.Matrix([c, 1])
>>> lu_solve(M, rhs) == list(M.LUsolve(rhs))
True
"""

from __future__ import annotations

import sympy as sp

__all__ = ["lu_solve"]


def _iszero(x):
    return x.is_zero


def _pivot(column, iszerofunc):
    """SymPy's naive pivot search: the first entry that is not zero, else the first
    that may not be; None if every entry is zero."""
    maybe = None
    for i, v in enumerate(column):
        z = iszerofunc(v)
        if z is False:
            return i
        if z is None and maybe is None:
            maybe = i
    return maybe


def _minus_product(x, scale, y):
    """``x - scale * y``, without the product when a factor is 0 as built."""
    if scale is sp.S.Zero or y is sp.S.Zero:
        return x
    return x - scale * y


def _decompose(M, iszerofunc):
    """SymPy's ``LUdecomposition_Simple`` of a square matrix (L below the diagonal,
    unit diagonal implied; U on and above it), and the row swaps."""
    n = M.rows
    lu = [list(M.row(i)) for i in range(n)]
    swaps = []
    for p in range(n - 1):
        off = _pivot([lu[r][p] for r in range(p, n)], iszerofunc)
        if off is None:
            raise ValueError("singular matrix")
        if off:
            swaps.append((p, p + off))
            lu[p], lu[p + off] = lu[p + off], lu[p]
        for r in range(p + 1, n):
            lr = lu[r][p]
            lr = sp.S.Zero if lr is sp.S.Zero else lr / lu[p][p]
            lu[r][p] = lr
            for c in range(p + 1, n):
                lu[r][c] = _minus_product(lu[r][c], lr, lu[p][c])
    if iszerofunc(lu[n - 1][n - 1]):
        raise ValueError("singular matrix")
    return lu, swaps


def lu_solve(M, rhs, iszerofunc=_iszero):
    """The solution x (a list) of ``M x = rhs`` for a square regular ``M`` and a
    column ``rhs``: the expressions of ``M.LUsolve(rhs, iszerofunc)``, built without
    products by zero.  Raises ValueError for a matrix that LU finds singular."""
    n = M.rows
    if M.cols != n or rhs.rows != n:
        raise ValueError("lu_solve needs a square matrix and a column of as many rows")
    lu, swaps = _decompose(M, iszerofunc)
    b = list(rhs)
    for i, j in swaps:
        b[i], b[j] = b[j], b[i]
    for i in range(n):                       # forward: the unit lower triangle
        for j in range(i):
            b[i] = _minus_product(b[i], lu[i][j], b[j])
    for i in range(n - 1, -1, -1):           # backward: the upper triangle
        for j in range(i + 1, n):
            b[i] = _minus_product(b[i], lu[i][j], b[j])
        b[i] = lu[i][i] ** -1 * b[i]
    return b
