# Sourced by the GPU host scripts, from the repository root: GLVND from .gl/
# when the host lacks it, NVIDIA's EGL vendor file, the bundle unpacked, and
# the host described. Sets out (logs, $OUT or ./gpu_host_out), work and bin.
if ! ldconfig -p | grep -q libEGL.so.1 && ls .gl/*.deb >/dev/null 2>&1; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
ldconfig -p | grep -q libEGL_nvidia || export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
out=${OUT:-gpu_host_out}
mkdir -p "$out"
work=$(mktemp -d)
tar -C "$work" -xzf bundle/svo-bundle.tar.gz
bin="$work/svo/bin"
{
  echo "== host"; nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader; nproc
  echo "== glinfo"; "$bin/svo" glinfo
} 2>&1 | tee "$out/host.txt"
