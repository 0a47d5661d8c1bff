#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite twice: the Release build, then
# the -fsanitize=address,undefined build; then each fuzz target for 20 s (clang's libFuzzer).
# Tests run headless (EGL; the parity tests also under OSMesa in the Release build, and the
# sanitizer build has no OSMesa); the window tests run under xvfb-run.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

scripts/setup.sh
echo "== tests: Release build"
(cd build && ctest --output-on-failure -j "$jobs")

scripts/setup.sh --sanitize
echo "== tests: sanitizer build (address, undefined)"
(cd build-sanitize && ctest --output-on-failure -j "$jobs")

echo "== fuzzing: each target for 20 s"
scripts/fuzz.sh 20
