#!/usr/bin/env bash
# Packs spear-server, the native benchmark programs and the shared libraries they load that another
# x86-64 Linux host may lack into BUILD/portable/ (stripped of debug information, then compressed into
# BUILD/portable.tar.xz), to run the benchmarks on a machine without Debian's packages (a GPU host, say).
# With --python the kit also carries this machine's Python 3.11 (the standard library, numpy, msgpack, Pillow) and
# the in-process module, so that the host runs spear in-process too, whatever Python it has itself.
#
#   bash bench/portable_kit.sh [--python] [BUILD]       # here, after a build
#   bash bench/run_portable.sh [FRAMES] [PNG_DIR]       # there, in a checkout holding BUILD/portable.tar.xz
#
# The C and C++ runtimes, EGL and OpenGL are left to the host: its GPU driver provides EGL through
# libglvnd, and its C++ runtime is at least as new as the one the kit was built against. Some GPU hosts
# carry the driver's vendor library (libEGL_nvidia) without libglvnd's dispatcher, so the kit keeps
# this machine's libglvnd (libEGL.so.1, libOpenGL.so.0, libGLdispatch.so.0) in glvnd/, which run_portable.sh puts on
# the library path only where the host has none.
set -euo pipefail

with_python=0
if [[ ${1:-} == --python ]]; then
    with_python=1
    shift
fi
build=${1:-build}
kit=$build/portable
programs=(python/spear/bin/spear-server "$build/bench/spear_mujoco_cosim_peer" "$build/bench/spear_mujoco_peer"
          "$build/core/render/bench/spear_render_bench" "$build/core/render/bench/spear_shading_probe")
host_provided='^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libgcc_s|libstdc\+\+|libEGL|libGL|libGLX|libGLdispatch|libOpenGL|libresolv|libutil|libanl|libnss_[a-z]*)\.'

# Copies the libraries `binary` loads (through its RPATH too) into the kit, but those the host provides.
collect_libraries() {
    ldd "$1" | awk '$3 ~ /^\// {print $1, $3}' | while read -r name path; do
        if [[ ! $name =~ $host_provided && ! -e $kit/lib/$name ]]; then
            objcopy --strip-debug "$(readlink -f "$path")" "$kit/lib/$name"
        fi
    done
}

rm -rf "$kit" "$kit.tar.xz"
mkdir -p "$kit/bin" "$kit/lib" "$kit/glvnd"
for library in libEGL.so.1 libOpenGL.so.0 libGLdispatch.so.0; do
    objcopy --strip-debug "$(readlink -f "/usr/lib/x86_64-linux-gnu/$library")" "$kit/glvnd/$library"
done
for program in "${programs[@]}"; do
    if [[ ! -x $program ]]; then
        echo "portable_kit: $program is missing: build the project first (cmake --build $build)" >&2
        exit 1
    fi
    objcopy --strip-debug "$program" "$kit/bin/$(basename "$program")"
    collect_libraries "$program"
done

if ((with_python)); then
    modules=(python/spear/_spear_engine.cpython-311-*.so)
    if [[ ${#modules[@]} -ne 1 || ! -f ${modules[0]} ]]; then
        echo "portable_kit: --python needs the in-process module built for Python 3.11 (python/spear/" \
             "_spear_engine.cpython-311-*.so): build the project with /usr/bin/python3" >&2
        exit 1
    fi
    module=${modules[0]}
    python=$kit/python # PYTHONHOME there: bin/python3.11, lib/python3.11, site/ (numpy, msgpack)
    mkdir -p "$kit/spear" "$python/bin" "$python/lib" "$python/site"
    objcopy --strip-debug "$module" "$kit/spear/$(basename "$module")"
    collect_libraries "$module"
    cp /usr/bin/python3.11 "$python/bin/"
    skip=(--exclude=__pycache__ --exclude=test --exclude=tests --exclude=idlelib --exclude=tkinter
          --exclude=ensurepip --exclude=lib2to3 --exclude=dist-packages --exclude='config-3.11-*'
          --exclude='_tkinter*')
    tar -C /usr/lib "${skip[@]}" -cf - python3.11 | tar -C "$python/lib" -xf -
    tar -C /usr/lib/python3/dist-packages "${skip[@]}" -cf - numpy msgpack PIL | tar -C "$python/site" -xf -
    collect_libraries /usr/bin/python3.11
    find "$python" -type f -name '*.so' | while read -r library; do collect_libraries "$library"; done
fi

tar -C "$build" -cJf "$kit.tar.xz" portable # embree alone is 44 MB uncompressed
du -sh "$kit" "$kit.tar.xz" | sed "s/^/portable_kit: /"
