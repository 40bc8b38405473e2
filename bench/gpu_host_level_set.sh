#!/usr/bin/env bash
# Level sets and solids on a GPU host: the level-set tests, then svo voxelize
# --sdf (band 3) against OpenVDB's meshToLevelSet (half width 3, the host's
# CPU cores) on the same mesh and grid, for the meshes of the target
# (the bunny, open: winding signs; the 1.3 M-triangle icosphere, closed:
# parity) and the elephant. svo's figure is the per-call wall time (--repeat,
# after a warm-up); OpenVDB's is its one call. Then the whole process of each,
# mesh file to .vdb file. Run from the repository root with the bundle and
# meshes carried (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.off" >/dev/null
ms() { echo $(( ($(date +%s%N) - $1) / 1000000 )); }
{
  echo "== tests"
  # The tests read libcgal-demo's meshes where the build put them.
  data=$(strings "$bin/test_level_set" | grep -m1 -o '/[^ ]*cgal_data/data' || true)
  [ -n "$data" ] && mkdir -p "$data" && ln -sfn "$PWD/bundle/meshes" "$data/meshes"
  "$bin/test_level_set" 2>&1 | tail -3
  for mesh in bundle/meshes/elephant.off bundle/meshes/stanford-bunny.obj "$work/icosphere.off"; do
    name=$(basename "$mesh")
    for r in ${RES:-256 1024 2048}; do
      echo "== $name $r"
      "$bin/svo" voxelize -v "$mesh" -r $r --sdf --repeat 5 --json "$out/sdf_${name}_$r.json" -o "$work/s.vdb" 2>&1 |
        grep -E "sign|voxels|band|packing|readback|level set grid|per call|total"
      "$bin/svo-mesh-to-volume" "$mesh" -r $r --level-set 3 2>&1 | tail -2
      t=$(date +%s%N); "$bin/svo" voxelize "$mesh" -r $r --sdf -o "$work/e.vdb" >/dev/null 2>&1
      echo "end to end svo voxelize --sdf: $(ms $t) ms"
    done
  done
} 2>&1 | tee "$out/level_set.txt"
