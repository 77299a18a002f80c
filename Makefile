# The two set-up commands of the README. Everything else is CMake (build/).
#   make demo   install missing Debian packages (as root), build, render the demo into out/demo/
#   make test   install missing Debian packages (as root), build, run the whole ctest suite
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo

.PHONY: all deps configure build demo test clean

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

clean:
	rm -rf $(BUILD) out
