# Two commands for a fresh machine with python3 and make:
#   make lab    set everything up and open the course in JupyterLab
#   make test   set everything up and run every test
# and for students:
#   make app CH=03       one chapter as an app (Voila: prose and live demos, no code)
#   make restore CH=03   put chapter 3's original back into my-notebooks/ (no CH: every chapter)
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

.PHONY: lab app restore badges test lint bench notebooks site pins clean

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

# The parts that state facts of simulated runs: the notebooks and the run-fact tests. Besides
# the full suite, they run under numpy's lower SIMD levels (AVX2, then the x86-64-v2 baseline:
# another CPU's rounding; disabling a feature the CPU lacks changes nothing) and with every
# noise draw scaled by 1 +- 1e-12 (tests/rounding.py): what they state must hold in every run.
FACTS    := tests/sim tests/demos tests/plots tests/test_rounding.py notebooks
NO_AVX512 := AVX512_ICL AVX512_SPR X86_V4
UNIT     := $(BIN)/pytest -m "not browser" -n 2 --dist loadfile --nbval-lax --nbval-current-env --nbval-cell-timeout=120

test: $(STAMP) lint $(AXE)
	$(UNIT) tests notebooks
	NPY_DISABLE_CPU_FEATURES="$(NO_AVX512)" $(UNIT) $(FACTS)
	NPY_DISABLE_CPU_FEATURES="$(NO_AVX512) X86_V3" $(UNIT) $(FACTS)
	$(UNIT) --perturb=1e-12 $(FACTS)
	$(UNIT) --perturb=-1e-12 $(FACTS)
	$(BIN)/pytest -m browser tests/browser

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
	$(BIN)/python -m benchmarks.bench_link

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
	rm -rf $(VENV) node_modules .pytest_cache .ruff_cache .hypothesis tests/browser/artifacts
