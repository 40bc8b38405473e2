#!/usr/bin/env bash
# The view's frame time on the GPU host, after a change to the renderer:
# the view's tests, the plain voxel view (bunny) and the Cornell box's AO
# and one-bounce GI at 256³ against the path-traced reference, at 1920x1080.
# Executables named *-old in the bundle (the same benchmarks built from the
# code before the change) run beside the new ones, in the same process order,
# so that both are measured in one run. Needs the bundle (scripts/bundle.sh)
# with svo-bench-view, svo-bench-ao, test_view and test_lighting, and
# bundle/meshes/stanford-bunny.obj.
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/test_view" 2>&1 | tail -3 | tee "$out/test_view.txt"
"$bin/test_lighting" 2>&1 | tail -3 | tee "$out/test_lighting.txt"
versions=("")
[ -x "$bin/svo-bench-view-old" ] && versions=("-old" "")
{
  for v in "${versions[@]}"; do
    echo "== view$v"
    "$bin/svo-bench-view$v" bundle/meshes/stanford-bunny.obj --res 256 2048 --frames 30
    echo "== ao$v"
    "$bin/svo-bench-ao$v" cornell --res 256 --cones 1 7 16 --samples 1024 --frames 10
    echo "== gi$v"
    "$bin/svo-bench-ao$v" cornell --render gi --res 256 --cones 1 7 16 --samples 1024 --frames 10
  done
} 2>&1 | tee "$out/frame.txt"
