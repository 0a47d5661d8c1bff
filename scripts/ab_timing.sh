#!/usr/bin/env bash
# Times the passes of `vplkit render` at another revision against this checkout's build (build/),
# alternating the two in one session: absolute times on a shared machine are noise, ratios
# measured in one run are not.
#   scripts/ab_timing.sh REV [RUNS] [render options...]
# Builds REV's vplkit in build-ab/<commit> (from a git worktree, build-ab/src-<commit>), runs RUNS
# (default 9) alternating pairs with the same render options, and prints the median of each pass
# of the pass table and the ratio (this checkout / REV). Each binary uses its own shaders.
# Example: scripts/ab_timing.sh HEAD~1 9 --technique rsm-alg6
# Afterwards `git worktree remove build-ab/src-<commit>` removes REV's checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 1 ]; then
  echo "usage: scripts/ab_timing.sh REV [RUNS] [render options...]" >&2
  exit 2
fi
commit=$(git rev-parse --verify --quiet "$1^{commit}") || { echo "ab_timing.sh: '$1' is not a revision of this repository" >&2; exit 2; }
shift
runs=9
if [ $# -gt 0 ] && [[ "$1" =~ ^[0-9]+$ ]]; then runs=$1; shift; fi
if [ "$runs" -lt 1 ] || [ "$runs" -gt 1000 ]; then echo "ab_timing.sh: RUNS must be in [1, 1000], got $runs" >&2; exit 2; fi
[ -x build/vplkit ] || { echo "ab_timing.sh: build/vplkit is missing; run scripts/setup.sh first" >&2; exit 1; }

source_dir=build-ab/src-$commit
build_dir=build-ab/$commit
if [ ! -d "$source_dir" ]; then
  mkdir -p build-ab
  git worktree add --detach "$source_dir" "$commit" >/dev/null
fi
cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DVPLKIT_BUILD_BENCH=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc 2>/dev/null || echo 2)" --target vplkit_cli >/dev/null

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One run: "pass<TAB>ms" for every row of the pass table.
run() {
  "$1" render --shader-dir "$2" --out "$work/image.png" "${@:3}" | awk -F'|' 'NF >= 4 && $3 ~ /^ *[0-9.]+ *$/ {
      gsub(/^ +| +$/, "", $2); gsub(/ /, "", $3); print $2 "\t" $3 }'
}
for ((i = 0; i < runs; ++i)); do
  run "$build_dir/vplkit" "$source_dir/shaders" "$@" | sed 's/^/before\t/' >> "$work/times"
  run build/vplkit shaders "$@" | sed 's/^/after\t/' >> "$work/times"
done
echo "passes of vplkit render $*: median of $runs alternating runs; before = ${commit:0:9}, after = this checkout"
echo "timing: $(build/vplkit render --out "$work/image.png" "$@" | grep '^timing:' | sed 's/^timing: //')"
echo "| pass | before ms | after ms | after / before |"
echo "|---|---:|---:|---:|"
awk -F'\t' '
  function median(list,   n, values, i, j, t) {
    n = split(list, values, " ")
    for (i = 2; i <= n; ++i) for (j = i; j > 1 && values[j - 1] + 0 > values[j] + 0; --j) { t = values[j]; values[j] = values[j - 1]; values[j - 1] = t }
    return n % 2 ? values[(n + 1) / 2] : (values[n / 2] + values[n / 2 + 1]) / 2
  }
  { key = $2; if (!(key in seen)) { seen[key] = 1; order[++passes] = key } times[$1, key] = times[$1, key] " " $3 }
  END {
    for (p = 1; p <= passes; ++p) {
      key = order[p]
      if (!((("before", key) in times) && (("after", key) in times))) continue
      b = median(times["before", key]); a = median(times["after", key])
      ratio = b > 0 ? sprintf("%.3f", a / b) : "-"
      printf "| %s | %.2f | %.2f | %s |\n", key, b, a, ratio
    }
  }' "$work/times"
