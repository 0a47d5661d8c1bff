#!/bin/sh
# The cost of several lights in the RSM and Light Wave techniques (docs/scenes.md, "Lights: the RSM
# techniques"; RSM faces 256^2, Light Wave at its defaults):
# render --stats's "every pass" total (wall clock around glFinish per pass on llvmpipe) for light 0,
# light 1 and both of each two-spot room, and for the room's point light, interleaved over
# `runs` rounds; prints the least of the rounds per configuration and the ratios
# (both / mean of one; point / spot light 0, the same face size).
#   sh bench/rsm_lights_cost.sh build/vplkit out/cost [technique] [runs] [size]
set -eu
vplkit=$1 out=$2 technique=${3:-rsm-radial} runs=${4:-3} size=${5:-128}
here=$(dirname "$0")
mkdir -p "$out"
frame_ms() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["timing"]["every_pass"]["frame_ms"])' "$1"; }
rooms="den studio workshop lw-study"
scene_of() { case $1 in lw-study) echo "$here/scenes/lw-two-spots-study.gltf" ;; *) echo "$here/scenes/$1-two-spots.gltf" ;; esac; }
run=1
while [ $run -le "$runs" ]; do
  for room in $rooms; do
    for L in 0 1 0,1 point; do
      if [ $L = point ]; then
        [ -f "$here/scenes/$room-point.gltf" ] || continue
        set -- --scene "$here/scenes/$room-point.gltf"
      else
        set -- --scene "$(scene_of $room)" --lights $L
      fi
      case $technique in rsm-*) set -- "$@" --rsm-size 256 ;; esac  # Light Wave has no RSM
      "$vplkit" render --technique "$technique" "$@" --size "$size" --stats "$out/$room-$L-$run.json" --out "$out/$room-$L.png" >/dev/null
      echo "$room $L $run $(frame_ms "$out/$room-$L-$run.json")" >> "$out/runs.txt"
    done
  done
  run=$((run + 1))
done
python3 - "$out/runs.txt" <<'PY'
import sys, collections
least = collections.defaultdict(lambda: float("inf"))
for line in open(sys.argv[1]):
    room, lights, run, ms = line.split()
    least[(room, lights)] = min(least[(room, lights)], float(ms))
print("| room | light 0 ms | light 1 ms | both ms | both / mean of one | point ms | point / light 0 |")
print("|---|---:|---:|---:|---:|---:|---:|")
for room in dict.fromkeys(r for r, _ in least):
    a, b, ab = least[(room, "0")], least[(room, "1")], least[(room, "0,1")]
    p = least.get((room, "point"))
    print("| %s | %.1f | %.1f | %.1f | %.2f | %s | %s |" % (room, a, b, ab, ab / ((a + b) / 2), "%.1f" % p if p else "-", "%.2f" % (p / a) if p else "-"))
PY
