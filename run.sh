#!/usr/bin/env bash
# The main job on the built-in default scene: installs what is missing, builds, and runs it.
#   bash run.sh
source "$(dirname "${BASH_SOURCE[0]}")/scripts/common.sh"
install_dependencies
build
say "run: examples/getting_started.py"
"$PYTHON" "$ROOT/examples/getting_started.py"
say "run: examples/render_image.py (the default scene, every camera modality)"
"$PYTHON" "$ROOT/examples/render_image.py" --out "$ROOT/out/render_image.png"
say "done: the contact sheet of every modality is $ROOT/out/render_image.png"
