#!/usr/bin/env bash
# The mesh's surface shaded through the octree (ViewLayers::surface, design
# §7c) on the GPU host: the lighting and view tests, AO of the Cornell box
# and the spheres at 256³ on the voxels and on the mesh (7 and 16 cones,
# references of 4096 paths a pixel), and one-bounce GI of the Cornell box
# at 256³ on both, frames timed at 1920x1080 (and with the light moved).
# Needs the bundle with svo-bench-ao, test_lighting and test_view
# (scripts/bundle.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/test_lighting" 2>&1 | grep -Ev "^\[ +(RUN|OK) +\]" | tail -20 | tee "$out/test_lighting.txt"
"$bin/test_view" 2>&1 | tail -3 | tee "$out/test_view.txt"
for surface in voxels mesh; do
  "$bin/svo-bench-ao" cornell spheres --surface "$surface" --res 256 --cones 7 16 --samples 4096 --frames 10 \
    --md "$out/ao_$surface.md" 2>&1 | tee -a "$out/surface.txt"
  "$bin/svo-bench-ao" cornell --render gi --surface "$surface" --res 256 --cones 7 --samples 1024 --frames 10 \
    --md "$out/gi_$surface.md" 2>&1 | tee -a "$out/surface.txt"
done
