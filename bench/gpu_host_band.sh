#!/usr/bin/env bash
# Level sets on a GPU host: error against GPU time over the band width
# (bench/band_error.py), for a closed mesh (elephant, parity signs) and an open
# one (the bunny, winding signs). Run from the repository root with the bundle
# and meshes carried (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
python3 bench/band_error.py --svo "$bin/svo" --res 256 512 1024 --band 1 2 3 5 8 --repeat 3 --md "$out/band.md" \
  bundle/meshes/elephant.off bundle/meshes/stanford-bunny.obj 2>/dev/null | tee "$out/band.txt"
