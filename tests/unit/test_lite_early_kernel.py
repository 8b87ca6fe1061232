"""scripts/lite_early_kernel.py: the step of the lite build that starts the
kernel's worker with the page, on a small stand-in of a built lite site."""
from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))

import lite_early_kernel as lek  # noqa: E402

OPTIONS = {"env": {"PYTHONSTARTUP": "/lib/start.py"}, "packages": ["micropip", "ipython"]}
PAGE = """<html><head>
    <link rel="preload" href="../build/lab/bundle.js">
    <script id="jupyter-config-data" type="application/json">{}</script>
    <script>import('../config-utils.js')</script>
</head></html>"""


def fake_site(tmp_path: Path, workers=("comlink.worker.0123abcd.js",), page=PAGE) -> Path:
    out = tmp_path / "lite"
    static = out / lek.KERNEL_STATIC
    static.mkdir(parents=True)
    for name in workers:
        (static / name).write_text("// the kernel's worker\n")
    (out / "static" / "pyodide").mkdir(parents=True)
    for name in lek.CORE_FILES:
        (out / "static" / "pyodide" / name).write_bytes(f"pyodide {name}".encode())
    (out / "lab").mkdir()
    (out / "lab" / "index.html").write_text(page)
    config = {"jupyter-config-data": {"litePluginSettings": {lek.KERNEL_PLUGIN: {
        "pyodideUrl": "./static/pyodide/pyodide.mjs", "loadPyodideOptions": OPTIONS}}}}
    (out / "jupyter-lite.json").write_text(json.dumps(config))
    return out


def test_install_wires_page_worker_loader_and_config(tmp_path):
    out = fake_site(tmp_path)
    lek.install(out, OPTIONS)
    html = (out / "lab" / "index.html").read_text()
    assert html.count(lek.TAG) == 1
    assert html.index(lek.TAG) < html.index('id="jupyter-config-data"')
    worker = (out / lek.WORKER).read_text()
    assert 'import "../../extensions/@jupyterlite/pyodide-kernel-extension/static/' \
           'comlink.worker.0123abcd.js";' in worker
    assert f"const OPTIONS = {json.dumps(OPTIONS, sort_keys=True)};" in worker
    assert "comlink.worker.0123abcd.js" in (out / lek.PAGE_SCRIPT).read_text()
    loader = (out / lek.LOADER).read_text()
    assert "__KERNEL_WORKER__" not in loader and "__OPTIONS__" not in loader
    kernel = json.loads((out / "jupyter-lite.json").read_text())["jupyter-config-data"][
        "litePluginSettings"][lek.KERNEL_PLUGIN]
    assert kernel["pyodideUrl"] == lek.PYODIDE_URL == "./static/pyodide/wt-pyodide.mjs"
    lek.install(out, OPTIONS)                          # twice: one tag, same files
    assert (out / "lab" / "index.html").read_text().count(lek.TAG) == 1


def test_install_refuses_two_or_no_kernel_workers(tmp_path):
    out = fake_site(tmp_path, workers=("comlink.worker.a.js", "comlink.worker.b.js"))
    with pytest.raises(SystemExit, match="expected one comlink.worker"):
        lek.install(out, OPTIONS)
    out = fake_site(tmp_path / "none", workers=())
    with pytest.raises(SystemExit, match="expected one comlink.worker"):
        lek.install(out, OPTIONS)


def test_install_refuses_a_page_it_cannot_place_the_script_in(tmp_path):
    out = fake_site(tmp_path, page="<html><head></head></html>")
    with pytest.raises(SystemExit, match="no jupyter-config-data script"):
        lek.install(out, OPTIONS)


def test_check_names_options_that_differ_from_the_kernels(tmp_path):
    out = fake_site(tmp_path)
    lek.install(out, OPTIONS)
    other = dict(OPTIONS, packages=["micropip"])
    with pytest.raises(SystemExit, match="loadPyodideOptions are not"):
        lek.check(out, other)


def test_pyodides_own_files_move_to_a_folder_named_by_their_content(tmp_path):
    out = fake_site(tmp_path)
    lek.install(out, OPTIONS)
    core = lek.core_dir(out)
    assert core.name == lek.core_name([core / n for n in lek.CORE_FILES])
    assert sorted(p.name for p in core.iterdir()) == sorted(lek.CORE_FILES)
    assert not [n for n in lek.CORE_FILES if (out / "static/pyodide" / n).exists()]
    assert f'from "../{core.name}/pyodide.mjs"' in (out / lek.LOADER).read_text()
    # another stdlib zip, another folder
    other = fake_site(tmp_path / "other")
    (other / "static/pyodide/python_stdlib.zip").write_bytes(b"another stdlib")
    lek.install(other, OPTIONS)
    assert lek.core_dir(other).name != core.name
    # a file changed after the build is caught
    (core / "pyodide.asm.wasm").write_bytes(b"changed")
    with pytest.raises(SystemExit, match="does not hold exactly the files"):
        lek.check(out, OPTIONS)
