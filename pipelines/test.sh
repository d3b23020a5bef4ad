#!/usr/bin/env bash
# Every test: install what is missing, build, run the Catch2 suite and the
# whole-pipeline checks under ctest (its last line is the summary).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
hexdyn_install
hexdyn_build
cd "$HEXDYN_BUILD"
ctest --output-on-failure -j"$(nproc)" --timeout 600
