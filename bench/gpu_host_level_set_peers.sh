#!/usr/bin/env bash
# Level sets end to end on the GPU host against vdb_tool -mesh2ls on the
# host's cores, in one run (bench/level_set_peers.py): an open mesh (the
# bunny: winding-number signs), a closed one (spot) and the 1.3 M-triangle
# icosphere, 256³ to 2048³, band 3. Needs the bundle with vdb_tool and
# vdb_print (scripts/bundle.sh build OUT /usr/bin/vdb_tool /usr/bin/vdb_print)
# and bundle/meshes/{stanford-bunny,spot}.obj (bench/gpu_host_env.sh).
set -uo pipefail
source bench/gpu_host_env.sh
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.obj" >/dev/null
# Fill svo's program cache first (a fresh machine compiles every program once).
for mesh in bundle/meshes/stanford-bunny.obj bundle/meshes/spot.obj; do
  "$bin/svo" voxelize "$mesh" -r 64 --sdf -o "$work/warm.vdb" >/dev/null 2>&1
done
python3 bench/level_set_peers.py --svo "$bin/svo" --vdb-tool "$bin/vdb_tool" --vdb-print "$bin/vdb_print" \
  --res 256 512 1024 2048 --timeout 300 --md "$out/level_set_peers.md" \
  --title "Level sets end to end on $(nvidia-smi --query-gpu=name --format=csv,noheader | head -1) and $(nproc) cores" \
  bundle/meshes/stanford-bunny.obj bundle/meshes/spot.obj "$work/icosphere.obj" 2>&1 | tee "$out/level_set_peers.txt"
