"""The symbolic core works without the [numerics] extra (numpy, scipy, tqdm).

This is what the in-browser site (Pyodide, no numpy) relies on. A subprocess
hides numpy, scipy, tqdm and matplotlib with a meta-path finder (as if they
were not installed), runs the symbolic unit tests there, and checks that a
numerics entry point then fails with an error that names the extra.
"""
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HIDDEN = ("numpy", "scipy", "tqdm", "matplotlib")
#: the symbolic unit tests (none of them needs the extra)
SYMBOLIC_TESTS = ["tests/unit/test_reduction.py", "tests/unit/test_system.py",
                  "tests/unit/test_verify.py", "tests/unit/test_section3.py",
                  "tests/unit/test_errors.py", "tests/unit/test_render_cli.py"]

HIDER = textwrap.dedent(f"""
    import importlib.abc, importlib.machinery, sys
    HIDDEN = {HIDDEN!r}

    class Hide(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in HIDDEN:
                raise ModuleNotFoundError(f"No module named {{name!r}} (hidden by the test)",
                                          name=name)
            return None

    for m in [m for m in sys.modules if m.split(".")[0] in HIDDEN]:
        del sys.modules[m]
    sys.meta_path.insert(0, Hide())
    # importlib.util.find_spec goes through the finders too: hidden is missing
    _find_spec = importlib.util.find_spec
    def find_spec(name, package=None):
        if name.split(".")[0] in HIDDEN:
            return None
        return _find_spec(name, package)
    importlib.util.find_spec = find_spec
""")


def _run(code, timeout=900):
    env = dict(os.environ, PYTHONHASHSEED="0",
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    return subprocess.run([sys.executable, "-c", HIDER + textwrap.dedent(code)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)


def test_hider_hides():
    r = _run("""
        try:
            import numpy
        except ModuleNotFoundError:
            print("hidden")
    """)
    assert r.stdout.strip() == "hidden", r.stderr


def test_numerics_entry_points_name_the_extra():
    r = _run("""
        import whittaker_teach as wt
        sledge = wt.examples.sledge()                      # symbolic: works
        print("sledge ok", len(sledge.accelerations()))
        for call in (lambda: sledge.simulate({}, {}, (0, 1), {}),
                     lambda: wt.examples.sledge_exact({"m": 1, "J": 1, "k": 1}, a=0.5),
                     lambda: __import__("whittaker_teach.numerics.codegen")):
            try:
                call()
            except ImportError as err:
                print(type(err).__name__, "|", err)
    """)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == "sledge ok 2"
    assert len(lines) == 4, r.stdout + r.stderr
    for line in lines[1:]:
        name, msg = line.split(" | ", 1)
        assert name == "MissingExtraError"
        assert "[numerics]" in msg and "numpy" in msg and "scipy" in msg


@pytest.mark.slow
def test_symbolic_tests_pass_without_numerics():
    r = _run(f"""
        import sys, pytest
        sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "-p", "no:randomly",
                              *{SYMBOLIC_TESTS!r}]))
    """)
    tail = "\n".join((r.stdout + r.stderr).splitlines()[-25:])
    assert r.returncode == 0, tail
    assert " passed" in tail and "failed" not in tail and "error" not in tail.lower(), tail
