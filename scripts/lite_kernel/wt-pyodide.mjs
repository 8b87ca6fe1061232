// whittaker-teach: the kernel's loadPyodide (the kernel's pyodideUrl points here).
//
// In the worker started early (wt-kernel.worker.mjs) it returns the Pyodide
// started there, if that one was started with the options the kernel asks for
// (the same packages, environment and index URL), with the kernel's stdout and
// stderr; otherwise (a restarted kernel, other options, a failed early start) it
// is Pyodide's own loadPyodide.
import { loadPyodide as load } from "./pyodide.mjs";

const same = (a, b) => JSON.stringify(a ?? null) === JSON.stringify(b ?? null);

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
    return await load(options);
  } finally {
    performance.mark("wt:kernel asks for Pyodide end");
  }
}
