#!/usr/bin/env bash
# Level sets of open meshes (winding-number signs) on the GPU host, before and
# after a change: the level-set tests, then `svo voxelize --sdf --repeat 3`
# by svo-old (built from the code before the change) and svo, one after the
# other on each mesh and grid, and whether both wrote the same grid (the
# files equal past their header's UUID). Needs the bundle with svo-old and
# test_level_set, and bundle/meshes/{stanford-bunny,spot,ogre}.obj and
# elephant.off (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
mkdir -p /work/main/build/tests/cgal_data/data/meshes && cp bundle/meshes/*.off /work/main/build/tests/cgal_data/data/meshes/
{
  echo "== tests"
  "$bin/test_level_set" 2>&1 | grep -E "winding  |OK|FAILED|PASSED" | tail -16
  for mesh in stanford-bunny spot ogre; do
    for r in 256 512 1024; do
      for v in -old ""; do
        echo "== $mesh $r svo$v"
        timeout 200 "$bin/svo$v" voxelize "bundle/meshes/$mesh.obj" -r $r --sdf --repeat 3 -o "$work/$mesh$v.vdb" 2>&1 \
          | grep -E "voxels|winding|band distance|total"
      done
      # The files' first 64 bytes hold the header and its UUID.
      echo "== $mesh $r: bytes differing past the header: $(cmp -l "$work/$mesh-old.vdb" "$work/$mesh.vdb" | awk '$1 > 64' | wc -l)"
    done
  done
} 2>&1 | tee "$out/sdf_ab.txt"
