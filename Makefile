# The two commands of the README's Quick start, and their parts.
#   make demo   install what is missing, build, run the main job on the bundled data
#   make test   install what is missing, build, run every test with ctest
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
CMAKE_ARGS ?=
CT ?= /usr/share/doc/invesalius-examples/examples/Cranium.inv3
DEMO_DIR ?= demo-output

FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60

.PHONY: all deps configure build test demo fuzz test-asan test-tsan format clean

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
	CMake/run-demo.sh $(BUILD_DIR) $(CT) $(DEMO_DIR)

# Each fuzzer runs FUZZ_SECONDS from its seed corpus (Testing/Fuzzing/corpus).
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIMLOP_BUILD_FUZZERS=ON
	cmake --build $(FUZZ_DIR) --parallel $(JOBS) --target vimlop-fuzzers
	CMake/run-fuzzers.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# AddressSanitizer + UndefinedBehaviorSanitizer on the unit tests.
test-asan: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIMLOP_ENABLE_SANITIZERS=ON
	cmake --build build-asan --parallel $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=0 ctest --output-on-failure --parallel $(JOBS) -LE 'cli|slow'

# ThreadSanitizer on the code that runs threads (Core: task pool, registration).
test-tsan: deps
	cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIMLOP_ENABLE_TSAN=ON
	cmake --build build-tsan --parallel $(JOBS) --target VIMLOPCoreTests
	cd build-tsan && TSAN_OPTIONS=halt_on_error=1 bin/VIMLOPCoreTests --gtest_filter='TaskPool.*:Registration.*:PoseUpdate.*'

format:
	git ls-files '*.h' '*.cxx' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
