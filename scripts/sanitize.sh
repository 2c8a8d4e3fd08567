#!/usr/bin/env bash
# The C++ tests of the engine's untrusted-input surfaces (core/base, core/reflect, core/rpc: files, values,
# messages) and a run of the RPC fuzzer, built with AddressSanitizer and UndefinedBehaviorSanitizer in their
# own folder (build-asan). Not part of test.sh: a second build of the engine does not fit the CI budget
# on two cores. Run it after changing core/base, core/reflect or core/rpc; RELIABILITY.md records the runs.
#   bash scripts/sanitize.sh [FUZZ_RUNS]     (default 200000)
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies

ASAN_DIR="${SPEAR_ASAN_DIR:-$ROOT/build-asan}"
FUZZ_RUNS="${1:-200000}"
FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"

say "sanitize: configuring and building in $ASAN_DIR (ASan + UBSan)"
cmake -S "$ROOT" -B "$ASAN_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPython3_EXECUTABLE="$PYTHON" \
    -DSPEAR_PACKAGE_DIR="$ASAN_DIR/package" -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_C_FLAGS="$FLAGS" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$ASAN_DIR" -j "${SPEAR_JOBS:-2}" --target spear_base_tests spear_reflect_tests spear_rpc_tests spear_physics_tests spear_rpc_fuzz

# Leak checking is off: Mesa's llvmpipe and EGL keep process-lifetime allocations that are not ours.
# handle_sigbus=0: SIGBUS is the engine's own to handle (core/rpc/shared_memory.h guards truncated
# segments, and a test checks that other faults still kill the process with it).
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:strict_string_checks=1:handle_sigbus=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for suite in base reflect rpc physics; do
    say "sanitize: spear_${suite}_tests"
    "$ASAN_DIR/tests/core/$suite/spear_${suite}_tests" --gtest_brief=1
done
say "sanitize: spear_rpc_fuzz, $FUZZ_RUNS runs"
"$ASAN_DIR/tests/core/rpc/spear_rpc_fuzz" "$ROOT/tests/core/rpc/fuzz/corpus" --runs "$FUZZ_RUNS" --seed 7
