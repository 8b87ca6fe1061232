// whittaker-teach: start the Python kernel's worker with the page.
//
// JupyterLab starts the kernel only once it has itself started and opened the
// notebook (about 3 s on a 2-core machine); the kernel then spends about as long
// again starting Pyodide, loading its packages and importing IPython. This script
// (loaded by lite/lab/index.html before JupyterLab) starts that worker at once,
// so that both happen at the same time, and hands it to the Pyodide kernel when
// the kernel asks for its worker: the worker script wt-kernel.worker.mjs is the
// kernel's own worker plus an early start of Pyodide, which the kernel then
// finds ready (wt-pyodide.mjs). Only the first kernel gets the early worker; a
// restarted kernel starts from nothing, as usual. Written by scripts/build_lite.py
// (scripts/lite_early_kernel.py), which fills in the two names below.
(function () {
  "use strict";
  // (when cross-origin isolated the kernel uses its other, coincident, worker)
  if (self.crossOriginIsolated || typeof self.Worker !== "function") return;
  const KERNEL_WORKER = "/extensions/@jupyterlite/pyodide-kernel-extension/static/__KERNEL_WORKER__";
  const EARLY_WORKER = "static/pyodide/wt-kernel.worker.mjs";
  const root = new URL("./", document.currentScript.src);
  const kernelWorker = new URL(KERNEL_WORKER.slice(1), root).href;
  const NativeWorker = self.Worker;
  let early = null;
  try {
    early = new NativeWorker(new URL(EARLY_WORKER, root), { type: "module" });
  } catch (err) {
    console.warn("whittaker-teach: could not start the kernel's worker early", err);
    return;
  }
  function Worker(url, options) {
    if (early !== null && new URL(String(url), location.href).href === kernelWorker
        && options && options.type === "module") {
      const worker = early;
      early = null;
      return worker;
    }
    return new NativeWorker(url, options);
  }
  Worker.prototype = NativeWorker.prototype;
  self.Worker = Worker;
})();
