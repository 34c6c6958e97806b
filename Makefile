# The README's two commands: `make demo` and `make test`. Both set up .venv first.
PY ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test venv fmu bench native-check docs clean

venv: $(STAMP)

# Reinstall only when the project's own dependency list changes.  The FMUs' binary is compiled
# from fmu_src/native/ (a C compiler is all it needs): install gcc where none is found.
$(STAMP): pyproject.toml
	command -v cc >/dev/null 2>&1 || { [ "$$(id -u)" = 0 ] && apt-get update -qq && \
	  apt-get install -y -qq gcc; } || { echo "make: a C compiler is needed (apt-get install gcc)"; exit 1; }
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

# the native layer's proofs: 300 + 50 fresh processes per FMU, 1000 load/free cycles, valgrind
native-check: $(STAMP)
	$(BIN)/python benchmarks/exit_clean.py --runs 300 --cli-runs 50
	$(BIN)/python benchmarks/soak.py --cycles 1000
	command -v valgrind >/dev/null 2>&1 || { apt-get update -qq && apt-get install -y -qq valgrind; }
	$(BIN)/python benchmarks/memcheck.py --out out/memcheck

test: $(STAMP)
	$(BIN)/python -m pytest -q

# regenerate README.md tables and docs/ (per-FMU variables, reference CSV, plot)
docs: $(STAMP)
	$(BIN)/python -m reduced_model.docs README.md
	$(BIN)/python -m harness.reference
	$(BIN)/python -m harness.validation

clean:
	rm -rf build out .pytest_cache
