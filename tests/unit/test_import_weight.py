"""What the sledge's whole derivation loads: not ``sympy.physics``.

``sympy.physics`` imports its ``units`` package (about 0.2 s natively, more in
Pyodide): a derivation that only needs coordinates of time must not pay it.
The library's own ``coordinates.dynamicsymbols`` makes the same objects as
``sympy.physics.mechanics.dynamicsymbols`` (compared below), so a model built
with either mixes freely.
"""
import subprocess
import sys
import textwrap

from sympy.physics.mechanics import dynamicsymbols as me_dynamicsymbols

from whittaker_teach.coordinates import T, dynamicsymbols


def test_sledge_derivation_does_not_import_sympy_physics():
    code = textwrap.dedent("""
        import sys
        import whittaker_teach as wt
        from whittaker_teach.examples import section3
        from whittaker_teach import system, reduction, nielsen, steps, verify, render
        red = wt.examples.sledge().reduce("x", +1)
        ok = red.verify().ok and all(s.check is None or s.check.holds
                                     for s in section3(reduction=red))
        print(ok, sorted(m for m in sys.modules if m.startswith("sympy.physics"))[:3])
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split(None, 1)
    assert out == ["True", "[]\n"]


def test_dynamicsymbols_equal_to_mechanics():
    assert T == me_dynamicsymbols._t and dynamicsymbols._t == T
    assert dynamicsymbols("x theta y") == me_dynamicsymbols("x theta y")
    r = dynamicsymbols("r", positive=True)
    assert r == me_dynamicsymbols("r", positive=True) and r.is_positive
    assert r != me_dynamicsymbols("r")                  # the assumptions are kept apart
    x = dynamicsymbols("x")
    assert (x.diff(T) - me_dynamicsymbols("x", 1)) == 0
