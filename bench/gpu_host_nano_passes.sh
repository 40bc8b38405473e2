#!/usr/bin/env bash
# Where the GPU NanoVDB builder's time goes (issue 45): svo's band topology
# and unsigned field at 1024³ and 2048³ with SVO_NANO_PASS_MS, which waits
# for each phase of a build and prints its milliseconds (keys, sort, scan,
# leaves, lower and upper nodes, ...), beside the stages' GPU times (-v).
# Needs the bundle (scripts/bundle.sh) and bundle/meshes.
#   OUT=dir [RES="1024 2048"] [MESHES="stanford-bunny spot"] bash bench/gpu_host_nano_passes.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
"$bin/svo" voxelize bundle/meshes/stanford-bunny.obj -r 64 --fill band -o "$work/warm.nvdb" >/dev/null 2>&1
for m in ${MESHES:-stanford-bunny spot}; do
  for r in ${RES:-1024 2048}; do
    for kind in "--fill band --topology mask" "--udf"; do
      echo "== $m $r $kind"
      SVO_NANO_PASS_MS=1 "$bin/svo" voxelize "bundle/meshes/$m.obj" -r "$r" $kind --band 3 --repeat 3 \
        -o "$work/passes.nvdb" -v 2>&1 | grep -E "nanovdb build ms|band distance|band leaves|nanovdb grid|voxels "
    done
  done
done 2>&1 | tee "$out/passes.txt"
