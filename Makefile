# The two commands of the README's Quick start, and their parts.
#   make demo   install what is missing, build, run the main job on the bundled data
#   make test   install what is missing, build, run every test with ctest
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
CMAKE_ARGS ?=
CT ?= /usr/share/doc/invesalius-examples/examples/Cranium.inv3
DEMO_DIR ?= demo-output

.PHONY: all deps configure build test demo format clean

all: build

deps:
	@CMake/install-dependencies.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD_DIR) --parallel $(JOBS)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure --parallel $(JOBS)

demo: build
	$(BUILD_DIR)/bin/vimlop info $(CT)

format:
	git ls-files '*.h' '*.cxx' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
