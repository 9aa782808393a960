# pelage: the two set-up commands are `make demo` and `make test` (see README.md).
BUILD      ?= build
BUILD_ASAN ?= build-asan
# The sanitizer build: -O1 (AddressSanitizer's advice) and line tables only, half the compile time
# of -O2 -g with the same reports (file and line in every stack frame).
ASAN_CMAKE = -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELAGE_WERROR=ON \
  -DPELAGE_SANITIZE=ON -DPELAGE_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=

.PHONY: all deps build demo test test-asan soak fuzz fuzz-ci farm-test cross-aarch64 bench format format-check clean

all: build

deps:
	@scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DPELAGE_WERROR=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# The main job on the built-in creature.
demo: build
	@scripts/demo.sh $(BUILD)

# Every test (unit, property, statistical, CLI and rendering tests).
test: build
	@scripts/ctest.sh $(BUILD) -j $(JOBS)

# The suite again under AddressSanitizer + UndefinedBehaviorSanitizer (+ LeakSanitizer), each suite
# one process, less the slow-labelled suites, the short soak runs (`make soak` runs the long ones
# under the sanitizers) and the large repeats tests/CMakeLists.txt names (PELAGE_SANITIZER_SKIP).
test-asan: deps
	@cmake $(ASAN_CMAKE) $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_ASAN) -j $(JOBS)
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  scripts/ctest.sh $(BUILD_ASAN) -j $(JOBS) -LE "slow|soak"

# 10,000 frames of the viewer update path and the export loop under the sanitizers, a change every
# frame, with resident memory at start and end (tests/viewer/soak_test.cpp); SOAK_FRAMES to change.
SOAK_FRAMES ?= 10000
soak: deps
	@cmake $(ASAN_CMAKE) $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_ASAN) -j $(JOBS) --target soak_tests
	@PELAGE_SOAK_FRAMES=$(SOAK_FRAMES) ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:quarantine_size_mb=16 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 $(BUILD_ASAN)/tests/soak_tests

# libFuzzer on every input reader (clang, ASan + UBSan): FUZZ_SECONDS per reader; see docs/reliability.md.
FUZZ_SECONDS ?= 60
fuzz: deps
	@scripts/fuzz.sh $(FUZZ_SECONDS)

# The bounded, fixed-seed fuzz run CI does (reproducible: same seed, same number of runs).
fuzz-ci: deps
	@scripts/fuzz.sh ci

# The render-farm and sweep recipes under a running one-node Slurm cluster (scripts/farm-test.sh;
# root; installs slurm-wlm and munge).
farm-test: build
	@scripts/farm-test.sh $(BUILD)

# The core libraries and their tests cross-compiled for aarch64 (the fur kernel on NEON), the
# suites (less the slow ones) run under qemu-user (scripts/cross-aarch64.sh; root; installs the
# cross compiler).
cross-aarch64:
	@scripts/cross-aarch64.sh

bench: build
	@for b in $(BUILD)/bin/bench_*; do echo "== $$b"; $$b; done

# Formatting (.clang-format): `make format` rewrites, `make format-check` (CI) fails on any diff.
format:
	@git ls-files '*.cpp' '*.h' | xargs clang-format -i

format-check: deps
	@git ls-files '*.cpp' '*.h' | xargs clang-format --dry-run -Werror && echo "format-check: clean"

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) out
