#!/usr/bin/env bash
# The compute backend against the raster backend and cuda_voxelizer, in one
# run on a GPU host. Needs the bundle (scripts/bundle.sh with test_api,
# test_gpu_voxelize and test_stability as extra executables), bundle/meshes,
# and cuda_voxelizer's sources in bundle/peers (with its build script).
#   OUT=dir [BACKENDS="raster compute"] bash bench/gpu_host_compute.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"

# The GPU suites: compute must equal raster on every scene there.
for t in test_gpu_voxelize test_gpu_octree test_stability test_api; do
  [ -x "$bin/$t" ] && SVO_CGAL_MESHES="$PWD/bundle/meshes" "$bin/$t" 2>&1 | tee "$out/$t.txt" | grep -E "^\[  |FAILED|PASSED|differs"
done

cv=""
if [ -d bundle/peers ]; then
  bash bundle/peers/build-cuda-voxelizer.sh "$work/cvb" >"$out/cuda_voxelizer_build.txt" 2>&1 && cv="$work/cvb/cuda_voxelizer"
fi
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.obj" >/dev/null
cp bundle/meshes/stanford-bunny.obj "$work/bunny.obj"

# svo: GPU ms of upload, voxelize, octree build and readback (median of 5 after a warm-up);
# cuda_voxelizer: its kernel time, median of 3 runs.
for mesh in bunny icosphere; do
  for res in 256 512 1024 2048; do
    for backend in ${BACKENDS:-raster compute}; do
      echo "== svo $mesh $res $backend"
      "$bin/svo" voxelize -v "$work/$mesh.obj" -r "$res" --backend "$backend" --repeat 5 --json "$work/r.json" 2>&1 \
        | grep -E "voxels  |voxel list|upload|voxelize |octree build|readback|error"
    done
    if [ -n "$cv" ]; then
      echo "== cuda_voxelizer $mesh $res"
      for i in 1 2 3; do (cd "$work" && "$cv" -f "$work/$mesh.obj" -s "$res" -o morton 2>&1 | grep -E "Voxelization GPU time"); done
    fi
  done
done 2>&1 | tee "$out/compute_timings.txt"
