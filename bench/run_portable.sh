#!/usr/bin/env bash
# Runs the renderer and Table 3 benchmarks from the portable kit (bench/portable_kit.sh) on a host without
# the build's Python: the renderer alone (spear_render_bench, per-pass GL timer queries), then Table 3
# beside MuJoCo: in-process and over RPC when the kit carries its Python (portable_kit.sh --python), else
# over RPC only, driven by the host's python3 (numpy and msgpack needed); with the kit's Python, last the
# vectorised environments at N = 16 (bench_vector.py, three rounds, without Dask).
#
#   bash bench/run_portable.sh [FRAMES] [PNG_DIR]     # in the checkout's root, build/portable.tar.xz present
set -euo pipefail

frames=${1:-1000}
png_dir=${2:-}
kit=build/portable
if [[ -f $kit.tar.xz ]]; then # unpacked afresh, so a newer kit is never shadowed by an older one
    rm -rf "$kit"
    python3 -c "import tarfile; tarfile.open('$kit.tar.xz').extractall('build')" # a bare host may lack xz
fi
if [[ -n $png_dir ]]; then
    mkdir -p "$png_dir"
fi
export LD_LIBRARY_PATH=$PWD/$kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} SPEAR_SERVER=$PWD/$kit/bin/spear-server
if ! ldconfig -p | grep -q 'libEGL\.so\.1 '; then # the driver's vendor library without libglvnd
    echo "run_portable: this host has no libEGL.so.1; using the kit's libglvnd ($kit/glvnd)"
    LD_LIBRARY_PATH=$PWD/$kit/glvnd:$LD_LIBRARY_PATH
fi
transports=(--no-inprocess)
python=python3
if [[ -x $kit/python/bin/python3.11 ]]; then
    cp "$kit"/spear/*.so python/spear/ # the in-process module, beside the package
    export PYTHONHOME=$PWD/$kit/python PYTHONPATH=$PWD/$kit/python/site${PYTHONPATH:+:$PYTHONPATH}
    python=$kit/python/bin/python3.11
    transports=()
fi
missing=$(ldd "$kit"/bin/* "$kit"/spear/*.so 2>/dev/null | grep "not found" | sort -u || true)
if [[ -n $missing ]]; then
    echo "run_portable: libraries this host lacks:" >&2
    echo "$missing" >&2
    exit 1
fi

echo "== host: $(uname -m), $("$python" --version), numpy $("$python" -c 'import numpy; print(numpy.__version__)')"
if command -v nvidia-smi >/dev/null; then
    nvidia-smi -L
fi
echo "== the renderer alone: $kit/bin/spear_render_bench --frames $((frames / 5))"
"$kit"/bin/spear_render_bench --frames $((frames / 5)) ${png_dir:+--png "$png_dir"}
echo "== Table 3 beside MuJoCo, $frames frames per cell"
PYTHONPATH=python${PYTHONPATH:+:$PYTHONPATH} "$python" bench/bench_cosim.py ${transports[@]+"${transports[@]}"} \
    --peer-dir "$kit/bin" \
    --frames "$frames" ${png_dir:+--png-dir "$png_dir"}
if [[ ${#transports[@]} -eq 0 ]]; then # the in-process column needs the kit's Python
    echo "== vectorised environments, N = 16, $((frames / 5)) steps, 3 rounds"
    PYTHONPATH=python${PYTHONPATH:+:$PYTHONPATH} "$python" bench/bench_vector.py --counts 16 --rounds 3 \
        --steps $((frames / 5)) --no-dask
fi
