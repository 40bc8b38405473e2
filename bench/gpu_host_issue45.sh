#!/usr/bin/env bash
# On the GPU host, in one device call: what remains of issue 45's runs, each
# step under its own time limit so that a slow one leaves the others' results
# (each in its own folder, with its log), packed into one archive in OUT at
# the end (a folder of many files does not come back from the device). The
# bundle (scripts/bundle.sh, with test_gpu_nano_grid, test_level_set,
# test_regions, svo-bench-nanovdb-gpu and nanovdb_validate), bundle/meshes,
# bundle/peers, the loader debs and .gl/svo_old.gz carried.
#   rm -f bundle/svo-bundle.tar.gz; bash scripts/bundle.sh build bundle/svo-bundle.tar.gz \
#     build/tests/test_gpu_nano_grid build/tests/test_level_set build/tests/test_regions \
#     build/bin/svo-bench-nanovdb-gpu /usr/bin/nanovdb_validate
#   OUT=dir [STEPS="builder peers sdf udf4096 peers4096"] [M2G=/tmp/m2g] bash bench/gpu_host_issue45.sh
# The limits add up past one device call's 600 s: calls on the same warm
# machine, STEPS="builder peers" then STEPS="peers2048 peers4096", then
# STEPS="sdf udf4096" (M2G keeps the MeshToGrid harness between them).
# Steps (expected figures: bench/nanovdb_expected.md):
#   builder   the builder's suites and timing (gpu_host_nano_builder.sh, 2048³)
#   peers     MeshToGrid side by side, six meshes, 512³ and 1024³
#   peers2048 the same at 2048³
#   sdf       old (70cf151) against new end to end: level sets, solids, channels
#   udf4096   the bunny's UDF at 4096³, regions' bricks against the old OpenVDB route
#   peers4096 MeshToGrid side by side at 4096³ (bunny, spot, icosphere)
#   passes    where the NanoVDB builder's time goes (gpu_host_nano_passes.sh)
#   quick     MeshToGrid side by side, the bunny and spot at 1024³ and 2048³
set -uo pipefail
out=${OUT:?a folder for the archive of the results}
top=$(mktemp -d /tmp/issue45.XXXXXX)
m2g=${M2G:-/tmp/m2g}
[ -f .gl/svo_old.gz ] && gunzip -c .gl/svo_old.gz > /tmp/svo_old
[ -f bundle/meshes/ogre.obj ] && mkdir -p .gl/meshes && cp bundle/meshes/ogre.obj .gl/meshes/
step() { # name, limit in seconds, script, then its VAR=value settings
  local name=$1 limit=$2 script=$3
  shift 3
  mkdir -p "$top/$name"
  echo "== $name (at most ${limit} s)"
  env OUT="$top/$name" "$@" timeout "$limit" bash "$script" > "$top/$name/log.txt" 2>&1
  echo "   exit $? after $SECONDS s in all"
}
for s in ${STEPS:-builder peers peers2048 peers4096 sdf udf4096}; do
  case $s in
  builder) step builder 120 bench/gpu_host_nano_builder.sh RES=2048 ;;
  peers) step peers 420 bench/gpu_host_nanovdb.sh "RES=512 1024" RUNS=3 M2G="$m2g" ;;
  peers2048) step peers2048 330 bench/gpu_host_nanovdb.sh RES=2048 RUNS=3 M2G="$m2g" ;;
  sdf) step sdf 240 bench/gpu_host_sdf_nvdb.sh SVO_OLD=/tmp/svo_old "KINDS=sdf solid channels" "RES=1024 2048" ;;
  udf4096) step udf4096 90 bench/gpu_host_sdf_nvdb.sh SVO_OLD=/tmp/svo_old KINDS=udf RES=4096 \
      MESHES=bundle/meshes/stanford-bunny.obj ;;
  peers4096) step peers4096 360 bench/gpu_host_nanovdb.sh RES=4096 RUNS=3 "MESHES=bunny spot icosphere" M2G="$m2g" ;;
  passes) step passes 120 bench/gpu_host_nano_passes.sh ;;
  quick) step quick 120 bench/gpu_host_nanovdb.sh "RES=1024 2048" RUNS=3 "MESHES=bunny spot" M2G="$m2g" ;;
  *) echo "gpu_host_issue45: unknown step $s" >&2 ;;
  esac
done
mkdir -p "$out"
tar czf "$out/issue45-$(date +%H%M%S).tgz" -C "$top" . && echo "results: $out/issue45-*.tgz"
