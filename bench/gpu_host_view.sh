#!/usr/bin/env bash
# svo view on a GPU host: the renderer's tests, then the frame time at
# 1920x1080 (svo-bench-view) for the bunny at 256³ to 2048³ and the
# 1.3 M-triangle icosphere at 2048³. Run from the repository root with the
# bundle and meshes carried (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.off" >/dev/null
{
  echo "== tests"
  "$bin/test_view" 2>&1 | grep -E "OK|FAILED|PASSED" | tail -12
  echo "== frame time, voxels"
  "$bin/svo-bench-view" bundle/meshes/stanford-bunny.obj --res 256 512 1024 2048 --frames 60 --md "$out/view_bunny.md"
  "$bin/svo-bench-view" "$work/icosphere.off" --res 2048 --frames 60 --md "$out/view_icosphere.md"
  echo "== frame time, voxels and outlines"
  "$bin/svo-bench-view" bundle/meshes/stanford-bunny.obj --res 256 2048 --frames 30 --layers voxels+outlines
} 2>&1 | tee "$out/view.txt"
