// Run a Python file inside the Pyodide that the lite site serves (node, no browser).
//
//     node scripts/pyc_lite.mjs PYODIDE_DIR SCRIPT.py JOB.json
//
// The host's file system is mounted at /host (NODEFS), so the script reads and
// writes host paths as "/host" + path. The script sees the job as the global
// JOB (a dict, from JOB.json) and prints what it did on stdout. Used by
// scripts/pyc_lite.py to compile the served wheels and stdlib with Pyodide's own
// CPython, so that their .pyc files carry exactly its magic number.
import { readFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
import path from "node:path";

const [pyodideDir, script, job] = process.argv.slice(2);
const dir = path.resolve(pyodideDir) + "/";
try {
  const { loadPyodide } = await import(pathToFileURL(dir + "pyodide.mjs").href);
  const py = await loadPyodide({ indexURL: dir, stdout: (s) => console.log(s),
                                 stderr: (s) => console.error(s) });
  py.FS.mkdir("/host");
  py.FS.mount(py.FS.filesystems.NODEFS, { root: "/" }, "/host");
  py.globals.set("JOB", py.toPy(JSON.parse(readFileSync(job, "utf8"))));
  py.runPython(readFileSync(script, "utf8"), { filename: script });
} catch (e) {
  // not the whole minified runtime in the message: the Python traceback's tail
  console.error("pyc_lite.mjs: " + String(e && e.message || e).slice(-4000));
  process.exit(1);
}
