#!/usr/bin/env bash
# A level set's .nvdb end to end on the GPU host (issue 45): this build, whose
# level sets of closed meshes are laid out by the GPU builder, against the
# build before it (SVO_OLD: its svo binary, rpath $ORIGIN/../lib, run from the
# bundle's bin), which read the band back and laid it out on the CPU. In one
# run: wall ms of a fresh process (median of RUNS), one `-v` stage table of
# each, and the two files compared byte for byte (they must be equal).
# Expected figures: bench/nanovdb_expected.md. With the old binary carried
# gzipped in .gl (carry ["bundle", ".gl"]):
#   gunzip -c .gl/svo_old.gz > /tmp/svo_old
#   OUT=dir SVO_OLD=/tmp/svo_old [RES="512 1024 2048"] [RUNS=3] bash bench/gpu_host_sdf_nvdb.sh
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
wall() { # exe mesh n file: ms of one fresh process
  local t0 t1
  t0=$(date +%s%N)
  "$bin/$1" voxelize "$2" -r "$3" --sdf -o "$4" >/dev/null 2>"$work/err.txt" || { cat "$work/err.txt" >&2; echo -1; return; }
  t1=$(date +%s%N)
  echo $(( (t1 - t0) / 1000000 ))
}
gpu=$(nvidia-smi --query-gpu=name --format=csv,noheader | head -1)
{
  echo "# SDF .nvdb end to end on $gpu: GPU builder (new) against the CPU layout (old)"
  echo
  echo "| mesh | N | sign | new ms | old ms | gain | bytes | same bytes |"
  echo "|---|---|---|---|---|---|---|---|"
} | tee "$out/sdf_nvdb.md"
for mesh in bundle/meshes/spot.obj "$work/icosphere.obj" .gl/meshes/elephant.off .gl/meshes/fandisk.off \
            bundle/meshes/stanford-bunny.obj; do
  name=$(basename "${mesh%.*}")
  for n in ${RES:-512 1024 2048}; do
    new=$(for r in $(seq "${RUNS:-3}"); do wall svo "$mesh" "$n" "$work/new.nvdb"; done | median)
    old=$(for r in $(seq "${RUNS:-3}"); do wall svo_old "$mesh" "$n" "$work/old.nvdb"; done | median)
    same=no
    cmp -s "$work/new.nvdb" "$work/old.nvdb" && same=yes
    for exe in svo svo_old; do
      { echo "== $exe $name $n"; "$bin/$exe" voxelize "$mesh" -r "$n" --sdf -o "$work/v.nvdb" -v 2>&1; } >> "$out/stages.txt"
    done
    sign=$(tac "$out/stages.txt" | grep -m1 "^  sign" | awk '{print $2}' | tr -d :)
    gain=$(awk -v a="$old" -v b="$new" 'BEGIN {if (b > 0) printf "%.2f", a / b; else print "-"}')
    bytes=$(stat -c %s "$work/new.nvdb")
    echo "| $name | $n | $sign | $new | $old | $gain | $bytes | $same |" | tee -a "$out/sdf_nvdb.md"
  done
done
