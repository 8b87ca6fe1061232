// Where the in-browser kernel's Python start-up goes, measured in node with the
// site's own Pyodide, lock and wheels (a diagnostic that prints, not a test).
//
//     node scripts/profile_lite_node.mjs _build/html/lite/static/pyodide [importtime]
//
// Prints the seconds of: loadPyodide (wasm + Python init), loading the kernel's
// packages from the lock (scripts/build_lite.py KERNEL_PACKAGES), the kernel's
// own `import pyodide_kernel` (IPython, jedi, ...), then loading and importing
// sympy and whittaker_teach and deriving the sledge. With "importtime", Python's
// -X importtime report (stderr) for the whole run.
import { existsSync, readdirSync, readFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
import path from "node:path";

const dir = path.resolve(process.argv[2] || "_build/html/lite/static/pyodide") + "/";
const importtime = process.argv[3] === "importtime";
const KERNEL = ["micropip", "piplite", "ipykernel", "comm", "pyodide-kernel", "jedi", "ipython"];
const t = () => performance.now() / 1000;
// Pyodide's own files: beside the lock, or in the site's content-named folder
// (static/pyodide-core-<hash>/, scripts/lite_early_kernel.py)
const core = existsSync(dir + "pyodide.mjs") ? dir : path.resolve(dir, "..",
  readdirSync(path.resolve(dir, "..")).find((n) => n.startsWith("pyodide-core-")) || "") + "/";
try {
  const { loadPyodide } = await import(pathToFileURL(core + "pyodide.mjs").href);
  let t0 = t();
  const py = await loadPyodide({ indexURL: core, lockFileURL: dir + "pyodide-lock.json",
                                 packageBaseUrl: dir,
                                 args: importtime ? ["-X", "importtime"] : [],
                                 stdout: (s) => console.log(s), stderr: (s) => console.error(s) });
  console.log(`loadPyodide               ${(t() - t0).toFixed(2)} s`);
  t0 = t();
  const lock = JSON.parse(readFileSync(dir + "pyodide-lock.json", "utf8")).packages;
  await py.loadPackage(KERNEL.filter((p) => p in lock), { messageCallback: () => {} });
  console.log(`loadPackage(kernel's)     ${(t() - t0).toFixed(2)} s`);
  t0 = t();
  py.runPython("import IPython");
  console.log(`import IPython            ${(t() - t0).toFixed(2)} s`);
  t0 = t();
  try {
    py.runPython("import pyodide_kernel");
    console.log(`import pyodide_kernel     ${(t() - t0).toFixed(2)} s (the rest of the kernel)`);
  } catch (e) {
    console.log(`import pyodide_kernel     failed under node: ${String(e.message).split("\n").slice(-2).join(" ")}`);
  }
  t0 = t();
  await py.loadPackage(["sympy", "mpmath", "whittaker-teach"], { messageCallback: () => {} });
  console.log(`loadPackage(sympy, wt)    ${(t() - t0).toFixed(2)} s`);
  for (const [label, code] of [["import sympy", "import sympy"],
                               ["import whittaker_teach", "import whittaker_teach as wt"],
                               ["reduce (sledge)", "red = wt.examples.sledge().reduce('x', direction=+1)"],
                               ["steps.to_latex", "_tex = red.steps.to_latex()"]]) {
    t0 = t();
    py.runPython(code);
    console.log(`${label.padEnd(26)}${(t() - t0).toFixed(2)} s`);
  }
} catch (e) {
  console.error("profile_lite_node.mjs: " + String(e && e.message || e).slice(-3000));
  process.exit(1);
}
