#!/usr/bin/env bash
# The library API on a GPU host, from the bundle (scripts/bundle.sh with
# svo-bench-warm-call and the test binaries as extra executables) and
# bundle/meshes: the GPU suites, validation, then the warm-call benchmark.
#   OUT=dir bash bench/gpu_host_api.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
for t in test_api test_gpu_layout test_gpu_voxelize test_gpu_octree test_validate; do
  [ -x "$bin/$t" ] && SVO_CGAL_MESHES="$PWD/bundle/meshes" "$bin/$t" 2>&1 | tee "$out/$t.txt" | grep -E "^\[  |FAILED|PASSED"
done
{ "$bin/svo" validate bundle/meshes/stanford-bunny.obj -r 512; "$bin/svo" validate bundle/meshes/elephant.off -r 256;
  "$bin/svo" voxelize -v bundle/meshes/stanford-bunny.obj -r 1024 --fog -o "$work/bunny.nvdb"; } 2>&1 | tee "$out/validate.txt" | grep -E "verdict|missed|error|output"
"$bin/svo-bench-warm-call" bundle/meshes/stanford-bunny.obj --res 256 1024 --calls 100 \
  --machine "an NVIDIA H100 host" --json "$out/warm_call.json" --md "$out/warm_call.md" 2>&1 | tail -4
