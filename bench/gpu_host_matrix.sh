#!/usr/bin/env bash
# The benchmark matrix on a GPU host, from the bundle (scripts/bundle.sh with
# svo-mesh-to-volume and vdb_tool as extra executables) and bundle/meshes.
#   OUT=dir bash bench/gpu_host_matrix.sh SCENE... (default: all four)
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(cornell spheres stanford-bunny.obj icosphere)
python3 bench/matrix.py --svo "$bin/svo" --peer "$bin/svo-mesh-to-volume" --vdb-tool "$bin/vdb_tool" \
  --machine nvidia-h100 --out "$out" --meshes bundle/meshes --scenes "${scenes[@]}" \
  --res 64 128 256 512 1024 2048 --methods hardware shader centroid cpu --repeat 5 2>&1 | tail -40
