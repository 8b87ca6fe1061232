#!/usr/bin/env python
"""Re-execute notebooks in place, storing their outputs deterministically.

    python scripts/execute_notebooks.py [PATH ...]      (default: book exercises)

Each PATH is a notebook or a folder searched recursively for *.ipynb
(skipping _build and .ipynb_checkpoints). Kernels run with PYTHONHASHSEED=0,
cells run from the notebook's own folder, and no timing metadata is written,
so re-running an unchanged notebook gives a byte-identical file.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

os.environ["PYTHONHASHSEED"] = "0"  # inherited by the kernel subprocess
os.environ.setdefault("MPLBACKEND", "module://matplotlib_inline.backend_inline")

import nbformat  # noqa: E402
from nbclient import NotebookClient  # noqa: E402

SKIP_PARTS = {"_build", ".ipynb_checkpoints", "build"}


def find_notebooks(paths: list[str]) -> list[Path]:
    found: list[Path] = []
    for p in map(Path, paths):
        if p.is_file() and p.suffix == ".ipynb":
            found.append(p)
        elif p.is_dir():
            found.extend(
                nb for nb in sorted(p.rglob("*.ipynb"))
                if not SKIP_PARTS.intersection(nb.parts)
            )
    return found


def merge_streams(outputs: list) -> list:
    """Join consecutive stdout (or stderr) chunks: how a print is split into chunks
    depends on when the kernel flushes, and the stored file must not."""
    merged: list = []
    for out in outputs:
        prev = merged[-1] if merged else None
        if (out.get("output_type") == "stream" and prev is not None
                and prev.get("output_type") == "stream" and prev.get("name") == out.get("name")):
            prev["text"] = prev["text"] + out["text"]
        else:
            merged.append(out)
    return merged


def execute(path: Path, timeout: int = 600) -> None:
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(
        nb,
        timeout=timeout,
        kernel_name="python3",
        record_timing=False,
        allow_errors=False,
        resources={"metadata": {"path": str(path.parent.resolve())}},
    )
    client.execute()
    for cell in nb.cells:
        cell.metadata.pop("execution", None)
        if cell.cell_type == "code":
            cell.outputs = merge_streams(cell.outputs)
    nb.metadata.pop("widgets", None)
    nbformat.validate(nb)
    text = nbformat.writes(nb) + "\n"
    if path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")
        print(f"executed {path} (outputs changed)")
    else:
        print(f"executed {path} (unchanged)")


def main(argv: list[str]) -> int:
    notebooks = find_notebooks(argv or ["book", "exercises"])
    if not notebooks:
        print("no notebooks found")
        return 0
    for nb in notebooks:
        execute(nb)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
