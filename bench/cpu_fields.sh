#!/usr/bin/env bash
# Level sets on the CPU backend (--backend cpu) against the default backend
# (llvmpipe on a machine without a GPU) and vdb_tool -mesh2ls, whole
# processes, mesh file to .vdb: wall seconds and peak RSS from /usr/bin/time
# -v, the median of RUNS runs each (RSS: of the same runs' median). vdb_tool
# gets svo's voxel size (its dim= would count the band's padding).
#
#   bench/cpu_fields.sh [MESH:RES ...]      (default: the cases below)
#   SVO=build/bin/svo RUNS=3 BAND=3 bench/cpu_fields.sh
#   LLVMPIPE=0 bench/cpu_fields.sh    (leaves out the default backend's column)
#
# Prints a Markdown table; svo's stages (wall ms) of the last CPU run per case
# follow it.
set -euo pipefail
SVO=${SVO:-build/bin/svo}
VDB_TOOL=${VDB_TOOL:-/usr/bin/vdb_tool}
RUNS=${RUNS:-3}
BAND=${BAND:-3}
LLVMPIPE=${LLVMPIPE:-1}
MESHES=${MESHES:-../shared/meshes}
CASES=("$@")
[ ${#CASES[@]} -gt 0 ] || CASES=("$MESHES/japanese-temple.obj:256" "$MESHES/stanford-bunny.obj:256"
                                 "$MESHES/stanford-bunny.obj:512" "$MESHES/spot.obj:256" "$MESHES/spot.obj:512")
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# One run: "<wall s> <max RSS MiB>" of the command.
measure() {
    /usr/bin/time -v "$@" >"$TMP/out" 2>"$TMP/time" || { echo "failed: $*" >&2; tail -5 "$TMP/time" >&2; echo "nan nan"; return; }
    local wall rss
    wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + p[i]; print s}' "$TMP/time")
    rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$TMP/time")
    echo "$wall $rss"
}

# RUNS runs: "<median wall s> <its RSS MiB>".
median() {
    for _ in $(seq "$RUNS"); do measure "$@"; done | sort -g | awk '{w[NR] = $1; r[NR] = $2} END {m = int((NR + 1) / 2); print w[m], r[m]}'
}

echo "| mesh | grid | sign | svo --backend cpu: s, MiB | svo default (llvmpipe): s, MiB | vdb_tool -mesh2ls: s, MiB | llvmpipe / cpu | vdb_tool / cpu |"
echo "|---|---|---|---|---|---|---|---|"
STAGES=""
for c in "${CASES[@]}"; do
    mesh=${c%:*} res=${c##*:}
    name=$(basename "$mesh" .obj)
    "$SVO" voxelize "$mesh" -r "$res" --sdf --band "$BAND" --backend cpu -o "$TMP/cpu.vdb" --json "$TMP/cpu.json" >/dev/null
    read -r size sign < <(python3 -c "import json, sys; j = json.load(open(sys.argv[1])); print(repr(j['voxel_size']), j['sign'].split(':')[0])" "$TMP/cpu.json")
    read -r cw cr < <(median "$SVO" voxelize "$mesh" -r "$res" --sdf --band "$BAND" --backend cpu -o "$TMP/cpu.vdb" --json "$TMP/cpu.json")
    if [ "$LLVMPIPE" = 1 ]; then
        read -r gw gr < <(median "$SVO" voxelize "$mesh" -r "$res" --sdf --band "$BAND" -o "$TMP/gpu.vdb")
    else
        gw=nan gr=-
    fi
    read -r pw pr < <(median "$VDB_TOOL" -read "$mesh" -mesh2ls "voxel=$size" "width=$BAND" -write "$TMP/peer.vdb")
    ratio() { python3 -c "import math, sys; a, b = map(float, sys.argv[1:]); print('-' if math.isnan(a / b) else f'{a / b:.2f}')" "$1" "$2"; }
    echo "| $name | ${res}³ | $sign | $cw, $cr | $gw, $gr | $pw, $pr | $(ratio "$gw" "$cw") | $(ratio "$pw" "$cw") |"
    STAGES+="$name ${res}³ (voxel size $size), --backend cpu stages (wall ms): "
    STAGES+=$(python3 -c "import json, sys; print(', '.join(f\"{s['name']} {s['wall_ms']:.0f}\" for s in json.load(open(sys.argv[1]))['stages']))" "$TMP/cpu.json")
    STAGES+=$'\n'
done
echo
echo "$STAGES"
