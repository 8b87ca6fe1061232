"""Grading a class: run each submitted notebook in a fresh, confined kernel and collect its checks.

``python -m whittaker_teach grade SUBMISSION.ipynb ... --out grades.csv [--feedback DIR]``

For each submission:

1. the file is read as a notebook (not a file at all, not JSON, truncated
   JSON, not a notebook: one row saying so);
2. it is copied into a fresh scratch folder, which is also the kernel's
   working directory and ``HOME``;
3. its cells run in order in a fresh kernel (nbclient), two submissions at a
   time, with a time limit per cell and per notebook.  The kernel is
   confined: a memory limit (``RLIMIT_AS``), a limit on the size of files it
   writes and on its output; as root on Linux it also runs in its own network
   namespace (no network at all) and its own mount namespace, where every
   file system but its scratch folder is read-only, and without capabilities
   (``unshare -mn``, ``setpriv``).  Without root, a ``sitecustomize`` refuses
   connections to anything but the local machine, and the scratch folder is
   only the working directory: run ``grade`` as root in a container to grade
   untrusted notebooks;
4. every ``check(...)`` the notebook makes is recorded (the environment
   variable ``WHITTAKER_TEACH_CHECK_LOG`` makes :func:`check` append a JSON
   line with the answer it was given), and the grader checks each recorded
   answer again itself, in its own process, so that a notebook cannot write
   its own grades.  The last check of each part counts; a part never checked
   is "not answered".

The CSV has one row per submission and part, ``submission,exercise,part,ok,
message``, and one row with ``part`` empty when the notebook could not be run
to the end (a timeout, an error in cell N, a kernel that died, not a
notebook).  ``--feedback DIR`` writes one HTML page per submission.

>>> row = Row("alice.ipynb", "kepler-orbit", "h", False, "not answered")
>>> row.csv()
['alice.ipynb', 'kepler-orbit', 'h', 'False', 'not answered']
"""

from __future__ import annotations

import csv
import html
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Row", "grade", "grade_one", "record_line", "main"]

CELL_TIMEOUT = 60          # seconds per cell
NOTEBOOK_TIMEOUT = 300     # seconds per notebook
MEMORY_MB = 3000           # address space of the kernel
MAX_NOTEBOOK_BYTES = 20_000_000
MAX_OUTPUT_CHARS = 1_000_000
MAX_ANSWER_CHARS = 50_000
LOG_NAME = ".whittaker-teach-checks.jsonl"
KERNEL_NAME = "whittaker-teach-grade"


@dataclass
class Row:
    """One line of the grades: a part of a submission, or (part "") why it could not run."""

    submission: str
    exercise: str
    part: str
    ok: bool
    message: str

    def csv(self):
        return [self.submission, self.exercise, self.part, str(bool(self.ok)), self.message]


# ---------------------------------------------------------------- recording
def _answer_text(answer):
    """The answer as text the safe parser reads back (None if it cannot be)."""
    if isinstance(answer, str):
        return answer[:MAX_ANSWER_CHARS]
    kind = type(answer).__module__.split(".")[0]
    if kind == "numpy" and getattr(answer, "ndim", None) == 0:
        answer = answer.item()
    if kind == "mpmath":
        import mpmath
        return mpmath.nstr(answer, 30) if isinstance(answer, mpmath.mpf) else None
    if isinstance(answer, bool) or answer is None:
        return None
    if isinstance(answer, (int, float)):
        text = repr(answer)
        return text if len(text) < 100 else None
    if "sympy" in sys.modules and kind == "sympy":
        import sympy as sp
        if isinstance(answer, sp.Basic):
            if sum(1 for _ in zip(range(5001), sp.preorder_traversal(answer))) > 5000:
                return None
            text = sp.sstr(answer)
            return text if len(text) <= MAX_ANSWER_CHARS else None
    import numbers
    from fractions import Fraction
    if isinstance(answer, Fraction):
        return f"Rational({answer.numerator}, {answer.denominator})"
    if isinstance(answer, numbers.Number) and not isinstance(answer, complex):  # Decimal
        text = str(answer)
        return text if len(text) < 100 else None
    return None


def record_line(feedback, answer):
    """The JSON line that ``check`` appends to the check log while a notebook is graded.

    The answer as text the grader can read again, or, for what cannot be
    recorded so, the reason it cannot be read.
    """
    text, why = None, ""
    if feedback.status != "unanswered":
        try:
            text = _answer_text(answer)
            if text is None:
                from .parsing import read_answer
                read_answer(answer)
                why = "the answer is too large to record for grading; simplify it"
        except BaseException as exc:  # noqa: BLE001 - AnswerError, TooExpensive, anything
            why = str(exc)[:300] or type(exc).__name__
    return json.dumps({"exercise": feedback.exercise, "part": feedback.part,
                       "status": feedback.status, "answer": text, "why": why})


# ---------------------------------------------------------------- reading a submission
def read_submission(path):
    """(notebook, None) or (None, why it is not a notebook)."""
    import nbformat
    path = Path(path)
    if not path.is_file():
        return None, "not a file"
    size = path.stat().st_size
    if size > MAX_NOTEBOOK_BYTES:
        return None, f"the file is {size // 1_000_000} MB; a notebook of at most " \
            f"{MAX_NOTEBOOK_BYTES // 1_000_000} MB is expected"
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        return None, "not a notebook (a binary file, not JSON text)"
    if not text.lstrip().startswith("{"):
        return None, "not a notebook (not JSON: download the .ipynb file from Jupyter)"
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        where = f"line {exc.lineno}, column {exc.colno}"
        if exc.pos >= len(text.rstrip()) - 1:
            return None, f"not a notebook: the JSON is truncated (it ends at {where})"
        return None, f"not a notebook: the JSON is damaged at {where} ({exc.msg})"
    try:
        nb = nbformat.from_dict(data)
        if nb.get("nbformat") != 4:
            return None, "not a notebook in format 4 (save it from a current Jupyter)"
        nb = nbformat.reads(text, as_version=4)
        nbformat.validate(nb)
    except Exception as exc:  # noqa: BLE001 - nbformat raises many kinds
        return None, f"not a valid notebook ({type(exc).__name__}: {str(exc)[:120]})"
    return nb, None


def exercise_of(nb):
    """The exercise id of a student notebook (metadata, else its check cells)."""
    import re
    meta = nb.metadata.get("whittaker_teach", {})
    if isinstance(meta, dict) and isinstance(meta.get("exercise"), str):
        return meta["exercise"]
    for cell in nb.cells:
        if cell.cell_type == "code":
            m = re.search(r"check\(\s*[\"']([\w-]+)[\"']", cell.source)
            if m:
                return m.group(1)
    return None


# ---------------------------------------------------------------- the kernel's confinement
_SITE = '''\
"""Installed by whittaker_teach's grader: no network but the local machine."""
import socket as _socket

_connect = _socket.socket.connect
_connect_ex = _socket.socket.connect_ex


def _local(address):
    if isinstance(address, (str, bytes)):          # a unix socket
        return True
    host = str(address[0])
    return host in ("localhost", "::1", "0.0.0.0") or host.startswith("127.")


def connect(self, address):
    if not _local(address):
        raise OSError(101, "no network while a submission is graded")
    return _connect(self, address)


def connect_ex(self, address):
    if not _local(address):
        return 101
    return _connect_ex(self, address)


_socket.socket.connect = connect
_socket.socket.connect_ex = connect_ex
'''

# run in the kernel before the student's cells: cap what it prints
_CAP_OUTPUT = f'''\
import sys as _sys


class _Capped:
    def __init__(self, stream, left):
        self._stream, self._left = stream, left

    def write(self, text):
        if self._left <= 0:
            return len(text)
        part = text[:self._left]
        self._left -= len(part)
        if self._left <= 0:
            part += "\\n[the grader cut the output here]\\n"
        return self._stream.write(part)

    def __getattr__(self, name):
        return getattr(self._stream, name)


_sys.stdout = _Capped(_sys.stdout, {MAX_OUTPUT_CHARS})
_sys.stderr = _Capped(_sys.stderr, {MAX_OUTPUT_CHARS})
del _Capped
'''


_CONFINE = []


def confinement_available():
    """Can kernels run in their own network and mount namespaces (root, unshare, setpriv)?

    Tried once: ``unshare -mn true`` must succeed (a container without the
    capability to make namespaces cannot).
    """
    if not _CONFINE:
        ok = (sys.platform.startswith("linux") and hasattr(os, "geteuid") and os.geteuid() == 0
              and all(shutil.which(c) for c in ("unshare", "setpriv", "mount")))
        if ok:
            try:
                ok = subprocess.run(["unshare", "-mn", "true"], capture_output=True,
                                    timeout=20).returncode == 0
            except (OSError, subprocess.SubprocessError):
                ok = False
        _CONFINE.append(ok)
    return _CONFINE[0]


def _kernel_main(argv):
    """``python -m whittaker_teach.exercises.grade kernel ROOT MEMORY_MB CONFINE -f FILE``.

    Runs inside ``unshare -mn`` when CONFINE is 1: make every mount but ROOT
    read-only, drop all capabilities, then become the IPython kernel.
    """
    import resource
    root, memory, confine, rest = argv[0], int(argv[1]), argv[2] == "1", argv[3:]
    if confine:
        subprocess.run(["mount", "--make-rprivate", "/"], check=True)
        subprocess.run(["mount", "--bind", root, root], check=True)
        with open("/proc/self/mounts", encoding="utf-8") as f:
            points = [line.split()[1] for line in f]
        for mp in sorted(set(points), key=len, reverse=True):
            if mp == root or mp.startswith(("/proc", "/sys")) or mp in ("/dev", "/dev/pts"):
                continue
            subprocess.run(["mount", "-o", "remount,bind,ro", mp], stderr=subprocess.DEVNULL,
                           check=False)
    limit = memory * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    resource.setrlimit(resource.RLIMIT_FSIZE, (100_000_000, 100_000_000))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    os.chdir(os.path.join(root, "work"))
    cmd = [sys.executable, "-m", "ipykernel_launcher", *rest]
    if confine:
        cmd = ["setpriv", "--bounding-set=-all", "--inh-caps=-all", "--no-new-privs", *cmd]
    os.execvp(cmd[0], cmd)


def _kernel_spec(ctl, root, memory, confine):
    """A kernelspec folder (in ctl) whose kernel is confined as described above."""
    argv = [sys.executable, "-m", "whittaker_teach.exercises.grade", "kernel", str(root),
            str(memory), "1" if confine else "0", "-f", "{connection_file}"]
    if confine:
        argv = ["unshare", "-mn", *argv]
    spec = Path(ctl) / "kernels" / KERNEL_NAME
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({"argv": argv, "display_name": "grade",
                                                  "language": "python"}), encoding="utf-8")
    return Path(ctl)


# ---------------------------------------------------------------- running one notebook
def _worker_main(argv):
    """``python -m whittaker_teach.exercises.grade run NOTEBOOK ROOT CELL_TIMEOUT MEMORY CONFINE
    RESULT``.

    Runs in a process of its own (the grader kills it at the notebook's time
    limit); writes one JSON object to RESULT (outside ROOT, where the kernel
    cannot write when confined): {"failure": "" or why the run stopped}.
    """
    import resource

    import nbformat
    from jupyter_client.manager import AsyncKernelManager
    from nbclient import NotebookClient
    from nbclient.exceptions import CellTimeoutError, DeadKernelError
    nb_path, root, cell_timeout, memory, confine, result = argv[0], Path(argv[1]), \
        float(argv[2]), int(argv[3]), argv[4] == "1", argv[5]
    limit = 4 * 1024**3         # the worker holds the outputs: bound it too
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    nb = nbformat.read(nb_path, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs = []
    km = AsyncKernelManager(kernel_name=KERNEL_NAME, transport="ipc",
                       ip=str(root / "ctl" / "kernel"))
    client = NotebookClient(nb, km=km, timeout=cell_timeout, allow_errors=True,
                            startup_timeout=60, kernel_name=KERNEL_NAME,
                            shutdown_kernel="immediate",
                            resources={"metadata": {"path": str(root / "work")}})
    failure = ""
    errors = []
    try:
        with client.setup_kernel(cwd=str(root / "work")):
            client.kc.execute(_CAP_OUTPUT, silent=True, store_history=False)
            n = 0
            for index, cell in enumerate(nb.cells):
                if cell.cell_type != "code":
                    continue
                n += 1
                try:
                    client.execute_cell(cell, index)
                except CellTimeoutError:
                    failure = f"timeout: code cell {n} ran longer than {cell_timeout:g} s"
                    break
                except DeadKernelError:
                    failure = f"the kernel died in code cell {n} (out of memory, or it exited)"
                    break
                for out in cell.outputs:
                    if out.get("output_type") == "error" and len(errors) < 3:
                        errors.append(f"error in code cell {n}: {out.get('ename', '')}: "
                                      f"{str(out.get('evalue', ''))[:150]}")
                cell.outputs = []          # not kept: only the checks count
    except DeadKernelError:
        failure = failure or "the kernel died"
    except Exception as exc:  # noqa: BLE001 - report, never crash the batch
        failure = failure or f"the notebook could not be run ({type(exc).__name__}: " \
            f"{str(exc)[:150]})"
    if not failure and errors:
        failure = "; ".join(errors)
    Path(result).write_text(json.dumps({"failure": failure}), encoding="utf-8")
    return 0


def _run(nb_path, cell_timeout, timeout, memory, confine):
    """Run one notebook in a fresh confined kernel: (check log lines, failure text)."""
    top = Path(tempfile.mkdtemp(prefix="wt-grade-"))
    private = Path(tempfile.mkdtemp(prefix="wt-grade-result-"))
    result = private / "result.json"
    try:
        work, ctl = top / "work", top / "ctl"
        work.mkdir()
        ctl.mkdir()
        (ctl / "site").mkdir()
        (ctl / "site" / "sitecustomize.py").write_text(_SITE, encoding="utf-8")
        shutil.copy(nb_path, work / "submission.ipynb")
        _kernel_spec(ctl, top, memory, confine)
        env = {k: v for k, v in os.environ.items()
               if not k.startswith(("JUPYTER", "WHITTAKER_TEACH", "IPYTHON"))}
        path = [str(ctl / "site")] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p]
        env.update({"HOME": str(work), "TMPDIR": str(work), "JUPYTER_PATH": str(ctl),
                    "JUPYTER_DATA_DIR": str(ctl), "JUPYTER_RUNTIME_DIR": str(ctl),
                    "JUPYTER_CONFIG_DIR": str(ctl), "IPYTHONDIR": str(ctl / "ipython"),
                    "PYTHONPATH": os.pathsep.join(path), "PYTHONHASHSEED": "0",
                    "WHITTAKER_TEACH_CHECK_LOG": str(ctl / LOG_NAME), "MPLBACKEND": "Agg",
                    "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1",
                    "http_proxy": "http://127.0.0.1:9", "https_proxy": "http://127.0.0.1:9",
                    "no_proxy": ""})
        cmd = [sys.executable, "-m", "whittaker_teach.exercises.grade", "run",
               str(work / "submission.ipynb"), str(top), str(cell_timeout), str(memory),
               "1" if confine else "0", str(result)]
        proc = subprocess.Popen(cmd, env=env, cwd=str(ctl), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
        try:
            proc.wait(timeout=timeout)
            try:
                failure = str(json.loads(result.read_text(encoding="utf-8"))["failure"])
            except (OSError, ValueError, KeyError, TypeError):
                failure = "the grader could not run the notebook (it stopped without a result)"
        except subprocess.TimeoutExpired:
            failure = f"timeout: the notebook ran longer than {timeout:g} s"
        finally:
            _kill(proc)
        log = ctl / LOG_NAME
        lines = []
        if log.is_file() and not log.is_symlink():
            with open(log, "rb") as f:
                raw = f.read(20_000_000)
            lines = raw.decode("utf-8", "replace").splitlines()
        return lines, failure
    finally:
        shutil.rmtree(top, ignore_errors=True)
        shutil.rmtree(private, ignore_errors=True)


def _kill(proc):
    """Kill the worker's whole session (the worker and its kernel)."""
    import signal
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # pragma: no cover
        pass


# ---------------------------------------------------------------- grading
def _last_checks(lines, exercise):
    """{part: record} of the last check of each part of this exercise."""
    out = {}
    for line in lines:
        try:
            rec = json.loads(line)
        except ValueError:
            continue
        if not isinstance(rec, dict) or rec.get("exercise") != exercise:
            continue
        part = rec.get("part")
        if isinstance(part, str):
            out[part] = rec
    return out


def _recheck(exercise, part, rec):
    """(ok, message) of a recorded answer, checked again here."""
    from .catalog import EXERCISES
    from .specs import check_part
    if rec.get("status") == "unanswered":
        return False, "not answered"
    answer = rec.get("answer")
    if not isinstance(answer, str):
        why = str(rec.get("why") or "the answer could not be recorded for grading")
        return False, why[:1].upper() + why[1:300]
    ex = EXERCISES[exercise]
    f = check_part(ex, ex.parts[part], answer, max_length=MAX_ANSWER_CHARS)
    if f.status == "unanswered":
        return False, "not answered"
    return bool(f.ok), f.message


def prepare(path):
    """(name, exercise or None, rows if it cannot be run)."""
    from . import exercises
    name = Path(path).name
    nb, why = read_submission(path)
    if nb is None:
        return name, None, [Row(name, "", "", False, why)]
    exercise = exercise_of(nb)
    if exercise not in exercises():
        return name, None, [Row(name, str(exercise or "")[:40], "", False,
                                "not a notebook of the exercises (no check(...) of a known "
                                "exercise in it)")]
    return name, exercise, None


def score(name, exercise, lines, failure):
    """The rows of a submission that ran: one per part, and one for a failure."""
    from . import parts
    checks = _last_checks(lines, exercise)
    rows = []
    for part in parts(exercise):
        rec = checks.get(part)
        if rec is None:
            rows.append(Row(name, exercise, part, False, "not answered"))
            continue
        ok, message = _recheck(exercise, part, rec)
        rows.append(Row(name, exercise, part, ok, message))
    if failure:
        rows.append(Row(name, exercise, "", False, failure))
    return rows


def grade_one(path, cell_timeout=CELL_TIMEOUT, timeout=NOTEBOOK_TIMEOUT, memory=MEMORY_MB,
              confine=None):
    """The rows of one submission (runs it; see the module docstring)."""
    name, exercise, rows = prepare(path)
    if rows is not None:
        return rows
    if confine is None:
        confine = confinement_available()
    lines, failure = _run(path, cell_timeout, timeout, memory, confine)
    return score(name, exercise, lines, failure)


def _progress(total, quiet):
    """A progress bar on a terminal (tqdm if installed, else a counter); None otherwise."""
    if quiet or not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
        return tqdm(total=total, unit="notebook", file=sys.stderr, ncols=100)
    except ImportError:
        class Counter:
            n = 0

            def update(self, k=1):
                self.n += k
                print(f"\rgraded {self.n}/{total}", end="", file=sys.stderr, flush=True)

            def close(self):
                print(file=sys.stderr)
        return Counter()


def grade(paths, out, feedback=None, jobs=2, cell_timeout=CELL_TIMEOUT,
          timeout=NOTEBOOK_TIMEOUT, memory=MEMORY_MB, quiet=False, confine=None):
    """Grade the submissions into the CSV ``out``: (rows, summary line).

    The notebooks run ``jobs`` at a time (each in its own worker process and
    kernel); their recorded answers are then checked again here, in the main
    thread, where each check has its time budget.
    """
    from .catalog import EXERCISES
    if confine is None:
        confine = confinement_available()
    prepared = {p: prepare(p) for p in paths}
    for _, exercise, _ in prepared.values():
        if exercise is not None:
            EXERCISES[exercise].build()      # once, before the notebooks run
    bar = _progress(len(paths), quiet)
    todo = [p for p in paths if prepared[p][2] is None]
    runs = {}
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures = {pool.submit(_safe_run, p, cell_timeout, timeout, memory, confine): p
                   for p in todo}
        for p in paths:
            if prepared[p][2] is not None and bar is not None:
                bar.update(1)
        for fut in as_completed(futures):
            runs[futures[fut]] = fut.result()
            if bar is not None:
                bar.update(1)
    if bar is not None:
        bar.close()
    results = {}
    for p in paths:
        name, exercise, rows = prepared[p]
        results[p] = rows if rows is not None else score(name, exercise, *runs[p])
    rows = [r for p in paths for r in results[p]]
    with open(out, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["submission", "exercise", "part", "ok", "message"])
        for r in rows:
            w.writerow(r.csv())
    if feedback:
        write_feedback(feedback, paths, results)
    return rows, summary(rows, len(paths))


def _safe_run(path, cell_timeout, timeout, memory, confine):
    try:
        return _run(path, cell_timeout, timeout, memory, confine)
    except Exception as exc:  # noqa: BLE001 - one submission never stops the batch
        return [], f"the grader could not run it ({type(exc).__name__}: {str(exc)[:150]})"


def summary(rows, n):
    """'30 submissions: 41 parts right, 49 parts wrong, 6 failures'."""
    right = sum(1 for r in rows if r.part and r.ok)
    wrong = sum(1 for r in rows if r.part and not r.ok)
    failures = len({r.submission for r in rows if not r.part})
    return (f"{n} submission{'s' if n != 1 else ''}: {right} part{'s' if right != 1 else ''} "
            f"right, {wrong} part{'s' if wrong != 1 else ''} wrong, {failures} "
            f"failure{'s' if failures != 1 else ''}")


_FEEDBACK_CSS = ("<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;"
                 "padding:0 1em;line-height:1.4}table{border-collapse:collapse}"
                 "td,th{padding:.4em .6em;border-bottom:1px solid #ddd;text-align:left;"
                 "vertical-align:top}td:nth-child(2){white-space:nowrap}</style>")


def write_feedback(folder, paths, results):
    """One HTML page per submission: its parts, right or not, and the messages."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for p in paths:
        rows = results[p]
        name = Path(p).name
        items = []
        for r in rows:
            colour = "#2e7d32" if r.ok else "#c62828"
            label = "right" if r.ok else ("could not run" if not r.part else "not yet right")
            items.append(f'<tr><td>{html.escape(r.part or "(notebook)")}</td>'
                         f'<td style="color:{colour}">{label}</td>'
                         f"<td>{html.escape(r.message)}</td></tr>")
        exercise = html.escape(rows[0].exercise) if rows else ""
        right = sum(1 for r in rows if r.part and r.ok)
        total = sum(1 for r in rows if r.part)
        page = ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
                f"<title>Feedback: {html.escape(name)}</title>" + _FEEDBACK_CSS +
                f"</head><body><h1>Feedback on {html.escape(name)}</h1>"
                f"<p>Exercise: {exercise}. {right} of {total} parts right.</p>"
                "<table><tr><th>part</th><th>result</th><th>message</th></tr>"
                + "".join(items) + "</table></body></html>\n")
        stem = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)
        (folder / f"{stem}.html").write_text(page, encoding="utf-8")


def main(args):
    """The ``grade`` subcommand."""
    paths = [str(p) for p in args.submissions]
    missing = [p for p in paths if not os.path.exists(p)]
    start = time.monotonic()
    rows, line = grade(paths, args.out, args.feedback, args.jobs, args.cell_timeout,
                       args.timeout, args.memory, args.quiet)
    took = time.monotonic() - start
    print(f"{line} ({took:.0f} s); grades in {args.out}"
          + (f", feedback in {args.feedback}" if args.feedback else ""))
    if missing:
        print(f"(not found: {', '.join(missing[:5])}{' ...' if len(missing) > 5 else ''})")
    if not confinement_available():
        print("(the kernels were not confined: grade as root on Linux, in a container, to "
              "give each its own network and read-only file systems)")
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "kernel":
        _kernel_main(sys.argv[2:])
    elif len(sys.argv) > 1 and sys.argv[1] == "run":
        sys.exit(_worker_main(sys.argv[2:]))
    else:
        sys.exit("usage: python -m whittaker_teach grade SUBMISSION.ipynb ... --out grades.csv")
