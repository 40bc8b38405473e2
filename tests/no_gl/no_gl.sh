#!/usr/bin/env bash
# svo on a machine with no GL: run by ctest (label no_gl) as
#   no_gl.sh <case> <svo> <python dir> <hide_gl.so>
# where <case> is
#   ldd        svo, svo-mesh-to-volume and the Python module need no GL or EGL library
#   cli        svo voxelize (default, --fog, --attributes normal) runs on the CPU and
#              writes what --backend cpu writes; --backend raster|compute, view and
#              glinfo fail with one line
#   python     the module imports, voxelizes on the CPU, and refuses raster in one error
#   no_driver  libEGL loads but no display gives a context (GLVND with no vendor):
#              auto still runs on the CPU; raster and a named --device fail in one line
#   level_set  svo voxelize --sdf and --fill solid with --backend auto succeed
# GL is hidden by bind-mounting an empty file over every GL and EGL library in a
# user and mount namespace of its own (unshare -rm: root or not, nothing outside
# changes), or, where unshare is refused (some containers), by hide_gl.so, an
# LD_PRELOAD shim whose dlopen refuses them (SVO_NO_GL_HOW=preload forces it).
# Either way the case first proves
# that libEGL.so.1 cannot be loaded.
set -euo pipefail
what=$1 svo=$2 pydir=$3 shim=$4
bindir=$(dirname "$svo")
gl_pattern='lib(EGL|OpenGL|GL|GLX|GLdispatch|GLES[^ ]*)(_[a-z]+)?\.so'

fail() { echo "no_gl $what: $*" >&2; exit 1; }

if [ "$what" = ldd ]; then
  module=$(ls "$pydir"/svo/_svo*.so)
  for f in "$svo" "$bindir/svo-mesh-to-volume" "$module"; do
    [ -e "$f" ] || continue
    if found=$(ldd "$f" | grep -E "$gl_pattern"); then fail "$f needs GL: $found"; fi
    echo "$f: no GL library ($(ldd "$f" | wc -l) libraries)"
  done
  exit 0
fi

if [ "$what" = no_driver ]; then
  # libEGL loads but GLVND finds no vendor library, so no display gives a context.
  export __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/no_vendor.json SVO_NO_GL_HIDDEN="no EGL vendor library"
fi
if [ "${SVO_NO_GL_HIDDEN:-}" = "" ]; then
  # SVO_NO_GL_HOW=preload takes the shim even where unshare works (its own test case).
  if [ "${SVO_NO_GL_HOW:-}" != preload ] && unshare -rm true 2>/dev/null; then
    SVO_NO_GL_HIDDEN=namespace exec unshare -rm bash "$0" "$@"
  fi
  SVO_NO_GL_HIDDEN=preload LD_PRELOAD=$shim exec bash "$0" "$@"
fi
if [ "$SVO_NO_GL_HIDDEN" = namespace ]; then
  empty=$(mktemp)
  # Each GL library the loader knows, by every name it has: the files they resolve to.
  for path in $(ldconfig -p | awk '{print $NF}' | grep -E "/$gl_pattern"); do
    real=$(readlink -f "$path")
    mount --bind "$empty" "$real"
  done
fi
export SVO_NO_GL_HIDDEN
# Proof that GL is gone, through the dlopen svo (libepoxy) uses.
if [ "$what" != no_driver ] && /usr/bin/python3 -c 'import ctypes; ctypes.CDLL("libEGL.so.1")' 2>/dev/null; then
  fail "libEGL.so.1 still loads: GL is not hidden ($SVO_NO_GL_HIDDEN)"
fi
echo "GL hidden by $SVO_NO_GL_HIDDEN"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export SVO_PROGRAM_CACHE=off

# expect_one_line_failure <words in the message> <command...>: exits non-zero, one stderr line.
expect_one_line_failure() {
  local words=$1
  shift
  if "$@" >out.txt 2>err.txt; then fail "$* succeeded without GL"; fi
  [ "$(wc -l <err.txt)" = 1 ] || fail "$* wrote $(wc -l <err.txt) lines to stderr: $(cat err.txt)"
  grep -q -- "$words" err.txt || fail "$* said: $(cat err.txt)"
  echo "refused: $* -> $(cat err.txt)"
}

case "$what" in
  cli)
    for flags in "" "--fog" "--attributes normal"; do
      name=$(echo "auto $flags" | tr -c 'a-z\n' _)
      # shellcheck disable=SC2086 # the flags are words
      "$svo" voxelize -r 48 -v $flags -o "$name.vdb" >"$name.txt" || fail "svo voxelize $flags failed: $(cat "$name.txt")"
      grep -qE "^  backend +cpu" "$name.txt" || fail "svo voxelize $flags did not say it ran on the CPU: $(cat "$name.txt")"
      # shellcheck disable=SC2086
      "$svo" voxelize -r 48 $flags --backend cpu -o "cpu_$name.vdb" >/dev/null
      # The same bytes but the header's UUID (bytes 21..56), which differs run to run.
      cmp <(head -c 21 "$name.vdb"; tail -c +58 "$name.vdb") <(head -c 21 "cpu_$name.vdb"; tail -c +58 "cpu_$name.vdb") ||
        fail "svo voxelize $flags: auto and --backend cpu differ"
      echo "voxelize $flags: on the CPU, as --backend cpu"
    done
    expect_one_line_failure "OpenGL is not available" "$svo" voxelize -r 16 --backend raster -o r.vdb
    expect_one_line_failure "OpenGL is not available" "$svo" voxelize -r 16 --backend compute -o c.vdb
    expect_one_line_failure "svo view needs OpenGL" "$svo" view --screenshot v.png
    expect_one_line_failure "svo view needs OpenGL" "$svo" view
    expect_one_line_failure "svo glinfo needs OpenGL" "$svo" glinfo
    [ ! -e r.vdb ] && [ ! -e c.vdb ] && [ ! -e v.png ] || fail "a refused command wrote its output"
    ;;
  python)
    PYTHONPATH=$pydir /usr/bin/python3 - <<'PY'
import numpy as np
import svo

v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
auto = set(map(tuple, svo.active_voxels(svo.voxelize(v, t, resolution=24).grid).tolist()))
cpu = set(map(tuple, svo.active_voxels(svo.voxelize(v, t, resolution=24, backend="cpu").grid).tolist()))
assert auto and auto == cpu, "auto without GL is not the CPU's voxels"
assert svo.Voxelizer().voxelize(v, t, resolution=24, attributes=["normal"]) is not None
for backend in ("raster", "compute"):
    try:
        svo.voxelize(v, t, resolution=8, backend=backend)
    except RuntimeError as e:
        assert "OpenGL is not available" in str(e) and "\n" not in str(e), str(e)
    else:
        raise AssertionError(backend + " ran without GL")
print(f"python: {len(auto)} voxels on the CPU; raster and compute refused")
PY
    ;;
  no_driver)
    "$svo" voxelize -r 32 -v -o auto.vdb >auto.txt || fail "svo voxelize failed: $(cat auto.txt)"
    grep -qE "^  backend +cpu" auto.txt || fail "svo voxelize did not say it ran on the CPU: $(cat auto.txt)"
    expect_one_line_failure "cannot create a headless OpenGL 4.5 core context" "$svo" voxelize -r 16 --backend raster -o r.vdb
    # A device the caller names is not given up for the CPU.
    expect_one_line_failure "cannot create a headless OpenGL 4.5 core context" "$svo" voxelize -r 16 --device software -o s.vdb
    ! ls "$pydir"/svo/_svo*.so >/dev/null 2>&1 || PYTHONPATH=$pydir /usr/bin/python3 -c '
import numpy as np, svo
v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
assert len(svo.active_voxels(svo.voxelize(v, t, resolution=16).grid)) > 0'
    echo "no EGL display: voxelize on the CPU; raster and a named device refused"
    ;;
  level_set)
    "$svo" voxelize -r 32 --sdf -o sdf.vdb >sdf.txt || fail "svo voxelize --sdf failed: $(cat sdf.txt)"
    "$svo" voxelize -r 32 --fill solid -o solid.vdb >solid.txt || fail "svo voxelize --fill solid failed: $(cat solid.txt)"
    echo "level set and solid: on the CPU"
    ;;
  *) fail "no such case" ;;
esac
