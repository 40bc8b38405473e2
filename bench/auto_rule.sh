#!/usr/bin/env bash
# What Backend::Auto should run on a machine whose GL is a software renderer:
# each kind of output on each backend, whole `svo voxelize` processes, median
# wall time and peak memory of N runs. The table it prints is
# bench/results/cpu-2core-llvmpipe/auto_rule.md.
#
#   bench/auto_rule.sh [svo] [runs]     (from the repository root, machine quiet)
set -euo pipefail
svo=${1:-build/bin/svo}
runs=${2:-3}
meshes=${MESHES:-"../shared/meshes/stanford-bunny.obj ../shared/meshes/japanese-temple.obj ../shared/meshes/ogre.obj"}
sizes=${SIZES:-"128 256 512"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Median wall seconds and peak MB of `runs` runs of svo voxelize with the given arguments.
measure() {
  local walls=() mems=()
  for _ in $(seq "$runs"); do
    rm -f "$work/out.vdb"
    /usr/bin/time -f "%e %M" -o "$work/time" "$svo" voxelize "$@" -o "$work/out.vdb" >/dev/null 2>"$work/err" ||
      { echo "failed: svo voxelize $*" >&2; cat "$work/err" >&2; return 1; }
    read -r wall kb <"$work/time"
    walls+=("$wall") mems+=("$((kb / 1024))")
  done
  local w m
  w=$(printf '%s\n' "${walls[@]}" | sort -g | sed -n "$(((runs + 1) / 2))p")
  m=$(printf '%s\n' "${mems[@]}" | sort -g | sed -n "$(((runs + 1) / 2))p")
  echo "$w $m"
}

echo "| mesh | N | kind | raster s | compute s | cpu s | auto s | raster MB | cpu MB | cpu / raster |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"
for mesh in $meshes; do
  for n in $sizes; do
    for kind in surface fog attributes; do
      case $kind in
        surface) extra=() ;;
        fog) extra=(--fog) ;;
        attributes) extra=(--attributes normal,triangle) ;;
      esac
      read -r rw rm < <(measure "$mesh" -r "$n" --backend raster "${extra[@]}")
      read -r cw _ < <(measure "$mesh" -r "$n" --backend compute "${extra[@]}")
      read -r pw pm < <(measure "$mesh" -r "$n" --backend cpu "${extra[@]}")
      read -r aw _ < <(measure "$mesh" -r "$n" "${extra[@]}") # the default: what auto picks
      ratio=$(awk -v a="$pw" -v b="$rw" 'BEGIN { printf "%.2f", a / b }')
      echo "| $(basename "$mesh" .obj) | $n | $kind | $rw | $cw | $pw | $aw | $rm | $pm | $ratio |"
    done
  done
done
