#!/usr/bin/env bash
# svo beside ParaView's Python on Debian 12 (CI runs this after the README's
# test command; .ci/run). python3-paraview conflicts with python3-vtk9, which
# libvtk9-dev depends on, so installing it removes VTK's development package;
# scripts/setup.sh then builds `svo vtk` against VTK's headers unpacked from
# that package (cmake/svoVTK.cmake). Then the README's two commands again: the
# first whole, the second with the tests labelled vtk (those that load VTK, and
# paraview_reads, which opens svo's files in pvbatch) and no fuzzers, since
# nothing else builds differently beside ParaView.
set -euo pipefail
cd "$(dirname "$0")/.."
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if ! dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends python3-paraview
fi
bash scripts/setup.sh run
SVO_FUZZ_RUNS=0 SVO_CTEST_ARGS="-L vtk" bash scripts/setup.sh test
