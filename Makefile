# skinmesh: thin wrapper over CMake. `make mesh` and `make test` work on a fresh
# Debian machine: they install the missing Debian packages first (.ci/install-deps).
BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
MOLECULE ?= data/gramicidinA_1grm_model1.pdb
OUT     ?= gramicidinA_1grm_model1.ply

SANITIZE_BUILD ?= build-sanitize
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 20
FUZZ_CXX ?= clang++-14

.PHONY: all deps configure build mesh test sanitize fuzz bench table1 stress viewer viewer-if-possible layers format format-check clean

all: build

deps:
	@bash .ci/install-deps

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# Mesh a bundled real molecule (gramicidin A by default) and verify the mesh.
mesh: build
	$(BUILD)/skinmesh mesh $(MOLECULE) -o $(OUT) --stats -

# Run the whole test suite through ctest. The headless-Chromium test of the
# trace viewer runs when chromium, node and npm are present (.ci/run installs
# them: bash .ci/install-deps --browser); otherwise it is skipped, and says so.
test: build
	@$(MAKE) --no-print-directory viewer-if-possible
	@rm -f $(BUILD)/browser_test.log
	cd $(BUILD) && ctest --output-on-failure
	@echo "--- the trace viewer's headless-Chromium test (ctest 'browser'):"; \
	  if [ -f $(BUILD)/browser_test.log ]; then grep -E "^(ok|not ok|#|SKIP)" $(BUILD)/browser_test.log | \
	  sed -e 's/^SKIP/SKIPPED/'; else echo "SKIPPED: it did not run"; fi

# The trace viewer (trace/viewer): three.js and esbuild from the npm registry,
# bundled into one page template, $(BUILD)/trace_viewer.html, that
# `skinmesh trace IN -o trace.html` fills with the recorded trace.
viewer:
	@command -v npm >/dev/null 2>&1 || { echo "make viewer needs node and npm (bash .ci/install-deps --browser)"; exit 1; }
	@mkdir -p $(BUILD)
	cd trace/viewer && npm ci --no-audit --no-fund --loglevel=error && node build.mjs $(abspath $(BUILD))/trace_viewer.html

viewer-if-possible:
	@if command -v npm >/dev/null 2>&1; then $(MAKE) --no-print-directory viewer || \
	  echo "note: the trace viewer could not be built (npm registry unreachable?); its browser test will be skipped"; \
	else echo "note: node/npm not found: the trace viewer is not built and its browser test will be skipped"; fi

# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer
# (any report fails the run), then the input readers under libFuzzer (make fuzz).
sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKINMESH_BUILD_BENCH=OFF \
	  -DSKINMESH_SANITIZE=ON > /dev/null
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && ctest --output-on-failure
	@$(MAKE) --no-print-directory fuzz

# libFuzzer on every input reader (tests/fuzz): the targets built with clang++,
# AddressSanitizer and UndefinedBehaviorSanitizer, then each run FUZZ_SECONDS on a
# scratch copy of its seed corpus. Any crash, sanitizer report, hang (> 10 s on one
# input) or memory above 2 GB fails; the input is kept in $(FUZZ_BUILD)/fuzz-artifacts.
fuzz:
	@bash .ci/install-deps --fuzz
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=$(FUZZ_CXX) \
	  -DSKINMESH_BUILD_BENCH=OFF -DSKINMESH_FUZZ=ON > /dev/null
	@cmake --build $(FUZZ_BUILD) --target skinmesh_fuzz -j $(JOBS)
	@bash tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# Google Benchmark: predicates, regular triangulation, the mesher (Table 1).
bench: build
	$(BUILD)/skinmesh_bench

# Cheng & Shi's Table 1 reproduced: sweep, dynamic-skin baseline and static
# variant on the Table-1 stand-ins, crambin, HIV protease, maltoporin and the
# Figure 4 cube, one thread, every mesh checked (papers/bench/table1.md).
# TABLE1_ARGS="--quick" for the small inputs only.
table1: build
	$(BUILD)/skinmesh_table1 $(TABLE1_ARGS)

# The seeded stress suite (tests/stress): a few hundred generated inputs through
# the whole pipeline, each checked against an independently computed topology.
# Failing cases can be written out with e.g. STRESS_ARGS="--dump /tmp/stress-fail".
stress: build
	$(BUILD)/skinmesh_stress $(STRESS_ARGS)

# The C++ style (.clang-format: Google's, 120 columns), applied to every tracked
# .cpp and .h (format) or checked without changing anything (format-check, which
# CI runs). Debian's clang-format 14 (.ci/install-deps installs it).
FORMAT_FILES = $(shell git ls-files '*.cpp' '*.h' 2>/dev/null | grep -v '^tests/fuzz/corpus/')
format:
	@clang-format -i --style=file $(FORMAT_FILES)

format-check:
	@command -v clang-format >/dev/null 2>&1 || { echo "make format-check needs clang-format (bash .ci/install-deps)"; exit 1; }
	@clang-format --dry-run --Werror --style=file $(FORMAT_FILES) && echo "format-check: $(words $(FORMAT_FILES)) files follow .clang-format"

# The module graph (one library per folder), printed and checked one-way
# (tests/layers/check_layers.py; also ctest 'layers').
layers:
	@python3 tests/layers/check_layers.py .
	@python3 tests/layers/check_layout.py .

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(FUZZ_BUILD)
