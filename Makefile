# The two commands of the README, and the targets they stand on.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

# Hostile input and long runs (docs/robustness.md): separate build directories, so that the
# normal build stays as it is.
SANITIZE_DIR ?= build-sanitize
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
# 0: a random seed each run; CI fixes it (docs/robustness.md).
FUZZ_SEED ?= 0
# The GPU tests that run under the sanitizers: the context, programs, VPLs, the naive renderer and
# one hierarchical frame cover the GL paths of every pass; the whole GPU suite under ASan on
# llvmpipe would not fit CI's time.
SANITIZE_GPU_TESTS ?= ContextTest.*:ProgramTest.*:ShaderSourceTest.*:Vpls.*:NaiveRenderer.*:HierarchicalGather.PlaneFacingTheLightIsGatheredAtTheCoarsestLevel
# The sanitizer runtimes of GCC 12 and LLVM 14 (ours) take a dynamic TLS block whose address is
# 16 bytes past a page boundary for a glibc 2.19 block with a header, and read its bounds from
# the 16 bytes before it; under glibc 2.25 and later that is whatever malloc left there, and at
# exit LeakSanitizer's tracer scans that range and dies ("Tracer caught signal 11"), a failure
# without a leak, and rare because it depends on where malloc put a block (once in CI, 0 of 76
# runs here). Mesa's driver, loaded with dlopen, uses dynamic TLS. Not intercepting
# __tls_get_addr avoids it, and leaks are still found (docs/robustness.md: how it was checked).
LEAK_CHECK_ASAN_OPTIONS = intercept_tls_get_addr=0
# Any report fails the run; tests/lsan.supp names the third-party libraries whose own leaks are
# not ours to fix. The GPU tests run with tests/keep_libraries_loaded.c preloaded, so that the GL
# driver Mesa unloads at eglTerminate stays loaded and its static blocks are not reported as
# leaks of an unknown module (the file says why). LEAK_CHECK_ASAN_OPTIONS: see its definition.
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1:$(LEAK_CHECK_ASAN_OPTIONS) \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp

.PHONY: all deps configure build demo test soak sanitize fuzz performance docs-images format clean

all: build

deps:
	scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	mkdir -p out
	$(BUILD_DIR)/penumbra render scenes/demo.scene -o out/demo.exr -o out/demo.png

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS) -LE soak

# 3000 frames in one process; memory and GL objects must stay flat.
soak: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -L soak

# AddressSanitizer and UndefinedBehaviorSanitizer. The build lists each test executable's tests
# by running it, which is no test run: leaks are not checked there.
sanitize: deps
	cmake -S . -B $(SANITIZE_DIR) -G Ninja -DPENUMBRA_SANITIZE=ON
	ASAN_OPTIONS=detect_leaks=0 cmake --build $(SANITIZE_DIR) -j $(JOBS) \
	  --target penumbra_cpu_tests penumbra_gpu_tests
	cd $(SANITIZE_DIR)/tests && $(SANITIZE_ENV) ./penumbra_cpu_tests
	cc -shared -fPIC -o $(SANITIZE_DIR)/keep-libraries-loaded.so tests/keep_libraries_loaded.c
	cd $(SANITIZE_DIR)/tests && \
	  LD_PRELOAD="$$(cc -print-file-name=libasan.so) $(CURDIR)/$(SANITIZE_DIR)/keep-libraries-loaded.so" \
	  $(SANITIZE_ENV) ./penumbra_gpu_tests --gtest_filter='$(SANITIZE_GPU_TESTS)'

# libFuzzer needs clang. Warnings are errors in the normal (gcc) build only, so that a warning
# only clang gives cannot stop the fuzzers.
fuzz: deps
	cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DPENUMBRA_FUZZ=ON -DPENUMBRA_WERROR=OFF
	cmake --build $(FUZZ_DIR) -j $(JOBS) --target penumbra_fuzz
	ASAN_OPTIONS=$(LEAK_CHECK_ASAN_OPTIONS) fuzz/run-fuzzers.sh $(FUZZ_DIR) $(FUZZ_SECONDS) $(FUZZ_SEED)

# docs/performance.md and its figures: every measurement again (about 25 minutes), on an
# otherwise idle machine.
performance: build
	bench/performance.sh $(BUILD_DIR)/penumbra

# The pictures of the README and docs/, rendered with the current defaults.
docs-images: build
	scripts/docs-images $(BUILD_DIR)/penumbra

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR) $(FUZZ_DIR) out
