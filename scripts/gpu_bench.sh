#!/usr/bin/env bash
# The papers' timing tables on whatever headless device EGL offers (a GPU first): the RSM sweep at
# [RSMV]'s 512^2 image and RSM (the structure of its Tables 5.1-5.3), the Light Wave sweep at
# [LW]'s 1280x720 (Tables 5.1-5.4 and more), and the final-gathering sweep at [FG]'s 700^2.
# Each writes markdown and CSV that name the renderer and driver (GL_RENDERER, GL_VERSION) and
# the timing method (GL timer queries on a GPU; wall clock around glFinish on a software
# renderer, where these resolutions take minutes: use --quick there).
#
#   scripts/gpu_bench.sh [--quick] [--device N] [--out output/gpu-bench]
set -euo pipefail
cd "$(dirname "$0")/.."
quick=()
out=output/gpu-bench
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=(--quick) ;;
    --device) export VPLKIT_EGL_DEVICE="$2"; shift ;;
    --out) out="$2"; shift ;;
    *) echo "gpu_bench.sh: unknown option '$1' (known: --quick, --device N, --out DIR)" >&2; exit 2 ;;
  esac
  shift
done
[ -x build/bench/vplkit_rsm_sweep ] || scripts/setup.sh
mkdir -p "$out"
export VPLKIT_CONTEXT=egl
build/vplkit info | tee "$out/device.txt"
size=512; width=1280; height=720; final_size=700; repeat=5
if [ ${#quick[@]} -gt 0 ]; then size=128; width=320; height=180; final_size=128; repeat=2; fi
build/bench/vplkit_rsm_sweep --size "$size" --rsm-size "$size" --repeat "$repeat" "${quick[@]}" --out "$out"
build/bench/vplkit_lightwave_sweep --width "$width" --height "$height" --repeat "$repeat" "${quick[@]}" --out "$out"
build/bench/vplkit_finalgather_sweep --size "$final_size" --repeat "$repeat" --out "$out"
echo "gpu_bench.sh: the tables are in $out/ (rsm_sweep.md, lightwave_sweep.md, finalgather_sweep.md and their .csv)"
