#!/usr/bin/env bash
# The main job on built-in data: builds Drape, makes a synthetic photo whose answer is known
# (seed 1: a t-shirt over pants on a sampled body, A-pose, gray interlock), recovers it with
# `drape eval-synthetic --save` (the same pipeline as `drape recover`) and prints the
# accuracy against the scene's truth. Outputs go to out/demo/ (git-ignored):
#   out/demo/scene/                     the synthetic photo, strokes, joints, truth.json
#   out/demo/recovery/scene_midday/     result.json, report.html, garments, patterns, glb, mask, overlay
#   out/demo/accuracy.json              the figures printed at the end
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" "$here/build"
drape="$here/build/apps/drape/drape"
out="$here/out/demo"
mkdir -p "$out"
"$drape" synth --seed 1 --garment tshirt+pants --pose a --material gray-interlock --edge 6 --samples 4 \
  --out "$out/scene"
"$drape" eval-synthetic "$out/scene" --lighting midday --quality fast --save "$out/recovery" \
  --out "$out/accuracy.json"
echo "demo: open $out/recovery/scene_midday/report.html; figures in $out/accuracy.json"
