#!/usr/bin/env bash
# On the GPU host: shader variants against the built-in shaders, in one run,
# without a rebuild. Each variant is a folder of shader files that replace
# the embedded ones of the same name (SVO_SHADER_DIR, docs/design.md). For
# each mesh and size: the warm stage medians of `svo voxelize ... --repeat R
# -v` (STAGE's GPU ms, default "band distance"), and the output compared
# byte for byte with the built-in shaders' (a variant must not change a bit).
#   OUT=dir VARIANTS="dir1 dir2" [MESHES="a.obj icosphere ..."] [RES="1024 2048"] [REPEAT=5]
#     [ARGS="--udf --band 3"] [STAGE="band distance"] bash bench/gpu_host_shader_ab.sh
set -uo pipefail
source "$(dirname "$0")/gpu_host_env.sh"
"$bin/svo" scene icosphere --level 8 -o "$work/icosphere.obj" >/dev/null
stage=${STAGE:-band distance}
ms() { # the stage's GPU ms in a -v stage table
  grep -m1 "^  $stage " "$1" | awk '{for (i = 1; i <= NF; ++i) if ($i ~ /^[0-9.]+$/) {print $i; exit}}'
}
{
  echo "| mesh | N | variant | $stage GPU ms | same bytes |"
  echo "|---|---|---|---|---|"
} | tee "$out/shader_ab.md"
for mesh in ${MESHES:-bundle/meshes/stanford-bunny.obj icosphere bundle/meshes/spot.obj}; do
  [ "$mesh" = icosphere ] && mesh="$work/icosphere.obj" # svo's 1.3 M-triangle scene, made here
  name=$(basename "${mesh%.*}")
  for n in ${RES:-1024 2048}; do
    for v in builtin ${VARIANTS:?folders of shader files}; do
      dir=$([ "$v" = builtin ] && echo "" || echo "$v")
      log="$out/${name}_${n}_$(basename "$v").txt"
      SVO_SHADER_DIR="$dir" "$bin/svo" voxelize "$mesh" -r "$n" ${ARGS:---udf --band 3} --repeat "${REPEAT:-5}" \
        -o "$work/$(basename "$v").nvdb" -v > "$log" 2>&1 || { echo "$v failed: $(tail -3 "$log")" >&2; continue; }
      same=yes
      [ "$v" = builtin ] || cmp -s "$work/builtin.nvdb" "$work/$(basename "$v").nvdb" || same=no
      echo "| $name | $n | $(basename "$v") | $(ms "$log") | $same |" | tee -a "$out/shader_ab.md"
    done
  done
done
