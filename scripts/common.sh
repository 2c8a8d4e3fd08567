# Shared by run.sh and test.sh: install what is missing, then configure and build.
# Everything uses Debian's /usr/bin/python3, which is the interpreter that sees the apt-installed packages.

set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PYTHON=/usr/bin/python3
BUILD_DIR="${SPEAR_BUILD_DIR:-$ROOT/build}"
export PYTHONPATH="$ROOT/python${PYTHONPATH:+:$PYTHONPATH}"

# Each stage says how long the script has run (test.sh's own time through the sanitizer script it calls),
# so a slow stage shows in any log.
export SPEAR_SCRIPT_START="${SPEAR_SCRIPT_START:-$(date +%s)}"
say() {
    local elapsed=$(($(date +%s) - SPEAR_SCRIPT_START))
    printf '\n\033[1m== [%dm%02ds] %s\033[0m\n' $((elapsed / 60)) $((elapsed % 60)) "$*"
}

# How many processes pytest spreads test files over: SPEAR_TEST_JOBS, else the cores up to four.
test_jobs() {
    local cores
    cores=$(nproc)
    echo "${SPEAR_TEST_JOBS:-$((cores < 4 ? cores : 4))}"
}

# Installs the Debian packages of a list (default: scripts/debian-packages.txt, what building and running need)
# that are missing.
install_dependencies() {
    local list="${1:-$ROOT/scripts/debian-packages.txt}"
    local missing=()
    while read -r pkg; do
        [[ -z "$pkg" || "$pkg" == \#* ]] && continue
        dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
    done < "$list"
    if ((${#missing[@]} == 0)); then
        say "dependencies: all $(grep -cv '^#' "$list") Debian packages of $(basename "$list") present"
        return
    fi
    say "dependencies: installing ${missing[*]}"
    local sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# Debian's node and npm, for the tools pinned from the npm registry: pyright (the typing tests) and tsc (the
# inspector page).
ensure_npm() {
    command -v npm >/dev/null 2>&1 && return
    say "dependencies: installing nodejs and npm"
    local sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends nodejs npm
}

# npm ci in folder $1 when its tool $2 (node_modules/.bin/$2) is missing or older than its package-lock.json.
npm_ci_if_stale() {
    local dir="$1" tool="$2"
    if [[ ! -x "$dir/node_modules/.bin/$tool" || "$dir/package-lock.json" -nt "$dir/node_modules/.package-lock.json" ]]; then
        say "dependencies: $tool (npm ci in ${dir#"$ROOT"/})"
        npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error
    fi
}

# pyright for the typing tests, pinned by tests/typing/pyright/package-lock.json.
install_pyright() {
    ensure_npm
    npm_ci_if_stale "$ROOT/tests/typing/pyright" pyright
}

# tsc for the inspector page and its generated client, pinned by inspector/package-lock.json (the build compiles
# the page when it is there).
install_typescript() {
    ensure_npm
    npm_ci_if_stale "$ROOT/inspector" tsc
}

# Runs the generator (`generate`, `check`, `dump-ir`) on the engine's reflected headers with the arguments the
# build passes it in core/engine/CMakeLists.txt.
engine_codegen() {
    local headers
    mapfile -t headers < <(grep -v '^#' "$ROOT/core/engine/reflected_headers.txt")
    (cd "$ROOT" && "$PYTHON" -m codegen "$1" --module engine --root . --out generated \
        --include-dir /usr/include/eigen3 --blueprint-dir assets/blueprints "${headers[@]}")
}

# A unity build (each target's sources compiled as a few files that #include them, CMake's UNITY_BUILD) parses
# the headers they share once per batch rather than once per source: a fresh build takes about half the time.
# Fresh build folders get one (the first run on a new machine, CI); a folder configured before keeps what it has,
# so a developer's incremental rebuilds stay per source. SPEAR_UNITY_BUILD=ON or OFF decides instead.
unity_build_option() {
    if [[ -n "${SPEAR_UNITY_BUILD:-}" ]]; then
        echo "-DCMAKE_UNITY_BUILD=$SPEAR_UNITY_BUILD"
    elif [[ ! -f "$1/CMakeCache.txt" ]]; then
        echo "-DCMAKE_UNITY_BUILD=ON"
    fi
}

build() {
    install_typescript
    say "build: configuring and building in $BUILD_DIR"
    # Warnings are errors in the project's own code (not in Debian's headers): the tree builds clean.
    # A folder configured before (by hand, with CMake's default generator) keeps its generator: CMake
    # refuses to switch one.
    local generator=(-G Ninja)
    [[ -f "$BUILD_DIR/CMakeCache.txt" ]] && generator=()
    cmake -S "$ROOT" -B "$BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DPython3_EXECUTABLE="$PYTHON" -DSPEAR_WERROR=ON $(unity_build_option "$BUILD_DIR") >/dev/null
    # Two jobs: the machines this runs on have two cores, and pybind11 translation units are large.
    cmake --build "$BUILD_DIR" -j "${SPEAR_JOBS:-2}"
}
