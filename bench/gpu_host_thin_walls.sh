#!/usr/bin/env bash
# Thin walls in six-way volumes (design §7d) on the GPU host: the lighting
# and view tests, then one-bounce GI with isotropic and six-way radiance on
# the two rooms (the dark room's leak), the Cornell box and the spheres,
# and AO on the Cornell box (unchanged by six-way volumes). Needs the bundle
# with svo-bench-ao, test_lighting and test_view (scripts/bundle.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/test_lighting" 2>&1 | grep -Ev "^\[ +(RUN|OK) +\]" | tail -20 | tee "$out/test_lighting.txt"
"$bin/test_view" 2>&1 | tail -3 | tee "$out/test_view.txt"
"$bin/svo-bench-ao" two_rooms cornell spheres --render gi --res 64 128 256 --cones 7 --samples 256 --frames 10 \
  --md "$out/thin_walls_isotropic.md" 2>&1 | tee "$out/thin_walls.txt"
"$bin/svo-bench-ao" two_rooms cornell spheres --render gi --directional --res 64 128 256 --cones 7 --samples 256 \
  --frames 10 --md "$out/thin_walls_directional.md" 2>&1 | tee -a "$out/thin_walls.txt"
"$bin/svo-bench-ao" cornell --res 256 --cones 7 --samples 1024 --frames 10 --md "$out/ao_cornell_256.md" 2>&1 |
  tee -a "$out/thin_walls.txt"
