# The README's two commands: `make demo` and `make test`. Both set up .venv first.
# The newest working Python 3.11-3.13 on the machine, or PY=...  (`command -v` alone is not
# enough: a pyenv shim exists for every version but runs only the selected ones).  Found inside
# an activated virtualenv, its base interpreter: a venv's Python may have no pip to bootstrap uv
PY ?= $(shell for v in 3.13 3.12 3.11; do p=$$(command -v python$$v) && "$$p" -c 'import sys' \
        >/dev/null 2>&1 || continue; b=$$("$$p" -c 'import os, sys; print(os.path.join( \
        sys.base_prefix, "bin", "python%d.%d" % sys.version_info[:2]))' 2>/dev/null); \
        [ -x "$$b" ] && "$$b" -c 'import sys' >/dev/null 2>&1 && p=$$b; echo "$$p"; break; done)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
UV := .uv/bin/uv
# uv installs uv.lock exactly; it never downloads a Python of its own
UV_ENV := UV_PROJECT_ENVIRONMENT=$(VENV) UV_PYTHON_DOWNLOADS=never UV_NO_PROGRESS=1

.DEFAULT_GOAL := demo

.PHONY: demo example test test-slow venv lock fmu bench native-check docs docs-quick clean cross-tools

venv: $(STAMP)

# the installer, pinned by hash, beside the project (the Python's own site-packages untouched)
$(UV): tools/uv.txt
	@[ -n "$(PY)" ] && "$(PY)" -c 'import sys; sys.exit(not (3, 11) <= sys.version_info[:2] <= (3, 13))' \
	  || { echo "make: Python 3.11, 3.12 or 3.13 is needed (none found as python3.1x; give one with PY=/path/to/python3)"; exit 1; }
	"$(PY)" -m pip --version >/dev/null 2>&1 || { [ "$$(id -u)" = 0 ] && apt-get update -qq && \
	  apt-get install -y -qq python3-pip; } || { echo "make: $(PY) has no pip (apt-get install python3-pip)"; exit 1; }
	rm -rf .uv
	"$(PY)" -m pip install --quiet --disable-pip-version-check --no-warn-script-location \
	  --require-hashes --target .uv -r tools/uv.txt
	touch $(UV)

# Reinstall only when the lock changes: exactly the locked versions (uv refuses a lock that no
# longer matches pyproject.toml).  The FMUs' binary is compiled from fmu_src/native/ (a C
# compiler is all it needs): install gcc where none is found.  Exudyn (the peer extra) where
# the registry has a wheel for this Python.
$(STAMP): uv.lock pyproject.toml $(UV)
	command -v cc >/dev/null 2>&1 || { [ "$$(id -u)" = 0 ] && apt-get update -qq && \
	  apt-get install -y -qq gcc; } || { echo "make: a C compiler is needed (apt-get install gcc)"; exit 1; }
	$(UV_ENV) $(UV) sync --locked --python "$(PY)" --extra test --extra peer \
	  || $(UV_ENV) $(UV) sync --locked --python "$(PY)" --extra test
	touch $(STAMP)

# the one command that updates the lock: every dependency to its newest release within
# pyproject.toml's ranges (then make test, and commit uv.lock with what it changed)
lock: $(UV)
	$(UV_ENV) $(UV) lock --upgrade --python "$(PY)"

# the main job: both FMUs (built when missing or stale) compared on the paper's scene
demo: $(STAMP)
	$(BIN)/tripod-thrust compare --out out

# the driveline example: a vehicle launch, the joint FMU beside a powertrain FMU in one SSP,
# run by FMPy and by libcosim (docs/driveline-example.md)
example: $(STAMP) cross-tools
	$(BIN)/tripod-thrust example --out out/example

fmu: $(STAMP) cross-tools
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

# the win64 cross build (mingw-w64) and, to run what it builds, wine64 (Debian's packages)
cross-tools:
	@command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 && [ -x /usr/lib/wine/wine64 ] || \
	  { [ "$$(id -u)" = 0 ] && apt-get update -qq && apt-get install -y -qq gcc-mingw-w64-x86-64 \
	  wine64 >/dev/null; } || { echo "make: the win64 build and its tests need mingw-w64 and wine64 (as root: apt-get install gcc-mingw-w64-x86-64 wine64)"; exit 1; }

# two workers (the machine's two cores; pytest-xdist), a module's tests on one worker (its
# fixtures, such as a compiled namespace or a scene grid, then computed once, not on both),
# the slowest tests named at the end;
# the slowest tests (marked slow: the needle row's convergence, a reference compiling in memory)
# in their own tier, which CI runs too
test: $(STAMP) cross-tools
	$(BIN)/python -m pytest -q -n 2 --dist loadscope --durations=15 -m "not slow"

test-slow: $(STAMP) cross-tools
	$(BIN)/python -m pytest -q -n 2 --dist loadscope --durations=10 -m slow

# regenerate every generated block of README.md and docs/ (harness/docgen.py) from one run:
# per-FMU variables, reference CSVs and plots, the validation grid, the demo's output, then the
# benchmarks' measured tables (about 30 min: the work-precision ladder and the stress grid)
BENCH_RUNS ?= 5
docs: docs-quick
	$(BIN)/tripod-thrust bench --runs $(BENCH_RUNS) --out out/bench
	$(BIN)/tripod-thrust bench --peer --runs $(BENCH_RUNS) --out out/bench
	$(BIN)/tripod-thrust stress --out out/stress
	$(BIN)/python benchmarks/fmu_speed.py --md out/speed.md
	$(BIN)/python benchmarks/transients.py --md out/transients.md
	$(BIN)/python benchmarks/needle_chaos.py --md out/needle_chaos.md
	$(BIN)/python -m benchmarks.step_budget --md out/step_budget.md
	$(BIN)/tripod-thrust example --out out/example
	cp out/example/launch.png out/example/order_map.png out/example/thrust_orders.png docs/
	$(BIN)/python -m harness.docgen --bench out/bench/bench.md --stress out/stress/stress.md \
	  --speed out/speed.md --peers out/bench/peers.md --example out/example/launch.md \
	  --transients out/transients.md --chaos out/needle_chaos.md --budget out/step_budget.md
	cp out/bench/work_precision.png docs/

# only what the code alone determines (seconds to minutes): no timings
docs-quick: $(STAMP)
	$(BIN)/python -m harness.reference
	$(BIN)/python -m harness.validation
	$(BIN)/python -m harness.docgen

clean:
	rm -rf build out .pytest_cache .uv
