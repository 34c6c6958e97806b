# The README's two commands: `make demo` and `make test`. Both set up .venv first.
PY ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test venv fmu bench docs clean

venv: $(STAMP)

# Reinstall only when the project's own dependency list changes.
$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PY) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# the main job: both FMUs (built when missing or stale) compared on the paper's scene
demo: $(STAMP)
	$(BIN)/tripod-thrust compare --out out

fmu: $(STAMP)
	$(BIN)/tripod-thrust build

bench: $(STAMP)
	$(BIN)/python benchmarks/fmu_speed.py

test: $(STAMP)
	$(BIN)/python -m pytest -q

# regenerate README.md tables and docs/ (per-FMU variables, reference CSV, plot)
docs: $(STAMP)
	$(BIN)/python -m reduced_model.docs README.md
	$(BIN)/python -m harness.reference

clean:
	rm -rf build out .pytest_cache
