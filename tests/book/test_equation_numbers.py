"""Every numbered equation of the paper appears on the site with its number.

The library renders each step as a display tagged ``\\tag{1.16}``; this test reads
the built pages (``_build/html``, made by ``make site``) and looks for each tag.
"""

import os
import re
from pathlib import Path

import pytest

SITE = Path(__file__).resolve().parents[2] / "_build" / "html"
LABELS = ([f"1.{i}" for i in range(1, 28)] + [f"2.{i}" for i in range(1, 5)]
          + [f"3.{i}" for i in range(1, 16)])


@pytest.fixture(scope="module")
def tags():
    if not (SITE / "index.html").exists():
        if os.environ.get("WT_REQUIRE_SITE"):
            pytest.fail("the site is not built: run `make site` first")
        pytest.skip("the site is not built (make site)")
    found = {}
    for page in SITE.rglob("*.html"):
        if page.relative_to(SITE).parts[0] == "lite":
            continue  # the JupyterLite application (tests/book/test_lite.py)
        for label in re.findall(r"\\tag\{([0-9.]+)\}", page.read_text(encoding="utf-8")):
            found.setdefault(label, set()).add(page.relative_to(SITE).as_posix())
    return found


@pytest.mark.parametrize("label", LABELS)
def test_equation_is_on_the_site(tags, label):
    assert label in tags, f"no page shows equation ({label}) with its number"
