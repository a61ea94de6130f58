#!/usr/bin/env bash
# The main job on built-in data: builds Drape, then makes a body from default measurements,
# poses it, writes the rigged glb + OBJ, and prints the measurements taken on the mesh.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" "$here/build"
out="$here/out"
mkdir -p "$out"
"$here/build/apps/drape/drape" body --params "$here/examples/body_params.json" \
  --pose "$here/examples/pose_walking.json" --out "$out/body.glb" --obj "$out/body.obj" --measure \
  | tee "$out/measurements.json"
echo "demo: wrote $out/body.glb, $out/body.obj and $out/measurements.json"
