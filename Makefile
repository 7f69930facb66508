# The two set-up commands of the README:
#   make reproduce   runs the main job (every figure and table of the paper into results/)
#   make test        runs the test suite
# Each creates .venv if needed, installs the package into it, and makes sure the
# system BLAS that OpenSeesPy's Linux wheel needs (libblas.so.3, Debian libblas3) is present.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.opsrock-installed
OUT    ?= results

.PHONY: reproduce test test-slow validate bench blas install clean

reproduce: install
	$(BIN)/opsrock reproduce --out $(OUT)

test: install
	$(BIN)/python -m pytest

test-slow: install
	$(BIN)/python -m pytest -m slow

validate: install
	$(BIN)/opsrock validate

bench: install
	$(BIN)/opsrock bench

install: blas $(STAMP)

blas:
	@sh tools/ensure-blas.sh

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test,dask]'
	@touch $(STAMP)

clean:
	rm -rf $(VENV) *.egg-info .pytest_cache
