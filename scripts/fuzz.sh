#!/usr/bin/env bash
# Fuzzes vplkit's input paths with libFuzzer (clang, with address and undefined-behaviour
# sanitizers): the OBJ/MTL parser, the PFM and PNG decoders, the comparison metrics, the command
# line's option checks and the glTF reader (tests/fuzz/; tinygltf itself is Debian's build, not
# instrumented: crashes in it are caught, its coverage does not guide the fuzzer).
#   scripts/fuzz.sh [seconds] [target...]   each target for `seconds` (default 60); all by default
# The fuzz targets build in the sanitizer build, build-sanitize/ (scripts/setup.sh --sanitize:
# clang, address and undefined-behaviour sanitizers, libFuzzer coverage), the tree whose tests
# the sanitizer pass runs. The working corpora live in build-sanitize/fuzz/corpus/<target>,
# seeded from tests/fuzz/corpus, the regression inputs, Debian's assimp test models and the npm
# meshes. A crash leaves its input in build-sanitize/fuzz/crashes/<target>/ and makes the script
# exit 1; copy the input to tests/fuzz/regressions/<target>/ with the fix, and the normal test
# suite replays it from then on.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ] || [ "$seconds" -gt 86400 ]; then
  echo "fuzz.sh: the time per target must be a whole number of seconds in [1, 86400], got '$seconds'" >&2
  exit 2
fi
shift || true
all_targets=(obj pfm png texture compare cli_options gltf)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${all_targets[@]}")
for target in "${targets[@]}"; do
  if [[ ! " ${all_targets[*]} " =~ " $target " ]]; then
    echo "fuzz.sh: unknown target '$target' (known: ${all_targets[*]})" >&2
    exit 2
  fi
done
# Only the fuzz targets asked for (and what they link); setup.sh installs clang and its runtime.
fuzz_binaries=()
for target in "${targets[@]}"; do fuzz_binaries+=(--target "vplkit_fuzz_$target"); done
scripts/setup.sh --sanitize --no-meshes "${fuzz_binaries[@]}"
build=build-sanitize

# Seeds. OBJ inputs are the OBJ text, then a NUL byte and the text of its material library.
seed_obj() {
  local folder=$build/fuzz/corpus/obj models=/usr/share/assimp/models/OBJ
  if [ -d "$models" ]; then
    for obj in "$models"/*.obj; do
      [ "$(stat -c %s "$obj")" -le 65536 ] || continue
      local name seed library
      name=$(basename "$obj" .obj)
      seed="$folder/assimp-$name"
      cp "$obj" "$seed"
      library=$(awk '$1 == "mtllib" { print $2; exit }' "$obj" | tr -d '\r')
      if [ -n "$library" ] && [ -f "$models/$library" ]; then
        printf '\0' >> "$seed"
        cat "$models/$library" >> "$seed"
      fi
    done
  fi
  # The npm meshes are megabytes; their first 40 faces, renumbered, make small seeds.
  for mesh in meshes/bunny.obj meshes/teapot.obj; do
    [ -f "$mesh" ] || continue
    awk '$1 == "v" { v[++n] = $0 }
         $1 == "f" && faces < 40 { faces++; line = "f"
           for (i = 2; i <= NF; i++) { split($i, p, "/"); k = p[1] < 0 ? n + 1 + p[1] : p[1]
             if (!(k in used)) { used[k] = ++m; order[m] = k }
             line = line " " used[k] }
           f[faces] = line }
         END { for (i = 1; i <= m; i++) print v[order[i]]; for (i = 1; i <= faces; i++) print f[i] }' \
      "$mesh" > "$folder/npm-$(basename "$mesh" .obj)"
  done
}
seed_png() {
  local folder=$build/fuzz/corpus/png
  while IFS= read -r png; do
    cp "$png" "$folder/assimp-$(echo "$png" | tr '/' '_')"
  done < <(find /usr/share/assimp/models -name '*.png' -size -16k 2>/dev/null | head -20)
}
seed_gltf() {
  local folder=$build/fuzz/corpus/gltf
  while IFS= read -r file; do
    cp "$file" "$folder/assimp-$(echo "$file" | tr '/' '_')"
  done < <(find /usr/share/assimp/models/glTF2 \( -name '*.gltf' -o -name '*.glb' \) -size -64k 2>/dev/null | head -40)
}

status=0
summary=()
for target in "${targets[@]}"; do
  corpus=$build/fuzz/corpus/$target crashes=$build/fuzz/crashes/$target
  mkdir -p "$corpus" "$crashes"
  cp tests/fuzz/corpus/"$target"/* tests/fuzz/regressions/"$target"/* "$corpus"/ 2>/dev/null || true
  [ "$target" = obj ] && seed_obj
  [ "$target" = png ] && seed_png
  [ "$target" = gltf ] && seed_gltf
  log=$build/fuzz/fuzz-$target.log
  echo "== fuzzing $target for ${seconds} s (corpus $corpus)"
  set +e
  "$build/tests/fuzz/vplkit_fuzz_$target" "$corpus" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -artifact_prefix="$crashes/" >"$log" 2>&1
  result=$?
  set -e
  executions=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log")
  if [ "$result" -eq 0 ]; then
    summary+=("$(printf '%-12s %12s executions  no crash' "$target" "${executions:-?}")")
  else
    status=1
    summary+=("$(printf '%-12s %12s executions  FAILED (rc %d): see %s, inputs in %s' "$target" "${executions:-?}" "$result" "$log" "$crashes")")
    grep -E "ERROR|SUMMARY|fuzz_" "$log" | head -5 >&2 || true
  fi
done
echo "== fuzz summary (${seconds} s per target)"
printf '%s\n' "${summary[@]}"
exit $status
