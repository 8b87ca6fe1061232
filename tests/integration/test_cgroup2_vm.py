"""The grader's cgroup v2 path on a real cgroup-v2-only kernel, in a VM (opt-in).

``WT_CGROUP2_VM=1 python -m pytest -q tests/integration/test_cgroup2_vm.py`` runs
scripts/cgroup2_vm.py: it installs what is missing (Debian's qemu-system-x86,
busybox-static and linux-image-amd64, virtme-ng in a venv of its own), boots the VM with
cgroup v2 alone and, as root in a delegated group, checks the grader's Hierarchy against
the kernel and grades an honest student, a memory hog, a fork bomb and a CPU hog
(``WT_CGROUP2_VM_STEPS``, default ``env,probe,class``; ``WT_CGROUP2_VM_PYTEST`` adds
the grader's own integration tests).  Needs root; under emulation (no usable KVM) it
takes about 15 minutes.  Without ``WT_CGROUP2_VM=1`` it is skipped, so ``make test``
neither installs nor boots anything.
"""
import os
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "cgroup2_vm.py"

pytestmark = [
    pytest.mark.skipif(os.environ.get("WT_CGROUP2_VM") != "1",
                       reason="opt-in: set WT_CGROUP2_VM=1 to boot a cgroup-v2-only VM "
                       "(installs qemu, a kernel and virtme-ng; needs root)"),
    pytest.mark.slow,
]


def test_the_grader_limits_by_cgroup_v2_on_a_cgroup_v2_only_kernel(tmp_path):
    if os.geteuid() != 0:
        pytest.skip("scripts/cgroup2_vm.py needs root (WT_CGROUP2_VM=1 was set)")
    cmd = [sys.executable, str(SCRIPT), "--install", "--out", str(tmp_path / "vm"),
           "--steps", os.environ.get("WT_CGROUP2_VM_STEPS", "env,probe,class")]
    if os.environ.get("WT_CGROUP2_VM_PYTEST"):
        cmd += ["--pytest", os.environ["WT_CGROUP2_VM_PYTEST"]]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=4 * 3600)
    assert proc.returncode == 0, proc.stdout[-6000:] + proc.stderr[-3000:]
    assert "FAILED" not in proc.stdout and "not run" not in proc.stdout, proc.stdout
