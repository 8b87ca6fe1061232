"""The converter that makes the in-browser (JupyterLite) copies of the notebooks."""
import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

import build_lite  # noqa: E402
import lite_notebooks as ln  # noqa: E402


def _index():
    idx = ln.Index(bib={"mei1983whittaker": ("Mei", "1983"),
                        "a2000": ("A and B", "2000")})
    idx.add("book/04-generalized-whittaker", {"cells": [
        {"cell_type": "markdown", "source": "# The generalized Whittaker equations\n"},
        {"cell_type": "markdown", "source": "```{exercise}\n:label: ch4-ex1\nOne.\n```\n"
                                            "````{exercise}\n:label: ch4-ex2\n\nTwo.\n````"},
    ]})
    idx.add("book/06-sledge", {"cells": [
        {"cell_type": "markdown", "source": "# The sledge\n\n(numerics-turning)=\n## Large amplitudes\n"},
    ]})
    return idx


def test_exercise_and_solution_become_bold_text_and_details():
    src = ("````{exercise}\n:label: ch4-ex2\n\nReduce the sledge.\n````\n\n"
           "````{solution} ch4-ex2\n:class: dropdown\n\n```python\nrm = 1\n```\n\nDone.\n````")
    out = ln.convert_markdown(src, "book/04-generalized-whittaker", _index())
    assert out.startswith("**Exercise 4.2.** Reduce the sledge.")
    assert "<details>\n<summary>Solution to Exercise 4.2</summary>\n\n```python\nrm = 1\n```" in out
    assert out.rstrip().endswith("</details>")
    assert "{exercise}" not in out and ":label:" not in out and ":class:" not in out


def test_roles():
    idx = _index()
    doc = "book/04-generalized-whittaker"
    conv = lambda s: ln.convert_markdown(s, doc, idx)  # noqa: E731
    assert conv("see {doc}`06-sledge`") == "see [The sledge](06-sledge.ipynb)"
    assert conv("see {doc}`the sledge <06-sledge>`") == "see [the sledge](06-sledge.ipynb)"
    assert conv("the {doc}`glossary`") == "the glossary"           # not a notebook
    assert conv("{ref}`ch4-ex1`") == "[Exercise 4.1](04-generalized-whittaker.ipynb)"
    assert conv("{ref}`numerics-turning`") == "[Large amplitudes](06-sledge.ipynb)"
    assert conv("{term}`Jacobi's form <Jacobi's principle>`") == "Jacobi's form"
    assert conv("{term}`holonomic`") == "holonomic"
    assert conv("{cite:p}`mei1983whittaker`") == "(Mei 1983)"
    assert conv("{cite:t}`mei1983whittaker`") == "Mei (1983)"
    assert conv("{cite:p}`mei1983whittaker,a2000`") == "(Mei 1983; A and B 2000)"
    assert conv("(sledge-errata)=\n## Errata") == "## Errata"
    idx_ex = ln.convert_markdown("{doc}`../book/06-sledge`", "exercises/x", idx)
    assert idx_ex == "[The sledge](../book/06-sledge.ipynb)"


def test_admonition_and_figure():
    out = ln.convert_markdown(":::{admonition} Errata\n:class: warning\n\nLine one.\n\nTwo.\n:::",
                              "book/06-sledge", _index())
    assert out == "> **Errata**\n>\n> Line one.\n>\n> Two."
    out = ln.convert_markdown("```{figure} figures/a.svg\n:name: fig-a\n:width: 100%\n\n"
                              "Error against time.\n```", "book/07-x", _index())
    assert out.startswith("![Error against time.](figures/a.svg)")


def test_code_outputs_removed_unless_the_notebook_needs_numpy():
    live = {"metadata": {}, "nbformat": 4, "nbformat_minor": 5, "cells": [
        {"cell_type": "code", "metadata": {"tags": ["hide-input"]}, "execution_count": 3,
         "outputs": [{"output_type": "stream", "name": "stdout", "text": "x"}],
         "source": "import sympy"}]}
    out = ln.lite_notebook(live, "book/01-x", _index())
    assert out["cells"][0]["outputs"] == [] and out["cells"][0]["execution_count"] is None
    assert out["cells"][0]["metadata"]["jupyter"]["source_hidden"] is True
    assert out["metadata"]["kernelspec"]["name"] == "python"
    assert live["cells"][0]["outputs"]                       # the source is not changed
    native = json.loads(json.dumps(live))
    native["cells"][0]["source"] = "import numpy as np"
    out = ln.lite_notebook(native, "book/07-x", _index())
    assert "runs locally, not in the browser" in out["cells"][0]["source"]
    assert out["cells"][1]["outputs"]                        # stored outputs kept
    assert out["metadata"]["whittaker_teach"]["runs_in_browser"] is False


@pytest.mark.parametrize("code, native", [
    ("import numpy as np", True), ("from scipy.integrate import solve_ivp", True),
    ("red.simulate(a, b, h, (0, 1), p)", True), ("wt.examples.sledge_exact(p, a=1)", True),
    ("import whittaker_teach.numerics", True),
    ("import sympy as sp\nsp.lambdify(x, y)", False), ("# numpy is not used", False),
])
def test_needs_native(code, native):
    nb = {"cells": [{"cell_type": "code", "source": code}]}
    assert ln.needs_native(nb) is native


def test_launch_mapping_opens_the_student_version():
    assert build_lite.lite_path("exercises/solutions/kepler-orbit") == "exercises/kepler-orbit.ipynb"
    assert build_lite.lite_path("book/06-sledge") == "book/06-sledge.ipynb"
    assert build_lite.lite_path("book/glossary") is None
    sys.path.insert(0, str(ROOT / "book" / "_ext"))
    import wt_lite_launch
    for doc in build_lite.toc_docs():
        assert wt_lite_launch.lite_path(ROOT, doc) == build_lite.lite_path(doc), doc


def test_every_book_notebook_converts_without_myst_left():
    docs = build_lite.lite_docs()
    index = ln.Index.from_notebooks([ROOT / f"{d}.ipynb" for d in docs])
    for d in docs:
        nb = json.loads((ROOT / f"{d}.ipynb").read_text(encoding="utf-8"))
        out = ln.lite_notebook(nb, d, index)
        for cell in out["cells"]:
            if cell["cell_type"] == "markdown":
                src = cell["source"]
                for bad in ("{exercise}", "{solution}", "{doc}`", "{ref}`", "{cite:", ":label:"):
                    assert bad not in src, (d, bad)


def test_show_renders_maths_in_the_pyodide_kernel(monkeypatch):
    """In JupyterLite the shell is pyodide_kernel's: show() displays LaTeX there too."""
    import IPython
    import IPython.display

    from whittaker_teach import render

    shown = []
    Interpreter = type("Interpreter", (), {"__module__": "pyodide_kernel.interpreter"})
    Terminal = type("TerminalInteractiveShell", (), {"__module__": "IPython.terminal"})
    def display(obj, raw=False):
        shown.append(sorted(obj) if raw else type(obj).__name__)
    monkeypatch.setattr(IPython.display, "display", display)
    for shell, in_notebook in ((Interpreter(), True), (Terminal(), False), (None, False)):
        monkeypatch.setattr(IPython, "get_ipython", lambda s=shell: s)
        assert render._in_notebook() is in_notebook
    monkeypatch.setattr(IPython, "get_ipython", lambda: Interpreter())
    import whittaker_teach as wt
    wt.examples.sledge().steps.only("1.1").show()
    captions = ["text/html", "text/markdown", "text/plain"]
    assert shown == [captions, captions, "Math"]     # title, the step's caption, (1.1)


def test_gated_exercises_and_solutions_become_plain_markdown():
    idx = ln.Index(labels={"ex-a": ("book/04-x", "Exercise 4.5")})
    start = ln.convert_markdown(":::{solution-start} ex-a\n:::", "book/04-x", idx)
    end = ln.convert_markdown(":::{solution-end}\n:::", "book/04-x", idx)
    assert start == "**Solution to Exercise 4.5.**" and end == "*(end of the solution)*"
    fig = ln.convert_markdown(":::{figure} f.svg\n:alt: a sledge seen from above\n\nCap.\n:::",
                                "book/03-x", idx)
    assert fig.startswith("![a sledge seen from above](f.svg)") and "{" not in fig
    assert ln.convert_markdown("see {numref}`fig-a`", "book/03-x", idx) == "see the figure"
