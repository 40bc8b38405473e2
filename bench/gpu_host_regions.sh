#!/usr/bin/env bash
# On the GPU host: Backend::Auto's rule on a hardware GPU (the GPU passes),
# regions against the whole grid on the hardware GPU (test_regions), and the
# GPU suites that name their backend (test_api, test_level_set, test_cpu_fields);
# SUITES names others (test_nanovdb_layout, test_view ...).
#   bash bench/gpu_host_regions.sh   (bundle built with the test binaries; .gl/meshes present)
set -uo pipefail
source bench/gpu_host_env.sh
export SVO_CGAL_MESHES=$PWD/.gl/meshes
mkdir -p /work/main/build/tests/cgal_data/data && ln -sfn "$PWD/.gl/meshes" /work/main/build/tests/cgal_data/data/meshes
for t in ${SUITES:-test_regions test_api test_level_set test_cpu_fields test_gpu_voxelize}; do
  [ -x "$bin/$t" ] || continue
  echo "== $t"
  "$bin/$t" --gtest_brief=1 2>&1 | tail -25
done 2>&1 | tee "$out/tests.txt"
{
  echo "== what auto runs on this machine"
  for kind in "" "--sdf" "--fill solid" "--attributes normal"; do
    "$bin/svo" voxelize -v .gl/meshes/stanford-bunny.obj -r 256 $kind -o "$work/x.vdb" 2>&1 | grep -E "^  backend" | sed "s|^|${kind:-surface}: |"
  done
} 2>&1 | tee "$out/auto.txt"
