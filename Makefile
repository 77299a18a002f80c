# The two set-up commands of the README. Everything else is CMake (build/).
#   make demo   install missing Debian packages (as root), build, render the demo into out/demo/
#   make test   install missing Debian packages (as root), build, run the whole ctest suite
# Benchmarks (not part of make test; a separate Release build in build-bench/):
#   make bench        also installs Embree and gnuplot, runs every scene and sweep, and
#                     regenerates docs/bench/ (RESULTS.md, plots, gallery) from scratch; slow
#   make bench-quick  the same on a small subset, into build-bench/bench-quick/ (< 2 minutes)
# Fuzzing (not part of make test; a clang ASan+UBSan build in build/fuzz-clang/):
#   make fuzz         installs clang and its libFuzzer runtime, runs every libFuzzer target for
#                     FUZZ_MINUTES (default 10) each and prints the table (tools/fuzz.sh,
#                     docs/fuzz.md); FUZZ_TARGETS="scene gears" picks targets
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo
BENCH_BUILD ?= build-bench
# The benchmark's library is compiled for this machine's CPU (-march=native, as a console
# build targets its CPU; Embree dispatches to the host's widest ISA at run time). The bytes
# are the same (ctest golden_target_arch); BENCH_ARCH= gives the compiler's default target.
BENCH_ARCH ?= native
# Valgrind cannot run AVX-512: the callgrind table of make bench comes from a second build
# for the compiler's default target.
BENCH_PROFILE_BUILD ?= build-bench-profile
PN_SCENES_DIR ?= $(abspath ../shared/scenes)

.PHONY: all deps configure build demo test clean bench bench-quick bench-build bench-profile-build fuzz

all: build

deps:
	@sh tools/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# PoCL compiles the OpenCL kernels once and caches them: inside the build directory.
demo: build
	POCL_CACHE_DIR=$(abspath $(BUILD))/pocl-cache $(BUILD)/tools/penumbra demo --out out/demo

# ctest sets POCL_CACHE_DIR=$(BUILD)/pocl-cache for the tests that build OpenCL kernels.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench-build:
	@sh tools/install-deps.sh bench
	@cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-g -DCMAKE_CXX_FLAGS=-g -DPN_BUILD_TESTS=OFF -DPN_TARGET_ARCH=$(BENCH_ARCH) >/dev/null
	@cmake --build $(BENCH_BUILD) -j $(JOBS) --target penumbra_bench penumbra_cli penumbra_memory

bench-profile-build: bench-build
	@cmake -S . -B $(BENCH_PROFILE_BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-g -DCMAKE_CXX_FLAGS=-g -DPN_BUILD_TESTS=OFF -DPN_TARGET_ARCH= >/dev/null
	@cmake --build $(BENCH_PROFILE_BUILD) -j $(JOBS) --target penumbra_bench penumbra_cli

bench: bench-build bench-profile-build
	PN_PROFILE_BENCH=$(BENCH_PROFILE_BUILD)/tools/penumbra_bench sh tools/bench.sh full $(BENCH_BUILD)/tools/penumbra_bench docs/bench $(PN_SCENES_DIR)

bench-quick: bench-build
	sh tools/bench.sh quick $(BENCH_BUILD)/tools/penumbra_bench $(BENCH_BUILD)/bench-quick $(PN_SCENES_DIR)

# FUZZ_MINUTES, FUZZ_TARGETS, FUZZ_SCRATCH, FUZZ_BUILD pass through the environment.
fuzz:
	@sh tools/install-deps.sh fuzz
	sh tools/fuzz.sh

clean:
	rm -rf $(BUILD) $(BENCH_BUILD) $(BENCH_PROFILE_BUILD) out
