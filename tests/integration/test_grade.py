"""`python -m whittaker_teach grade`: a generated class graded into the CSV.

`make test` grades one submission of every kind (15 files); `make slow` grades
the whole class of 31, with the ordinary kinds repeated as in a real class.

All right, all wrong, partly answered, unanswered, answers as strings and as
SymPy objects, a cell that raises, an infinite loop, a 10 GB allocation, a
notebook that writes and deletes outside its folder, one that prints 30 MB,
one that opens a network connection, one that forges its own check log, a
file that is not a notebook and a truncated JSON file.  The batch must finish,
with the expected row for every part of every submission.
"""
import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

import whittaker_teach
from whittaker_teach.grading import run as grading

from .kepler_answers import EX
from .kepler_answers import RIGHT as TYPED_RIGHT
from .kepler_answers import WRONG as TYPED_WRONG

# every test that grades in the sandbox runs in one xdist worker (test_grade_attacks.py
# says why; make unit runs with --dist loadgroup)
pytestmark = pytest.mark.xdist_group("sandbox")

# the answers as string literals in the students' code cells
RIGHT = {part: json.dumps(text) for part, text in TYPED_RIGHT.items()}
WRONG = {part: json.dumps(text) for part, text in TYPED_WRONG.items()}
SYMPY_RIGHT = {
    "L_star": "sp.sqrt(2*h + 2*m*mu/r)*sp.sqrt(m*(r**2 + rp**2))",
    "r_pp": "(r**2*(2*h*r + m*mu) + rp**2*(4*h*r + 3*m*mu))/(2*r*(h*r + m*mu))",
    "h": "m*mu*(e**2 - 1)/(2*p)"}
PARTS = list(RIGHT)
SYMBOLS = ("import sympy as sp\nm, mu, p, r = sp.symbols('m mu p r', positive=True)\n"
           "h, e, rp = sp.symbols('h e rprime')")


def _notebook(path, cells, exercise=EX):
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    if exercise:
        nb.metadata["whittaker_teach"] = {"exercise": exercise}
    nb.cells = [nbformat.v4.new_markdown_cell("# a submission")]
    nb.cells += [nbformat.v4.new_code_cell(c) for c in cells]
    nbformat.write(nb, path)


def _checks(answers):
    return [f"check({EX!r}, {answers[p]}, part={p!r})" for p in PARTS]


def _class(folder, outside, full=True):
    """{file name: (expected {part: ok}, words of the failure row or None)}; with
    ``full=False`` one submission of each ordinary kind instead of a class's worth."""
    start = "from whittaker_teach.exercises import check"
    none = dict.fromkeys(PARTS, "None")
    expected = {}

    def add(name, cells, oks, failure=None, exercise=EX):
        _notebook(folder / name, cells, exercise)
        expected[name] = (oks, failure)

    def copies(n):
        return range(n if full else 1)

    for i in copies(4):
        add(f"right{i}.ipynb", [start, *_checks(RIGHT)], dict.fromkeys(PARTS, True))
    for i in copies(2):
        add(f"right-sympy{i}.ipynb", [start, SYMBOLS, *_checks(SYMPY_RIGHT)],
            dict.fromkeys(PARTS, True))
    for i in copies(6):
        add(f"wrong{i}.ipynb", [start, *_checks(WRONG)], dict.fromkeys(PARTS, False))
    for i in copies(3):
        add(f"partly-a{i}.ipynb", [start, *_checks({**none, "L_star": RIGHT["L_star"]})],
            {"L_star": True, "r_pp": False, "h": False})
        add(f"partly-b{i}.ipynb",
            [start, *_checks({**none, "h": RIGHT["h"], "r_pp": WRONG["r_pp"]})],
            {"L_star": False, "r_pp": False, "h": True})
    for i in copies(4):
        add(f"blank{i}.ipynb", [start, *_checks(none)], dict.fromkeys(PARTS, False))
    checks = _checks(RIGHT)
    add("raises.ipynb", [start, checks[0], "1/0", *checks[1:]], dict.fromkeys(PARTS, True),
        "error in code cell 3: ZeroDivisionError")
    add("loops.ipynb", [start, checks[0], "while True:\n    pass", *checks[1:]],
        {"L_star": True, "r_pp": False, "h": False}, "timeout: code cell 3")
    add("memory.ipynb", [start, checks[0], "x = bytearray(10 * 1024**3)", *checks[1:]],
        dict.fromkeys(PARTS, True), "MemoryError")
    add("vandal.ipynb", [start, *checks,
                         f"import os, shutil\nos.remove({str(outside / 'keep.txt')!r})",
                         f"open({str(outside / 'new.txt')!r}, 'w').write('x')",
                         "shutil.rmtree(os.path.expanduser('~'), ignore_errors=True)"],
        dict.fromkeys(PARTS, True), "error in code cell")
    add("noisy.ipynb", [start, "print('x' * 30_000_000)", *checks],
        dict.fromkeys(PARTS, True))
    add("network.ipynb", [start, *checks, "import socket\n"
                          "socket.create_connection(('93.184.216.34', 80), timeout=3)"],
        dict.fromkeys(PARTS, True), "error in code cell")
    forged = json.dumps({"exercise": EX, "part": "h", "kind": "answer", "status": "correct",
                         "ok": True, "answer": "m*mu", "why": ""})
    add("forged.ipynb", [start, *_checks(none),
                         f"import os\nos.write(int(os.environ['WHITTAKER_TEACH_CHECK_FD']), "
                         f"{forged!r}.encode() + b'\\n')"],
        {"L_star": False, "r_pp": False, "h": False})
    (folder / "essay.ipynb").write_text("My answers are on paper.\n", encoding="utf-8")
    expected["essay.ipynb"] = (None, "not a notebook")
    text = (folder / "right0.ipynb").read_text(encoding="utf-8")
    (folder / "cut.ipynb").write_text(text[: len(text) // 2], encoding="utf-8")
    expected["cut.ipynb"] = (None, "truncated")
    return expected


@pytest.fixture
def package_path(monkeypatch):
    """Kernels import this copy of whittaker_teach (not the editable install's)."""
    root = str(Path(whittaker_teach.__file__).resolve().parents[1])
    old = os.environ.get("PYTHONPATH", "")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([root] + ([old] if old else [])))
    return root


@pytest.mark.parametrize("full", [pytest.param(False, id="one-of-each-kind"),
                                  pytest.param(True, id="class-of-31", marks=pytest.mark.slow)])
def test_a_class_is_graded_into_the_expected_csv(tmp_path, package_path, full):
    folder = tmp_path / "submissions"
    folder.mkdir()
    outside = tmp_path / "lecturer"
    outside.mkdir()
    (outside / "keep.txt").write_text("keep me", encoding="utf-8")
    expected = _class(folder, outside, full)
    assert len(expected) == (31 if full else 15)
    paths = sorted(str(p) for p in folder.iterdir())
    out = tmp_path / "grades.csv"
    rows, line = grading.grade(paths, str(out), feedback=str(tmp_path / "feedback"), jobs=2,
                               cell_timeout=10, timeout=100, quiet=True)
    with open(out, newline="", encoding="utf-8") as f:
        table = list(csv.reader(f))
    assert table[0] == ["submission", "exercise", "part", "ok", "points", "max_points",
                        "message"]
    got = {}
    for sub, ex, part, ok, _, _, message in table[1:]:
        got.setdefault(sub, []).append((ex, part, ok, message))
    assert sorted(got) == sorted(expected)
    for sub, (oks, failure) in expected.items():
        lines = got[sub]
        fails = [m for _, part, _, m in lines if part == ""]
        if oks is None:                                     # could not be read at all
            assert len(lines) == 1 and lines[0][2] == "False" and failure in lines[0][3], lines
            continue
        parts = {part: (ok == "True", m) for _, part, ok, m in lines if part}
        assert {p: v[0] for p, v in parts.items()} == oks, (sub, lines)
        for p, (ok, message) in parts.items():
            if not ok and "blank" in sub:
                assert message == "not answered"
        if failure is None:
            assert not fails, (sub, fails)
        else:
            assert len(fails) == 1 and failure in fails[0], (sub, fails)
    # the lecturer's files are intact (the kernel could only write its scratch folder)
    assert (outside / "keep.txt").read_text(encoding="utf-8") == "keep me"
    assert not (outside / "new.txt").exists()
    right = sum(1 for r in rows if r.part and r.ok)
    wrong = sum(1 for r in rows if r.part and not r.ok)
    assert line == f"{len(expected)} submissions: {right} parts right, {wrong} parts wrong, " \
        f"{sum(1 for _, f in expected.values() if f)} failures"
    pages = sorted(p.name for p in (tmp_path / "feedback").iterdir())
    assert len(pages) == len(expected) and "right0.ipynb.html" in pages
    page = (tmp_path / "feedback" / "wrong0.ipynb.html").read_text(encoding="utf-8")
    assert "not yet right" in page and "<table>" in page


def test_the_command_line(tmp_path, package_path):
    (tmp_path / "a.ipynb").write_text("{\"cells\": [", encoding="utf-8")
    (tmp_path / "b.txt").write_text("hello", encoding="utf-8")
    out = tmp_path / "g.csv"
    proc = subprocess.run([sys.executable, "-m", "whittaker_teach", "grade",
                           str(tmp_path / "a.ipynb"), str(tmp_path / "b.txt"), "--out", str(out)],
                          capture_output=True, text=True, timeout=120,
                          env={**os.environ, "PYTHONPATH": package_path})
    assert proc.returncode == 0, proc.stderr
    assert "2 submissions: 0 parts right, 0 parts wrong, 2 failures" in proc.stdout
    rows = list(csv.reader(open(out, encoding="utf-8")))
    assert rows[1][:4] == ["a.ipynb", "", "", "False"] and "truncated" in rows[1][6]
    assert rows[2][:4] == ["b.txt", "", "", "False"] and "not a notebook" in rows[2][6]


def test_recorded_answers_are_graded_as_they_were_checked():
    """Every correct form of the unit tests (strings, SymPy objects from the library,
    numbers of every kind) survives recording: the grader's re-check agrees."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "unit"))
    import test_exercise_checks as cases

    from whittaker_teach.exercises import check
    from whittaker_teach.exercises.feedback import Feedback
    for (ex, part), (good, bad) in sorted(cases.CASES.items()):
        for spec in good + cases.MORE_GOOD.get((ex, part), []) + [b for b, _ in bad]:
            answer = cases._answer(spec)
            want = check(ex, answer, part=part).ok
            rec = json.loads(grading.record_line(Feedback(False, "", ex, part, "invalid"),
                                                 answer))
            ok, message = grading._recheck(ex, part, rec)
            assert ok == want, (ex, part, spec, message)


def test_file_names_beginning_with_a_dash(tmp_path, package_path):
    """`grade *.ipynb` where a file is called -x.ipynb, and `grade --out F -- *.ipynb`."""
    _notebook(tmp_path / "-x.ipynb", ["from whittaker_teach.exercises import check",
                                     *_checks(RIGHT)])
    (tmp_path / "b.txt").write_text("hello", encoding="utf-8")
    for argv in (["-x.ipynb", "b.txt", "--out", "g.csv"], ["--out", "g.csv", "--", "-x.ipynb",
                                                           "b.txt"]):
        proc = subprocess.run([sys.executable, "-m", "whittaker_teach", "grade", *argv],
                              capture_output=True, text=True, timeout=120, cwd=tmp_path,
                              env={**os.environ, "PYTHONPATH": package_path})
        assert proc.returncode == 0, proc.stderr
        assert "2 submissions: 3 parts right, 0 parts wrong, 1 failure" in proc.stdout
        rows = list(csv.reader(open(tmp_path / "g.csv", encoding="utf-8")))
        assert rows[1][0] == "'-x.ipynb" or rows[2][0] == "'-x.ipynb"
    proc = subprocess.run([sys.executable, "-m", "whittaker_teach", "grade", "--out", "g.csv",
                           "--nonsense"], capture_output=True, text=True, timeout=60,
                          cwd=tmp_path, env={**os.environ, "PYTHONPATH": package_path})
    assert proc.returncode == 2 and "unrecognized arguments: --nonsense" in proc.stderr


def test_without_the_sandbox_grade_refuses_unless_unsafe(tmp_path, monkeypatch, capsys):
    import argparse

    from whittaker_teach.grading import sandbox
    monkeypatch.setattr(sandbox, "_AVAILABLE", ["bubblewrap is not installed"])
    with pytest.raises(grading.SandboxUnavailable, match="bubblewrap is not installed"):
        grading.grade([], str(tmp_path / "g.csv"))
    (tmp_path / "essay.ipynb").write_text("not a notebook", encoding="utf-8")
    args = argparse.Namespace(submissions=[str(tmp_path / "essay.ipynb")],
                              out=str(tmp_path / "g.csv"), feedback=None,
                              jobs=1, cell_timeout=5, timeout=5, memory=500, quiet=True,
                              unsafe=False, gradebook=None, canvas=None, moodle=None)
    assert grading.main(args) == 2
    assert "refusing" in capsys.readouterr().err and not (tmp_path / "g.csv").exists()
    args.unsafe = True
    assert grading.main(args) == 0
    assert "UNSAFE" in capsys.readouterr().out


@pytest.mark.slow
def test_every_solution_notebook_gets_full_marks_in_the_sandbox(tmp_path):
    """The exercises' own solutions, graded as students' notebooks: every part right (so each
    exercise's solvers flag allows what its student notebook needs; a solution that confirms
    a hand derivation with the library where solvers are not allowed gets a note row)."""
    from whittaker_teach.grading import sandbox
    if sandbox.available():
        pytest.skip(sandbox.available())
    root = Path(__file__).resolve().parents[2] / "exercises" / "solutions"
    paths = sorted(str(p) for p in root.glob("*.ipynb"))
    assert paths
    rows, line = grading.grade(paths, str(tmp_path / "g.csv"), jobs=2, quiet=True,
                               cell_timeout=120, timeout=600)
    bad = [(r.submission, r.part, r.message) for r in rows if r.part and not r.ok]
    assert not bad, bad
    assert {r.submission for r in rows} == {Path(p).name for p in paths}


def run_processes(run):
    """The processes the grader run ``run`` (its pid) started that are still there: the
    sandbox marks them WHITTAKER_TEACH_RUN=<run> (never every process of a sandbox uid:
    another grader may be running at the same time)."""
    mark, out = f"WHITTAKER_TEACH_RUN={run}".encode(), []
    for pid in os.listdir("/proc"):
        try:
            if pid.isdigit():
                with open(f"/proc/{pid}/environ", "rb") as f:
                    if mark in f.read().split(b"\0"):
                        out.append(pid)
        except OSError:
            pass
    return out


def groups_of(run):
    """The cgroups the grader run ``run`` made that are still there."""
    found = []
    for top in ("/sys/fs/cgroup", ):
        for d, dirs, _ in os.walk(top):
            found += [os.path.join(d, x) for x in dirs if x.startswith(f"wt-grade-{run}-")]
            if d.count("/") > 8:
                dirs[:] = []
    return found


@pytest.mark.parametrize("signal_name", ["SIGINT", "SIGTERM"])
def test_an_interrupted_batch_keeps_its_rows_and_leaves_nothing_running(tmp_path,
                                                                         package_path,
                                                                         signal_name):
    """Ctrl-C (SIGINT) or SIGTERM while notebooks run: the rows graded so far stay in the
    CSV, the Moodle worksheet and the identity report are written for the students graded
    so far, no new run starts, and the running ones are killed with every process they
    started; no cgroup and no temporary folder of the run is left."""
    import signal
    import time

    from whittaker_teach.grading import sandbox
    if sandbox.available():
        pytest.skip(sandbox.available())
    subs, tmp = tmp_path / "subs", tmp_path / "tmp"
    tmp.mkdir()
    start = "from whittaker_teach.exercises import check"
    loop = ["import subprocess, time\nsubprocess.Popen(['sleep', '600'])\n"
            "while True:\n    time.sleep(1)"]
    # graded in this order, two at a time: Eve's run and Jane's start, Jane is graded, the
    # signal comes while Eve's and Vic's runs go on
    for folder, cells in (("Eve 111111_222222_assignsubmission_file", loop),
                          ("Jane Doe_123456_assignsubmission_file", [start]),
                          ("Vic Tim_111111_assignsubmission_file", loop)):
        (subs / folder).mkdir(parents=True)
        _notebook(subs / folder / "kepler.ipynb", [*cells, *_checks(RIGHT)])
    worksheet = Path(__file__).resolve().parents[1] / "fixtures" / "lms" / \
        "moodle-worksheet.csv"
    out = tmp_path / "g.csv"
    proc = subprocess.Popen([sys.executable, "-m", "whittaker_teach", "grade", "--exercise",
                             EX, "--moodle", str(worksheet), "--moodle-out",
                             str(tmp_path / "m.csv"), "--out", str(out), "--cell-timeout",
                             "60", "--jobs", "2", "--quiet", str(subs)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "PYTHONPATH": package_path, "TMPDIR": str(tmp)})
    end = time.monotonic() + 120            # until Jane is graded (the loops never end)
    while time.monotonic() < end and not (out.exists() and "Jane Doe" in out.read_text()):
        time.sleep(0.5)
    time.sleep(2)
    assert run_processes(proc.pid), "no run was going on when the signal was sent"
    proc.send_signal(getattr(signal, signal_name))
    stdout, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "interrupted" in err, (stdout, err)
    assert "keyrings:" in stdout and "memory:" in stdout        # the limits, printed first
    rows = list(csv.DictReader(open(out, encoding="utf-8")))
    assert {r["submission"].split("/")[0] for r in rows} == {
        "Jane Doe_123456_assignsubmission_file"} and all(r["ok"] == "True" for r in rows)
    moodle = {r["Identifier"]: r for r in csv.DictReader(open(tmp_path / "m.csv",
                                                             encoding="utf-8"))}
    assert moodle["Participant 123456"]["Grade"] == "100.00"
    assert moodle["Participant 222222"]["Grade"] == ""
    report = {r["student_id"]: r for r in csv.DictReader(open(tmp_path / "g-identities.csv",
                                                              encoding="utf-8"))}
    assert report["123456"]["status"] == "graded"
    for sid in ("222222", "111111"):
        assert report[sid]["status"] == "not-graded" and "interrupted" in \
            report[sid]["detail"], report[sid]
    for _ in range(100):            # killed processes take a moment to be reaped
        if not run_processes(proc.pid):
            break
        time.sleep(0.1)

    def described(pids):
        out = []
        for pid in pids:
            try:
                out.append((pid, open(f"/proc/{pid}/cmdline", "rb").read()
                            .replace(b"\0", b" ").decode(errors="replace")[:120]))
            except OSError:
                out.append((pid, "(gone)"))
        return out
    assert run_processes(proc.pid) == [], described(run_processes(proc.pid))
    assert groups_of(proc.pid) == []
    assert os.listdir(tmp) == []                # its package copy and submission folders


def test_an_assignment_graded_with_a_roster_into_moodle_and_canvas(tmp_path, package_path):
    """`grade --exercise --roster` on Moodle's folders layout, in the sandbox: the honest
    student is graded under her participant number and her grade is written into the
    worksheet, scaled to its Maximum Grade; a notebook of another exercise, a second
    notebook of one student and a folder of no one on the roster are reported, never
    graded under anyone; the command exits 1 to say so."""
    from whittaker_teach.grading import sandbox
    if sandbox.available():
        pytest.skip(sandbox.available())
    subs = tmp_path / "subs"
    start = "from whittaker_teach.exercises import check"

    def hand_in(folder, name, cells, exercise=EX):
        (subs / folder).mkdir(parents=True, exist_ok=True)
        _notebook(subs / folder / name, cells, exercise)
    hand_in("Jane Doe_123456_assignsubmission_file", "kepler.ipynb", [start, *_checks(RIGHT)])
    hand_in("Vic Tim_111111_assignsubmission_file", "easy.ipynb",
            [start, "check('identity-1-19', None, part='x')"], exercise="identity-1-19")
    hand_in("Eve 111111_222222_assignsubmission_file", "a.ipynb", [start, *_checks(RIGHT)])
    hand_in("Eve 111111_222222_assignsubmission_file", "b.ipynb", [start, *_checks(WRONG)])
    hand_in("Mallory_999_assignsubmission_file", "k.ipynb", [start, *_checks(RIGHT)])
    (subs / "Jane Doe_123456_assignsubmission_file" / "notes.txt").write_text("x")
    worksheet = Path(__file__).resolve().parents[1] / "fixtures" / "lms" / \
        "moodle-worksheet.csv"
    out = tmp_path / "g.csv"
    proc = subprocess.run([sys.executable, "-m", "whittaker_teach", "grade", "--exercise", EX,
                           "--moodle", str(worksheet), "--moodle-out", str(tmp_path / "m.csv"),
                           "--out", str(out), "--quiet", str(subs)],
                          capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PYTHONPATH": package_path})
    assert proc.returncode == 1, proc.stderr
    assert "2 submissions" in proc.stdout and "Moodle: 1 grades" in proc.stdout
    report = {}
    for r in csv.DictReader(open(tmp_path / "g-identities.csv", encoding="utf-8")):
        report.setdefault(r["status"], []).append(r)
    assert [r["student_id"] for r in report["graded"]] == ["123456"]
    assert [r["student_id"] for r in report["other-exercise"]] == ["111111"]
    assert sorted(r["submission"].rsplit("/", 1)[1] for r in report["duplicate"]) == \
        ["a.ipynb", "b.ipynb"]
    assert report["unknown"][0]["submission"].startswith("Mallory_999")
    assert [r["student_id"] for r in report["no-submission"]] == ["333333"]
    rows = {r["Identifier"]: r for r in csv.DictReader(open(tmp_path / "m.csv",
                                                           encoding="utf-8"))}
    assert rows["Participant 123456"]["Grade"] == "100.00"
    assert rows["Participant 111111"]["Grade"] == "50.00"          # as downloaded
    assert rows["Participant 222222"]["Grade"] == ""
    graded = list(csv.DictReader(open(out, encoding="utf-8")))
    assert {r["submission"].split("/")[0] for r in graded} == {
        "Jane Doe_123456_assignsubmission_file", "Vic Tim_111111_assignsubmission_file"}
    assert all(r["exercise"] == EX for r in graded)
