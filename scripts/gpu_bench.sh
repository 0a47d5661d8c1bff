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
# Issue 42's ratios (docs/performance.md), each from one interleaved run: the post filter's share of
# the frame (atrium 512^2 thesis configuration, Cornell box 256^2) and polygon / point final
# gathering, whole frame (sphere 512^2, M = 4).
column() {  # column NAME FILE ROW: the value of column NAME in data row ROW (1-based) of a sweep.csv
  awk -F, -v name="$1" -v row="$3" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i } NR == row + 1 { print $c }' "$2"
}
build/vplkit sweep --technique rsm-alg6 --scene atrium --size 512 --rsm-size 512 --preset thesis --vary seed=0 --out "$out/ratios/post-atrium"
build/vplkit sweep --technique rsm-alg6 --scene cornell-box --size 256 --rsm-size 256 --vary seed=0 --out "$out/ratios/post-cornell"
build/vplkit sweep --technique finalgather-polygon --size 512 --vary technique=finalgather-polygon,finalgather-point --out "$out/ratios/final-gather"
{
  for scene in atrium cornell; do
    csv="$out/ratios/post-$scene/sweep.csv"
    awk -v post="$(column post_processing_ms "$csv" 1)" -v frame="$(column frame_ms "$csv" 1)" -v scene="$scene" \
      'BEGIN { printf "post processing share of the frame, %s: %.3f (goal <= 0.15)\n", scene, post / frame }'
  done
  csv="$out/ratios/final-gather/sweep.csv"
  awk -v polygon="$(column frame_ms "$csv" 1)" -v point="$(column frame_ms "$csv" 2)" \
    'BEGIN { printf "final gathering polygon / point, whole frame: %.3f (goal <= 1.5)\n", polygon / point }'
} | tee "$out/ratios.txt"
echo "gpu_bench.sh: the tables are in $out/ (a folder per section, each with sweep.md, sweep.csv and plots), issue 42's ratios in $out/ratios.txt"
