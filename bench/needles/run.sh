#!/usr/bin/env bash
# One needle and one quad through both GPU backends: voxel counts and wall
# times of whole `svo voxelize` runs (median of 3), for bench/results/<machine>/needles.md.
#   bash bench/needles/run.sh SVO_BINARY [OUT_DIR]
set -euo pipefail
svo=$1
out=${2:-.}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| mesh | -r | backend | voxels | voxelize ms (GPU) | wall s (median of 3) |\n|---|---:|---|---:|---:|---:|\n'
for job in "seg 1024" "seg 4096" "seg 16384" "quad 4096"; do
  set -- $job
  for backend in raster compute; do
    walls=()
    for i in 1 2 3; do
      start=$(date +%s.%N)
      "$svo" voxelize "$here/$1.obj" -r "$2" --backend "$backend" --topology mask -o "$tmp/x.vdb" --json "$tmp/x.json" > "$tmp/log" 2>&1
      end=$(date +%s.%N)
      walls+=("$(awk -v a="$start" -v b="$end" 'BEGIN{print b-a}')")
    done
    median=$(printf '%s\n' "${walls[@]}" | sort -g | sed -n 2p)
    voxels=$(python3 -c "import json;d=json.load(open('$tmp/x.json'));print(d['voxels'])" 2>/dev/null || grep -m1 voxels "$tmp/log")
    gpu=$(python3 -c "import json;d=json.load(open('$tmp/x.json'));print(next((s.get('gpu_ms') for s in d['stages'] if s['name']=='voxelize'),''))" 2>/dev/null || true)
    printf '| %s | %s | %s | %s | %s | %.2f |\n' "$1" "$2" "$backend" "$voxels" "$gpu" "$median"
  done
done
