#!/usr/bin/env bash
# On the GPU host: the GPU NanoVDB builder (gl::buildNanoGridGpu) byte for
# byte against the CPU layout (test_gpu_nano_grid), the CPU layout against
# NanoVDB's converter with nanovdb_validate in the bundle (test_nanovdb_layout),
# the winding suites after the tree of pieces (test_level_set, test_cpu_fields),
# the builder's timing (svo-bench-nanovdb-gpu) on the bunny and spot, and the
# front door's .nvdb on them (svo voxelize --udf / surfaces -o x.nvdb -v: the stages
# "band leaves", "nanovdb grid (gpu)" (build and checksum), "nanovdb readback";
# expected figures: bench/nanovdb_expected.md, "the front door on the GPU builder").
#   bash scripts/bundle.sh build bundle/svo-bundle.tar.gz build/tests/test_gpu_nano_grid \
#     build/tests/test_nanovdb_layout build/tests/test_level_set build/tests/test_cpu_fields \
#     build/bin/svo-bench-nanovdb-gpu /usr/bin/nanovdb_validate
#   OUT=dir [RES="256 512 1024 2048"] bash bench/gpu_host_nano_builder.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
export PATH="$bin:$PATH" SVO_CGAL_MESHES=$PWD/.gl/meshes
mkdir -p /work/main/build/tests/cgal_data/data && ln -sfn "$PWD/.gl/meshes" /work/main/build/tests/cgal_data/data/meshes
for t in test_gpu_nano_grid test_nanovdb_layout test_level_set test_cpu_fields test_regions; do
  [ -x "$bin/$t" ] || continue
  echo "== $t"
  "$bin/$t" --gtest_brief=1 2>&1 | tail -25
done 2>&1 | tee "$out/tests.txt"
# The bunny (open: winding signs) and spot (closed: parity, whose level set
# the builder flood fills: the table's flood fill columns).
for mesh in stanford-bunny spot; do
  "$bin/svo-bench-nanovdb-gpu" bundle/meshes/$mesh.obj --res ${RES:-256 512 1024 2048} --runs 5 --backend gpu
done 2>&1 | tee "$out/gpu_builder.md"
# The front door, end to end (the first run of each size warms the program
# cache; --repeat 3 reports each run's stages).
for r in ${RES:-256 512 1024 2048}; do
  echo "== bunny $r --udf --band 3 -o x.nvdb"
  "$bin/svo" voxelize bundle/meshes/stanford-bunny.obj -r "$r" --udf --band 3 -o "$work/udf.nvdb" >/dev/null 2>&1
  /usr/bin/time -f "end to end %e s" "$bin/svo" voxelize bundle/meshes/stanford-bunny.obj -r "$r" --udf --band 3 \
    -o "$work/udf.nvdb" -v --json "$out/front_door_udf_$r.json" 2>&1
  nanovdb_validate "$work/udf.nvdb" && echo "nanovdb_validate: ok"
  echo "== spot $r --sdf -o x.nvdb (parity: flood filled by the builder)"
  /usr/bin/time -f "end to end %e s" "$bin/svo" voxelize bundle/meshes/spot.obj -r "$r" --sdf \
    -o "$work/sdf.nvdb" -v --json "$out/front_door_sdf_spot_$r.json" 2>&1
  nanovdb_validate "$work/sdf.nvdb" && echo "nanovdb_validate: ok"
  echo "== bunny $r surface -o x.nvdb (the CLI's surfaces go through writeOctree: CPU layout, a reference)"
  /usr/bin/time -f "end to end %e s" "$bin/svo" voxelize bundle/meshes/stanford-bunny.obj -r "$r" \
    -o "$work/surface.nvdb" -v --json "$out/front_door_surface_$r.json" 2>&1
done 2>&1 | tee "$out/front_door.txt"
