#!/usr/bin/env bash
# The generator on the engine's reflected headers, with the arguments the build gives it
# (core/engine/CMakeLists.txt: the header list, Eigen's include folder, the blueprint folder).
#   bash scripts/codegen.sh generate     # rewrite generated/ (what the build does when a header changes)
#   bash scripts/codegen.sh check        # non-zero when the committed generated/ is stale
#   bash scripts/codegen.sh dump-ir      # the IR as JSON
#   bash scripts/codegen.sh watch        # generate on every save of a reflected header or blueprint (the
#                                        # stubs an editor reads follow at once; the build does the C++)
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
engine_codegen "${1:?usage: bash scripts/codegen.sh generate|check|dump-ir|watch}"
