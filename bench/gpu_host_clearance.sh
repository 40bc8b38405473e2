#!/usr/bin/env bash
# Cones clear of voxels (Illumination::clearance, design §7d) on the GPU
# host: the lighting and view tests, then one-bounce GI of the two rooms
# (the dark room's leak), the Cornell box and the spheres with isotropic and
# six-way radiance, each with and without clearance, and AO of the Cornell
# box at 256³ with the defaults. Needs the bundle with svo-bench-ao,
# test_lighting, test_view and test_cone_reference (scripts/bundle.sh).
#   bash bench/gpu_host_clearance.sh [variant ...]
# variants: isotropic isotropic_clear directional directional_clear ao (all by default).
set -uo pipefail
variants=" ${*:-isotropic isotropic_clear directional directional_clear ao} "
want() { [[ "$variants" == *" $1 "* ]]; }
source bench/gpu_host_env.sh
for t in test_lighting test_view test_cone_reference; do
  "$bin/$t" 2>&1 | grep -Ev "^\[ +(RUN|OK) +\]" | tail -6 | tee "$out/$t.txt"
done
run() { # name, then svo-bench-ao's options
  local name=$1; shift
  "$bin/svo-bench-ao" two_rooms cornell spheres --render gi --res 128 256 --cones 5 --samples 256 --frames 10 \
    --md "$out/clearance_$name.md" "$@" 2>&1 | tee -a "$out/clearance.txt"
}
want isotropic && run isotropic
want isotropic_clear && run isotropic_clear --clearance
want directional && run directional --directional
want directional_clear && run directional_clear --directional --clearance
want ao && "$bin/svo-bench-ao" cornell --res 256 --cones 5 --samples 1024 --frames 10 --md "$out/ao_cornell_256.md" 2>&1 |
  tee -a "$out/clearance.txt"
