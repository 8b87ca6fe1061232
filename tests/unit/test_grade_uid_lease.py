"""Two graders at once never share a sandbox uid (issue 37, item 5: they reused the same
uids and killed each other's students)."""
import os
import subprocess
import sys

import pytest

from whittaker_teach.grading import sandbox


def test_leases_are_exclusive_and_given_back(tmp_path):
    a = sandbox.UidLease(tmp_path / "leases", kill_left=False)
    b = sandbox.UidLease(tmp_path / "leases", kill_left=False)
    assert a.uid != b.uid and {a.uid, b.uid} <= set(range(sandbox.UID_BASE, sandbox.UID_BASE
                                                             + sandbox.UID_COUNT))
    first = a.uid
    a.close()
    c = sandbox.UidLease(tmp_path / "leases", kill_left=False)
    assert c.uid == first
    b.close()
    c.close()


def test_another_process_holding_a_uid_is_respected(tmp_path):
    """A second grader (another process) holds the first uid: this one takes the next."""
    d = tmp_path / "leases"
    holder = subprocess.Popen([sys.executable, "-c", (
        "import sys, time; from whittaker_teach.grading import sandbox; "
        f"l = sandbox.UidLease({str(d)!r}, kill_left=False); print(l.uid, flush=True); "
        "time.sleep(30)")], stdout=subprocess.PIPE, text=True)
    try:
        held = int(holder.stdout.readline())
        mine = sandbox.UidLease(d, kill_left=False)
        assert mine.uid != held
        mine.close()
    finally:
        holder.kill()
        holder.wait()


def test_a_lease_folder_others_can_write_is_refused(tmp_path):
    d = tmp_path / "open"
    d.mkdir()
    os.chmod(d, 0o777)
    with pytest.raises(RuntimeError, match="private folder"):
        sandbox.UidLease(d, kill_left=False)
