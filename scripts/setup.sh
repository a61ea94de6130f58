#!/usr/bin/env bash
# Installs the Debian 12 packages Drape builds with (only those missing; idempotent) and
# builds it. Usage: scripts/setup.sh [BUILD_DIR] [extra cmake args...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
shift || true

packages=(
  build-essential cmake pkg-config
  libeigen3-dev          # geometry currency
  libceres-dev           # body fitting (brings SuiteSparse, glog, gflags)
  libopenblas0-serial    # BLAS/LAPACK behind CHOLMOD (serial: no threads competing with TBB)
  libhdf5-dev            # body model files
  libassimp-dev          # glTF / OBJ export and import
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev   # images (apps)
  nlohmann-json3-dev     # JSON in the app layer
  libcli11-dev           # command line
  libtbb-dev             # parallel loops (cloth assembly)
  libpagmo-dev           # particle swarm search of the garment sizing (recovery)
  libcgal-dev            # pattern triangulation (garments)
  libembree-dev          # ray-traced renders (app layer)
  catch2                 # tests
  assimp-testmodels      # BVH motion captures for the animation tests (skipped when absent)
  clang libfuzzer-14-dev libclang-rt-14-dev   # fuzz harnesses (scripts/fuzz.sh; docs/hardening.md)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The Khronos glTF-Validator, run by the .glb tests (skipped when absent): npm package, global.
if command -v npm >/dev/null && ! NODE_PATH="$(npm root -g)" node -e "require('gltf-validator')" 2>/dev/null; then
  echo "setup: installing the npm package gltf-validator"
  npm install -g --silent gltf-validator || echo "setup: gltf-validator not installed (the glb validation tests will skip)"
fi

cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
