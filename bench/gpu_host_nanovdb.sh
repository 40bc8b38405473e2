#!/usr/bin/env bash
# svo's NanoVDB grids against NanoVDB's own CUDA MeshToGrid on the GPU host,
# in one run (bench/nanovdb_peers.py, issue 45): the harness
# bench/nanovdb_mesh_to_grid.cu is built here with nvcc from bundle/peers/nanovdb
# (../shared/peers/nanovdb: CUDA and headers only), then both tools convert the
# same OBJ files at the same voxel size. Needs the bundle (scripts/bundle.sh),
# bundle/meshes and bundle/peers.
#   OUT=dir [RES="256 ... 4096"] [RUNS=5] [ARCH=sm_90] [MESHES="bunny icosphere ..."] [M2G=path] bash bench/gpu_host_nanovdb.sh
# M2G: where the harness is built, kept for a later call on the same machine
# (built only when missing there; default a fresh temporary folder).
# MESHES picks among bunny icosphere spot ogre rocker-arm fandisk (default: all six).
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
m2g="${M2G:-$work/m2g}"
[ -x "$m2g" ] || nvcc -O3 -std=c++17 -arch="${ARCH:-sm_90}" --extended-lambda --expt-relaxed-constexpr \
  -I bundle/peers/nanovdb bench/nanovdb_mesh_to_grid.cu -o "$m2g" > "$out/m2g_build.txt" 2>&1
if [ ! -x "$m2g" ]; then
  echo "gpu_host_nanovdb: the MeshToGrid harness did not build; see $out/m2g_build.txt" >&2
  tail -30 "$out/m2g_build.txt" >&2
  exit 1
fi
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.obj" >/dev/null
# Fill svo's program cache first (a fresh machine compiles every program once).
"$bin/svo" voxelize bundle/meshes/stanford-bunny.obj -r 64 --udf -o "$work/warm.nvdb" >/dev/null 2>&1
"$bin/svo" voxelize bundle/meshes/stanford-bunny.obj -r 64 -o "$work/warm.nvdb" >/dev/null 2>&1
meshes=()
for m in ${MESHES:-bunny icosphere spot ogre rocker-arm fandisk}; do
  case "$m" in
    bunny) meshes+=(bundle/meshes/stanford-bunny.obj) ;;
    icosphere) meshes+=("$work/icosphere.obj") ;;
    *) meshes+=("bundle/meshes/$m.obj") ;;
  esac
done
gpu=$(nvidia-smi --query-gpu=name --format=csv,noheader | head -1)
python3 bench/nanovdb_peers.py --svo "$bin/svo" --m2g "$m2g" --res ${RES:-256 512 1024 2048 4096} --runs "${RUNS:-5}" \
  --md "$out/nanovdb_peers.md" --json "$out/nanovdb_peers.jsonl" --title "svo NanoVDB output against MeshToGrid on $gpu" \
  "${meshes[@]}" 2>&1 | tee "$out/nanovdb_peers.txt"
