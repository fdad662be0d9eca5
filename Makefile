# Two commands for a fresh machine with python3 and make:
#   make lab    set everything up and open the course in JupyterLab
#   make test   set everything up and run every test
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
PORT   ?= 8888
STAMP  := $(VENV)/.kfcourse-installed
ROOT_FLAG := $(if $(filter 0,$(shell id -u)),--allow-root,)

.PHONY: lab test lint bench notebooks pins clean

$(STAMP): binder/requirements.txt requirements-dev.txt pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -r requirements-dev.txt
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps -e .
	@touch $@

lab: $(STAMP)
	@echo ""
	@echo "  kfcourse: open  http://127.0.0.1:$(PORT)/lab/tree/00_the_problem.ipynb  in your browser"
	@echo "  (Ctrl-C here stops the server)"
	@echo ""
	$(BIN)/jupyter lab --no-browser --ServerApp.ip=127.0.0.1 --ServerApp.port=$(PORT) \
	  --ServerApp.port_retries=0 --IdentityProvider.token='' \
	  --PasswordIdentityProvider.hashed_password='' --ServerApp.root_dir=notebooks $(ROOT_FLAG)

test: $(STAMP) lint
	$(BIN)/pytest -m "not browser" -n 2 --dist loadfile --nbval-lax --nbval-current-env \
	  --nbval-cell-timeout=120 tests notebooks
	$(BIN)/pytest -m browser tests/browser

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_filters.py
	$(BIN)/python benchmarks/bench_demos.py
	$(BIN)/python benchmarks/bench_batch.py

# Re-execute the notebooks and store the outputs of the NBVAL_CHECK_OUTPUT cells only.
notebooks: $(STAMP)
	$(BIN)/python tools/store_outputs.py notebooks/*.ipynb

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
	rm -rf $(VENV) .pytest_cache .ruff_cache .hypothesis tests/browser/artifacts
