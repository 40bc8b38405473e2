#!/usr/bin/env bash
# Level sets', solids' and surface channels' .nvdb end to end on the GPU
# host (issue 45): this build, which lays them out on the GPU builder (level
# sets signed by parity or winding numbers, solids, normals and triangle
# ids), against the build before (SVO_OLD: 70cf151's
# svo binary, rpath $ORIGIN/../lib, run from the bundle's bin), which laid
# them all out on the CPU.
# In one run: wall ms of a fresh process (median of RUNS), one `-v` stage
# table of each, and the two files compared byte for byte (they must be
# equal). Expected figures: bench/nanovdb_expected.md. With the old binary
# carried gzipped in .gl, and the open meshes (ogre, japanese-temple) copied
# into .gl/meshes from ../shared/meshes (carry ["bundle", ".gl"]):
#   gunzip -c .gl/svo_old.gz > /tmp/svo_old
#   OUT=dir SVO_OLD=/tmp/svo_old [RES="512 1024 2048"] [RUNS=3] [KINDS="sdf solid channels"] [MESHES="a.obj icosphere"] bash bench/gpu_host_sdf_nvdb.sh
# KINDS may also name udf (--udf --band 3: past one shader buffer at 4096³ on
# an H200, the regions' bricks joined against the build before's OpenVDB route).
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
cp "${SVO_OLD:?the svo binary of the build before}" "$bin/svo_old"
chmod +x "$bin/svo_old"
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.obj" >/dev/null
# Fill both program caches first (a fresh machine compiles every program once).
for exe in svo svo_old; do
  "$bin/$exe" voxelize bundle/meshes/spot.obj -r 64 --sdf -o "$work/warm.nvdb" >/dev/null 2>&1
done
median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
flags() { # a kind's options: sdf, solid, channels (a surface with its fog, normals and triangle ids), or udf
  case "$1" in
    solid) echo "--fill solid" ;; channels) echo "--fog --attributes normal triangle" ;; udf) echo "--udf --band 3" ;;
    *) echo "--sdf" ;;
  esac
}
wall() { # exe mesh n file kind: ms of one fresh process
  local t0 t1
  t0=$(date +%s%N)
  "$bin/$1" voxelize "$2" -r "$3" $(flags "$5") -o "$4" >/dev/null 2>"$work/err.txt" || { cat "$work/err.txt" >&2; echo -1; return; }
  t1=$(date +%s%N)
  echo $(( (t1 - t0) / 1000000 ))
}
gpu=$(nvidia-smi --query-gpu=name --format=csv,noheader | head -1)
{
  echo "# Level set and solid .nvdb end to end on $gpu: GPU builder (new) against the CPU layout (old)"
  echo
  echo "| kind | mesh | N | sign | new ms | old ms | gain | bytes | same bytes |"
  echo "|---|---|---|---|---|---|---|---|---|"
} | tee "$out/sdf_nvdb.md"
for kind in ${KINDS:-sdf solid channels}; do
all="bundle/meshes/spot.obj $work/icosphere.obj .gl/meshes/elephant.off bundle/meshes/fandisk.obj
     bundle/meshes/stanford-bunny.obj .gl/meshes/ogre.obj .gl/meshes/japanese-temple.obj"
for mesh in ${MESHES:-$all}; do
  [ "$mesh" = icosphere ] && mesh="$work/icosphere.obj"
  [ -f "$mesh" ] || { echo "missing $mesh" >&2; continue; }
  name=$(basename "${mesh%.*}")
  for n in ${RES:-512 1024 2048}; do
    new=$(for r in $(seq "${RUNS:-3}"); do wall svo "$mesh" "$n" "$work/new.nvdb" "$kind"; done | median)
    old=$(for r in $(seq "${RUNS:-3}"); do wall svo_old "$mesh" "$n" "$work/old.nvdb" "$kind"; done | median)
    same=no
    cmp -s "$work/new.nvdb" "$work/old.nvdb" && same=yes
    for exe in svo svo_old; do
      { echo "== $exe $kind $name $n"; "$bin/$exe" voxelize "$mesh" -r "$n" $(flags "$kind") -o "$work/v.nvdb" -v 2>&1; } >> "$out/stages.txt"
    done
    sign=$(tac "$out/stages.txt" | grep -m1 "^  sign" | awk '{print $2}' | tr -d :)
    gain=$(awk -v a="$old" -v b="$new" 'BEGIN {if (b > 0) printf "%.2f", a / b; else print "-"}')
    bytes=$(stat -c %s "$work/new.nvdb")
    echo "| $kind | $name | $n | $sign | $new | $old | $gain | $bytes | $same |" | tee -a "$out/sdf_nvdb.md"
  done
done
done
