# The two set-up commands of the README:
#   make reproduce   runs the main job (every figure and table of the paper into results/)
#   make test        runs the test suite
# Each creates .venv if needed, installs the package into it, and makes sure the
# system BLAS that OpenSeesPy's Linux wheel needs (libblas.so.3, Debian libblas3) is present.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.opsrock-installed
LOCK   := requirements.lock
OUT    ?= results

.PHONY: reproduce test bytecode test-lowest test-slow test-fuzz test-pelicun test-siconos test-wheel docs dist validate bench blas install lock clean

reproduce: install
	$(BIN)/opsrock reproduce --out $(OUT)

# The suite on every core (pytest-xdist): a test file is the unit of distribution (--dist loadfile), so a
# module's expensive fixtures (a quick study, a campaign) are computed once, not once per worker; numba's kernels
# are compiled before the workers start (tests/conftest.py). One worker more than the cores: the suite's tests wait
# on their console-script processes, pools and timeouts for part of their time, and with one worker per core a core
# idled meanwhile (fresh private clone, 2 cores, quiet: 3:53 of pytest with 2 workers, 3:38 with 3, the same
# 1,528 tests). TEST_WORKERS=0 runs it in one process.
TEST_WORKERS ?= $(shell n=$$(nproc 2>/dev/null || echo 1); echo $$((n + 1)))

test: bytecode
	$(BIN)/python -m pytest --numprocesses $(TEST_WORKERS) --dist loadfile

# The package's modules byte-compiled before the suite starts its thousand console-script processes: where
# PYTHONDONTWRITEBYTECODE is set (the project's machines set it) no import writes a .pyc, and every process
# compiled opsrock's modules from source again (0.08-0.1 s of CPU each). A module edited later is recompiled here
# (compileall skips the up-to-date ones); a stale .pyc is never used (Python checks its source's stamp).
bytecode: install
	@$(BIN)/python -m compileall -q -j 0 opsrock > /dev/null

# The fragility, plot and inventory tests with the lowest scipy and numpy that pyproject.toml allows (scipy 1.10.0, numpy 1.24.1,
# pinned with the rest in requirements-lowest.txt), in a venv of their own: the fits use no private scipy name
# and must give the same answers on every scipy in the declared range. .ci/run calls it after make test.
# `make test-lowest LOWEST_TESTS=` runs the whole suite there.
LOWEST_VENV  := .venv-lowest
LOWEST       := requirements-lowest.txt
LOWEST_TESTS ?= tests/unit/fragility tests/model/fragility tests/unit/plots tests/unit/inventory tests/model/inventory

test-lowest: blas $(LOWEST_VENV)/.opsrock-installed
	$(LOWEST_VENV)/bin/python -m pytest $(LOWEST_TESTS)

$(LOWEST_VENV)/.opsrock-installed: pyproject.toml $(LOWEST)
	@test -x $(LOWEST_VENV)/bin/python || $(PYTHON) -m venv $(LOWEST_VENV)
	$(LOWEST_VENV)/bin/python -m pip install --quiet -c $(LOWEST) pip
	$(LOWEST_VENV)/bin/python -m pip install --quiet -c $(LOWEST) -e '.[test,dask,records]'
	@touch $@

test-slow: bytecode
	$(BIN)/python -m pytest -m slow

# Property tests with fresh random seeds and ten times the examples (make test is derandomised), and
# fresh random option values through the console script.
test-fuzz: install
	HYPOTHESIS_PROFILE=fuzz $(BIN)/python -m pytest tests/unit/test_input_properties.py \
	    tests/e2e/inputs/test_hostile_inputs.py::test_random_option_values_are_refused_or_answered

# The FEMA P-58 / pelicun export loads in pelicun: pelicun 3.10 pins scipy < 1.16 and pandas < 3, so it
# gets a venv of its own; opsrock writes a sample export and pelicun reads every parameter back.
# The contents study (opsrock contents) writes damage models pelicun loads, and a real pelicun damage
# assessment of its small inventory (3 of each FEMA P-58 unanchored item on each floor of the study, PFV
# demands of the FEMA P695 far-field records as recorded, through the study's building) runs twice, with
# FEMA P-58's E.20.22 fragilities and with opsrock's: first on a quick study made now from this checkout,
# then on the committed study (studies/contents/pelicun/), whose expected numbers of overturned items
# studies/contents/README.md quotes.
# tools/pelicun_inventory.py --dl-calculation runs pelicun's own DL_calculation on the quick study's folder too: the
# FEMA P-58 nine have no repair cost, so it has no loss model and DL_calculation runs its damage assessment only
# (its outputs kept in .pelicun-venv/contents/pelicun/results/; the tool says that no loss was computed and why).
# Then the user's route (opsrock contents --inventory --motions): the shipped example inventory on the shipped
# example floor motions, quick, into .pelicun-venv/inventory; pelicun runs its pelicun/ folder as it is (damage
# and loss, tools/pelicun_inventory.py, and pelicun's own DL_calculation on its config.json, its outputs kept in
# .pelicun-venv/inventory/pelicun/results/) and prints per item and floor, each unit once, the expected units
# damaged, overturned and repair cost beside the exact expectations over the records; it fails when pelicun's
# means differ from them by more than four standard errors of its sampling.
EXAMPLE_INVENTORY := opsrock/data/inventories/example.csv
EXAMPLE_MOTIONS   := opsrock/data/examples/floor-motions/motions.csv

test-pelicun: install
	@test -x .pelicun-venv/bin/python || $(PYTHON) -m venv .pelicun-venv
	.pelicun-venv/bin/python -m pip install --quiet 'pelicun==3.10.0'
	$(BIN)/python -c "from opsrock.fragility.pelicun_export import ComponentFragility as C, write_pelicun_csv as w; \
	  w([C('opsrock.sample.PFA', 'pfa', 6.055398004958769, 0.6505432263063391), \
	     C('opsrock.sample.PFV', 'pfv', 0.6115985322309946, 0.36682703654629484)], '.pelicun-venv/sample.csv')"
	.pelicun-venv/bin/python tools/pelicun_load.py .pelicun-venv/sample.csv
	$(BIN)/opsrock contents --quick --no-progress --force --out .pelicun-venv/contents
	.pelicun-venv/bin/python tools/pelicun_load.py .pelicun-venv/contents/pelicun/fragility.csv
	.pelicun-venv/bin/python tools/pelicun_inventory.py .pelicun-venv/contents/pelicun --repeat 20 --dl-calculation
	.pelicun-venv/bin/python tools/pelicun_assess.py .pelicun-venv/contents/pelicun --repeat 20
	.pelicun-venv/bin/python tools/pelicun_assess.py studies/contents/pelicun
	$(BIN)/opsrock contents --inventory $(EXAMPLE_INVENTORY) --motions $(EXAMPLE_MOTIONS) \
	    --out .pelicun-venv/inventory --quick --no-progress --force
	.pelicun-venv/bin/python tools/pelicun_inventory.py .pelicun-venv/inventory/pelicun --dl-calculation

# The Siconos model of the 3-D block (opsrock/data/siconos/siconos_block3d.py, the independent reference of rigid3d): Debian's
# python3-siconos 4.4 for Debian's own /usr/bin/python3, installed with apt-get when missing (as root; otherwise
# the line to run is printed), seen by .siconos-venv (--system-site-packages; numpy and siconos only: opsrock needs
# pandas >= 2, Debian has 1.5). The quick form (21 cases: every tenth of validation/siconos3d's set) runs both
# solvers, prints the agreement table and fails below its targets; `make test-siconos SICONOS_FULL=1` runs the
# 208 cases and the interleaved timing run and writes validation/siconos3d/{cases,summary,cost}.csv and tilt.png.
# The same for the cylinder (opsrock/data/siconos/siconos_cylinder3d.py against cylinder3d, issue 45): quick form 7
# cases, full form 32 written to validation/siconos_cylinder/{cases,summary}.csv.
SICONOS_PY := /usr/bin/python3

test-siconos: install
	@$(SICONOS_PY) -c "import siconos.kernel" 2>/dev/null || { [ "$$(id -u)" = "0" ] && apt-get update -qq >/dev/null \
	    && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-siconos >/dev/null; } \
	    || { echo "opsrock: install Debian's python3-siconos (sudo apt-get install python3-siconos) and retry" >&2; exit 1; }
	@test -x .siconos-venv/bin/python || $(SICONOS_PY) -m venv --system-site-packages .siconos-venv
	$(BIN)/python -m opsrock.validation.siconos3d_compare $(if $(SICONOS_FULL),--out validation/siconos3d --cost,--quick)
	$(BIN)/python -m opsrock.validation.siconos_cylinder $(if $(SICONOS_FULL),--out validation/siconos_cylinder,--quick)

# A wheel built from this checkout, installed (not editable) into a fresh venv, runs `opsrock run tiny`,
# `opsrock validate --quick` and `opsrock reproduce` from an empty folder elsewhere (.ci/run calls it).
test-wheel: blas
	sh tools/wheel_check.sh $(PYTHON) $(CURDIR)/$(LOCK)

# The documentation site into docs/_build/html: Sphinx (pydata theme, numpydoc, MyST, sphinx-gallery) with
# warnings as errors; every example of examples/ is executed; then every relative link of the repository's
# Markdown files is checked (docs/check_links.py). The docs extra goes into the project venv.
DOCS_STAMP := $(VENV)/.opsrock-docs-installed

docs: install $(DOCS_STAMP)
	$(BIN)/python -m sphinx -W --keep-going -q -b html docs docs/_build/html
	$(BIN)/python docs/check_links.py

$(DOCS_STAMP): pyproject.toml $(LOCK)
	$(BIN)/python -m pip install --quiet -c $(LOCK) -e '.[test,dask,records,docs,release]'
	@touch $@

# A release's sdist and wheel into dist/ (python -m build: the sdist from the checkout, the wheel from the sdist),
# checked as a package index checks them (twine check --strict).
dist: install $(DOCS_STAMP)
	rm -rf dist
	$(BIN)/python -m build --outdir dist .
	$(BIN)/python -m twine check --strict dist/*

validate: install
	$(BIN)/opsrock validate

bench: install
	$(BIN)/opsrock bench

install: blas $(STAMP)

blas:
	@sh tools/ensure-blas.sh

# Installs the exact versions of the lock file (see its header); pyproject.toml keeps the ranges.
# pyproject.toml holds the version, which the installed metadata repeats: a new version reinstalls.
$(STAMP): pyproject.toml $(LOCK)
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet -c $(LOCK) pip
	$(BIN)/python -m pip install --quiet -c $(LOCK) -e '.[test,dask,records]'
	@touch $(STAMP)

# Refresh the lock file: the newest versions within pyproject.toml's ranges, in a throw-away venv.
# Run make test afterwards, and commit the lock only if it passes.
lock:
	rm -rf .lock-venv
	$(PYTHON) -m venv .lock-venv
	.lock-venv/bin/python -m pip install --quiet --upgrade pip
	.lock-venv/bin/python -m pip install --quiet '.[test,dask,records]'
	{ sed -n '/^#/p' $(LOCK); .lock-venv/bin/python -m pip freeze --all --exclude-editable \
	    | grep -v -e '^opsrock' -e '^setuptools' -e '^wheel'; } > $(LOCK).new
	mv $(LOCK).new $(LOCK)
	rm -rf .lock-venv

clean:
	rm -rf $(VENV) $(LOWEST_VENV) *.egg-info .pytest_cache .hypothesis .lock-venv .pelicun-venv dist docs/_build \
	    docs/api docs/validation docs/studies docs/auto_examples docs/sg_execution_times.rst
