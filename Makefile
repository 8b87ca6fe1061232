# whittaker-teach: the two everyday commands are `make book` and `make test`.
#
#   make setup      install the package + [numerics,test,book,lite] extras (editable),
#                   vendor MathJax 3 into build/vendor/mathjax, fetch Pyodide + wheels
#                   for the in-browser site into build/lite (idempotent)
#   make book       setup, build the site into _build/html (with the in-browser
#                   JupyterLite site in _build/html/lite), print the sledge derivation
#   make serve      serve _build/html on http://127.0.0.1:8000 (JupyterLite needs http)
#   make pdf        the whole book as one PDF (_build/pdf/whittaker-teach.pdf, linked from the site)
#   make student    the student edition (graded exercises as statements only) in _build/student
#   make test       setup, then unit + integration tests, doctests, nbval over the
#                   stored notebook outputs (the site and its PDF built beside them),
#                   then the browser/PDF tests
#   make notebooks  re-execute every notebook in book/ and exercises/ in place
#   make clean      remove everything generated
#
# Pieces of `make test` can be run alone: unit, doctest, nbval, site, lite, pdf, browser;
# `make slow` runs the slow tests (not in `make test`); `make screenshots` takes
# whole-page screenshots of the built site at 1280 and 390 px.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help

PYTHON ?= python
MATHJAX_VERSION ?= 3.2.2
# extra arguments for the unit/integration pytest run, e.g. PYTEST_ARGS="-x"
PYTEST_ARGS ?=
# pytest-xdist workers for the unit, nbval and browser runs: the CPUs this process
# may use, at most 4 (JOBS=1 runs each in one process, as plain pytest would)
JOBS ?= $(shell $(PYTHON) -c 'import os; print(min(4, len(os.sched_getaffinity(0))))' 2>/dev/null || echo 1)
XDIST = $(if $(filter-out 1,$(JOBS)),-n $(JOBS))

# `jupyter-book` through the current interpreter (no reliance on a console
# script being on PATH, e.g. pyenv shims before a rehash)
JUPYTER_BOOK := $(PYTHON) -c 'import sys; from jupyter_book.cli.main import main; sys.argv[0] = "jupyter-book"; sys.exit(main())'

SETUP_STAMP := build/.setup.stamp
PYODIDE_VERSION ?= 314.0.6
SERVE_PORT ?= 8000
MATHJAX_DIR := build/vendor/mathjax
NOTEBOOK_DIRS := book exercises

export PIP_DISABLE_PIP_VERSION_CHECK := 1

.PHONY: help setup sysdeps mathjax lite-fetch lite serve bench-lite book site student pdf derive test unit slow doctest nbval browser screenshots notebooks exercises figures bench clean

help:
	@sed -n '3,19p' Makefile | sed 's/^# \{0,1\}//'

# ---------------------------------------------------------------- set-up
setup: $(SETUP_STAMP) mathjax lite-fetch

# Re-install when pyproject.toml changes, or when the package first appears.
$(SETUP_STAMP): pyproject.toml requirements/constraints.txt $(wildcard whittaker_teach/__init__.py)
	$(PYTHON) -m pip install -q --root-user-action=ignore -c requirements/constraints.txt -e ".[numerics,test,book,lite]"
	@mkdir -p $(@D) && touch $@

# The Debian packages the tests and the book need (chromium, poppler-utils,
# fonts-wqy-zenhei, bubblewrap): installed when root, otherwise a clear failure
# naming them. A prerequisite of `book` and `test`, so both fail (or install)
# before anything else runs, never midway.
sysdeps:
	@bash scripts/system_deps.sh

mathjax:
	@MATHJAX_VERSION=$(MATHJAX_VERSION) bash scripts/fetch_mathjax.sh $(MATHJAX_DIR)

# Pyodide's core files (npm) and the wheels it is served (PyPI), once (stamps).
lite-fetch:
	@$(PYTHON) scripts/fetch_lite.py --pyodide $(PYODIDE_VERSION)

# ---------------------------------------------------------------- the book
book: sysdeps setup
	@$(MAKE) --no-print-directory site pdf-after-site derive

# The Jupyter Book site, then the JupyterLite site inside it (_build/html/lite).
site: setup
	$(JUPYTER_BOOK) build . -W -n --keep-going
	@$(MAKE) --no-print-directory lite

# The in-browser site alone (the notebooks' lite copies are made here, every time).
lite: setup
	$(PYTHON) scripts/build_lite.py --pyodide $(PYODIDE_VERSION) --out _build/html/lite

# The student edition (exercises/course.yml names the graded exercises: statements
# only, no solutions, no answer data) into _build/student/{html,pdf}.
student: sysdeps setup
	$(PYTHON) scripts/student_edition.py

# JupyterLite does not work from file://: serve the built site on 127.0.0.1.
serve:
	@test -f _build/html/index.html || { echo "serve: run 'make book' first"; exit 1; }
	$(PYTHON) scripts/serve.py --port $(SERVE_PORT) --directory _build/html

# Size, bytes downloaded, time to kernel ready, browser/native ratio of the
# first derivation cell (prints figures; needs the built site).
bench-lite: setup
	$(PYTHON) scripts/bench_lite.py

derive: setup
	$(PYTHON) -m whittaker_teach derive sledge

# The printable edition: the built site's pages joined, printed by headless
# Chromium (scripts/make_pdf.py); the PDF is copied into _build/html too.
pdf: setup sysdeps
	@[ -f _build/html/index.html ] || $(MAKE) --no-print-directory site
	$(PYTHON) scripts/make_pdf.py

# ---------------------------------------------------------------- tests
# The site and the PDF are built beside the Python tests (they leave a core idle
# for most of their minute), their log printed when both are done; then the browser
# test. Every part runs and reports even if an earlier one failed; `make test`
# still fails if any part failed.
test: sysdeps setup
	@mkdir -p _build/logs; log=_build/logs/site-and-pdf.log; status=0; \
	set -m; $(MAKE) --no-print-directory site pdf-after-site student > $$log 2>&1 & site=$$!; set +m; \
	trap 'kill -- -'$$site' 2>/dev/null || true' EXIT INT TERM; \
	echo "test: building the site and the PDF beside the Python tests (log: $$log)"; \
	$(MAKE) --no-print-directory --keep-going unit doctest nbval || status=1; \
	if wait $$site; then cat $$log; else status=1; cat $$log; echo "test: the site or the PDF failed (log above: $$log)"; fi; \
	$(MAKE) --no-print-directory browser || status=1; \
	exit $$status

# tests/unit and tests/integration; a folder without test files is skipped
# (pytest would exit 5, "no tests collected").
unit: sysdeps setup
	@dirs=""; \
	for d in tests/unit tests/integration; do \
	  if [ -n "$$(find $$d \( -name 'test_*.py' -o -name '*_test.py' \) -print -quit 2>/dev/null)" ]; then \
	    dirs="$$dirs $$d"; \
	  else echo "unit: no tests in $$d yet, skipped"; fi; \
	done; \
	if [ -n "$$dirs" ]; then \
	  echo "PYTHONHASHSEED=0 $(PYTHON) -m pytest$$dirs -q -m 'not slow' $(XDIST) $(if $(XDIST),--dist loadgroup) $(PYTEST_ARGS)"; \
	  PYTHONHASHSEED=0 $(PYTHON) -m pytest $$dirs -q -m "not slow" $(XDIST) $(if $(XDIST),--dist loadgroup) $(PYTEST_ARGS); \
	fi

# The tests marked slow (minutes each: a 1e5-period run under tracemalloc, the quick
# study run twice); not part of `make test`.
slow: setup
	PYTHONHASHSEED=0 $(PYTHON) -m pytest tests/unit tests/integration -q -m slow $(XDIST) $(PYTEST_ARGS)

doctest: setup
	@if [ -d whittaker_teach ] && grep -rqs --include='*.py' '>>>' whittaker_teach; then \
	  echo "PYTHONHASHSEED=0 $(PYTHON) -m pytest --doctest-modules whittaker_teach -q"; \
	  PYTHONHASHSEED=0 $(PYTHON) -m pytest --doctest-modules whittaker_teach -q; \
	else echo "doctest: no doctests in whittaker_teach yet, skipped"; fi

# Stored notebook outputs must match a fresh run (_build and checkpoints are
# excluded by norecursedirs in pyproject.toml); --dist loadfile: every cell of a
# notebook in one worker's kernel, in order.
nbval: setup
	@dirs=""; \
	for d in $(NOTEBOOK_DIRS); do \
	  if [ -n "$$(find $$d -name '*.ipynb' -not -path '*/_build/*' -not -path '*/.ipynb_checkpoints/*' -print -quit 2>/dev/null)" ]; then \
	    dirs="$$dirs $$d"; \
	  else echo "nbval: no notebooks in $$d, skipped"; fi; \
	done; \
	if [ -n "$$dirs" ]; then \
	  echo "PYTHONHASHSEED=0 $(PYTHON) -m pytest --nbval --nbval-current-env$$dirs -p no:randomly -q $(XDIST) $(if $(XDIST),--dist loadfile)"; \
	  PYTHONHASHSEED=0 $(PYTHON) -m pytest --nbval --nbval-current-env $$dirs -p no:randomly -q $(XDIST) $(if $(XDIST),--dist loadfile); \
	fi

# (in `make test`, after `site`: the PDF of the site just built)
pdf-after-site: setup sysdeps
	$(PYTHON) scripts/make_pdf.py

# Headless Chromium against the site built into _build/html by `make site`,
# and the PDF of `make pdf`: missing Chromium/poppler, site or PDF fail.
# one test per page load (tests/book/test_site.py), spread over the workers.
browser: setup sysdeps
	WT_REQUIRE_SITE=1 WT_REQUIRE_PDF=1 WT_REQUIRE_STUDENT=1 $(PYTHON) -m pytest tests/book -q $(XDIST)

# Whole-page screenshots of every page at 1280 and 390 px into _build/screenshots/
# (the browser test keeps only each page's first screen), with the same checks.
screenshots: setup sysdeps
	WT_REQUIRE_SITE=1 WT_FULL_SCREENSHOTS=1 $(PYTHON) -m pytest tests/book/test_site.py -q $(XDIST)

# ---------------------------------------------------------------- notebooks
notebooks: setup
	PYTHONHASHSEED=0 $(PYTHON) scripts/execute_notebooks.py $(NOTEBOOK_DIRS)

# The drawings of the systems (book/figures/systems/<name>.py writes <name>.svg beside
# itself, deterministically; a unit test fails when a stored SVG is out of date).
figures: setup
	@for f in book/figures/systems/[a-z]*.py; do echo "$$f"; PYTHONHASHSEED=0 MPLBACKEND=svg $(PYTHON) "$$f"; done

# The exercise notebooks (student and solution) from their sources in
# exercises/src/; only changed ones are re-executed (EXERCISES_ARGS=--all: every one).
exercises: setup
	PYTHONHASHSEED=0 $(PYTHON) scripts/make_exercises.py $(EXERCISES_ARGS)

# ---------------------------------------------------------------- numerics
# Speed against error and the hard cases: re-run the studies whose stored
# figures and tables the book shows (book/figures/numerics/; about 5 minutes).
# `python -m whittaker_teach bench numerics --quick` is the short version.
bench: setup
	PYTHONHASHSEED=0 $(PYTHON) -m whittaker_teach.numerics.figures

# ---------------------------------------------------------------- clean
clean:
	rm -rf _build build *.egg-info .pytest_cache .hypothesis
	find . -path ./.git -prune -o \( -name __pycache__ -o -name .ipynb_checkpoints \) -type d -prune -exec rm -rf {} +
