"""What runs a graded notebook inside its sandbox: ``python -m whittaker_teach.grading.worker``.

It runs the notebook from top to bottom with nbclient (a time limit per
cell; per-process limits set before the kernel starts) and writes one JSON
object to its stdout, the only thing the grader reads from it besides the
check log.  It imports nothing of whittaker_teach: the sandbox's copy of the
package holds it, the recorder and (where the exercise allows) the library,
never the grader, the answers or the checker.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

MAX_OUTPUT_CHARS = 1_000_000

def _private_stdout():
    """Keep fd 1 for the result only; the kernel inherits /dev/null; no one may open ours."""
    private = os.dup(1)                       # not inheritable
    devnull = os.open(os.devnull, os.O_RDWR)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    try:                                      # /proc/<worker>/fd becomes root's
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(4, 0, 0, 0, 0)   # PR_SET_DUMPABLE = 0
    except (OSError, AttributeError):
        pass
    return private


def _worker_main(argv):
    """``python -m whittaker_teach.grading.worker worker NOTEBOOK SCRATCH CELL_TIMEOUT MEMORY_MB
    PROCESSES DISK_MB LOG_FD``: run the notebook, write one JSON object to stdout.

    {"failure": None or {"kind", "cell"}, "errors": [{"cell", "ename"}]}; the
    kernel's check log goes to the pipe LOG_FD (``/dev/fd/LOG_FD``).
    """
    import resource
    private = _private_stdout()
    nb_path, scratch, cell_timeout = argv[0], Path(argv[1]), float(argv[2])
    memory, pids, disk, log_fd = int(argv[3]), int(argv[4]), int(argv[5]), int(argv[6])
    os.environ["WHITTAKER_TEACH_CHECK_FD"] = str(log_fd)              # the sandbox's recorder
    if not os.environ.get("WHITTAKER_TEACH_SANDBOX"):                 # the package's check
        os.environ["WHITTAKER_TEACH_CHECK_LOG"] = f"/dev/fd/{log_fd}"
    limit = memory * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    resource.setrlimit(resource.RLIMIT_FSIZE, (disk * 1024 * 1024,) * 2)
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if os.environ.get("WHITTAKER_TEACH_NPROC") == "1":    # its processes alone are counted
        resource.setrlimit(resource.RLIMIT_NPROC, (pids, pids))
    cpu = os.environ.get("WHITTAKER_TEACH_CPU_SECONDS", "")
    if cpu.isdigit() and int(cpu) > 0:          # CPU time per process (every process)
        resource.setrlimit(resource.RLIMIT_CPU, (int(cpu), int(cpu) + 5))
    for d in ("home", "tmp", ".grade", ".jupyter/runtime", ".ipython", ".matplotlib"):
        (scratch / d).mkdir(parents=True, exist_ok=True)
    home = scratch / "home"
    result = {"failure": None, "errors": []}
    try:
        _execute(nb_path, home, cell_timeout, log_fd, result)
    except BaseException as exc:  # noqa: BLE001 - report, never crash silently
        result["failure"] = result["failure"] or {"kind": "start", "cell": 0,
                                                  "ename": type(exc).__name__}
    data = json.dumps(result).encode("utf-8")
    view = memoryview(data)
    while view:
        view = view[os.write(private, view):]
    return 0


def _execute(nb_path, home, cell_timeout, log_fd, result):
    import nbformat
    from jupyter_client.manager import AsyncKernelManager
    from nbclient import NotebookClient
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    class Client(NotebookClient):
        """Keeps at most MAX_OUTPUT_CHARS of output (streams, displays, errors) in memory."""

        kept = 0

        def output(self, outs, msg, display_id, cell_index):
            content = msg.get("content", {})
            size = sum(len(str(v)) for v in content.values()) if isinstance(content, dict) \
                else MAX_OUTPUT_CHARS
            if msg.get("msg_type") != "error":
                self.kept += size
                if self.kept > MAX_OUTPUT_CHARS:
                    return None
            return super().output(outs, msg, display_id, cell_index)

    nb = nbformat.read(nb_path, as_version=4)
    for c in nb.cells:
        if c.cell_type == "code":
            c.outputs = []
    km = AsyncKernelManager(kernel_name="python3")
    client = Client(nb, km=km, timeout=cell_timeout, allow_errors=True, startup_timeout=60,
                    kernel_name="python3", shutdown_kernel="immediate",
                    resources={"metadata": {"path": str(home)}})
    n = 0
    try:
        with client.setup_kernel(cwd=str(home), pass_fds=(log_fd,)):
            for index, c in enumerate(nb.cells):
                if c.cell_type != "code":
                    continue
                n += 1
                try:
                    client.execute_cell(c, index)
                except CellTimeoutError:
                    result["failure"] = {"kind": "cell-timeout", "cell": n}
                    return
                except DeadKernelError:
                    result["failure"] = {"kind": "dead", "cell": n}
                    return
                for out in c.outputs:
                    if out.get("output_type") == "error" and len(result["errors"]) < 3:
                        result["errors"].append({"cell": n, "ename": str(out.get("ename"))[:80]})
                c.outputs = []
    except DeadKernelError:
        result["failure"] = result["failure"] or {"kind": "dead", "cell": n}


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "worker":
        sys.exit(_worker_main(sys.argv[2:]))
    sys.exit("usage: python -m whittaker_teach.grading.worker worker NOTEBOOK SCRATCH ...")
