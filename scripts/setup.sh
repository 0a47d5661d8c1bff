#!/usr/bin/env bash
# Sets up a Debian 12 machine for vplkit and builds it.
#   scripts/setup.sh             install what is missing, configure and build build/ (Release)
#   scripts/setup.sh --sanitize  the same for build-sanitize/ (-fsanitize=address,undefined)
# Installs only missing Debian packages, running `apt-get update` once and only then; a second
# run installs nothing and says so. Needs root, or sudo without a password prompt.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake g++ make pkg-config libglm-dev doctest-dev libglfw3-dev libegl-dev libegl-mesa0 libosmesa6-dev
          python3-glad xvfb xauth libcli11-dev libspng-dev libbenchmark-dev
          assimp-testmodels libembree-dev libtinygltf-dev libimgui-dev xdotool gnuplot-nox clang libclang-rt-dev)
# node and npm fetch the test meshes; a machine may have them from elsewhere than Debian.
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)

build_dir=build
cmake_options=(-DCMAKE_BUILD_TYPE=Release)
case "${1:-}" in
  "") ;;
  --sanitize) build_dir=build-sanitize
              # Also the build without OSMesa (Mesa >= 25.1 has none): EGL only.
              cmake_options=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DVPLKIT_SANITIZE=ON -DVPLKIT_BUILD_BENCH=OFF -DVPLKIT_WITH_OSMESA=OFF) ;;
  *) echo "setup.sh: unknown option '$1' (known: --sanitize)" >&2; exit 2 ;;
esac

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
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${as_root[@]}" apt-get update -q
  "${as_root[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Test meshes from the npm registry (bunny, teapot: public domain), converted to OBJ once.
if [ -f meshes/bunny.obj ] && [ -f meshes/teapot.obj ]; then
  echo "setup: meshes/bunny.obj and meshes/teapot.obj are there"
else
  if npm install --silent --no-audit --no-fund --no-save --prefix meshes/npm bunny@1.0.1 teapot@1.0.0; then
    node scripts/npm_mesh_to_obj.js meshes/npm/node_modules meshes
  else
    echo "setup: warning: could not fetch the npm packages bunny and teapot; the tests that use them will be skipped" >&2
  fi
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B "$build_dir" "${cmake_options[@]}" >/dev/null
cmake --build "$build_dir" -j "$jobs"
echo "setup: built $build_dir/"
