#!/usr/bin/env bash
# Runs on a GPU host from the repository root, with the bundle and meshes in
# bundle/ (scripts/bundle.sh) and, if the host lacks them, GLVND debs in .gl/.
# Writes logs to $OUT (or ./gpu_host_out).
set -uo pipefail
out=${OUT:-gpu_host_out}
mkdir -p "$out"
if ! ldconfig -p | grep -q libEGL.so.1 && ls .gl/*.deb >/dev/null 2>&1; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
ldconfig -p | grep -q libEGL_nvidia || export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
work=$(mktemp -d)
tar -C "$work" -xzf bundle/svo-bundle.tar.gz
svo="$work/svo/bin/svo"
{
  echo "== host"; nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader; nproc
  echo "== glinfo"; "$svo" glinfo
} 2>&1 | tee "$out/host.txt"

# The GPU test suite against the CPU reference, with the meshes where the build expects them.
tests="$work/svo/bin/test_gpu_voxelize"
if [ -x "$tests" ]; then
  SVO_CGAL_MESHES="$PWD/bundle/meshes" "$tests" 2>&1 | tee "$out/test_gpu_voxelize.txt" | grep -E "^\[  |FAILED|PASSED|band" 
fi

# Timings: bunny and ogre, both dilation modes, median of 5 after a warm-up.
for mesh in stanford-bunny ogre; do
  for res in 256 512 1024 2048; do
    for mode in hardware shader; do
      echo "== $mesh $res $mode"
      "$svo" voxelize "bundle/meshes/$mesh.obj" -r $res --conservative $mode --repeat 5 -o "$work/out.vdb" 2>&1 \
        | grep -E "voxels  |backend|voxelize |upload|readback|sort|vdb |total|list|error"
    done
  done
done 2>&1 | tee "$out/timings.txt"
