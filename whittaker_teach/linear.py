"""Solving M x = b for expressions: SymPy's LU solve, without its products by zero.

SymPy's ``Matrix.LUsolve`` eliminates with every entry, zero or not.  A product
``0 * y`` asks whether each factor of ``y`` is finite (0 times a pole is not 0): on
a banded mass matrix with large entries, a walk of assumption queries for every
structural zero.  :func:`lu_solve` is the same algorithm (the same pivots, the same
operations in the same order, so the same expressions) that skips a product with a
factor that is ``0`` as built, whose result is known: ``x - 0 * y`` is ``x``.
Valid for finite entries, as the equations of motion are at an admissible point.

Its pivots divide by entries that may vanish where the matrix does not (a pivot -sin(theta)
of a matrix whose determinant is sin(phi)): a removable singularity made real.  Where a
solution is read or evaluated at any point, :func:`fraction_free_solve` gives each unknown
as one fraction in lowest terms whose denominator divides the determinant, so that the only
poles are those of the matrix itself (fraction-free elimination in a polynomial ring,
:func:`.polywalk.fractions`, then a gcd).

>>> import sympy as sp
>>> a, b, c = sp.symbols("a b c", positive=True)
>>> M, rhs = sp.Matrix([[a, 0], [0, b]]), sp.Matrix([c, 1])
>>> lu_solve(M, rhs) == list(M.LUsolve(rhs))
True
"""

from __future__ import annotations

import sympy as sp

from . import polywalk

__all__ = ["lu_solve", "fraction_free_solve", "solve_with_regular_poles"]

#: :func:`fraction_free_solve` gives up (``polywalk.TooLarge``) when a product of the
#: numbers of terms of two polynomials whose gcd it takes exceeds this
FRACTION_FREE_TERMS_LIMIT = 20000


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


def fraction_free_solve(M, rhs, limit=FRACTION_FREE_TERMS_LIMIT):
    """The solution of ``M x = rhs`` (a square matrix, a column of expressions) as a list of
    (numerator, denominator) expressions, each in lowest terms, the denominator with a
    positive leading coefficient.  The entries are taken into one polynomial ring whose
    generators are their symbols, functions and roots (:func:`.polywalk.fractions`); each
    row is brought over one denominator, then Bareiss's fraction-free elimination (its
    divisions exact) and a back substitution that cancels the gcd at each step.  The
    generators being independent there, Cramer's rule holds in the ring: every denominator
    divides the determinant (of the rows over their denominators), so a solution has no
    pole where the matrix is regular and its entries finite.

    ``ValueError`` when the matrix is singular as polynomials; ``polywalk.NotPolynomial``
    when an entry is not a rational function of such generators; ``polywalk.TooLarge``
    when a gcd would be of polynomials with more than ``limit`` terms multiplied.

    >>> th, ph, a, b = sp.symbols("theta phi a b")
    >>> M = sp.Matrix([[-sp.sin(th), sp.cos(th)], [-sp.sin(th + ph), sp.cos(th + ph)]])
    >>> M.LUsolve(sp.Matrix([a, b]))[1].has(1/sp.sin(th))
    True
    >>> for num, den in fraction_free_solve(M, sp.Matrix([a, b])):
    ...     print(num, "/", den)
    -a*cos(phi + theta) + b*cos(theta) / sin(theta)*cos(phi + theta) - sin(phi + theta)*cos(theta)
    -a*sin(phi + theta) + b*sin(theta) / sin(theta)*cos(phi + theta) - sin(phi + theta)*cos(theta)
    """
    n = M.rows
    if M.cols != n or rhs.rows != n:
        raise ValueError("fraction_free_solve needs a square matrix and a column of as many "
                         "rows")
    walk, parts = polywalk.fractions([*M, *rhs])
    R = walk.ring
    rows = []
    for i in range(n):
        row = [parts[i * n + j] for j in range(n)] + [parts[n * n + i]]
        common = R.one
        for _, d in row:
            if d != 1:
                common = common.lcm(d)
        rows.append([num if d == common else num * common.exquo(d) for num, d in row])
    previous = R.one
    for k in range(n):                                  # Bareiss: every division exact
        pivot = next((r for r in range(k, n) if rows[r][k]), None)
        if pivot is None:
            raise ValueError("singular matrix")
        rows[k], rows[pivot] = rows[pivot], rows[k]
        p = rows[k]
        for r in range(k + 1, n):
            row, lead = rows[r], rows[r][k]
            for c in range(k + 1, n + 1):
                e = row[c] * p[k] - lead * p[c] if lead else row[c] * p[k]
                row[c] = e.exquo(previous) if previous != 1 else e
            row[k] = R.zero
        previous = p[k]

    def lowest(num, den):
        if len(num) * len(den) > limit:
            raise polywalk.TooLarge(num)
        _, num, den = num.cofactors(den)
        return num, den

    x = [None] * n
    for i in range(n - 1, -1, -1):                      # back substitution, in lowest terms
        num, den = rows[i][n], R.one
        for j in range(i + 1, n):
            if rows[i][j]:
                p, q = x[j]
                num, den = lowest(num * q - rows[i][j] * p * den, den * q)
        x[i] = lowest(num, den * rows[i][i])
    out = []
    for num, den in x:
        if den.LC < 0:
            num, den = -num, -den
        out.append((walk.as_expr(num), walk.as_expr(den)))
    return out


def solve_with_regular_poles(M, rhs):
    """The solution (a list) of ``M x = rhs`` whose only poles are those of ``M``: the
    elimination is fraction-free in M's entries alone (:func:`fraction_free_solve` with a
    right-hand side of placeholders), and ``rhs`` is put in afterwards, so that a large
    right-hand side (accelerations, their derivatives) never enters a gcd.  The identity
    is solved as it stands; a matrix whose entries are not rational functions of their
    symbols, functions and roots, or too large for a gcd, by :func:`lu_solve`.

    >>> th, ph, a, b = sp.symbols("theta phi a b")
    >>> M = sp.Matrix([[-sp.sin(th), sp.cos(th)], [-sp.sin(th + ph), sp.cos(th + ph)]])
    >>> x = solve_with_regular_poles(M, sp.Matrix([a, b]))
    >>> any(d.has(sp.sin(th)) and not d.has(ph) for d in (sp.fraction(e)[1] for e in x))
    False
    >>> sp.expand(sp.expand_trig(sp.simplify(M * sp.Matrix(x) - sp.Matrix([a, b])))) == sp.zeros(2, 1)
    True
    """
    n = M.rows
    if M == sp.eye(n):
        return list(rhs)
    slots = [sp.Dummy(f"r{i}") for i in range(n)]
    try:
        parts = fraction_free_solve(M, sp.Matrix(slots))
    except (polywalk.NotPolynomial, polywalk.TooLarge):
        return lu_solve(M, rhs)
    put = dict(zip(slots, rhs))
    return [num.xreplace(put) / den for num, den in parts]

