#!/usr/bin/env bash
# Runs `vplkit render` (32x32, RSM 64^2) on every glTF, GLB and OBJ file of Debian's
# assimp-testmodels, side by side on every core, and classifies each outcome:
#   renders    exit 0 (the features it has that vplkit does not read, from the notes)
#   refused    exit 1 or 2 with a "vplkit: error: FILE: ..." message (the message, without FILE),
#              by what the message says: an unsupported format (glTF 1.0), nothing to draw (no
#              triangles or faces: points, lines, no scene) or invalid input (anything else)
#   CRASH      anything else: a signal, another exit code, a sanitizer report, no message, or
#              more than 300 s
# and prints the table (file, outcome, reason) as Markdown.
#   scripts/corpus.sh VPLKIT [--check DOC | --update DOC]
#     --check DOC    exit 1 unless no file crashed and DOC's table (between the lines
#                    "<!-- corpus table -->" and "<!-- end of corpus table -->") is this one;
#                    the slow-tier test `corpus: assimp-testmodels` runs this on docs/hardening.md
#     --update DOC   write the table into DOC between those lines
# VPLKIT_ASSIMP_MODELS changes the folder (default /usr/share/assimp/models); without it the
# script says so and exits 77 (ctest: skipped).
set -euo pipefail
vplkit=${1:-}
mode=${2:-}
doc=${3:-}
if [ -z "$vplkit" ] || [ ! -x "$vplkit" ]; then
  echo "corpus.sh: usage: scripts/corpus.sh VPLKIT [--check DOC | --update DOC], VPLKIT the vplkit executable (got '$vplkit')" >&2
  exit 2
fi
case "$mode" in
  "") ;;
  --check|--update)
    if [ -z "$doc" ] || [ ! -f "$doc" ]; then
      echo "corpus.sh: $mode needs an existing document (got '$doc')" >&2
      exit 2
    fi ;;
  *) echo "corpus.sh: unknown option '$mode' (known: --check DOC, --update DOC)" >&2; exit 2 ;;
esac
models=${VPLKIT_ASSIMP_MODELS:-/usr/share/assimp/models}
if [ ! -d "$models" ]; then
  echo "corpus.sh: $models is missing (scripts/setup.sh installs assimp-testmodels)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One file ("<n><TAB><path>"): its exit code and output into $work/<n>.{code,out}.
run_one() {
  local work=$1 vplkit=$2 n=${3%%$'\t'*} file=${3#*$'\t'}
  mkdir -p "$work/$n"
  set +e
  timeout 300 "$vplkit" render --scene "$file" --size 32 --rsm-size 64 --out "$work/$n/image.png" >"$work/$n.out" 2>&1
  echo $? >"$work/$n.code"
  rm -rf "${work:?}/$n"
}
export -f run_one
start=$(date +%s)
find "$models" -type f \( -iname '*.gltf' -o -iname '*.glb' -o -iname '*.obj' \) | LC_ALL=C sort >"$work/files"
total=$(wc -l <"$work/files")
awk '{ print NR "\t" $0 }' "$work/files" |
  xargs -d '\n' -P "$(nproc)" -n 1 bash -c 'run_one "$@"' _ "$work" "$vplkit" ||
  xargs_failed=1
seconds=$(( $(date +%s) - start ))

# Markdown cells: | and newlines escaped, cut to 300 characters.
cell() { printf '%s' "$1" | tr '\n' ' ' | sed 's/|/\\|/g' | cut -c1-300; }
table=$work/table
crashes=0
renders=0
refused=0
{
  echo "| file | outcome | reason |"
  echo "|---|---|---|"
  n=0
  while IFS= read -r file; do
    n=$((n + 1))
    code=$(cat "$work/$n.code" 2>/dev/null || echo missing)
    out=$(cat "$work/$n.out" 2>/dev/null || true)
    name=${file#"$models"/}
    if grep -qE 'Sanitizer|runtime error:' <<<"$out"; then
      outcome=CRASH; reason="sanitizer report (exit $code)"
    elif [ "$code" = 0 ]; then
      outcome=renders
      # The features not read, from the notes ("...: FEATURE not read (consequence)").
      reason=$(sed -n 's/^note: .*: \(.*\) not read (.*$/\1/p' <<<"$out" | LC_ALL=C sort -u | paste -sd ';' | sed 's/;/; /g')
      [ -n "$reason" ] && reason="not read: $reason"
    elif { [ "$code" = 1 ] || [ "$code" = 2 ]; } && grep -q '^vplkit: error: ' <<<"$out"; then
      message=$(grep -m1 '^vplkit: error: ' <<<"$out" | sed 's/^vplkit: error: //')
      reason=${message//"$file: "/}
      reason=${reason//"$file"/FILE}
      reason=${reason//"$models/"/}
      # What kind of refusal, from the message.
      if grep -q 'glTF 1\.0' <<<"$reason"; then
        outcome="refused: unsupported format"
      elif grep -qE '^no triangles in its scene|^no faces' <<<"$reason"; then
        outcome="refused: nothing to draw"
      else
        outcome="refused: invalid input"
      fi
    else
      outcome=CRASH; reason="exit $code, $(tail -n 1 <<<"$out")"
    fi
    case $outcome in
      CRASH) crashes=$((crashes + 1)) ;;
      renders) renders=$((renders + 1)) ;;
      refused*) refused=$((refused + 1)) ;;
    esac
    echo "| \`$(cell "$name")\` | $outcome | $(cell "$reason") |"
  done <"$work/files"
} >"$table"
cat "$table"
echo
summary="$total files: $renders render, $refused refused with a message, $crashes crashed ($seconds s on $(nproc) cores)"
echo "corpus.sh: $summary"
[ -z "${xargs_failed:-}" ] || { echo "corpus.sh: running the files failed" >&2; exit 1; }

# The document's table: the lines between the markers.
begin='<!-- corpus table -->'
end='<!-- end of corpus table -->'
case "$mode" in
  --update)
    awk -v begin="$begin" -v end="$end" -v table="$table" '
      $0 == begin { print; while ((getline line < table) > 0) print line; skip = 1; next }
      $0 == end { skip = 0 }
      !skip { print }' "$doc" >"$work/doc"
    grep -qxF "$begin" "$doc" || { echo "corpus.sh: $doc has no line '$begin'" >&2; exit 1; }
    cat "$work/doc" >"$doc"
    echo "corpus.sh: wrote the table into $doc" ;;
  --check)
    awk -v begin="$begin" -v end="$end" '$0 == end { inside = 0 } inside { print } $0 == begin { inside = 1 }' "$doc" >"$work/documented"
    if ! diff -u "$work/documented" "$table" >"$work/diff"; then
      cat "$work/diff"
      echo "corpus.sh: the table in $doc is not what vplkit does now (above: documented -> now); scripts/corpus.sh VPLKIT --update $doc rewrites it" >&2
      exit 1
    fi
    echo "corpus.sh: the table in $doc is what vplkit does" ;;
esac
if [ "$crashes" -gt 0 ]; then
  echo "corpus.sh: $crashes file(s) crashed vplkit" >&2
  exit 1
fi
