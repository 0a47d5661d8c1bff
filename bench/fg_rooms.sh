#!/usr/bin/env bash
# The final-gathering comparison of docs/scenes.md on the rooms of bench/make_fg_rooms.py:
# polygon-to-point, point-to-point and the environment map against the one-bounce Monte Carlo
# reference of the object's indirect light, the bunny near a wall and far from the walls (two
# poses each) in each room, three seeds of the reference. One line per render:
#   room place technique seed rel_rmse rel_bias rel_rmse_corrected
#   bench/fg_rooms.sh [VPLKIT] [OUT_FOLDER] [LIGHTS]     (default: build/vplkit, output/fg-rooms, spot)
# LIGHTS picks the rooms' light variant (bench/make_fg_rooms.py): spot (fg-studio.gltf,
# fg-hall.gltf), point (fg-*-point.gltf: a bulb) or two (fg-*-two.gltf: the spot and the bulb).
set -euo pipefail
cd "$(dirname "$0")/.."
vplkit=${1:-build/vplkit}
out=${2:-output/fg-rooms}
case "${3:-spot}" in
  spot) variant= ;;
  point) variant=-point ;;
  two) variant=-two ;;
  *) echo "fg_rooms.sh: LIGHTS is spot, point or two, not '$3'" >&2; exit 2 ;;
esac
mkdir -p "$out"
# room | place name | object centre | camera eye (it looks at the object)
poses=(
  "fg-studio far-1 0,1.3,0.6 0.9,1.5,1.7"
  "fg-studio far-2 0.3,1.6,-0.5 -0.4,1.5,0.7"
  "fg-studio wall-green -1.42,1.5,-0.6 -0.3,1.6,-0.2"
  "fg-studio wall-back -0.5,1.4,-1.82 -0.2,1.5,-0.6"
  "fg-hall far-1 0,1.2,0.5 1.2,1.5,1.6"
  "fg-hall far-2 2.5,1.5,-1.5 1.5,1.6,-0.3"
  "fg-hall wall-yellow 0,1.5,-2.72 0.4,1.6,-1.5"
  "fg-hall wall-left -3.72,1,1 -2.5,1.3,1.4"
)
for pose in "${poses[@]}"; do
  read -r room place centre eye <<<"$pose"
  for technique in finalgather-polygon finalgather-point envmap; do
    for seed in 1 2 3; do
      log="$out/$room$variant-$place-$technique-$seed.txt"
      "$vplkit" render --technique "$technique" --scene "bench/scenes/$room$variant.gltf" --object meshes/bunny.obj --object-position "$centre" \
        --object-size 0.4 --camera "$eye,$centre" --size 128 --face-size 256 --reference monte-carlo --samples 512 --reference-seed "$seed" \
        --out "$out/$room$variant-$place-$technique-$seed.png" >"$log" 2>&1
      value() { awk -v name="$1" -F'|' '$2 ~ "^ "name" $" { gsub(/ /, "", $3); print $3 }' "$log"; }
      echo "$room$variant $place $technique $seed $(value rel_rmse) $(value rel_bias) $(value rel_rmse_corrected)"
    done
  done
done
