"""Benchmarks that print figures (never timed tests).

``python -m whittaker_teach bench derivation``: in fresh processes, the time
to build the sledge, derive every step of the paper and verify them all,
against the time sympy.physics.mechanics' LagrangesMethod takes to form and
solve the sledge's time-domain equations (with a Lagrange multiplier), and
the time of ``import whittaker_teach``.  Each figure is the median over
``--repeat`` fresh processes.
"""

import statistics
import subprocess
import sys

OURS = """
import time; t0 = time.perf_counter()
import whittaker_teach as wt
from whittaker_teach.examples import section3
red = wt.examples.sledge().reduce("x", +1)
ok = red.verify().ok and all(s.check is None or s.check.holds for s in section3(reduction=red))
print(time.perf_counter() - t0, ok)
"""

CORE = """
import time; t0 = time.perf_counter()
import whittaker_teach as wt
ok = wt.examples.sledge().reduce("x", +1).verify().ok
print(time.perf_counter() - t0, ok)
"""

PEER = """
import time; t0 = time.perf_counter()
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols, LagrangesMethod
t = dynamicsymbols._t
m, J, k = sp.symbols("m J k", positive=True)
x, th, y = dynamicsymbols("x theta y")
L = m/2*(x.diff(t)**2 + y.diff(t)**2) + J/2*th.diff(t)**2 - k**2*th**2/2
lm = LagrangesMethod(L, [x, th, y], nonhol_coneqs=[y.diff(t) - x.diff(t)*sp.tan(th)])
lm.form_lagranges_equations()
rhs = lm.rhs()
print(time.perf_counter() - t0, True)
"""

IMPORT = """
import time; t0 = time.perf_counter()
import whittaker_teach
print(time.perf_counter() - t0, True)
"""


def _once(code):
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    if out[1] != "True":
        raise RuntimeError("a verification failed during the benchmark")
    return float(out[0])


def _interleaved(codes, repeat):
    """Median time of each code over ``repeat`` rounds, one run of each per round, so
    that a load on the machine falls on all of them alike."""
    times = [[] for _ in codes]
    for _ in range(repeat):
        for i, code in enumerate(codes):
            times[i].append(_once(code))
    return [statistics.median(t) for t in times]


def main(args):
    n = args.repeat
    ours, core, peer, imp = _interleaved([OURS, CORE, PEER, IMPORT], n)
    print(f"fresh-process medians over {n} runs (Python {sys.version.split()[0]})")
    print(f"  whittaker_teach: sledge, every step (1.1)-(2.4) and (3.1)-(3.15) derived "
          f"and verified: {ours:7.3f} s")
    print(f"  whittaker_teach: the general derivation (1.1)-(2.4) only, verified: "
          f"{core:7.3f} s")
    print(f"  sympy.physics.mechanics LagrangesMethod: sledge time-domain equations "
          f"formed and solved: {peer:7.3f} s")
    print(f"  ratio (ours / peer): {ours / peer:.2f} with section 3, {core / peer:.2f} without "
          "(target <= 2)")
    print(f"  import whittaker_teach: {imp:.3f} s  (target < 0.5 s)")
    return 0
