#!/usr/bin/env bash
# Fuzzes vplkit's input paths with libFuzzer (clang, with address and undefined-behaviour
# sanitizers): the OBJ/MTL parser, the PFM and PNG decoders, the comparison metrics, the command
# line's option checks and the glTF reader (tests/fuzz/; tinygltf itself is Debian's build, not
# instrumented: crashes in it are caught, its coverage does not guide the fuzzer).
#   scripts/fuzz.sh [seconds] [target...]   each target for `seconds` (default 60); all by default,
#                                           as many side by side as there are cores
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
all_targets=(obj pfm png texture compare cli_options gltf shader_includes)
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
  done < <(find /usr/share/assimp/models/glTF2 \( -name '*.gltf' -o -name '*.glb' \) -size -1024k 2>/dev/null | head -60)
  # Deep seeds near the 1 MiB limit: a chain of 40,000 nodes, extras nested 200,000 deep.
  local triangle='"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],"bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]'
  awk -v triangle="$triangle" 'BEGIN { printf "{\"asset\":{\"version\":\"2.0\"},%s,\"nodes\":[", triangle
    for (i = 1; i < 40000; i++) printf "{\"children\":[%d]},", i
    printf "{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}" }' > "$folder/chain-40000"
  awk -v triangle="$triangle" 'BEGIN { printf "{\"asset\":{\"version\":\"2.0\",\"extras\":"
    for (i = 0; i < 200000; i++) printf "["; for (i = 0; i < 200000; i++) printf "]"
    printf "},%s,\"nodes\":[{\"mesh\":0}]}", triangle }' > "$folder/extras-200000"
}

# The targets run side by side, one per core (each fuzzer is one process on one core, so each still
# gets its whole time); each writes its summary line to $results/<target>, read back in order.
results=$build/fuzz/results
mkdir -p "$results"
fuzz_target() {
  local target=$1 corpus=$build/fuzz/corpus/$1 crashes=$build/fuzz/crashes/$1 log=$build/fuzz/fuzz-$1.log
  mkdir -p "$corpus" "$crashes"
  cp tests/fuzz/corpus/"$target"/* tests/fuzz/regressions/"$target"/* "$corpus"/ 2>/dev/null || true
  [ "$target" = obj ] && seed_obj
  [ "$target" = png ] && seed_png
  [ "$target" = gltf ] && seed_gltf
  echo "== fuzzing $target for ${seconds} s (corpus $corpus)"
  local options=(-max_len=65536)
  [ "$target" = gltf ] && options=(-max_len=1048576 -dict=tests/fuzz/gltf.dict)
  local result=0
  "$build/tests/fuzz/vplkit_fuzz_$target" "$corpus" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 -rss_limit_mb=2048 \
    "${options[@]}" -artifact_prefix="$crashes/" >"$log" 2>&1 || result=$?
  local executions rate
  executions=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log")
  rate=$(awk '/stat::average_exec_per_sec/ { print $2 }' "$log")
  if [ "$result" -eq 0 ]; then
    printf '%-16s %12s executions %8s/s  no crash\n' "$target" "${executions:-?}" "${rate:-?}" > "$results/$target"
  else
    printf '%-16s %12s executions %8s/s  FAILED (rc %d): see %s, inputs in %s\n' "$target" "${executions:-?}" "${rate:-?}" "$result" "$log" \
      "$crashes" > "$results/$target"
    grep -E "ERROR|SUMMARY|fuzz_" "$log" | head -5 >&2 || true
  fi
}
cores=$(nproc 2>/dev/null || echo 2)
running=0
for target in "${targets[@]}"; do
  rm -f "$results/$target"
  fuzz_target "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$cores" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true

status=0
echo "== fuzz summary (${seconds} s per target)"
for target in "${targets[@]}"; do
  if [ -s "$results/$target" ]; then
    cat "$results/$target"
    grep -q "no crash" "$results/$target" || status=1
  else
    printf '%-16s did not finish: see %s\n' "$target" "$build/fuzz/fuzz-$target.log"
    status=1
  fi
done
exit $status
