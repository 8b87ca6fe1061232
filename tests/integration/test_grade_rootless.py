"""Rootless grading (issue 37, item 6): a grader that is not root runs each notebook in a
user namespace of its own (bwrap --unshare-user) and says at start what it enforces.

The grader here runs as ``nobody`` (so the test needs root to start it, bubblewrap, and
unprivileged user namespaces).  A few folders it must read (this Python, when it lives
under root's 0700 home) are made visible to it in a mount namespace of the test's own;
nothing else of the machine is changed.
"""
import csv
import os
import pwd
import shutil
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import whittaker_teach

from .kepler_answers import RIGHT, WRONG
from .test_grade_attacks import KEY_READ, KEY_STORE, START, checks, notebook, steal

pytestmark = pytest.mark.xdist_group("sandbox")


def nobody():
    try:
        return pwd.getpwnam("nobody").pw_uid
    except KeyError:
        return None


def _closed_ancestor(path):
    """The topmost folder above ``path`` that others cannot pass through, or None."""
    for d in reversed(Path(path).resolve().parents):
        if not os.stat(d).st_mode & stat.S_IXOTH:
            return d
    return None


def as_nobody(argv, cwd):
    """argv run as nobody in a mount namespace where this Python and the package can be
    read (a closed folder above them replaced by an empty tmpfs with them bound in)."""
    uid = nobody()
    needed = [Path(sys.prefix).resolve(), Path(whittaker_teach.__file__).resolve().parents[1]]
    args = ["bwrap", "--dev-bind", "/", "/"]
    closed = {c for c in map(_closed_ancestor, needed) if c is not None}
    for c in sorted(closed):
        args += ["--perms", "0755", "--tmpfs", str(c)]
    for p in needed:
        for c in closed:
            if c in p.parents:
                for d in reversed(p.parents):
                    if c in d.parents:
                        args += ["--perms", "0755", "--dir", str(d)]
                args += ["--ro-bind", str(p), str(p)]
    args += ["--chdir", str(cwd), "--", "setpriv", f"--reuid={uid}", f"--regid={uid}",
             "--clear-groups", "--", "env", f"HOME={cwd}", f"TMPDIR={cwd}/tmp",
             f"PYTHONPATH={Path(whittaker_teach.__file__).resolve().parents[1]}", *argv]
    return subprocess.run(args, capture_output=True, text=True, timeout=600)


@pytest.fixture
def work():
    d = Path(tempfile.mkdtemp(prefix="wt-rootless-", dir="/tmp"))
    (d / "subs").mkdir()
    (d / "tmp").mkdir()
    yield d
    shutil.rmtree(d, ignore_errors=True)


@pytest.mark.skipif(os.geteuid() != 0 or nobody() is None or shutil.which("bwrap") is None
                    or shutil.which("setpriv") is None,
                    reason="needs root (to start a grader as nobody), bubblewrap, setpriv")
def test_a_grader_that_is_not_root(work):
    subs = work / "subs"
    notebook(subs / "honest.ipynb", [START, checks(RIGHT)])
    notebook(subs / "wrong.ipynb", [START, checks(WRONG)])
    notebook(subs / "processes.ipynb", [START, checks(RIGHT, ["L_star"]),
                                        "import subprocess\n"
                                        "ps = [subprocess.Popen(['sleep', '600']) "
                                        "for _ in range(300)]"])
    notebook(subs / "keyring-a-store.ipynb", [START, KEY_STORE, steal("found")])
    notebook(subs / "keyring-b-read.ipynb", [START, KEY_READ, steal("found")])
    # the grader's folders (its uid's, as the sandbox's is now) are not in its file system
    notebook(subs / "reach-out.ipynb", [START, "found = [p for p in ("
                                        f"{str(work)!r}, {str(subs / 'honest.ipynb')!r}, "
                                        f"{str(Path(whittaker_teach.__file__).parents[1])!r})"
                                        " if os.path.exists(p)]", steal("found")])
    for root, dirs, files in os.walk(work):
        for name in dirs + files + [""]:
            os.chown(os.path.join(root, name), nobody(), nobody())
    os.chmod(work, 0o755)
    proc = as_nobody([sys.executable, "-m", "whittaker_teach", "grade", "--quiet", "--jobs",
                      "1", "--out", str(work / "g.csv"), str(subs)], work)
    if "cannot make a user namespace" in proc.stderr:
        pytest.skip(proc.stderr.strip()[-300:])
    assert proc.returncode == 0, (proc.stdout, proc.stderr)
    assert "rootless: the grader's own uid, in a user namespace of its own" in proc.stdout
    assert "keyrings:  add_key, request_key and keyctl denied" in proc.stdout
    got = {}
    for r in csv.DictReader(open(work / "g.csv", encoding="utf-8")):
        got.setdefault(r["submission"], {})[r["part"]] = (r["ok"] == "True", r["message"])
    parts = {name: {p: v[0] for p, v in rows.items() if p} for name, rows in got.items()}
    everything = dict.fromkeys(RIGHT, True)
    nothing = dict.fromkeys(RIGHT, False)
    assert parts["honest.ipynb"] == everything and parts["wrong.ipynb"] == nothing
    for name in ("keyring-a-store.ipynb", "keyring-b-read.ipynb", "reach-out.ipynb"):
        assert parts[name] == nothing, (name, got[name])
    assert parts["processes.ipynb"] == {"L_star": True, "r_pp": False, "h": False}
    assert "error in code cell 3" in got["processes.ipynb"][""][1]      # RLIMIT_NPROC or pids
    assert os.listdir(work / "tmp") == []
