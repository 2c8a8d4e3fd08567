#!/usr/bin/env bash
# Runs the renderer and Table 3 benchmarks from the portable kit (bench/portable_kit.sh) on a host without
# the build's Python: the renderer alone (spear_render_bench, per-pass GL timer queries), then Table 3 over
# RPC beside MuJoCo, driven by the host's python3 (numpy and msgpack needed) from this checkout.
#
#   bash bench/run_portable.sh [FRAMES] [PNG_DIR]     # in the checkout's root, build/portable.tar.xz present
set -euo pipefail

frames=${1:-1000}
png_dir=${2:-}
kit=build/portable
python=${PYTHON:-python3}
if [[ ! -d $kit ]]; then  # Python's tarfile, as a bare host may have no xz
    "$python" -c "import tarfile; tarfile.open('$kit.tar.xz').extractall('build')"
fi
export LD_LIBRARY_PATH=$PWD/$kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} SPEAR_SERVER=$PWD/$kit/bin/spear-server
missing=$(ldd "$kit"/bin/* | grep "not found" | sort -u || true)
if [[ -n $missing ]]; then
    echo "run_portable: libraries this host lacks:" >&2
    echo "$missing" >&2
    exit 1
fi

echo "== host: $(uname -m), $("$python" --version), numpy $("$python" -c 'import numpy; print(numpy.__version__)')"
command -v nvidia-smi >/dev/null && nvidia-smi -L
echo "== the renderer alone: $kit/bin/spear_render_bench --frames $((frames / 5))"
"$kit"/bin/spear_render_bench --frames $((frames / 5)) ${png_dir:+--png "$png_dir"}
echo "== Table 3 over RPC beside MuJoCo, $frames frames per cell"
PYTHONPATH=python${PYTHONPATH:+:$PYTHONPATH} "$python" bench/bench_cosim.py --no-inprocess --peer-dir "$kit/bin" --frames "$frames" \
    ${png_dir:+--png-dir "$png_dir"}
