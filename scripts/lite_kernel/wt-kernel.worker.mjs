// whittaker-teach: the Pyodide kernel's worker, started early (see wt-early-kernel.js).
//
// It is the kernel's own worker (imported first, so that it listens before the
// kernel's first message), and it starts Pyodide at once, with the packages and
// environment the kernel will ask for, then imports what the kernel's start
// imports (piplite, pyodide_kernel: IPython). When the kernel asks for Pyodide,
// wt-pyodide.mjs hands over this one. The kernel's start-up file waits for that
// moment (wtKernelAsked) before it imports SymPy in the background, so that the
// kernel is not kept waiting by that import. Written by scripts/build_lite.py,
// which fills in the kernel's worker and the options (the kernel's
// loadPyodideOptions in jupyter-lite.json).
import "../../extensions/@jupyterlite/pyodide-kernel-extension/static/__KERNEL_WORKER__";
import { startPyodide } from "./wt-pyodide.mjs";

const OPTIONS = __OPTIONS__;
const copy = (value) => JSON.parse(JSON.stringify(value));   // (loadPyodide may change its options)
const step = async (label, work) => {          // (marks read by scripts/bench_lite.py)
  performance.mark("wt:" + label);
  try { return await work(); } finally { performance.mark("wt:" + label + " end"); }
};
let kernelAsked;
self.wtKernelAsked = new Promise((resolve) => { kernelAsked = resolve; });
self.wtEarlyPyodide = {
  options: { indexURL: new URL("./", import.meta.url).href, ...copy(OPTIONS) },
  kernelAsked,
  ready: (async () => {
    const pyodide = await step("early: loadPyodide, with the kernel's packages", () =>
      startPyodide({
        indexURL: new URL("./", import.meta.url).href, ...copy(OPTIONS),
        stdout: (text) => console.log(text), stderr: (text) => console.error(text),
      }));
    await step("early: import piplite, pyodide_kernel (IPython)", () =>
      pyodide.runPythonAsync("import piplite.piplite\nimport pyodide_kernel"));
    return pyodide;
  })(),
};
