#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite, every test at least once:
#   1. the Release build (GCC; target vplkit_release_tier): of the fast tier, the CPU-only part
#      (the kernels' tests, `kernel:`) and what the sanitizer build does not build (the
#      benchmarks' tools, `bench:`); then the whole slow tier;
#   2. the sanitizer build (clang, -fsanitize=address,undefined,float-cast-overflow, with
#      libFuzzer coverage), what its fast tier runs (target vplkit_fast_tier), its whole fast tier;
#   3. each fuzz target for FUZZ_SECONDS (default 10) in that same build (scripts/fuzz.sh).
# So the C++ kernels are tested under both compilers, and the GL, command-line and consumer tests
# of the fast tier run once, under the sanitizers, not twice: CI (2 cores) must stay under 15
# minutes (docs/development.md, "CI time").
# Ends with a table of where the time went: wall and CPU seconds per step.
#   scripts/test.sh          everything (what CI runs, .ci/run)
#   scripts/test.sh --fast   the developer's loop: the Release build and its whole fast tier only
# Tests run headless (EGL; the parity tests also under OSMesa in the Release build's slow tier;
# the sanitizer build has no OSMesa); the window tests run under xvfb-run. Parallel tests share
# the cores: each test process gets cores / jobs threads for llvmpipe and Embree.
set -euo pipefail
cd "$(dirname "$0")/.."

fast=no
case "${1:-}" in
  "") ;;
  --fast) fast=yes ;;
  *) echo "test.sh: unknown option '$1' (known: --fast)" >&2; exit 2 ;;
esac
fuzz_seconds=${FUZZ_SECONDS:-10}
if ! [[ "$fuzz_seconds" =~ ^[0-9]+$ ]] || [ "$fuzz_seconds" -lt 1 ] || [ "$fuzz_seconds" -gt 86400 ]; then
  echo "test.sh: FUZZ_SECONDS must be a whole number of seconds in [1, 86400], got '$fuzz_seconds'" >&2
  exit 2
fi
jobs=$(nproc 2>/dev/null || echo 2)
threads_per_test=1

steps=()
times=()
cpu_times=()
started=$SECONDS
# The CPU time (user + system) of this shell's finished children, in clock ticks: fields 16 and 17
# of /proc/<shell>/stat (cutime, cstime), which count every descendant that was waited for. On a
# machine that others share, wall time measures the load; CPU time is what idle cores would take.
clock_ticks=$(getconf CLK_TCK)
children_ticks() {
  local stat
  read -r stat < /proc/$$/stat
  set -- ${stat##*) }  # the fields after the command name, from field 3 on
  echo $(( ${14} + ${15} ))
}
cpu_started=$(children_ticks)
# timed <label> <command...>: runs the step and records its wall and CPU time; a failing step
# prints the table so far and stops the run with its status.
timed() {
  local label=$1 start=$SECONDS cpu_start status=0
  cpu_start=$(children_ticks)
  shift
  echo "== $label"
  "$@" || status=$?
  steps+=("$label")
  times+=($((SECONDS - start)))
  cpu_times+=($(( ($(children_ticks) - cpu_start) / clock_ticks )))
  if [ $status -ne 0 ]; then
    table
    echo "test.sh: '$label' failed (exit $status)" >&2
    exit $status
  fi
}
table() {
  echo
  echo "| step | seconds | CPU seconds |"
  echo "|---|---:|---:|"
  for i in "${!steps[@]}"; do printf '| %s | %d | %d |\n' "${steps[$i]}" "${times[$i]}" "${cpu_times[$i]}"; done
  printf '| **total** | **%d** | **%d** |\n' $((SECONDS - started)) $(( ($(children_ticks) - cpu_started) / clock_ticks ))
  echo "(CPU seconds: user + system of every process of the step; on $jobs idle cores a step takes"
  echo " at least CPU seconds / $jobs)"
}
# tests <build folder> <label> [ctest options...]: ctest of the tests with one label (a tier, or
# `release`: tests/CMakeLists.txt), side by side on every core.
tests() {
  local folder=$1 label=$2
  shift 2
  (cd "$folder" && ctest --output-on-failure -j "$jobs" -L "^$label\$" "$@")
}

# Each test process's threads (LP_NUM_THREADS for llvmpipe, VPLKIT_THREADS for Embree and the
# CPU references): cores / jobs while ctest runs `jobs` of them at once.
threads=(-DVPLKIT_TEST_THREADS=$threads_per_test)
timed "setup: Debian packages, npm meshes" scripts/setup.sh --no-build
# The Release build makes what its runs below need and everything a user gets
# (vplkit_release_tier, CMakeLists.txt), not the fuzz replays' and the installed headers' objects,
# which only the fast tier runs, in the sanitizer build; --fast runs the whole fast tier here.
release_targets=(--target vplkit_release_tier)
[ "$fast" = yes ] && release_targets=()
timed "build: Release (GCC), tests and benchmarks" scripts/setup.sh --no-meshes "${release_targets[@]}" "${threads[@]}"
if [ "$fast" = yes ]; then
  timed "tests: Release, fast tier" tests build fast
  table
  exit 0
fi
# The rest of the fast tier runs in the sanitizer build, below.
timed "tests: Release, fast tier's kernel and benchmark tests" tests build release
timed "tests: Release, slow tier" tests build slow
# The sanitizer build makes what its fast tier runs (tests/CMakeLists.txt, vplkit_fast_tier): not
# the slow tier's executables, which it does not run; scripts/fuzz.sh links the fuzz executables.
timed "build: sanitizer (clang, ASan + UBSan + libFuzzer coverage), the fast tier's executables" \
  scripts/setup.sh --sanitize --no-meshes --target vplkit_fast_tier "${threads[@]}"
timed "tests: sanitizer, fast tier" tests build-sanitize fast
timed "fuzzing: each target for ${fuzz_seconds} s" scripts/fuzz.sh "$fuzz_seconds"
table
