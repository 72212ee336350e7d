# Everything a fresh machine needs: `make demo` and `make test` create .venv, install urdftool
# (with uv, itself installed into the venv) with compiled bytecode, and run.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
INSTALLED := $(VENV)/.installed

.PHONY: demo test test-fast bench fuzz clean

$(INSTALLED): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --disable-pip-version-check uv
	$(VENV)/bin/uv pip install --quiet --compile-bytecode --python $(PY) -e '.[analysis,test]'
	$(PY) -m compileall -q urdftool  # PYTHONDONTWRITEBYTECODE machines would compile it every run
	touch $(INSTALLED)

demo: $(INSTALLED)
	$(VENV)/bin/urdftool check robots/
	$(VENV)/bin/urdftool tree robots/r2d2/r2d2.urdf.xacro
	@echo; echo "A broken robot (exit code 1; the finding points into the included macro file):"
	@$(VENV)/bin/urdftool check tests/cases/U005_xacro_error/robot.urdf.xacro || true

test: $(INSTALLED)
	$(PY) -m pytest -n auto

# The inner loop: unit tests only, without the corpus, parity, fuzz and README runs.
test-fast: $(INSTALLED)
	$(PY) -m pytest -n auto -m "not integration and not network"

bench: $(INSTALLED)
	$(PY) benchmarks/run.py

fuzz: $(INSTALLED)
	$(PY) -m tests.fuzz.run 10000 --in-process; status=$$?; \
	$(PY) -m tests.fuzz.run 10000 && exit $$status

clean:
	rm -rf $(VENV) .pytest_cache build *.egg-info
