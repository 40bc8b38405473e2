#!/usr/bin/env bash
# svo setup on Debian 12: install dependencies, build, then run a job.
#   bash scripts/setup.sh run    # build, then `svo voxelize` on the built-in scene
#   bash scripts/setup.sh test   # build, then the whole test suite through ctest, then the fuzzers
#                                #   (SVO_FUZZ_RUNS per target, default 600000; 0 skips them;
#                                #   SVO_CTEST_ARGS adds ctest arguments, such as -L vtk)
# Idempotent: packages already present are skipped by apt, and the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-run}
case "$mode" in run|test|build) ;; *) echo "usage: $0 run|test|build" >&2; exit 2 ;; esac

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libopenvdb-dev libopenvdb-tools libboost-iostreams-dev libtbb-dev
  libopenmesh-dev libcgal-dev libcgal-demo
  libglfw3-dev libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libvtk9-dev xvfb xauth libpng-dev libimgui-dev
  libcli11-dev libfmt-dev libgtest-dev libfast-float-dev
  pybind11-dev python3-dev python3-pytest python3-numpy python3-distributed python3-venv python3-pip
  nlohmann-json3-dev libnanovdb-dev libnanovdb-tools libblosc-dev zlib1g-dev python3-openvdb libboost-python1.74-dev
  libembree-dev libtinygltf-dev libdraco-dev
  assimp-utils assimp-testmodels
)
# The fuzz targets need clang and its libFuzzer runtime.
[ "$mode" = test ] && packages+=(clang-14 libclang-rt-14-dev)
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
# ParaView's Python (python3-paraview) conflicts with python3-vtk9, which
# libvtk9-dev depends on. Beside it, `svo vtk` is built against VTK's headers
# unpacked from libvtk9-dev (below) and libvtk9.1's libraries, which do not
# conflict (cmake/svoVTK.cmake).
beside_paraview=false
if installed python3-paraview; then
  beside_paraview=true
  packages=("${packages[@]/#libvtk9-dev/libvtk9.1}")
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
missing=()
for p in "${packages[@]}"; do installed "$p" || missing+=("$p"); done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# unpack PACKAGE[=VERSION] FOLDER DEST: copies FOLDER of the package's files
# into DEST, without installing the package.
unpack() {
  local tmp
  tmp=$(mktemp -d)
  (cd "$tmp" && { apt-get download -q "$1" || { $sudo apt-get update -q && apt-get download -q "$1"; }; } &&
     dpkg-deb -x ./*.deb root)
  $sudo mkdir -p "$3"
  $sudo cp -r "$tmp/root/$2/." "$3/"
  rm -rf "$tmp"
}

# Dear ImGui's GLFW and OpenGL 3 backends ship as sources under /usr/share/doc,
# which minimal images leave out (dpkg path-exclude): unpack them from the
# package into /usr/local/share/svo/imgui-backends then.
if [ ! -f /usr/share/doc/libimgui-dev/examples/backends/imgui_impl_glfw.cpp ] &&
   [ ! -f /usr/local/share/svo/imgui-backends/imgui_impl_glfw.cpp ]; then
  unpack libimgui-dev usr/share/doc/libimgui-dev/examples/backends /usr/local/share/svo/imgui-backends
fi
# VTK's headers beside ParaView, of the very version of the installed
# libraries: unpacked again when libvtk9.1 has changed since (the version
# they came with is kept beside them).
if $beside_paraview; then
  vtk_version=$(dpkg-query -W -f='${Version}' libvtk9.1)
  vtk_headers=/usr/local/share/svo/vtk-9.1
  if [ "$(cat "$vtk_headers/version" 2>/dev/null)" != "$vtk_version" ]; then
    $sudo rm -rf "$vtk_headers/include"
    unpack "libvtk9-dev=$vtk_version" usr/include/vtk-9.1 "$vtk_headers/include"
    echo "$vtk_version" | $sudo tee "$vtk_headers/version" >/dev/null
  fi
fi

# The layer diagram (docs/design.md) before anything is built: a dependency
# that reaches up fails the tests at once.
[ "$mode" = test ] && python3 scripts/check_layers.py

build=${SVO_BUILD_DIR:-build}
# Paths under the checkout reach ccache as relative ones, so that a clone in
# another folder (CI's) reuses what an earlier build compiled.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
# Debian's own Python: the one python3-openvdb (pyopenvdb) is built for.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build "$build" --parallel "$(nproc)"

case "$mode" in
  run)
    "$build/bin/svo" voxelize -o "${SVO_OUTPUT:-cornell_box.vdb}" ;;
  test)
    # SVO_CTEST_ARGS: extra ctest arguments, such as a label (-L vtk).
    # shellcheck disable=SC2086
    ctest --test-dir "$build" --output-on-failure --timeout 1500 ${SVO_CTEST_ARGS:-}
    runs=${SVO_FUZZ_RUNS:-600000}
    [ "$runs" = 0 ] || bash scripts/fuzz.sh "$runs" ;;
  build) ;;
  *) echo "usage: $0 run|test|build" >&2; exit 2 ;;
esac
