#!/usr/bin/env bash
# Lit voxels (issue 16) on the GPU host: the lighting tests, then AO (from
# the volume and from the octree), direct light and one-bounce GI against
# the path-traced reference over resolutions and cone counts, and a
# 1920x1080 picture. Needs the bundle with svo-bench-ao, test_lighting and
# test_view (scripts/bundle.sh), and bundle/meshes/spot.obj (../shared/meshes).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/test_lighting" 2>&1 | grep -Ev "^\[ +(RUN|OK) +\]" | tail -40 | tee "$out/test_lighting.txt"
"$bin/test_view" 2>&1 | tail -3 | tee "$out/test_view.txt"
mesh=bundle/meshes/spot.obj
[ -f "$mesh" ] || mesh=
"$bin/svo-bench-ao" cornell spheres $mesh --ao-source both --res 64 128 256 512 --cones 1 3 7 16 --samples 1024 \
  --frames 10 --md "$out/ao.md" 2>&1 | tee "$out/ao.txt"
"$bin/svo-bench-ao" cornell spheres --render direct --res 64 128 256 512 --cones 1 --samples 1 --frames 10 \
  --md "$out/direct.md" 2>&1 | tee "$out/direct.txt"
"$bin/svo-bench-ao" cornell spheres two_rooms --render gi --res 64 128 256 512 --cones 1 3 7 16 --samples 1024 --frames 10 \
  --md "$out/gi.md" 2>&1 | tee "$out/gi.txt"
"$bin/svo-bench-ao" cornell spheres two_rooms --render gi --directional --res 64 128 256 512 --cones 1 3 7 16 --samples 1024 \
  --frames 10 --md "$out/gi_directional.md" 2>&1 | tee "$out/gi_directional.txt"
"$bin/svo" view -r 256 --render gi --size 1920x1080 --screenshot "$out/gi_cornell_256.png" 2>&1 | tee -a "$out/gi.txt"
