#!/usr/bin/env bash
# The engine's untrusted-input surfaces under AddressSanitizer (everywhere) and UndefinedBehaviorSanitizer (where
# it decodes input), in their own build folder (build-asan): the C++ tests of core/base, core/reflect, core/rpc
# (files, values, messages) and core/physics, a run of the RPC fuzzer, and the Python RPC tests against an
# instrumented spear-server.
# bash test.sh runs it last with a short fuzz run; RELIABILITY.md records longer runs.
#   bash scripts/sanitize.sh [FUZZ_RUNS]     (default 200000)
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies

ASAN_DIR="${SPEAR_ASAN_DIR:-$ROOT/build-asan}"
FUZZ_RUNS="${1:-200000}"
# -O1 without debug information: the sanitizers' recommended level, and the quickest instrumented build
# (reports still name functions; rebuild with -g added to FLAGS for file:line). The build type is one
# CMake has no flags for, so FLAGS are all there is: an empty one would become the project's default,
# RelWithDebInfo, whose -O2 -g doubled every instrumented compile (core/scene/scene_io.cpp: 16 -> 32 s).
# AddressSanitizer everywhere; UndefinedBehaviorSanitizer (SPEAR_UBSAN_FLAGS) in the parts that decode what a
# client sends and in their tests, not in the renderer's (CMakeLists.txt says which and why).
FLAGS="-O1 -fsanitize=address -fno-omit-frame-pointer"
UBSAN_FLAGS="-fsanitize=undefined;-fno-sanitize-recover=undefined"

say "sanitize: configuring and building in $ASAN_DIR (ASan + UBSan)"
cmake -S "$ROOT" -B "$ASAN_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize -DPython3_EXECUTABLE="$PYTHON" \
    -DSPEAR_PACKAGE_DIR="$ASAN_DIR/package" -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_C_FLAGS="$FLAGS" \
    -DSPEAR_UBSAN_FLAGS="$UBSAN_FLAGS" $(unity_build_option "$ASAN_DIR") \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
# The inspector page too where this configuration has it (node and tsc present), for test_inspector.py. The
# target list is read whole before grep looks at it: `cmake ... | grep -q` under pipefail fails whenever grep
# exits before cmake has written everything (SIGPIPE), which dropped the page at random.
targets=$(cmake --build "$ASAN_DIR" --target help)
inspector=()
grep -q '^spear_inspector:' <<<"$targets" && inspector=(spear_inspector)
cmake --build "$ASAN_DIR" -j "${SPEAR_JOBS:-2}" --target spear_base_tests spear_reflect_tests spear_rpc_tests spear_physics_tests spear_rpc_fuzz \
    spear-server "${inspector[@]}"

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

# The Python side is the main build's (the in-process engine module, for the tests that compare both
# transports); every server these tests launch is the instrumented one. By default the suites of the
# surfaces that take untrusted input: messages and transports, values refused by type and range, misuse,
# asynchronous calls, shared memory, the files a client names (scenes, blueprints, asset paths, file roots),
# the lane queries' point arrays, and the inspector's HTTP and WebSocket framing. SPEAR_SANITIZE_ALL=1 runs every test on the RPC transport instead: since global illumination
# became the default, each rendering test lights its probes with the instrumented path tracer, and that run
# takes about ten minutes more (RELIABILITY.md).
build
TESTS=(tests/python/test_rpc_transport.py tests/python/test_rpc_robustness.py tests/python/test_rpc_spin.py
    tests/python/test_misuse_parity.py tests/python/test_set_time_validation.py tests/python/test_async_calls.py
    tests/python/test_process_memory.py tests/python/test_typed_results.py tests/python/test_world_api.py
    tests/python/test_scenes.py tests/python/test_blueprints.py tests/python/test_asset_path.py
    tests/python/test_file_roots.py tests/python/test_lanes.py tests/python/test_traffic.py
    tests/python/test_inspector.py)
[[ "${SPEAR_SANITIZE_ALL:-0}" == 1 ]] && TESTS=(tests/python)
say "sanitize: the Python tests on the RPC transport (${TESTS[*]}), against the instrumented spear-server"
cd "$ROOT" && SPEAR_SERVER="$ASAN_DIR/package/bin/spear-server" SPEAR_BUILD_DIR="$BUILD_DIR" "$PYTHON" -m pytest -q \
    -n "$(test_jobs)" --dist loadfile -k "rpc or parity" "${TESTS[@]}"
