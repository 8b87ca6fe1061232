// whittaker-teach: the kernel's loadPyodide (the kernel's pyodideUrl points here).
//
// Pyodide's own files (pyodide.mjs, pyodide.asm.mjs and .wasm, python_stdlib.zip)
// are in a folder named by their content (__CORE__), so that a server can let
// the browser keep them for good (scripts/serve.py does): a browser that
// revalidates pyodide.asm.wasm on every visit also compiles it again. The lock
// and the wheels, which change with every build, are beside this file.
//
// In the worker started early (wt-kernel.worker.mjs) loadPyodide returns the
// Pyodide started there, if that one was started with the options the kernel
// asks for (the same packages, environment and index URL), with the kernel's
// stdout and stderr; otherwise (a restarted kernel, other options, a failed early
// start) it starts Pyodide itself.
import { loadPyodide as load } from "../__CORE__/pyodide.mjs";

const HERE = new URL("./", import.meta.url).href;
const CORE = new URL("../__CORE__/", import.meta.url).href;
const same = (a, b) => JSON.stringify(a ?? null) === JSON.stringify(b ?? null);

/** Pyodide's loadPyodide, with its files from the content-named folder. */
export function startPyodide(options) {
  return load({ ...options, indexURL: CORE, lockFileURL: HERE + "pyodide-lock.json",
                packageBaseUrl: HERE });
}

export async function loadPyodide(options) {
  performance.mark("wt:kernel asks for Pyodide");
  const early = self.wtEarlyPyodide;
  self.wtEarlyPyodide = undefined;
  try {
    if (early) {
      const differ = ["indexURL", "packages", "env"]
        .filter((key) => !same(options[key], early.options[key]));
      if (differ.length === 0) {
        try {
          const pyodide = await early.ready;
          early.kernelAsked();            // (the start-up file's SymPy import may begin)
          if (options.stdout) pyodide.setStdout({ batched: options.stdout });
          if (options.stderr) pyodide.setStderr({ batched: options.stderr });
          return pyodide;
        } catch (err) {
          console.warn("whittaker-teach: the early Pyodide failed; starting again", err);
        }
      } else {
        console.warn("whittaker-teach: the kernel asks for other", differ.join(", "),
                     "than the early Pyodide has; starting again");
      }
    }
    // (an early Pyodide not used stays idle: its start-up file waits for ever)
    delete self.wtKernelAsked;
    return await startPyodide(options);
  } finally {
    performance.mark("wt:kernel asks for Pyodide end");
  }
}
