#!/usr/bin/env bash
# README command 1: set up, build, and render the built-in default scene headless.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/vplkit render --out output/cornell-box.png "$@"
echo "The images are in $(pwd)/output/: cornell-box.png (final), cornell-box-indirect.png,"
echo "cornell-box-visibility-difference.png, and cornell-box-indirect.pfm (the linear indirect irradiance)"
