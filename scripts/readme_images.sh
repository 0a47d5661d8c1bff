#!/usr/bin/env bash
# Renders the small images the README shows into docs/images/, so that the README renders on a
# fresh clone and on the web. Rerun it after a change that alters what a technique draws, and
# commit the images. Usage: scripts/readme_images.sh (builds first when build/vplkit is missing).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/vplkit ] || scripts/setup.sh
out=docs/images
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# [RSMV]: the Cornell box with Alg. 6, its indirect light and what the visibility removes.
build/vplkit render --technique rsm-alg6 --size 256 --out "$work/cornell-box.png" >/dev/null
cp "$work/cornell-box.png" "$work/cornell-box-indirect.png" "$work/cornell-box-visibility-difference.png" "$out/"
# [LW]: the boxes scene with accurate indirect shadows.
build/vplkit render --technique lightwave-accurate --size 320x180 --out "$work/boxes-lightwave-accurate.png" >/dev/null
cp "$work/boxes-lightwave-accurate.png" "$out/"
# [FG]: the sphere near the green wall, polygon-to-point against point-to-point form factors.
for technique in finalgather-polygon finalgather-point; do
  build/vplkit render --technique "$technique" --size 192 --object-position 0.6,0.7,0 --out "$work/sphere-$technique.png" >/dev/null
  cp "$work/sphere-$technique.png" "$out/"
done
# The viewer with its panel, under a virtual X server when there is no display.
xvfb=()
[ -n "${DISPLAY:-}" ] || xvfb=(xvfb-run -a)
"${xvfb[@]}" build/vplkit view --technique rsm-alg6 --size 512 --frames 3 --screenshot "$work/viewer.png" >/dev/null
cp "$work/viewer.png" "$out/"
ls -l "$out"
