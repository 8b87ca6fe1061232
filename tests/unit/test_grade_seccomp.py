"""The sandbox's seccomp filter denies the kernel's key management (issue 37, item 5:
kernel keyrings persisted per uid, so a later student read an earlier one's key; and
every sandbox process inherited the grader's session keyring).  The filter is run here
under bubblewrap as ``grade`` loads it; tests/integration/test_grade_attacks.py runs the
attack (one submission stores a key, the next looks for it) in a graded batch."""
import os
import platform
import shutil
import subprocess
import sys

import pytest

from whittaker_teach.grading import sandbox

pytestmark = pytest.mark.skipif(
    shutil.which("bwrap") is None or platform.machine() not in ("x86_64", "aarch64"),
    reason="needs bubblewrap on x86_64 or aarch64")

NUMBERS = {"x86_64": {"add_key": 248, "request_key": 249, "keyctl": 250, "getpid": 39},
           "aarch64": {"add_key": 217, "request_key": 218, "keyctl": 219, "getpid": 172}}

# each call as the sandbox would make it: (name, syscall number, arguments)
PROBE = r"""
import ctypes, json, os, sys
n = json.loads(sys.argv[1])
libc = ctypes.CDLL(None, use_errno=True)
libc.syscall.restype = ctypes.c_long
calls = {
    "keyctl": (n["keyctl"], 0, -4, 0),                    # KEYCTL_GET_KEYRING_ID, user keyring
    "keyctl-session": (n["keyctl"], 0, -3, 0),            # ... the session keyring
    "request_key": (n["request_key"], b"user", b"wt-grade-test", None, 0),
    "add_key": (n["add_key"], b"user", b"wt-grade-test", b"x", 1, -2**31),   # no keyring
    "getpid": (n["getpid"],),
}
if "x32" in n:
    calls["x32-keyctl"] = (n["keyctl"] | n["x32"], 0, -4, 0)
out = {}
for name, args in calls.items():
    ctypes.set_errno(0)
    r = libc.syscall(*args)
    out[name] = "ok" if r >= 0 else os.strerror(ctypes.get_errno())
print(json.dumps(out))
"""


def probe(filtered):
    import json
    numbers = dict(NUMBERS[platform.machine()])
    if platform.machine() == "x86_64":
        numbers["x32"] = 0x40000000
    fd = sandbox.seccomp_fd() if filtered else None
    args = ["bwrap", "--ro-bind", "/", "/", "--proc", "/proc", "--dev", "/dev"]
    if fd is not None:
        args += ["--seccomp", str(fd)]
    try:
        proc = subprocess.run(args + ["--", sys.executable, "-I", "-c", PROBE,
                                      json.dumps(numbers)],
                              capture_output=True, text=True, timeout=60,
                              pass_fds=() if fd is None else (fd,))
    finally:
        if fd is not None:
            os.close(fd)
    if proc.returncode and "Operation not permitted" in proc.stderr and not filtered:
        pytest.skip(f"bubblewrap cannot run here: {proc.stderr.strip()[:200]}")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_without_the_filter_the_keyrings_are_reachable():
    """(What the filter is for: the same probe, unfiltered, reaches the keyrings.)"""
    got = probe(False)
    assert got["keyctl"] == "ok" and got["keyctl-session"] == "ok" and got["getpid"] == "ok"


def test_the_filter_denies_key_management_and_nothing_else():
    got = probe(True)
    denied = {k: v for k, v in got.items() if k != "getpid"}
    assert set(denied.values()) == {"Operation not permitted"}, got
    assert got["getpid"] == "ok"


def test_the_filter_program():
    prog = sandbox.seccomp_filter("x86_64")
    assert len(prog) // 8 == 9 and len(prog) % 8 == 0   # 2 loads, 5 tests, 2 returns
    assert sandbox.seccomp_filter("riscv64") is None      # unknown: grade says not denied
