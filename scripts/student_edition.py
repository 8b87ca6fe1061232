#!/usr/bin/env python
"""Build the student edition of the course: the site, its in-browser site and its PDF,
without the solutions and the answer data of the graded exercises.

    python scripts/student_edition.py [--out _build/student] [--no-pdf]

Which exercises are graded is the course's choice, in ``exercises/course.yml``
(``graded:``); every other exercise is practice and keeps its solution page and
its self-check.  The edition is built from a staged copy of the sources
(``<out>/src``) in which

* each graded exercise's page is its student notebook ``exercises/<id>.ipynb``
  (the statement and empty answer cells), not its solution notebook, and every
  link to ``solutions/<id>`` points there instead;
* ``exercises/src/`` (the one source of each exercise, solution included) and
  the graded solution notebooks are left out;
* the in-browser site's wheel of ``whittaker_teach`` carries, for a graded
  exercise, only the statement's data (``answers.withheld``): ``check`` there
  reads an answer back and says that the part is graded.

Output: ``<out>/html`` (open ``index.html``; ``<out>/html/lite`` in the browser
over http, as for the instructor edition), ``<out>/pdf/whittaker-teach.pdf``.
``tests/book/test_student_edition.py`` searches every published file for the
graded answers.
"""
from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COURSE = ROOT / "exercises" / "course.yml"


def graded_ids(course: Path = COURSE) -> list[str]:
    """The graded exercises named in the course file, each checked to exist."""
    import yaml
    data = yaml.safe_load(course.read_text(encoding="utf-8")) or {}
    ids = data.get("graded") or []
    if not isinstance(ids, list) or not all(isinstance(i, str) for i in ids):
        raise SystemExit(f"student_edition: {course}: 'graded' must be a list of exercise ids")
    sys.path.insert(0, str(ROOT))
    from whittaker_teach.exercises.answers import DATA_DIR
    for i in ids:
        missing = [p for p in (DATA_DIR / f"{i}.json", ROOT / "exercises" / f"{i}.ipynb")
                   if not p.is_file()]
        if missing:
            raise SystemExit(f"student_edition: {course}: graded exercise {i!r} has no "
                             f"{', '.join(str(p.relative_to(ROOT)) for p in missing)}")
    return ids


def relinked(text: str, graded: list[str]) -> str:
    """``text`` with every reference to a graded solution page pointed at the statement.

    >>> relinked("{doc}`../exercises/solutions/kepler-orbit` and solutions/other", ["kepler-orbit"])
    '{doc}`../exercises/kepler-orbit` and solutions/other'
    """
    for i in graded:
        text = re.sub(rf"\bsolutions/{re.escape(i)}(?![\w-])", i, text)
    return text


def stage(src: Path, graded: list[str]) -> None:
    """The sources of the student edition, in ``src`` (emptied first)."""
    if src.exists():
        shutil.rmtree(src)
    src.mkdir(parents=True)
    ignore = shutil.ignore_patterns("_build", ".ipynb_checkpoints", "__pycache__")
    shutil.copytree(ROOT / "book", src / "book", ignore=ignore)
    ex = src / "exercises"
    ex.mkdir()
    for p in (ROOT / "exercises").iterdir():
        if p.is_file() and p.suffix in (".ipynb", ".md"):
            shutil.copy2(p, ex / p.name)
    (ex / "solutions").mkdir()
    for p in sorted((ROOT / "exercises" / "solutions").glob("*.ipynb")):
        if p.stem not in graded:
            shutil.copy2(p, ex / "solutions" / p.name)
    (src / "build").symlink_to(ROOT / "build")           # build/vendor: the local MathJax
    config = (ROOT / "_config.yml").read_text(encoding="utf-8")
    config = re.sub(r'^title: "(.*)"$', r'title: "\1 (student edition)"', config, count=1,
                    flags=re.M)
    (src / "_config.yml").write_text(config, encoding="utf-8")
    (src / "_toc.yml").write_text(relinked((ROOT / "_toc.yml").read_text(encoding="utf-8"),
                                           graded), encoding="utf-8")
    for p in list(src.rglob("*.md")) + list(src.rglob("*.ipynb")):
        if "build" in p.relative_to(src).parts[:1]:
            continue
        text = p.read_text(encoding="utf-8")
        new = relinked(text, graded)
        if new != text:
            p.write_text(new, encoding="utf-8")


def run(cmd, **kw):
    print("student_edition:", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True, **kw)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "_build" / "student")
    ap.add_argument("--no-pdf", action="store_true", help="the site and the in-browser site only")
    args = ap.parse_args(argv)
    out = args.out.resolve()
    graded = graded_ids()
    src, html = out / "src", out / "html"
    stage(src, graded)
    jb = ("import sys; from jupyter_book.cli.main import main; "
          "sys.argv[0] = 'jupyter-book'; sys.exit(main())")
    run([sys.executable, "-c", jb, "build", src, "-W", "-n", "--keep-going"])
    if html.exists():
        shutil.rmtree(html)
    shutil.move(str(src / "_build" / "html"), html)
    (html / "graded.json").write_text(json.dumps({"graded": graded}) + "\n", encoding="utf-8")
    run([sys.executable, ROOT / "scripts" / "build_lite.py", "--root", src, "--out",
         html / "lite", "--edition", "student", *[a for i in graded for a in ("--withhold", i)]])
    if not args.no_pdf:
        run([sys.executable, ROOT / "scripts" / "make_pdf.py", "--site", html, "--out",
             out / "pdf" / "whittaker-teach.pdf", "--toc", src / "_toc.yml"])
    print(f"student_edition: {html}/index.html; graded (statements only): {', '.join(graded)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
