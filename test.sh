#!/usr/bin/env bash
# Every test: generator checks, C++ tests (CTest), Python API tests, codegen golden cases and typing
# cases (pytest, which runs mypy --strict, pyright and tsc, and drives the inspector in headless chromium), a
# format check, and the sanitizer build's tests.
#   bash test.sh
source "$(dirname "${BASH_SOURCE[0]}")/scripts/common.sh"
install_dependencies
# A browser for the inspector's end-to-end tests (tests/python/test_inspector_browser.py).
install_dependencies "$ROOT/scripts/debian-test-packages.txt"
install_pyright

# Before the build, which regenerates generated/: the committed copy must already match the headers.
say "check: committed generated/ matches the reflected headers"
engine_codegen check
(cd "$ROOT" && "$PYTHON" -m codegen.protocol check --root .)

build

say "format: clang-format on project C++ sources"
(cd "$ROOT" && git ls-files 'core/*.cpp' 'core/*.h' 'tests/core/*.cpp' | xargs clang-format --dry-run -Werror)

say "test: C++ (CTest)"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j 2

say "test: Python API, generator and typing (pytest)"
# The plugin tests build examples/plugin against this build (find_package(spear) in $BUILD_DIR).
export SPEAR_BUILD_DIR="$BUILD_DIR"
# Files spread over up to four processes (pytest-xdist; a file's tests stay together, so its module fixtures
# and the files it writes are its own): most tests wait on a server, a build or llvmpipe's threads.
# A crash of the engine in a test or an example it runs prints the Python stack it happened under.
export PYTHONFAULTHANDLER=1
cd "$ROOT" && "$PYTHON" -m pytest -q -n "$(test_jobs)" --dist loadfile tests

# Last, the untrusted-input surfaces again under AddressSanitizer + UndefinedBehaviorSanitizer (their own
# build in build-asan/): C++ suites, a short fuzz run, and the RPC tests against an instrumented server.
cd "$ROOT" && bash scripts/sanitize.sh "${SPEAR_FUZZ_RUNS:-200000}"
