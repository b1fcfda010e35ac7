# skinmesh: thin wrapper over CMake. `make mesh` and `make test` work on a fresh
# Debian machine: they install the missing Debian packages first (.ci/install-deps).
BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
MOLECULE ?= data/gramicidinA_1grm_model1.pdb
OUT     ?= gramicidinA_1grm_model1.ply

SANITIZE_BUILD ?= build-sanitize

.PHONY: all deps configure build mesh test sanitize bench stress clean

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

# Run the whole test suite through ctest.
test: build
	cd $(BUILD) && ctest --output-on-failure

# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer
# (any report fails the run).
sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKINMESH_BUILD_BENCH=OFF \
	  -DSKINMESH_SANITIZE=ON > /dev/null
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && ctest --output-on-failure

# Google Benchmark: predicates, regular triangulation, the mesher (Table 1).
bench: build
	$(BUILD)/skinmesh_bench

# The seeded stress suite (tests/stress): a few hundred generated inputs through
# the whole pipeline, each checked against an independently computed topology.
# Failing cases can be written out with e.g. STRESS_ARGS="--dump /tmp/stress-fail".
stress: build
	$(BUILD)/skinmesh_stress $(STRESS_ARGS)

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD)
