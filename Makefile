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

.PHONY: all deps configure build test demo fuzz test-asan test-tsan format format-check clean

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
fuzz:
	@CMake/install-dependencies.sh clang
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIMLOP_BUILD_FUZZERS=ON
	cmake --build $(FUZZ_DIR) --parallel $(JOBS) --target vimlop-fuzzers
	CMake/run-fuzzers.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# AddressSanitizer + UndefinedBehaviorSanitizer on the unit tests of the
# modules that hold the algorithm and every reader of the CLI's inputs: Core,
# Raycast, Video (frames, video, COLMAP, intrinsics, tracker, SfM files),
# Imaging (CT volumes, DICOM series, meshes, displacement fields, poses) and
# Cohort (manifests, row records, Slurm records, the runner's processes). The
# rendering modules, the VTK face and the CLI executable are left out (their
# build would double the stage's; rendering needs Mesa under Xvfb).
ASAN_DIR ?= build-asan
ASAN_TESTS ?= VIMLOPCoreTests VIMLOPRaycastTests VIMLOPVideoTests VIMLOPImagingTests VIMLOPCohortTests
test-asan: deps
	cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIMLOP_ENABLE_SANITIZERS=ON
	cmake --build $(ASAN_DIR) --parallel $(JOBS) --target $(ASAN_TESTS)
	cd $(ASAN_DIR) && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure --parallel $(JOBS) -L '^($(subst $() ,|,$(ASAN_TESTS)))$$'

# ThreadSanitizer on the code that runs threads (Core: task pool, the
# parallel stages of the registration, the pose update; Cohort: the runner's
# rows at once, each a child process).
TSAN_DIR ?= build-tsan
test-tsan: deps
	cmake -S . -B $(TSAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVIMLOP_ENABLE_TSAN=ON
	cmake --build $(TSAN_DIR) --parallel $(JOBS) --target VIMLOPCoreTests VIMLOPCohortTests
	cd $(TSAN_DIR) && TSAN_OPTIONS=halt_on_error=1 bin/VIMLOPCoreTests \
	  --gtest_filter='TaskPool.*:Registration.*:PoseUpdate.*:MultiStartRegistration.*:CorrespondenceSearch.*:PoseEstimator.*'
	cd $(TSAN_DIR) && TSAN_OPTIONS=halt_on_error=1 bin/VIMLOPCohortTests --gtest_filter='CohortRunner.*'

format:
	git ls-files '*.h' '*.cxx' | xargs clang-format -i

# Fails, naming the files and lines, when a tracked source differs from clang-format's layout.
format-check:
	@CMake/install-dependencies.sh clang-format
	git ls-files '*.h' '*.cxx' | xargs clang-format --dry-run -Werror

clean:
	rm -rf $(BUILD_DIR)
