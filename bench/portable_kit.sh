#!/usr/bin/env bash
# Packs spear-server, the native benchmark programs and the shared libraries they load that another
# x86-64 Linux host may lack into BUILD/portable/, stripped of debug information, to run the benchmarks
# on a machine without Debian's packages (a GPU host, say). There the host's own Python 3 (with numpy
# and msgpack) drives the engine over RPC from this checkout's python/ folder:
#
#   bash bench/portable_kit.sh [BUILD]           # here, after a build
#   export LD_LIBRARY_PATH=$PWD/build/portable/lib SPEAR_SERVER=$PWD/build/portable/bin/spear-server
#   PYTHONPATH=python python3 bench/bench_cosim.py --transports rpc --peer-dir build/portable/bin
#
# The C and C++ runtimes, EGL and OpenGL are left to the host: its GPU driver provides EGL through
# libglvnd, and its C++ runtime is at least as new as the one the kit was built against.
set -euo pipefail

build=${1:-build}
kit=$build/portable
programs=(python/spear/bin/spear-server "$build/bench/spear_mujoco_cosim_peer" "$build/bench/spear_mujoco_peer"
          "$build/core/render/bench/spear_render_bench")
host_provided='^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libgcc_s|libstdc\+\+|libEGL|libGL|libGLX|libGLdispatch|libOpenGL)\.'

rm -rf "$kit"
mkdir -p "$kit/bin" "$kit/lib"
for program in "${programs[@]}"; do
    if [[ ! -x $program ]]; then
        echo "portable_kit: $program is missing: build the project first (cmake --build $build)" >&2
        exit 1
    fi
    objcopy --strip-debug "$program" "$kit/bin/$(basename "$program")"
    # ldd resolves what the program loads through its RPATH too (libspear_core.so beside the server).
    ldd "$program" | awk '$3 ~ /^\// {print $1, $3}' | while read -r name path; do
        if [[ ! $name =~ $host_provided && ! -e $kit/lib/$name ]]; then
            objcopy --strip-debug "$(readlink -f "$path")" "$kit/lib/$name"
        fi
    done
done
tar -C "$build" -cJf "$kit.tar.xz" portable  # the compressed kit travels more easily (embree alone is 44 MB)
du -sh "$kit" "$kit.tar.xz" | sed "s/^/portable_kit: /"
