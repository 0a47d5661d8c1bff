#!/usr/bin/env bash
# Sets up a Debian 12 machine for vplkit and builds it.
#   scripts/setup.sh [--sanitize] [--target T]... [--no-meshes] [--no-build] [-DVAR=VALUE]...
#     (no option)   install what is missing, fetch the test meshes, configure and build build/
#                   (Release): the library, the tools, the tests and the benchmarks
#     --sanitize    the same for build-sanitize/: clang with -fsanitize=address,undefined,
#                   float-cast-overflow, and coverage instrumentation for libFuzzer, so that the
#                   fuzz targets (scripts/fuzz.sh) build in the same tree as the tests they share
#                   their code with; builds the tests, not the benchmarks
#     --target T    build only target T (and what it needs); repeatable
#     --no-meshes   do not fetch the npm test meshes (nothing but the tests reads them)
#     --no-build    install and fetch only
#     -DVAR=VALUE   passed to cmake's configure step (e.g. -DVPLKIT_TEST_THREADS=1)
# Installs only missing Debian packages, running `apt-get update` once and only then; a second
# run installs nothing and says so. Needs root, or sudo without a password prompt.
# Prints one line per step; the configure and build output goes to <build folder>/setup.log, which
# an error names (with its last lines). Uses Ninja, and ccache when it is installed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake ninja-build g++ make pkg-config libglm-dev doctest-dev libglfw3-dev libegl-dev libegl-mesa0 libosmesa6-dev
          python3-glad xvfb xauth libcli11-dev libspng-dev libturbojpeg0-dev libbenchmark-dev
          assimp-testmodels libembree-dev libtinygltf-dev libimgui-dev xdotool gnuplot-nox clang libclang-rt-dev
          glslang-tools spirv-tools libglu1-mesa-dev libdraco-dev nlohmann-json3-dev glslang-dev libvulkan-dev mesa-vulkan-drivers)

build_dir=build
cmake_options=(-DCMAKE_BUILD_TYPE=Release)
targets=()
meshes=yes
build=yes
cache_options=()
while [ $# -gt 0 ]; do
  case "$1" in
    --sanitize)
      build_dir=build-sanitize
      # Also the build without OSMesa (Mesa >= 25.1 has none): EGL only. -gline-tables-only instead
      # of RelWithDebInfo's -g: the sanitizers' reports need functions, files and lines (inlined
      # frames included), which line tables hold; full debug info cost a quarter more compile time
      # per file (tests/kernels/test_rsm_gather.cpp: 15.6 s of one core against 11.5 s) and
      # larger objects to link.
      cmake_options=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
                     "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG"
                     "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG"
                     -DVPLKIT_SANITIZE=ON -DVPLKIT_BUILD_BENCH=OFF -DVPLKIT_WITH_OSMESA=OFF) ;;
    --target)
      [ $# -ge 2 ] || { echo "setup.sh: --target needs a target name" >&2; exit 2; }
      targets+=(--target "$2"); shift ;;
    --no-meshes) meshes=no ;;
    --no-build) build=no ;;
    -D?*=*) cache_options+=("$1") ;;
    *) echo "setup.sh: unknown option '$1' (known: --sanitize, --target T, --no-meshes, --no-build, -DVAR=VALUE)" >&2; exit 2 ;;
  esac
  shift
done
# node and npm fetch the test meshes; a machine may have them from elsewhere than Debian.
if [ "$meshes" = yes ]; then
  command -v node >/dev/null 2>&1 || packages+=(nodejs)
  command -v npm >/dev/null 2>&1 || packages+=(npm)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} Debian packages are installed; nothing to install"
else
  if [ "$(id -u)" -eq 0 ]; then
    as_root=()
  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    as_root=(sudo)
  else
    echo "setup: these Debian packages are missing: ${missing[*]}" >&2
    echo "setup: installing them needs root or password-less sudo; run as root, or install them with" >&2
    echo "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt_log=$(mktemp)
  if ! { "${as_root[@]}" apt-get update -q && "${as_root[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"; } >"$apt_log" 2>&1; then
    tail -n 20 "$apt_log" >&2
    echo "setup: apt-get failed (above: the last lines of its output)" >&2
    exit 1
  fi
  rm -f "$apt_log"
fi

# Test meshes from the npm registry (bunny, teapot: public domain), converted to OBJ once.
if [ "$meshes" = no ]; then
  :
elif [ -f meshes/bunny.obj ] && [ -f meshes/teapot.obj ]; then
  echo "setup: meshes/bunny.obj and meshes/teapot.obj are there"
else
  if npm install --silent --no-audit --no-fund --no-save --prefix meshes/npm bunny@1.0.1 teapot@1.0.0 >/dev/null 2>&1; then
    node scripts/npm_mesh_to_obj.js meshes/npm/node_modules meshes
    echo "setup: fetched the npm meshes bunny and teapot into meshes/"
  else
    echo "setup: warning: could not fetch the npm packages bunny and teapot; the tests that use them will be skipped" >&2
  fi
fi

[ "$build" = yes ] || exit 0

# Ninja for a new build folder (a folder configured before keeps its generator); ccache when the
# machine has it, with paths taken relative to the checkout so that clones share the cache.
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake_options+=(-G Ninja)
fi
if command -v ccache >/dev/null 2>&1; then
  cmake_options+=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # pch_defines, time_macros: what ccache needs to cache the files compiled with the precompiled
  # CLI11 header (it declines them otherwise).
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1 CCACHE_SLOPPINESS=pch_defines,time_macros
fi
mkdir -p "$build_dir"
log="$build_dir/setup.log"
: > "$log"
fail() {
  tail -n 25 "$log" >&2
  echo "setup: $1 failed; the whole log is $PWD/$log (above: its last lines)" >&2
  exit 1
}
jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS
cmake -S . -B "$build_dir" "${cmake_options[@]}" "${cache_options[@]}" >>"$log" 2>&1 || fail "configuring $build_dir/"
what="everything"
[ ${#targets[@]} -eq 0 ] || what=$(printf '%s ' "${targets[@]}" | sed 's/--target //g; s/ $//')
echo "setup: building $what in $build_dir/ (log: $log)"
cmake --build "$build_dir" -j "$jobs" "${targets[@]}" >>"$log" 2>&1 || fail "building $build_dir/"
echo "setup: built $build_dir/ in $((SECONDS - start)) s"
