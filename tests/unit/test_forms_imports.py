"""whittaker_teach.forms sits above the core: the core never imports it, the forms run
without the numerics extra, and importing the subpackage builds nothing."""
from pathlib import Path

from tests.unit.test_import_graph import _cycles, _graph

ROOT = Path(__file__).resolve().parents[2]


def _is_forms(mod):
    return mod == "whittaker_teach.forms" or mod.startswith("whittaker_teach.forms.")


def test_the_core_never_imports_forms():
    bad = {m: sorted(w for w in e if _is_forms(w)) for m, e in _graph().items()
           if not _is_forms(m)}
    assert {m: e for m, e in bad.items() if e} == {}


def test_forms_import_no_numerics_and_no_circles():
    edges = _graph()
    assert "whittaker_teach.forms.model" in edges["whittaker_teach.forms.routh_voss"] or \
        "whittaker_teach.forms._form" in edges["whittaker_teach.forms.routh_voss"]
    forms = {m: {w for w in e if _is_forms(w)} for m, e in edges.items() if _is_forms(m)}
    assert _cycles(forms) == []
    assert not any(w.startswith("whittaker_teach.numerics") for m, e in edges.items()
                   if _is_forms(m) for w in e)


BLOCKED = r"""
import whittaker_teach.forms as F
before = set(sys.modules)
from whittaker_teach.forms import examples, agree
print(agree(examples.sledge_in_a_well(), points=2).ok,
      F.frobenius(examples.sledge()).is_holonomic)
"""


def test_forms_run_without_numpy(run_without_numerics):
    assert run_without_numerics(BLOCKED).split() == ["True", "False"]
