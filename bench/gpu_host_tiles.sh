#!/usr/bin/env bash
# Grids beyond GPU memory: the bunny from 2048^3 to 16384^3 with the compute
# backend, once within the device's free memory (auto budget) and once within
# a forced budget that makes it tile; cuda_voxelizer where its dense bit table
# fits. Also the GPU suites the tiles touch. Needs the bundle (scripts/bundle.sh
# with test_gpu_octree, test_gpu_voxelize, test_stability and test_api as extra
# executables), bundle/meshes and bundle/peers.
#   OUT=dir bash bench/gpu_host_tiles.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"

for t in test_gpu_octree test_gpu_voxelize test_stability test_api; do
  [ -x "$bin/$t" ] && SVO_CGAL_MESHES="$PWD/bundle/meshes" "$bin/$t" >"$out/$t.txt" 2>&1
  echo "== $t: $(grep -cE '^\[       OK' "$out/$t.txt") ok, $(grep -cE '^\[  FAILED  \] [A-Z]' "$out/$t.txt") failed"
  grep -E "tiles, GPU|^\[  FAILED" "$out/$t.txt"
done

cv=""
if [ -d bundle/peers ]; then
  bash bundle/peers/build-cuda-voxelizer.sh "$work/cvb" >"$out/cuda_voxelizer_build.txt" 2>&1 && cv="$work/cvb/cuda_voxelizer"
fi
cp bundle/meshes/stanford-bunny.obj "$work/bunny.obj"
for res in ${RESOLUTIONS:-2048 4096 8192 16384}; do
  # A forced budget about a quarter of what the grid takes untiled.
  case $res in 2048) budget=128M ;; 4096) budget=512M ;; 8192) budget=2G ;; *) budget=8G ;; esac
  for b in auto "$budget"; do
    echo "== svo bunny $res budget $b"
    args=(); [ "$b" != auto ] && args=(--gpu-memory "$b")
    # The bunny is 0.155 units long: at 16384^3 its voxels (9.5e-6) are below the
    # smallest an OpenVDB transform takes (1.44e-5), so the octree is written as .svo.
    ext=vdb; [ "$res" -ge 16384 ] && ext=svo
    timeout 280 "$bin/svo" voxelize -v "$work/bunny.obj" -r "$res" --backend compute "${args[@]}" -o "$work/b.$ext" \
      --json "$out/tiles_${res}_${b}.json" 2>&1 | grep -E "voxels  |voxel list|upload|voxelize |octree build|readback|merge|vdb|total|error|EGL|programs"
    rm -f "$work/b.vdb" "$work/b.svo"
  done
  if [ -n "$cv" ] && [ "$res" -le 4096 ]; then  # 8192^3 bits take 64 GiB of host memory too
    echo "== cuda_voxelizer bunny $res"
    (cd "$work" && timeout 200 "$cv" -f "$work/bunny.obj" -s "$res" -o morton 2>&1 | grep -iE "time|error|memory" | head -8)
    rm -f "$work"/*.binvox "$work"/*.morton* 2>/dev/null
  fi
done 2>&1 | tee "$out/tiles_timings.txt"
nvidia-smi --query-gpu=memory.used,memory.total --format=csv,noheader
