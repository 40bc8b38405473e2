#!/usr/bin/env bash
# On the GPU host, after the layered refactor, libepoxy and the CPU field
# paths: the GPU suites on the hardware GPU, the CPU fields against the
# hardware GPU's (test_cpu_fields), and level sets on the GPU against the CPU
# backend on the host's cores, whole processes.
#   bash bench/gpu_host_layers.sh   (bundle built with the test binaries; .gl/meshes present)
set -uo pipefail
source bench/gpu_host_env.sh
export SVO_CGAL_MESHES=$PWD/.gl/meshes
# The tests' compiled-in mesh folder, where the bundle's binaries look.
mkdir -p /work/main/build/tests/cgal_data/data && ln -sfn "$PWD/.gl/meshes" /work/main/build/tests/cgal_data/data/meshes
for t in test_gpu_voxelize test_gpu_octree test_api test_level_set test_cpu_fields; do
  [ -x "$bin/$t" ] || continue
  echo "== $t"
  "$bin/$t" --gtest_brief=1 2>&1 | tail -25
done 2>&1 | tee "$out/tests.txt"
{
  echo "== level sets: GPU (auto) against the CPU backend on $(nproc) cores, wall s (median of 3) and peak MB"
  for case in "stanford-bunny.obj 512" "japanese-temple.obj 256" "japanese-temple.obj 512" "spot.obj 512"; do
    set -- $case
    for backend in auto cpu; do
      ws=()
      for i in 1 2 3; do
        /usr/bin/time -f "%e %M" -o "$work/t" "$bin/svo" voxelize ".gl/meshes/$1" -r "$2" --sdf --backend "$backend" -o "$work/x.vdb" >"$work/log" 2>&1 || { cat "$work/log"; break; }
        ws+=("$(cat "$work/t")")
        rm -f "$work/x.vdb"
      done
      echo "$1 $2 $backend: $(printf '%s\n' "${ws[@]}" | sort -g | sed -n 2p)"
    done
  done
} 2>&1 | tee "$out/level_sets.txt"
