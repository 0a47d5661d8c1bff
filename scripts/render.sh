#!/usr/bin/env bash
# README command 1: set up, build the vplkit executable (and only what it needs: no tests,
# fuzzers or benchmarks), and render the built-in default scene headless.
#   scripts/render.sh [render options...]   e.g. --technique lightwave-accurate --scene boxes
# One line per step; the build log is build/setup.log, which an error names.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --no-meshes --target vplkit_cli
echo "render: build/vplkit render --out output/cornell-box.png $*"
log=build/render.log
if ! build/vplkit render --out output/cornell-box.png "$@" >"$log" 2>&1; then
  cat "$log" >&2
  echo "render: failed (above: its output, also in $PWD/$log)" >&2
  exit 1
fi
echo "render: the pass times are in $PWD/$log"
echo "The images are in $PWD/output/:"
sed -n 's|^wrote |  |p' "$log"
