#!/usr/bin/env python
"""Generate the exercise notebooks from their single sources.

    python scripts/make_exercises.py            generate, and execute what changed
    python scripts/make_exercises.py --all      generate and execute every notebook
    python scripts/make_exercises.py --check    exit 1 if a stored notebook is out of date
    python scripts/make_exercises.py ID ...     only these exercises

Each exercise is written once, in ``exercises/src/<id>.py`` (Jupyter's
"percent" format: cells start with ``# %%``).  From it come

* ``exercises/<id>.ipynb``, the student notebook: the solution code is
  replaced by placeholders (``answer = None  # your answer here``), the
  solution-only cells are left out, each ``check(...)`` says "not
  answered yet", and a last cell says how to hand it in and what the
  lecturer runs (``python -m whittaker_teach grade``); its metadata names
  the exercise (``"whittaker_teach": {"exercise": id}``) for the grader;
* ``exercises/solutions/<id>.ipynb``, the solution notebook, which is also
  the exercise's page on the book's site: the statement in an
  ``{exercise}`` box and each solution in a ``{solution}`` dropdown
  (sphinx-exercise's gated syntax, which can hold code cells).

and ``whittaker_teach/exercises/data/<id>.json``, the exercise's answer data (package data): the
solution notebook is first run with ``$WHITTAKER_TEACH_COLLECT`` set, so
that each ``check(id, answer, part=...)`` of the solution records its
answer as the part's expected one; with the ``# %% exercise`` cell (the
symbols and their domain, the parts with their points and messages:
``whittaker_teach.exercises.authoring``) it is written as JSON, and
``check`` reads it (no edit of the package for a new exercise).

Both notebooks are executed with their outputs stored (``PYTHONHASHSEED=0``, no
timing metadata: see ``scripts/execute_notebooks.py``).  A notebook whose
cells did not change, and whose answer data is up to date, is not
re-executed unless ``--all`` is given.

Cell markers in a source:

``# %% [markdown]``               markdown (each line's leading ``# `` removed)
``# %% [markdown] statement``     the exercise statement (boxed on the site)
``# %% [markdown] solution``      markdown of the solution only
``# %% [markdown] student``       markdown of the student notebook only
``# %%``                          code, in both notebooks
``# %% solution``                 code of the solution only
``# %% exercise``                 ``EXERCISE = {...}``: what the exercise is (in neither notebook)
``# %% tag=nbval-ignore-output``  a cell tag (only for timing outputs)
``# %% alt="..."``                the alt text of the figure a code cell draws

and inside a code cell, the lines between ``### BEGIN SOLUTION`` and
``### END SOLUTION`` are replaced, in the student notebook, by the
``### PLACEHOLDER: <code>`` lines of that cell.
"""
from __future__ import annotations

import argparse
import os
import re
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "exercises" / "src"
STUDENT_DIR = ROOT / "exercises"
SOLUTION_DIR = ROOT / "exercises" / "solutions"
# In this repository the answer data is package data (the wheel carries it); in a course
# folder of a lecturer's own (no whittaker_teach/ beside scripts/) it is written to
# exercises/answers/, which WHITTAKER_TEACH_ANSWERS then names for `check` and `grade`.
ANSWER_DIR = (ROOT / "whittaker_teach" / "exercises" / "data"
              if (ROOT / "whittaker_teach" / "__init__.py").is_file()
              else ROOT / "exercises" / "answers")

HEADER = re.compile(r"^# %%(?P<rest>.*)$")
KERNELSPEC = {"display_name": "Python 3", "language": "python", "name": "python3"}


class SourceError(ValueError):
    pass


def parse_source(text: str, name: str = "<source>") -> list[dict]:
    """Cells of a percent-format source: [{"type", "roles", "tags", "source"}]."""
    cells: list[dict] = []
    current = None
    for lineno, line in enumerate(text.splitlines(), 1):
        m = HEADER.match(line)
        if m:
            rest = m.group("rest")
            alt = re.search(r'\balt="([^"]+)"', rest)      # a figure's alt text
            rest = rest[:alt.start()] + rest[alt.end():] if alt else rest
            words = rest.split()
            kind = "code"
            if words and words[0] == "[markdown]":
                kind = "markdown"
                words = words[1:]
            roles = {w for w in words if not w.startswith("tag=")}
            tags = [w[4:] for w in words if w.startswith("tag=")]
            unknown = roles - {"statement", "solution", "student", "exercise"}
            if unknown:
                raise SourceError(f"{name}:{lineno}: unknown cell marker {sorted(unknown)}")
            if alt:
                tags.append("alt:" + alt.group(1))
            current = {"type": kind, "roles": roles, "tags": tags, "lines": []}
            cells.append(current)
            continue
        if current is None:
            if line.strip():
                raise SourceError(f"{name}:{lineno}: text before the first '# %%' marker")
            continue
        if current["type"] == "markdown":
            if line.strip() and not line.startswith("#"):
                raise SourceError(f"{name}:{lineno}: a markdown line must start with '#'")
            line = line[2:] if line.startswith("# ") else line[1:]
        current["lines"].append(line)
    for c in cells:
        while c["lines"] and not c["lines"][-1].strip():
            c["lines"].pop()
        while c["lines"] and not c["lines"][0].strip():
            c["lines"].pop(0)
        c["source"] = "\n".join(c.pop("lines"))
    return cells


def _split_solution(source: str, name: str) -> tuple[str, str, bool]:
    """(solution code, student code, has_solution) of a code cell."""
    sol, stu, placeholders = [], [], []
    inside = found = False
    for line in source.splitlines():
        s = line.strip()
        if s == "### BEGIN SOLUTION":
            if inside:
                raise SourceError(f"{name}: nested BEGIN SOLUTION")
            inside = found = True
            stu.append(None)  # where the placeholders go
        elif s == "### END SOLUTION":
            if not inside:
                raise SourceError(f"{name}: END SOLUTION without BEGIN")
            inside = False
        elif s.startswith("### PLACEHOLDER:"):
            indent = line[:len(line) - len(line.lstrip())]
            placeholders.append(indent + s[len("### PLACEHOLDER:"):].strip())
        else:
            sol.append(line)
            if not inside:
                stu.append(line)
    if inside:
        raise SourceError(f"{name}: BEGIN SOLUTION without END")
    if found and not placeholders:
        raise SourceError(f"{name}: a solution block needs a '### PLACEHOLDER: ...' line")
    out = []
    for line in stu:
        if line is None:
            out.extend(placeholders)
            placeholders = []
        else:
            out.append(line)
    return "\n".join(sol), "\n".join(out), found


HAND_IN = """## Handing in

1. Restart the kernel and run every cell (*Kernel > Restart Kernel and Run All Cells*):
   the grader runs your notebook the same way, from top to bottom in a fresh kernel,
   with a time limit per cell and no network.
2. Save it, then download it: *File > Download* (JupyterLab) or
   *File > Download as > Notebook (.ipynb)*. Hand in that `.ipynb` file, not a PDF
   or a copy of the text.

Your lecturer grades the whole class with

```
python -m whittaker_teach grade --exercise {ex_id} --roster roster.csv submissions/ --out grades.csv --feedback feedback/
```

which checks every answer you passed to `check(...)` again (the last check of each
part counts; a part you never checked is "not answered") and writes one row per part
and a feedback page for you. You are recognised by the file name your course's
system gives your upload, checked against the class list; a notebook of another
exercise is refused for this one."""


def _nb(cells: list[tuple[str, str, list]], ex_id: str):
    nb = nbformat.v4.new_notebook()
    nb.metadata = {"kernelspec": dict(KERNELSPEC), "language_info": {"name": "python"},
                   "whittaker_teach": {"exercise": ex_id}}
    for i, (kind, source, tags) in enumerate(cells):
        if kind == "markdown":
            cell = nbformat.v4.new_markdown_cell(source)
        else:
            cell = nbformat.v4.new_code_cell(source)
        cell.id = f"{ex_id}-{i:02d}"[-64:]
        alts = [t[4:] for t in tags if t.startswith("alt:")]
        tags = [t for t in tags if not t.startswith("alt:")]
        if tags:
            cell.metadata["tags"] = list(tags)
        if alts:                       # the alt text of the figure the cell draws
            cell.metadata["mystnb"] = {"image": {"alt": alts[0]}}
        nb.cells.append(cell)
    return nb


def build(ex_id: str, text: str):
    """(student notebook, solution notebook) of one source, not executed."""
    cells = parse_source(text, f"{ex_id}.py")
    label = f"ex-{ex_id}"
    student, solution = [], []
    group: list = []          # pending solution cells, wrapped in a dropdown

    def flush():
        if group:
            solution.append(("markdown", f"```{{solution-start}} {label}\n:class: dropdown\n```",
                             []))
            solution.extend(group)
            solution.append(("markdown", "```{solution-end}\n```", []))
            group.clear()

    statements = 0
    for c in cells:
        roles, src, tags = c["roles"], c["source"], c["tags"]
        if "exercise" in roles:
            continue                                   # read by spec_of, in no notebook
        if c["type"] == "markdown":
            if "statement" in roles:
                statements += 1
                student.append(("markdown", src, tags))
                flush()
                box = f":::{{exercise}}\n:label: {label}\n:nonumber:\n\n{src}\n:::"
                solution.append(("markdown", box, tags))
            elif "solution" in roles:
                group.append(("markdown", src, tags))
            elif "student" in roles:
                student.append(("markdown", src, tags))
            else:
                student.append(("markdown", src, tags))
                flush()
                solution.append(("markdown", src, tags))
            continue
        if "student" in roles:
            raise SourceError(f"{ex_id}: a code cell cannot be for the student only; use "
                              "### PLACEHOLDER lines")
        sol, stu, has = _split_solution(src, ex_id)
        if "solution" in roles:
            if has:
                raise SourceError(f"{ex_id}: a solution-only cell needs no BEGIN SOLUTION")
            group.append(("code", sol, tags))
        elif has:
            student.append(("code", stu, tags))
            group.append(("code", sol, tags))
        else:
            student.append(("code", src, tags))
            flush()
            solution.append(("code", src, tags))
    flush()
    student.append(("markdown", HAND_IN.format(ex_id=ex_id), []))
    if statements != 1:
        raise SourceError(f"{ex_id}: exactly one '# %% [markdown] statement' cell is needed, "
                          f"found {statements}")
    return _nb(student, ex_id), _nb(solution, ex_id)


def spec_of(ex_id: str, text: str) -> dict:
    """The ``EXERCISE`` dict of a source's ``# %% exercise`` cell (read, not run)."""
    from whittaker_teach.exercises.authoring import read_spec
    cells = [c for c in parse_source(text, f"{ex_id}.py") if "exercise" in c["roles"]]
    if len(cells) != 1 or cells[0]["type"] != "code":
        raise SourceError(f"{ex_id}: exactly one '# %% exercise' code cell is needed, found "
                          f"{len(cells)}")
    return read_spec(cells[0]["source"], f"{ex_id}.py")


def source_sha(text: str) -> str:
    import hashlib
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def answers_target(ex_id: str, answer_dir: Path | None = None) -> Path:
    return (answer_dir or ANSWER_DIR) / f"{ex_id}.json"


def answers_stale(ex_id: str, text: str, answer_dir: Path | None = None) -> bool:
    import json
    path = answers_target(ex_id, answer_dir)
    if not path.exists():
        return True
    try:
        return json.loads(path.read_text(encoding="utf-8")).get("source_sha256") != \
            source_sha(text)
    except ValueError:
        return True


def collect_answers(ex_id: str, text: str, solution, answer_dir: Path | None = None) -> Path:
    """Run the solution notebook collecting its answers; write the answer data (JSON)."""
    import json
    import tempfile
    from whittaker_teach.exercises.authoring import COLLECT, make_data
    spec = spec_of(ex_id, text)
    sys.path.insert(0, str(ROOT / "scripts"))
    from execute_notebooks import execute
    with tempfile.TemporaryDirectory() as tmp:
        # run where the solution notebook lives (same relative paths), from a copy
        SOLUTION_DIR.mkdir(parents=True, exist_ok=True)
        nb_path = SOLUTION_DIR / f".collect-{ex_id}-{os.getpid()}.ipynb"
        log = Path(tmp) / "collected.jsonl"
        nb_path.write_text(nbformat.writes(solution) + "\n", encoding="utf-8")
        old = os.environ.get(COLLECT)
        os.environ[COLLECT] = str(log)
        try:
            execute(nb_path)
        finally:
            nb_path.unlink(missing_ok=True)
            if old is None:
                os.environ.pop(COLLECT, None)
            else:
                os.environ[COLLECT] = old
        records = [json.loads(line) for line in log.read_text(encoding="utf-8").splitlines()] \
            if log.exists() else []
    data = make_data(ex_id, spec, records, source_sha(text))
    target = answers_target(ex_id, answer_dir)
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(data, indent=1, ensure_ascii=False, sort_keys=True) + "\n",
                      encoding="utf-8")
    print(f"answers of {ex_id} -> {target.relative_to(ROOT) if target.is_relative_to(ROOT) else target}")
    return target


def sources(ids=None) -> dict[str, Path]:
    found = {p.stem: p for p in sorted(SRC.glob("*.py"))}
    if ids:
        missing = sorted(set(ids) - set(found))
        if missing:
            raise SystemExit(f"no source for {', '.join(missing)} in {SRC}")
        found = {k: v for k, v in found.items() if k in ids}
    return found


def targets(ex_id: str) -> tuple[Path, Path]:
    return STUDENT_DIR / f"{ex_id}.ipynb", SOLUTION_DIR / f"{ex_id}.ipynb"


def cell_signature(nb) -> list[tuple]:
    """What must match between a generated and a stored notebook (outputs aside)."""
    return [(c.cell_type, c.source, tuple(c.metadata.get("tags", ()))) for c in nb.cells]


def stale(generated, path: Path) -> bool:
    if not path.exists():
        return True
    stored = nbformat.read(path, as_version=4)
    if cell_signature(stored) != cell_signature(generated):
        return True
    if stored.metadata.get("whittaker_teach") != generated.metadata.get("whittaker_teach"):
        return True
    return any(c.cell_type == "code" and c.execution_count is None and c.source.strip()
               for c in stored.cells)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("ids", nargs="*", help="exercise ids (default: all)")
    ap.add_argument("--all", action="store_true", help="re-execute every notebook")
    ap.add_argument("--check", action="store_true", help="only report stale notebooks")
    args = ap.parse_args(argv)
    todo, collect = [], []
    for ex_id, path in sources(args.ids).items():
        text = path.read_text(encoding="utf-8")
        student, solution = build(ex_id, text)
        spec_of(ex_id, text)                      # a bad exercise cell stops here, early
        fresh = answers_stale(ex_id, text)
        if fresh or args.all:
            collect.append((ex_id, text, solution))
        for nb, target in zip((student, solution), targets(ex_id)):
            if args.all or fresh or stale(nb, target):
                todo.append((nb, target))
    if args.check:
        for ex_id, _, _ in collect:
            print(f"out of date: {answers_target(ex_id).relative_to(ROOT)}")
        for _, target in todo:
            print(f"out of date: {target.relative_to(ROOT)}")
        if todo or collect:
            print("run `make exercises` to regenerate them")
        return 1 if todo or collect else 0
    if not todo and not collect:
        print("exercise notebooks are up to date")
        return 0
    # the notebooks are checked against the data written here (inherited by the kernels)
    os.environ["WHITTAKER_TEACH_ANSWERS"] = str(ANSWER_DIR)
    sys.path.insert(0, str(ROOT / "scripts"))
    from execute_notebooks import execute  # sets PYTHONHASHSEED=0 for the kernels
    for ex_id, text, solution in collect:
        collect_answers(ex_id, text, solution)
    for nb, target in todo:
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(nbformat.writes(nb) + "\n", encoding="utf-8")
        execute(target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
