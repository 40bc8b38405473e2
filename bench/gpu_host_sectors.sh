#!/usr/bin/env bash
# Ambient occlusion kept per sector of each cone's cross-section (design
# §7c, "Occluders seen twice") on the GPU host: the lighting, view and
# cone-reference tests, then AO of the Cornell box and the spheres at 256³
# on the voxels and on the mesh (7 and 16 cones, references of 4096 paths a
# pixel), frames timed at 1920x1080.
# Needs the bundle with svo-bench-ao, test_lighting, test_view and
# test_cone_reference (scripts/bundle.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/test_lighting" 2>&1 | tail -3 | tee "$out/test_lighting.txt"
"$bin/test_view" 2>&1 | tail -3 | tee "$out/test_view.txt"
"$bin/test_cone_reference" 2>&1 | tail -3 | tee "$out/test_cone_reference.txt"
for surface in voxels mesh; do
  "$bin/svo-bench-ao" cornell spheres --surface "$surface" --res 256 --cones 7 16 --samples 4096 --frames 10 \
    --md "$out/ao_$surface.md" 2>&1 | tee -a "$out/sectors.txt"
done
