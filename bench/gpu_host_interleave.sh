#!/usr/bin/env bash
# Interleaved cones (design §7c, "One cone set, sixteen") on the GPU host:
# the lighting, view and cone-reference tests; AO of the Cornell box and the
# spheres at 256³ on the mesh and on the voxels, 3 to 16 cones, the cones
# interleaved and fixed (references of 4096 paths a pixel); GI of both at
# 256³ (1024 paths), 4 to 7 cones; frames timed at 1920x1080 after one
# warm-up run; and svo view's GI picture of the built-in Cornell box with
# its defaults. Results, and all.tgz of them, under $OUT.
# Needs the bundle with svo, svo-bench-ao, test_lighting, test_view and
# test_cone_reference (scripts/bundle.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/test_lighting" 2>&1 | tail -3 | tee "$out/test_lighting.txt"
"$bin/test_view" 2>&1 | tail -3 | tee "$out/test_view.txt"
"$bin/test_cone_reference" 2>&1 | tail -3 | tee "$out/test_cone_reference.txt"
"$bin/svo-bench-ao" cornell --res 256 --cones 5 --samples 16 --frames 20 > /dev/null 2>&1 # warm-up: clocks, caches
for pattern in interleaved fixed; do
  for surface in mesh voxels; do
    "$bin/svo-bench-ao" cornell spheres --surface "$surface" --cone-pattern "$pattern" --res 256 --cones 3 4 5 7 16 \
      --samples 4096 --frames 10 --md "$out/ao_${surface}_$pattern.md" 2>&1 | tee -a "$out/interleave.txt"
  done
done
for pattern in interleaved fixed; do
  for surface in mesh voxels; do
    "$bin/svo-bench-ao" cornell spheres --render gi --surface "$surface" --cone-pattern "$pattern" --res 256 \
      --cones 4 5 7 --samples 1024 --frames 10 --md "$out/gi_${surface}_$pattern.md" 2>&1 | tee -a "$out/interleave.txt"
  done
done
"$bin/svo" view -r 256 --render gi --size 1920x1080 --screenshot "$out/gi_cornell_256.png" 2>&1 | tail -2 |
  tee -a "$out/interleave.txt"
(cd "$out" && tar czf /tmp/all.tgz --exclude all.tgz . && mv /tmp/all.tgz all.tgz)
