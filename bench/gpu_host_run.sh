#!/usr/bin/env bash
# Runs on a GPU host from the repository root, with the bundle and meshes in
# bundle/ (scripts/bundle.sh) and, if the host lacks them, GLVND debs in .gl/.
# Writes logs to $OUT (or ./gpu_host_out).
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
svo="$bin/svo"

# The GPU test suites against the CPU and CGAL references, with the meshes where the build expects them.
for t in test_gpu_voxelize test_gpu_octree test_validate test_program_cache; do
  if [ -x "$work/svo/bin/$t" ]; then
    SVO_CGAL_MESHES="$PWD/bundle/meshes" "$work/svo/bin/$t" 2>&1 | tee "$out/$t.txt" | grep -E "^\[  |FAILED|PASSED"
  fi
done

# Octree build time and bytes per voxel against the voxel count.
if command -v python3 >/dev/null; then
  python3 bench/octree_build.py --svo "$svo" --machine gpu-host --out "$out" --meshes bundle/meshes \
    --mesh stanford-bunny.obj ogre.obj elephant.off --res 256 512 1024 2048 --repeat 5 2>&1 | tail -3
fi

# Start-up: EGL set-up and programs with the program cache and the driver's shader cache empty or warm.
if command -v python3 >/dev/null; then
  python3 bench/startup.py --svo "$svo" --machine gpu-host --out "$out" --runs 5 2>&1 | tee "$out/startup.txt"
fi

# Exact validation of the NVIDIA path (hardware conservative raster).
{ "$svo" validate bundle/meshes/stanford-bunny.obj -r 512; "$svo" validate bundle/meshes/elephant.off -r 256; } 2>&1 | tee "$out/validate.txt"

# Timings: bunny and ogre, both dilation modes, median of 5 after a warm-up.
for mesh in stanford-bunny ogre; do
  for res in 256 512 1024 2048; do
    for mode in hardware shader; do
      echo "== $mesh $res $mode"
      "$svo" voxelize -v "bundle/meshes/$mesh.obj" -r $res --conservative $mode --repeat 5 -o "$work/out.vdb" 2>&1 \
        | grep -E "voxels  |octree  |backend|voxelize |upload|readback|octree build|vdb |total|list|error"
    done
  done
done 2>&1 | tee "$out/timings.txt"
