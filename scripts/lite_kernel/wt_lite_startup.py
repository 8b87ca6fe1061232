# The in-browser kernel's start-up file (whittaker-teach's lite site).
#
# scripts/build_lite.py ships this module in a small wheel that the kernel loads
# with its own packages, and points PYTHONSTARTUP at it (loadPyodideOptions.env in
# jupyter-lite.json); IPython runs that file when the kernel starts, in the
# user's namespace. There it only calls start() of the module: once the kernel
# has said it is ready, SymPy, mpmath and whittaker_teach are loaded (wheels
# unpacked) and imported in the background while the reader reads, so that the
# first cell does not wait for them. A cell run meanwhile waits for the import to
# finish (the kernel is single-threaded); nothing is printed, and a failure here
# is silent (the cell's own import then reports it).
if __name__ == "wt_lite_startup":
    #: packages loaded and modules imported in the background (lock names; modules)
    PACKAGES = ("mpmath", "sympy", "whittaker-teach")
    MODULES = ("sympy", "whittaker_teach")
    task = None
    error = None

    async def warm_up(delay_s=0.2):
        global error
        import asyncio
        import contextlib
        import io
        import warnings

        try:
            import js
            import pyodide_js
            from pyodide.ffi import to_js

            # In the worker started with the page (lite/static/pyodide/
            # wt-kernel.worker.mjs) this file runs before JupyterLab has even asked
            # for the kernel: wait until it has, or the import below (a second of
            # work that nothing can interrupt) would keep the kernel from starting.
            asked = getattr(js, "wtKernelAsked", None)
            if asked is not None:
                await asked
            await asyncio.sleep(delay_s)     # let the kernel report ready first

            await pyodide_js.loadPackage(to_js(list(PACKAGES)))
            sink = io.StringIO()
            with warnings.catch_warnings(), contextlib.redirect_stdout(sink), \
                    contextlib.redirect_stderr(sink):
                warnings.simplefilter("ignore")
                for name in MODULES:
                    __import__(name)
        except BaseException as exc:         # noqa: BLE001 (reported by the cell's import)
            error = repr(exc)

    def start():
        global task
        import asyncio
        if task is None:
            task = asyncio.ensure_future(warm_up())
        return task
else:                                        # run as PYTHONSTARTUP: define nothing here
    __import__("wt_lite_startup").start()
