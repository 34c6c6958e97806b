# The README's two commands: `make demo` and `make test`. Both set up .venv first.
PY ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test venv fmu bench native-check docs docs-quick clean

venv: $(STAMP)

# Reinstall only when the project's own dependency list changes.  The FMUs' binary is compiled
# from fmu_src/native/ (a C compiler is all it needs): install gcc where none is found.
$(STAMP): pyproject.toml
	command -v cc >/dev/null 2>&1 || { [ "$$(id -u)" = 0 ] && apt-get update -qq && \
	  apt-get install -y -qq gcc; } || { echo "make: a C compiler is needed (apt-get install gcc)"; exit 1; }
	test -x $(BIN)/python || $(PY) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test,peer]' || $(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# the main job: both FMUs (built when missing or stale) compared on the paper's scene
demo: $(STAMP)
	$(BIN)/tripod-thrust compare --out out

fmu: $(STAMP)
	$(BIN)/tripod-thrust build

bench: $(STAMP)
	$(BIN)/python benchmarks/fmu_speed.py

# the native layer's proofs: 300 + 50 fresh processes per FMU (and 50 with the needle row,
# numba-compiled), 1000 load/free cycles, valgrind
native-check: $(STAMP)
	$(BIN)/python benchmarks/exit_clean.py --runs 300 --cli-runs 50 --needle-runs 50
	$(BIN)/python benchmarks/soak.py --cycles 1000
	command -v valgrind >/dev/null 2>&1 || { apt-get update -qq && apt-get install -y -qq valgrind; }
	$(BIN)/python benchmarks/memcheck.py --out out/memcheck

test: $(STAMP)
	$(BIN)/python -m pytest -q

# regenerate every generated block of README.md and docs/ (harness/docgen.py) from one run:
# per-FMU variables, reference CSVs and plots, the validation grid, the demo's output, then the
# benchmarks' measured tables (about 30 min: the work-precision ladder and the stress grid)
BENCH_RUNS ?= 5
docs: docs-quick
	$(BIN)/tripod-thrust bench --runs $(BENCH_RUNS) --out out/bench
	$(BIN)/tripod-thrust bench --peer --runs $(BENCH_RUNS) --out out/bench
	$(BIN)/tripod-thrust stress --out out/stress
	$(BIN)/python benchmarks/fmu_speed.py --md out/speed.md
	$(BIN)/python -m harness.docgen --bench out/bench/bench.md --stress out/stress/stress.md \
	  --speed out/speed.md --peers out/bench/peers.md
	cp out/bench/work_precision.png docs/

# only what the code alone determines (seconds to minutes): no timings
docs-quick: $(STAMP)
	$(BIN)/python -m harness.reference
	$(BIN)/python -m harness.validation
	$(BIN)/python -m harness.docgen

clean:
	rm -rf build out .pytest_cache
