#!/usr/bin/env bash
# Relocatable bundle of the svo CLI (and optionally test binaries) for another
# x86-64 Linux with a GPU driver but no OpenVDB/TBB/Boost:
#   bin/   the executables, rpath $ORIGIN/../lib
#   lib/   every non-system shared library they load
#   lib/svo/libsvo_vtk.so  the module `svo vtk` loads, when the build has it
# GL and EGL (GLVND and the vendor driver) and glibc come from the host.
#   bash scripts/bundle.sh [build-dir] [out.tar.gz] [extra executables...]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-bundle/svo-bundle.tar.gz}
shift $(( $# > 2 ? 2 : $# )) || true
command -v patchelf >/dev/null || { echo "bundle: needs patchelf (apt-get install patchelf)" >&2; exit 1; }

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/svo/bin" "$stage/svo/lib"
for exe in "$build/bin/svo" "$@"; do
  cp "$exe" "$stage/svo/bin/"
done
# Host-provided: glibc, and the GL/EGL dispatch libraries that must match the driver.
# X11 client libraries (VTK links them) travel with the bundle.
system='^(linux-vdso|ld-linux|libc\.|libm\.|libpthread|libdl|librt|libresolv|libGL\.so|libEGL|libOpenGL|libGLX|libGLdispatch|libgbm|libdrm)'
for exe in "$stage"/svo/bin/*; do
  ldd "$exe" | awk '/=> \// {print $1, $3}' | while read -r name path; do
    [[ "$name" =~ $system ]] && continue
    [ -e "$stage/svo/lib/$name" ] || cp -L "$path" "$stage/svo/lib/$name"
  done
  patchelf --set-rpath '$ORIGIN/../lib' "$exe"
done
# svo vtk's module (libsvo_vtk.so), where svo looks for it: the same path from bin as in the build.
module=$(find "$build" -name libsvo_vtk.so -print -quit)
if [ -n "$module" ]; then
  place="$stage/svo/bin/$(realpath -m --relative-to="$build/bin" "$module")"
  mkdir -p "$(dirname "$place")"
  cp "$module" "$place"
  ldd "$place" | awk '/=> \// {print $1, $3}' | while read -r name path; do
    [[ "$name" =~ $system ]] && continue
    [ -e "$stage/svo/lib/$name" ] || cp -L "$path" "$stage/svo/lib/$name"
  done
  patchelf --set-rpath "\$ORIGIN/$(realpath -m --relative-to="$(dirname "$place")" "$stage/svo/lib")" "$place"
fi
for lib in "$stage"/svo/lib/*; do [ -f "$lib" ] && patchelf --set-rpath '$ORIGIN' "$lib"; done
mkdir -p "$(dirname "$out")"
tar -C "$stage" -czf "$out" svo
echo "bundle: $out ($(du -h "$out" | cut -f1)), $(ls "$stage/svo/lib" | wc -l) libraries"
