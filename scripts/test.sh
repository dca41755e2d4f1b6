#!/usr/bin/env bash
# Runs the whole test suite: the CTest suite of the main build, then the unit
# and shading tests again in an AddressSanitizer + UBSan build (build-asan/),
# the fuzzers for 20 s each (scripts/fuzz.sh, build-fuzz/).
# Exits non-zero when anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"

cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

# -O1 -g1 for the sanitizer builds, as the sanitizers' own documentation
# advises: the tests ran 4-5x faster than at -O0 (an Embree update test 17.7
# -> 4.0 s, the 64 MiB scene 5.8 -> 1.2 s), and line tables keep every
# report's file:line while the build makes far less debug information.
sanitizer_flags=(-DCMAKE_BUILD_TYPE=Debug "-DCMAKE_C_FLAGS_DEBUG=-O1 -g1" "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1")

cmake -S . -B build-asan -G Ninja "${sanitizer_flags[@]}" -DPRISM_SANITIZE=ON
cmake --build build-asan -j"$jobs" --target prism_unit_suite
# LeakSanitizer is on (ASan's default). The 100,000-sphere scene (label
# "large") is left to the main build: under ASan at -O0 it alone takes ~15 min.
# So are the checks of the repository's files (label "repository": GLSL
# compiled by glslangValidator, the docs' folder table, ...): scripts and
# system tools that no sanitizer instruments, which took ~80 s here.
# tests/support/lsan.supp lists the third-party leaks left out.
# intercept_tls_get_addr=0: LeakSanitizer's tracking of dynamic TLS (the
# blocks __tls_get_addr hands out for dlopen'ed libraries: OpenImageIO and
# its ~250 dependencies, GL and Vulkan drivers) made its stop-the-world
# tracer crash ("Tracer caught signal 11", addr 0x2eb0) in tests that write
# images while other tests run; reproduced 3 of 3 at ctest -j4, gone with it.
# Lavapipe (Mesa 22.3.6-1+deb12u2) keeps a block it reallocs at start-up in
# a global of its own. The Vulkan loader unloads the driver when the instance
# is destroyed; LeakSanitizer then finds the block unreachable, with only
# "<unknown module>" frames that no suppression can name (2 x 128 bytes in
# every Vulkan test). Keeping the driver loaded (preloaded, so the loader's
# dlclose leaves it mapped) keeps the block reachable, as it is;
# verify_asan_link_order=0 lets the preloaded driver come before the ASan
# runtime in the library list (ASan still intercepts its allocations: the
# executables are instrumented and initialise it first).
lavapipe="$(ls /usr/lib/*-linux-gnu/libvulkan_lvp.so 2>/dev/null | head -n 1 || true)"
LD_PRELOAD="${lavapipe}" \
ASAN_OPTIONS=abort_on_error=1:intercept_tls_get_addr=0:verify_asan_link_order=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS="suppressions=$PWD/tests/support/lsan.supp:print_suppressions=0" \
  PRISM_REQUIRE_BACKENDS=reference,embree,opengl,vulkan \
  ctest --test-dir build-asan --output-on-failure -j"$jobs" -L 'unit|shading' -LE repository

# 20 s of libFuzzer on each of the scene loader and the ray reader
# (build-fuzz/, clang), after replaying every input that once found a bug.
# Long runs are separate: scripts/fuzz.sh --seconds 3600.
scripts/fuzz.sh --seconds 20

# ThreadSanitizer: the concurrency test only (two scenes rendered at once
# through the core's API), with just what it loads: the core, the primitive
# plugins and the reference and embree backends (target prism_concurrency_suite).
cmake -S . -B build-tsan -G Ninja "${sanitizer_flags[@]}" -DPRISM_TSAN=ON
cmake --build build-tsan -j"$jobs" --target prism_concurrency_suite
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" PRISM_REQUIRE_BACKENDS=reference,embree \
  build-tsan/bin/prism_concurrency_test
