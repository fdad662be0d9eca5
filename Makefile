# Two commands for a fresh machine with python3 and make:
#   make lab    set everything up and open the course in JupyterLab
#   make test   set everything up and run every test
# and for students:
#   make app CH=03       one chapter as an app (Voila: prose and live demos, no code)
#   make restore CH=03   put chapter 3's original back into my-notebooks/ (no CH: every chapter)
# and for developers:
#   make check           lint, the unit tests, and the notebooks changed
# and for instructors:
#   make badges REPO=me/kfcourse REF=v1.0   every Binder link to a fork and a tag
PYTHON   ?= python3
VENV     ?= .venv
BIN      := $(VENV)/bin
PORT     ?= 8888
APP_PORT ?= 8866
WORK     ?= my-notebooks
CH       ?=
STAMP    := $(VENV)/.kfcourse-installed
AXE      := node_modules/axe-core/axe.min.js

# Python keeps the modules it compiles (__pycache__/, git-ignored) even where the environment says not to
# (PYTHONDONTWRITEBYTECODE): otherwise every test worker, kernel and pass compiles the course again, and pytest
# rewrites every test module's asserts again, about 7 s a worker a pass.
unexport PYTHONDONTWRITEBYTECODE

.PHONY: lab app restore badges test check lint bench notebooks site pins clean

$(STAMP): binder/requirements.txt requirements-dev.txt pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r requirements-dev.txt
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps -e .
	@touch $@

# JupyterLab on 127.0.0.1 with a token, over the student's own copy $(WORK)/ (made on the first
# run, never overwritten); prints the address to open once the server answers.
lab: $(STAMP)
	@$(BIN)/python tools/course.py lab --port $(PORT) --work '$(WORK)'

# One chapter as an app (Voila), on 127.0.0.1 with a token: make app CH=03
ifneq ($(filter app,$(MAKECMDGOALS)),)
ifeq ($(strip $(CH)),)
$(error make app needs a chapter: make app CH=03)
endif
endif
app: $(STAMP)
	@$(BIN)/python tools/course.py app --port $(APP_PORT) --chapter '$(CH)'

# The original of chapter CH (of every chapter without CH) back into $(WORK)/; the replaced
# version is kept in $(WORK)/backup/.
restore:
	@$(PYTHON) tools/course.py restore --work '$(WORK)' --chapter '$(CH)'

# The tests, two workers (one file at a time: a notebook's cells share its kernel), in passes:
#  1. every test and every notebook once, the browser suite apart (the notebooks first: the
#     longest files start early, so neither worker waits long on the other at the end);
#  2. the facts of seeded runs again (tests marked `fact` and every notebook, the `slow` ones
#     apart: tests/facts.py), as another CPU's rounding, perturbed (tests/repeats.py): once for
#     each numpy SIMD level below this CPU's (once as this CPU if there is none), with every noise
#     draw scaled by 1 + 1e-12 (1 - 1e-12 in a second repeat: tests/rounding.py). What they state must hold.
#     NPY_DISABLE_CPU_FEATURES="X86_V4 AVX512_ICL" make test: an AVX-512 CPU runs every pass as an AVX2 one;
#  3. the browser suite, which waits on the page much of its time: the repeats run beside it, at a lower
#     priority (nice 10), and their output follows the suite's (Ctrl-C stops both).
# Each pass writes its timings to $(TIMES); the last line prints the 15 slowest tests of all.
PYTEST   := $(BIN)/pytest -n 2 --dist loadfile --nbval-lax --nbval-current-env --nbval-cell-timeout=120
TIMES    := .test-times

test: $(STAMP) lint $(AXE)
	@rm -rf $(TIMES) && mkdir -p $(TIMES)
	$(PYTEST) -m "not browser" --junitxml=$(TIMES)/1-main.xml notebooks tests
	@echo "The repeats (tests/repeats.py) run beside the browser suite; their output follows it."
	@trap 'kill -- -$$repeats 2>/dev/null || kill $$repeats 2>/dev/null; exit 130' INT TERM; \
	$(BIN)/python -m tests.repeats run $(TIMES) $(PYTEST) -m "fact and not slow and not browser" notebooks tests \
	  > $(TIMES)/2-repeats.log 2>&1 & repeats=$$!; \
	echo "$(BIN)/pytest -m browser tests/browser"; \
	$(BIN)/pytest -m browser --junitxml=$(TIMES)/3-browser.xml tests/browser; browser=$$?; \
	wait $$repeats; repeated=$$?; \
	cat $(TIMES)/2-repeats.log; \
	[ $$browser -eq 0 ] && [ $$repeated -eq 0 ]
	@$(BIN)/python -m tests.slowest $(TIMES)

# For every day: lint, the unit tests (not the facts of seeded runs, the slow or the browser ones: tests/facts.py),
# and the notebooks that differ from git's HEAD (or CH="03 08": those chapters), in a few minutes. make test before a push.
CHANGED   = $(wildcard $(if $(strip $(CH)),$(foreach c,$(CH),notebooks/$(c)_*.ipynb),\
            $(shell { git diff --name-only HEAD; git ls-files --others --exclude-standard; } -- notebooks 2>/dev/null)))
check: $(STAMP) lint
	$(PYTEST) -m "not fact and not slow and not browser" tests
	$(if $(strip $(CHANGED)),$(PYTEST) $(CHANGED))

# axe-core, the accessibility checker of the browser tests, at the version package-lock.json pins:
# installed again whenever the lock file is newer than it.
$(AXE): package-lock.json
	npm ci --no-audit --no-fund
	@touch $@

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_filters.py
	$(BIN)/python benchmarks/bench_particle.py
	$(BIN)/python benchmarks/bench_demos.py
	$(BIN)/python benchmarks/bench_pictures.py
	$(BIN)/python benchmarks/bench_batch.py
	$(BIN)/python benchmarks/bench_check.py
	$(BIN)/python benchmarks/bench_real_run.py
	$(BIN)/python benchmarks/bench_chapters.py
	$(BIN)/python -m benchmarks.bench_link
	$(BIN)/python -m benchmarks.bench_browser

# Re-execute the notebooks and store the outputs of the NBVAL_CHECK_OUTPUT cells only.
notebooks: $(STAMP)
	$(BIN)/python tools/store_outputs.py notebooks/*.ipynb

# The static HTML edition: every chapter executed, each demo as a picture of its first frame
# (and a short recording of its run where it has Run/Pause). Open site/index.html.
site: $(STAMP)
	$(BIN)/python tools/build_site.py --out site

# Point every Binder link (README, each chapter's badge cell, so the app view and the site too)
# at a fork and a tag: make badges REPO=OWNER/NAME REF=v1.0 (either may be left out).
badges: $(STAMP)
	@$(BIN)/python tools/badges.py $(if $(REPO),--repo '$(REPO)') $(if $(REF),--ref '$(REF)')

# Re-resolve the pinned environments from the ranges in pyproject.toml.
pins:
	rm -rf .pins-venv && $(PYTHON) -m venv .pins-venv
	.pins-venv/bin/pip install --quiet -e '.[course]'
	{ sed -n '1,2p' binder/requirements.txt; .pins-venv/bin/pip freeze --exclude-editable; } > binder/requirements.txt.new
	.pins-venv/bin/pip install --quiet -e '.[dev]'
	{ sed -n '1,3p' requirements-dev.txt; .pins-venv/bin/pip freeze --exclude-editable \
	  | grep -vxFf binder/requirements.txt.new; } > requirements-dev.txt
	mv binder/requirements.txt.new binder/requirements.txt
	rm -rf .pins-venv

clean:
	rm -rf $(VENV) node_modules .pytest_cache .ruff_cache .hypothesis tests/browser/artifacts $(TIMES)
