#!/usr/bin/env bash
# End to end on a GPU host, mesh file to .vdb, in one run with the peers
# (bench/end_to_end.py): svo as new processes, vdb_tool -mesh2ls on every
# core, and cuda_voxelizer built from its sources here. Needs the bundle
# (scripts/bundle.sh with /usr/bin/vdb_tool), bundle/meshes and bundle/peers
# (../shared/peers).
#   OUT=dir [SCENES="..."] [RES="64 ... 2048"] [RUNS=3] bash bench/gpu_host_end_to_end.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
cv=()
if [ -d bundle/peers ]; then
  bash bundle/peers/build-cuda-voxelizer.sh "$work/cvb" >"$out/cuda_voxelizer_build.txt" 2>&1 \
    && cv=(--cuda-voxelizer "$work/cvb/cuda_voxelizer")
fi
# The first svo process on a fresh machine compiles its programs; later ones load them.
"$bin/svo" voxelize -v bundle/meshes/stanford-bunny.obj -r 64 -o "$work/warm.vdb" > "$out/first_process.txt" 2>&1
scenes=(${SCENES:-bundle/meshes/stanford-bunny.obj icosphere bundle/meshes/spot.obj bundle/meshes/ogre.obj})
python3 bench/end_to_end.py --svo "$bin/svo" --vdb-tool "$bin/vdb_tool" "${cv[@]}" --machine nvidia-h100 \
  --out "$out" --scenes "${scenes[@]}" --icosphere-off --res ${RES:-64 128 256 512 1024 2048} --runs "${RUNS:-3}" 2>&1 \
  | tee "$out/end_to_end_log.txt"
