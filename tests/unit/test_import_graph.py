"""The package's imports run one way: no circles, and the symbolic core never imports numerics.

The core is every module of ``whittaker_teach`` outside ``numerics/``: it needs
only SymPy and mpmath (it runs in Pyodide), and numerics builds on it.  The
graph is read from the source (every ``import`` statement, also those inside
functions, which a run would only meet on some paths), so a lazy import counts.
``simulate`` reaches numerics through :mod:`whittaker_teach.backends`, where the
numerics package registers its entries.
"""
import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "whittaker_teach"

#: modules allowed to import numerics although outside it: the command line sits above
#: both (``bench numerics`` runs the numerics study); ``examples._exact`` is the thin
#: wrapper of the closed-form sledge (numerics.exact) that ``examples`` re-exports
FRONT_ENDS = {"whittaker_teach.__main__", "whittaker_teach.examples._exact"}


def _modules():
    mods = {}
    for p in PKG.rglob("*.py"):
        parts = list(p.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        mods[".".join(parts)] = p
    return mods


def _graph():
    mods = _modules()
    edges = {}
    for mod, path in mods.items():
        package = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
        out = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package[:len(package) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module
                for alias in node.names:
                    sub = f"{target}.{alias.name}"
                    out.add(sub if sub in mods else target)
            elif isinstance(node, ast.Import):
                out.update(alias.name for alias in node.names)
        edges[mod] = {o for o in out if o in mods and o != mod}
    return edges


def _cycles(edges):
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def _is_numerics(mod):
    return mod == "whittaker_teach.numerics" or mod.startswith("whittaker_teach.numerics.")


def test_graph_is_read():
    edges = _graph()
    assert "whittaker_teach.reading" in edges["whittaker_teach.nielsen"]
    assert "whittaker_teach.reduction" in edges["whittaker_teach.numerics"]
    # the detector finds a circle when there is one
    assert _cycles({"a": {"b"}, "b": {"a"}, "c": set()}) == [["a", "b"]]


def test_no_circles_in_core_and_numerics():
    edges = {m: e for m, e in _graph().items() if not m.startswith("whittaker_teach.exercises")
             and not m.startswith("whittaker_teach.grading")}
    edges = {m: {w for w in e if w in edges} for m, e in edges.items()}
    assert _cycles(edges) == []


def test_no_circles_anywhere_checking_and_grading_included():
    """Issue 37, item 9: grade.py and gradebook.py imported each other; now nothing does."""
    assert _cycles(_graph()) == []


#: the only modules of exercises/ that name the grader: aliases of moved modules, for old
#: scripts (exercises.sandbox is grading.sandbox; exercises.grade forwards any name but
#: record_line to grading.run when it is asked for, without an import statement)
GRADING_ALIASES = {"whittaker_teach.exercises.sandbox"}


def _in(mod, package):
    return mod == package or mod.startswith(package + ".")


def test_checking_never_imports_the_grader():
    edges = _graph()
    bad = {m: sorted(w for w in e if _in(w, "whittaker_teach.grading"))
           for m, e in edges.items() if _in(m, "whittaker_teach.exercises")
           and m not in GRADING_ALIASES}
    assert {m: e for m, e in bad.items() if e} == {}
    assert edges["whittaker_teach.exercises.grade"] == {"whittaker_teach.exercises.recorder"}


def test_the_grader_uses_checking_but_not_authoring():
    """grading/ may call check (the package, its catalogue, the recorder); never the authoring
    tools; its roster, exports, rows and worker import nothing outside grading/."""
    edges = _graph()
    allowed = {"whittaker_teach", "whittaker_teach.exercises",
               "whittaker_teach.exercises.catalog", "whittaker_teach.exercises.recorder"}
    for mod, out in edges.items():
        if not _in(mod, "whittaker_teach.grading"):
            continue
        outside = {w for w in out if not _in(w, "whittaker_teach.grading")}
        assert outside <= allowed, (mod, sorted(outside - allowed))
        if mod.rsplit(".", 1)[-1] in ("roster", "exports", "rows", "worker", "grading"):
            assert outside == set(), (mod, sorted(outside))
    assert edges["whittaker_teach.grading.worker"] == set()
    assert edges["whittaker_teach.grading"] == set()


def test_core_never_imports_numerics():
    bad = {m: sorted(w for w in e if _is_numerics(w)) for m, e in _graph().items()
           if not _is_numerics(m) and m not in FRONT_ENDS}
    assert {m: e for m, e in bad.items() if e} == {}


CORE_IMPORTS = r"""
import importlib, importlib.abc, pkgutil, sys
BLOCKED = ("numpy", "scipy", "matplotlib", "whittaker_teach.numerics")

class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if any(name == b or name.startswith(b + ".") for b in BLOCKED):
            raise ModuleNotFoundError(f"{name} is blocked by the test", name=name)
        return None

sys.meta_path.insert(0, Block())
import whittaker_teach
names = sorted(m.name for m in pkgutil.walk_packages(whittaker_teach.__path__,
                                                      "whittaker_teach.")
               if not m.name.startswith("whittaker_teach.numerics"))
for name in names:
    importlib.import_module(name)
import whittaker_teach as wt
red = wt.examples.sledge().reduce("x")
print(len(names), sorted(m for m in sys.modules if m.split(".")[0] in ("numpy", "scipy")
                         or m.startswith("whittaker_teach.numerics")), red.verify().ok)
"""


def test_core_modules_import_and_derive_with_numerics_blocked():
    env = dict(os.environ, PYTHONHASHSEED="0",
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, "-c", CORE_IMPORTS], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    count, rest = r.stdout.split(" ", 1)
    assert int(count) > 15
    assert rest.strip() == "[] True"


@pytest.mark.filterwarnings("ignore")
def test_simulate_goes_through_the_registered_backend():
    pytest.importorskip("scipy")
    import whittaker_teach as wt
    from whittaker_teach import backends
    import whittaker_teach.numerics as numerics
    assert backends.provided("simulate") is numerics.simulate
    sledge = wt.examples.sledge()
    x, th, y = sledge.coordinates
    traj = sledge.simulate({x: 0, th: 0.3, y: 0}, {x: 1.0, th: 0.0}, (0, 1),
                           {"m": 1.0, "J": 1.0, "k": 1.0}, rtol=1e-8)
    assert abs(traj.q[th][-1]) < 1
