#!/bin/sh
# The RSM techniques against the Monte Carlo reference on the point-light rooms of
# bench/make_light_rooms.py (docs/scenes.md, "Lights: the RSM techniques"): three camera poses per
# room (the file's and two more), pattern seeds 1 and 2, each rsm-* technique's filtered indirect
# light (image-wide mean ratio) and the direct light (mean ratio over lit pixels, share darker than
# half) against the ray-traced ones. One line per frame on stdout:
#   room pose technique seed indirect-ratio direct-line
#   sh bench/rsm_lights_measure.sh build/vplkit out/lights [size] [samples]
set -eu
vplkit=$1 out=$2 size=${3:-128} samples=${4:-256}
here=$(dirname "$0")
mkdir -p "$out"
poses() {
  case $1 in
    den) echo "file -"; echo "back -1.2,1.8,-2.2,1.0,0.6,1.5"; echo "side 1.7,1.2,1.5,-1.5,0.5,-1.0" ;;
    studio) echo "file -"; echo "corner -2.6,2.0,1.7,1.5,0.5,-1.0"; echo "back 0.0,1.4,-1.8,0.5,0.8,1.9" ;;
    workshop) echo "file -"; echo "corner 2.2,1.5,1.9,-1.5,0.6,-1.5"; echo "high -1.0,2.3,-2.0,0.5,0.3,1.5" ;;
  esac
}
for room in den studio workshop; do
  scene=$here/scenes/$room-point.gltf
  poses $room | while read -r pose camera; do
    set -- ; [ "$camera" = - ] || set -- --camera "$camera"
    stem=$out/$room-$pose
    [ -f "$stem-mc-direct.pfm" ] || "$vplkit" reference --method monte-carlo --scene "$scene" "$@" --size "$size" --samples "$samples" \
      --out "$stem-mc.pfm" >/dev/null 2>&1
    for t in rsm-original rsm-radial rsm-alg2 rsm-alg3 rsm-alg6 rsm-alg6-ray rsm-voxel; do
      for seed in 1 2; do
        "$vplkit" render --technique $t --scene "$scene" "$@" --size "$size" --rsm-size 256 --seed $seed --out "$stem-$t-$seed.png" >/dev/null
        echo "$room $pose $t $seed $(python3 "$here/light_sums.py" ratio "$stem-$t-$seed-indirect.pfm" "$stem-mc-indirect.pfm")" \
             "$(python3 "$here/light_sums.py" direct "$stem-$t-$seed-direct.pfm" "$stem-mc-direct.pfm")"
      done
    done
  done
done
