#!/usr/bin/env bash
# The papers' timing tables on whatever headless device EGL offers (a GPU first), run by
# `vplkit sweep` from their specifications in bench/: [RSMV]'s Tables 5.1-5.3 at its 512^2
# image and RSM, [LW]'s Tables 5.1-5.15 at its 1280x720, [FG]'s variants at its 700^2. Each
# sweep writes sweep.md and sweep.csv naming the renderer and driver (GL_RENDERER, GL_VERSION)
# and the timing method (GL timer queries on a GPU; wall clock around glFinish on a software
# renderer, where these resolutions take long: use --quick there).
#
#   scripts/gpu_bench.sh [--quick] [--device N] [--out output/gpu-bench]
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
out=output/gpu-bench
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --device) export VPLKIT_EGL_DEVICE="$2"; shift ;;
    --out) out="$2"; shift ;;
    *) echo "gpu_bench.sh: unknown option '$1' (known: --quick, --device N, --out DIR)" >&2; exit 2 ;;
  esac
  shift
done
[ -x build/vplkit ] || scripts/setup.sh
mkdir -p "$out"
export VPLKIT_CONTEXT=egl
build/vplkit info | tee "$out/device.txt"
if [ "$quick" = 1 ]; then
  rsm=(--size 128 --rsm-size 128 --repeat 5)
  final=(--size 128 --repeat 5)
else
  rsm=()
  final=(--size 700)
fi
build/vplkit sweep --spec bench/rsm-tables.sweep "${rsm[@]}" --out "$out/rsm-tables"
# Light Wave: the specification runs a quarter of the thesis's 1280x720; at full size each
# section's own sizes are replaced too.
sections=("5.1-5.5 ray angle" "5.2-5.6 VPLs per ray" "5.3-5.7 resolution" "5.4-5.8 indirect shadow maps" "5.8 shadow variant"
          "5.9 alternatives" "5.11-5.12 integrated steps" "5.13 integrated steps, 185 VPLs" "5.14-5.15 scene complexity")
for section in "${sections[@]}"; do
  args=(--repeat 5)
  if [ "$quick" = 0 ]; then
    args=(--size 1280x720 --interleave 2)
    case "$section" in
      "5.3-5.7 resolution") args+=(--vary size=1280x720,1120x630,960x540,800x450,640x360,1440x810) ;;
      "5.11-5.12 integrated steps") args+=(--vary size=1280x720,640x360) ;;
    esac
  fi
  build/vplkit sweep --spec bench/lightwave-tables.sweep --section "$section" "${args[@]}" --out "$out/lightwave-tables"
done
build/vplkit sweep --spec bench/finalgather-tables.sweep "${final[@]}" --out "$out/finalgather-tables"
echo "gpu_bench.sh: the tables are in $out/ (a folder per section, each with sweep.md, sweep.csv and plots)"
