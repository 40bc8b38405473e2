#!/usr/bin/env bash
# Level sets and solids on a GPU host: the level-set and thin-mode tests, then
# svo voxelize --sdf / --fill solid against OpenVDB's meshToLevelSet (the
# host's CPU) on the same mesh and grid. Run from the repository root with
# the bundle and meshes carried (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
{
  echo "== tests"
  "$bin/test_level_set" 2>&1 | tail -4
  "$bin/test_gpu_voxelize" --gtest_filter='*Thin*' 2>&1 | tail -3
  "$bin/test_stability" --gtest_filter='*Thin*' 2>&1 | tail -3
  for mesh in bundle/meshes/stanford-bunny.obj bundle/meshes/elephant.off; do
    for r in 256 512 1024 2048; do
      echo "== $(basename $mesh) $r"
      "$bin/svo" voxelize "$mesh" -r $r --sdf --repeat 5 --json "$out/sdf_$(basename $mesh)_$r.json" 2>&1 | grep -E "voxels|work|band distance|parity|level set grid|total"
      "$bin/svo" voxelize "$mesh" -r $r --fill solid --repeat 5 --json "$out/solid_$(basename $mesh)_$r.json" 2>&1 | grep -E "voxels|total"
      [ $r -le 1024 ] && "$bin/svo-mesh-to-volume" "$mesh" -r $r --level-set 3
    done
  done
} 2>&1 | tee "$out/level_set.txt"
