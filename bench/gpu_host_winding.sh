#!/usr/bin/env bash
# Winding-number signs on a GPU host: the level-set tests, error against GPU
# time over the accuracy beta (svo-bench-winding), and level sets of open
# meshes through svo voxelize --sdf (auto picks the winding number). Run from
# the repository root with the bundle and meshes carried (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
mkdir -p /work/main/build/tests/cgal_data/data/meshes && cp bundle/meshes/*.off /work/main/build/tests/cgal_data/data/meshes/
{
  echo "== tests"
  "$bin/test_level_set" 2>&1 | grep -E "winding  |OK|FAILED|PASSED" | tail -16
  echo "== winding error against time"
  "$bin/svo-bench-winding" bundle/meshes/elephant.off --res 256 512 --beta 1 1.5 2 3 4 8 --runs 3 --md "$out/winding_elephant.md"
  "$bin/svo-bench-winding" bundle/meshes/stanford-bunny.obj --res 256 512 --beta 1 1.5 2 3 4 --reference-beta 8 --runs 3 \
    --md "$out/winding_bunny.md"
  echo "== open meshes: level sets and solids"
  for mesh in bundle/meshes/stanford-bunny.obj bundle/meshes/spot.obj bundle/meshes/ogre.obj; do
    for r in 256 512 1024; do
      echo "== $(basename $mesh) $r"
      timeout 120 "$bin/svo" voxelize -v "$mesh" -r $r --sdf --repeat 3 --json "$out/sdf_$(basename $mesh)_$r.json" 2>&1 \
        | grep -E "sign|voxels|work|band distance|winding|level set grid|total"
    done
  done
} 2>&1 | tee "$out/winding.txt"
