#!/usr/bin/env bash
# Band distances before and after a change, on the GPU host, in one run:
# the bundle carries the old build's CLI as svo_old (scripts/bundle.sh build
# OUT /path/to/old/svo_old [build/tests/test_level_set]). For the bunny, spot and the 1.3 M-triangle
# icosphere at 256³-2048³, band 3: each build's band-distance and per-call
# GPU ms (--repeat 5, medians after a warm-up), and whether the two .vdb
# files are the same past their header (the file's UUID).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.obj" >/dev/null
for exe in svo_old svo; do # fill each build's program cache
  "$bin/$exe" voxelize bundle/meshes/spot.obj -r 64 --sdf -o "$work/warm.vdb" >/dev/null 2>&1
done
{
  if [ -x "$bin/test_level_set" ]; then # the level-set tests on this GPU, if bundled
    echo "== test_level_set"
    data=$(strings "$bin/test_level_set" | grep -m1 -o '/[^ ]*cgal_data/data' || true)
    [ -n "$data" ] && mkdir -p "$data" && ln -sfn "$PWD/bundle/meshes" "$data/meshes"
    "$bin/test_level_set" 2>&1 | tail -3
  fi
  for mesh in bundle/meshes/stanford-bunny.obj bundle/meshes/spot.obj "$work/icosphere.obj"; do
    for r in ${RES:-256 1024 2048}; do
      for exe in svo_old svo; do
        echo "== $(basename "$mesh") $r $exe"
        "$bin/$exe" voxelize "$mesh" -r "$r" --sdf --band 3 --repeat 5 -o "$work/$exe.vdb" 2>&1 |
          grep -E "band distance|parity crossings|winding per voxel|per call|total"
      done
      cmp -s -i 64 "$work/svo_old.vdb" "$work/svo.vdb" && echo "grids: identical" || echo "grids: DIFFER"
    done
  done
} 2>&1 | tee "$out/band_ab.txt"
