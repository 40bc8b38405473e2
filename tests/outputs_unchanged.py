#!/usr/bin/python3
"""Byte identity of svo's outputs: a fixed list of svo commands, each output hashed.

What it proves: every file (and `svo info`'s stdout) that the commands below
write has the same SHA-256, after the narrow normalisations listed further
down, as the reference in tests/outputs_unchanged.sha256. A refactor that
passes it changed no output byte of these commands: .vdb, .nvdb and .svo
files of every voxelize mode, convert's outputs, `svo info`'s text, `svo
validate --json` reports, `svo vtk`'s VTK XML files and picture, and `svo view`
screenshots.

The reference is tied to the machine's software: Mesa llvmpipe (svo runs on
EGL's software device here, SVO_EGL_DEVICE=software), its LLVM, and the
OpenVDB, NanoVDB, VTK, zlib and libpng versions. The reference file's header
names the renderer it was made with; a mismatch on another renderer is no
proof of a change in svo.

Run (ctest runs it as `outputs_unchanged`):
  /usr/bin/python3 tests/outputs_unchanged.py --svo build/bin/svo \
      --work /tmp/outputs_unchanged --hashes tests/outputs_unchanged.sha256

Regenerate the reference only when an output is meant to change, and say in
that commit which outputs change and why:
  /usr/bin/python3 tests/outputs_unchanged.py --svo build/bin/svo \
      --work /tmp/outputs_unchanged --hashes tests/outputs_unchanged.sha256 --update

--skip-vtk and --skip-validate leave out the commands of a build without
`svo vtk` (SVO_WITH_VTK=OFF) or `svo validate` (SVO_WITH_VALIDATE=OFF); their
reference lines are then reported as skipped, not compared. --update refuses
them, so the reference always holds every output.

Normalised before hashing (found by running every command twice and comparing
the bytes; everything else was identical run to run):
  * .vdb files: the 36-character UUID OpenVDB writes into every file header
    (random per file, openvdb::io::Archive) at bytes 21..56, after the magic,
    file version, library version and has-grid-offsets fields. Exactly those
    bytes, and only after checking they are a UUID, are replaced by zeros.
  * `svo validate --json`: the values of "gpu_ms", "validation_seconds" and,
    in --sdf's "openvdb" block, "seconds" are wall-clock and GPU timings.
  * `svo voxelize --json`: the values of "gpu_ms" and "wall_ms" (per stage),
    "egl_ms" and "program_ms" (start-up), "total_wall_ms" (timings) and
    "peak_rss_mb" (the process's peak resident memory, which moves with
    allocator and thread timing).
  In JSON only numeric values of those keys become the string "<varies>"; the
  keys stay in place (a key that disappears or moves still changes the hash)
  and a null (a stage with no GPU time) stays null.
Not hashed: the stdout and stderr of commands other than `svo info` (voxelize's
and validate's print stage timings); the files they write are hashed instead.

The environment of every command is fixed: SVO_EGL_DEVICE=software (llvmpipe
even where a GPU exists), SVO_PROGRAM_CACHE=off (no GL program binaries from
earlier runs; every run compiles the same programs), DISPLAY and
WAYLAND_DISPLAY removed (`svo vtk --png` then draws through an Xvfb of its own,
never a desktop's GL; `svo view --screenshot` is headless EGL either way, as in
tests/test_cli.cpp), LC_ALL=C. Every command runs in <work>/outputs with
relative paths, so no path of the work folder reaches an output.
"""
import argparse
import hashlib
import os
import re
import shutil
import subprocess
import sys
import time

# (name, svo arguments, outputs, needs): an output is a file name the command
# writes, or "stdout" for its standard output; needs is None, "vtk" or
# "validate". Names are unique: they key the reference file. Commands run in
# this order (later ones read earlier ones' files). -r 64 (-r 32 for the
# slower ones) keeps the whole list within seconds on llvmpipe.
R = ["-r", "64"]
COMMANDS = [
    # Mesh files for the commands that take one: the Cornell box as .off, a
    # closed icosphere (parity signs, a real inside for the hole check) as .obj.
    ("scene_cornell", ["scene", "cornell", "-o", "cornell.off"], ["cornell.off"], None),
    ("scene_icosphere", ["scene", "icosphere", "--level", "3", "-o", "ico.obj"], ["ico.obj"], None),
    # voxelize, the built-in Cornell box.
    ("voxelize_default", ["voxelize", *R, "-o", "default.vdb", "--json", "default.json"],
     ["default.vdb", "default.json"], None),
    ("voxelize_fog", ["voxelize", *R, "--fog", "-o", "fog.vdb"], ["fog.vdb"], None),
    ("voxelize_sdf", ["voxelize", *R, "--sdf", "-o", "sdf.vdb"], ["sdf.vdb"], None),
    ("voxelize_udf", ["voxelize", *R, "--udf", "-o", "udf.vdb"], ["udf.vdb"], None),
    ("voxelize_solid", ["voxelize", *R, "--fill", "solid", "-o", "solid.vdb"], ["solid.vdb"], None),
    ("voxelize_attributes", ["voxelize", *R, "--attributes", "normal,triangle", "-o", "attributes.vdb"],
     ["attributes.vdb", "attributes.triangle.vdb"], None),
    ("voxelize_thin", ["voxelize", *R, "--mode", "thin", "-o", "thin.vdb"], ["thin.vdb"], None),
    ("voxelize_svo", ["voxelize", *R, "-o", "default.svo"], ["default.svo"], None),
    ("voxelize_nvdb", ["voxelize", *R, "-o", "default.nvdb"], ["default.nvdb"], None),
    # voxelize, more of its paths: the other backends, tiles under a GPU
    # budget, MaskGrid topology, fog in .nvdb, attributes in .svo, and mesh files.
    ("voxelize_compute", ["voxelize", *R, "--backend", "compute", "-o", "compute.vdb"], ["compute.vdb"], None),
    ("voxelize_cpu", ["voxelize", *R, "--backend", "cpu", "-o", "cpu.vdb"], ["cpu.vdb"], None),
    ("voxelize_tiles", ["voxelize", *R, "--gpu-memory", "1M", "-o", "tiles.vdb"], ["tiles.vdb"], None),
    ("voxelize_mask", ["voxelize", *R, "--topology", "mask", "-o", "mask.vdb"], ["mask.vdb"], None),
    ("voxelize_fog_nvdb", ["voxelize", *R, "--fog", "-o", "fog.nvdb"], ["fog.nvdb"], None),
    ("voxelize_attributes_svo", ["voxelize", *R, "--attributes", "normal", "triangle", "-o", "attributes.svo"],
     ["attributes.svo"], None),
    ("voxelize_off", ["voxelize", *R, "cornell.off", "--udf", "--closest-triangle", "-o", "cornell_udf.vdb"],
     ["cornell_udf.vdb", "cornell_udf.triangle.vdb"], None),
    ("voxelize_obj_sdf", ["voxelize", *R, "ico.obj", "--sdf", "--closest-triangle", "-o", "ico_sdf.vdb"],
     ["ico_sdf.vdb", "ico_sdf.triangle.vdb"], None),
    ("voxelize_obj_solid", ["voxelize", *R, "ico.obj", "--fill", "solid", "-o", "ico_solid.vdb"],
     ["ico_solid.vdb"], None),
    # convert
    ("convert_vdb_svo", ["convert", "default.vdb", "-o", "convert_vdb.svo"], ["convert_vdb.svo"], None),
    ("convert_svo_vdb", ["convert", "default.svo", "-o", "convert_svo.vdb"], ["convert_svo.vdb"], None),
    ("convert_vdb_nvdb", ["convert", "default.vdb", "-o", "convert_vdb.nvdb"], ["convert_vdb.nvdb"], None),
    ("convert_nvdb_vdb", ["convert", "default.nvdb", "-o", "convert_nvdb.vdb"], ["convert_nvdb.vdb"], None),
    ("convert_svo_nvdb", ["convert", "attributes.svo", "-o", "convert_svo.nvdb"], ["convert_svo.nvdb"], None),
    ("convert_sdf_nvdb", ["convert", "sdf.vdb", "-o", "convert_sdf.nvdb"], ["convert_sdf.nvdb"], None),
    ("convert_topology_svo", ["convert", "attributes.vdb", "--topology-only", "-o", "convert_topology.svo"],
     ["convert_topology.svo"], None),
    ("convert_topology_fog", ["convert", "sdf.vdb", "--topology-only", "--fog", "--topology", "mask",
                              "-o", "convert_topology_fog.vdb"], ["convert_topology_fog.vdb"], None),
    # info: its stdout (no timings in it)
    ("info_vdb", ["info", "default.vdb"], ["stdout"], None),
    ("info_svo", ["info", "default.svo"], ["stdout"], None),
    ("info_nvdb", ["info", "fog.nvdb"], ["stdout"], None),
    ("info_grid", ["info", "attributes.vdb", "--grid", "normal"], ["stdout"], None),
    ("info_mesh", ["info", "-r", "32", "ico.obj"], ["stdout"], None),
    # validate: the JSON report (timings normalised), and the errors grid
    ("validate_default", ["validate", *R, "--json", "validate.json", "--errors", "validate_errors.vdb"],
     ["validate.json", "validate_errors.vdb"], "validate"),
    ("validate_thin", ["validate", *R, "--mode", "thin", "--strict", "--json", "validate_thin.json"],
     ["validate_thin.json"], "validate"),
    ("validate_holes", ["validate", *R, "ico.obj", "--json", "validate_holes.json"], ["validate_holes.json"], "validate"),
    ("validate_sdf", ["validate", "-r", "32", "--sdf", "ico.obj", "--json", "validate_sdf.json"],
     ["validate_sdf.json"], "validate"),
    # vtk: VTK XML files and a picture (Xvfb)
    ("vtk_htg", ["vtk", "default.vdb", "-o", "vtk.htg"], ["vtk.htg"], "vtk"),
    ("vtk_vtu", ["vtk", "default.vdb", "-o", "vtk.vtu"], ["vtk.vtu"], "vtk"),
    ("vtk_vtp_png", ["vtk", "default.svo", "-o", "vtk.vtp", "--png", "vtk.png", "--size", "160"],
     ["vtk.vtp", "vtk.png"], "vtk"),
    ("vtk_mesh_levels", ["vtk", "-r", "32", "ico.obj", "-o", "vtk_ico.htg", "--levels", "1..3"], ["vtk_ico.htg"], "vtk"),
    # view --screenshot: headless EGL
    ("view_default", ["view", *R, "--size", "160x120", "--screenshot", "view.png"], ["view.png"], None),
    ("view_layers", ["view", "default.vdb", "--size", "160x120", "--layers", "voxels,outlines,bricks",
                     "--view", "+x", "--screenshot", "view_layers.png"], ["view_layers.png"], None),
    ("view_normal", ["view", "attributes.svo", "--size", "160x120", "--color", "normal",
                     "--screenshot", "view_normal.png"], ["view_normal.png"], None),
    ("view_ao", ["view", "-r", "32", "--size", "160x120", "--render", "ao", "--screenshot", "view_ao.png"],
     ["view_ao.png"], None),
    ("view_gi", ["view", "-r", "32", "--size", "160x120", "--render", "gi", "--screenshot", "view_gi.png"],
     ["view_gi.png"], None),
    ("view_mesh_direct", ["view", "-r", "32", "ico.obj", "--size", "160x120", "--render", "direct",
                          "--surface", "mesh", "--screenshot", "view_direct.png"], ["view_direct.png"], None),
]

VDB_MAGIC = b"\x20BDV\x00\x00\x00\x00"
UUID = re.compile(rb"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}")
UUID_AT = 21  # magic 8 + file version 4 + library major 4 + minor 4 + has-grid-offsets 1

# JSON keys whose numeric values are timings or memory high-water marks.
VALIDATE_VARYING = ("gpu_ms", "validation_seconds", "seconds")
VOXELIZE_VARYING = ("gpu_ms", "wall_ms", "egl_ms", "program_ms", "total_wall_ms", "peak_rss_mb")
NUMBER = rb"-?[0-9]+(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?"


class Failure(Exception):
    pass


def normalise_vdb(data, name):
    """Zero the header's UUID, the only bytes of a .vdb that vary run to run."""
    if data[:8] != VDB_MAGIC:
        raise Failure(f"{name}: not a .vdb file (no OpenVDB magic)")
    version = int.from_bytes(data[8:12], "little")
    if version < 222:  # older layouts put the UUID elsewhere; svo writes 224
        raise Failure(f"{name}: OpenVDB file version {version}, this test knows the header of 222 and later")
    if not UUID.fullmatch(data[UUID_AT:UUID_AT + 36]):
        raise Failure(f"{name}: no UUID at bytes {UUID_AT}..{UUID_AT + 35} of the header")
    return data[:UUID_AT] + b"0" * 36 + data[UUID_AT + 36:]


def normalise_json(data, keys):
    """Replace the numeric values of the given keys (at any depth) by "<varies>"."""
    pattern = re.compile(rb'("(?:' + b"|".join(re.escape(k.encode()) for k in keys) + rb')": )' + NUMBER)
    return pattern.sub(rb'\1"<varies>"', data)


def normalise(command, output, data):
    if output.endswith(".vdb") or data.startswith(VDB_MAGIC):
        return normalise_vdb(data, output)
    if output.endswith(".json"):
        if command[0] == "validate":
            return normalise_json(data, VALIDATE_VARYING)
        if command[0] == "voxelize":
            return normalise_json(data, VOXELIZE_VARYING)
        raise Failure(f"{output}: no normalisation known for JSON of svo {command[0]}")
    return data


def environment(work):
    env = dict(os.environ)
    for name in ("DISPLAY", "WAYLAND_DISPLAY"):
        env.pop(name, None)
    env.update(SVO_EGL_DEVICE="software", SVO_PROGRAM_CACHE="off", LC_ALL="C")
    return env


def read_reference(path):
    hashes, header = {}, []
    with open(path, encoding="ascii") as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if line.startswith("#") or not line:
                header.append(line)
                continue
            digest, sep, name = line.partition("  ")
            if not sep or not re.fullmatch(r"[0-9a-f]{64}", digest) or name in hashes:
                raise Failure(f"{path}:{n}: not '<sha256>  <output>': {line!r}")
            hashes[name] = digest
    return hashes, header


def renderer(svo, env, cwd):
    """The GL renderer and version that `svo glinfo` reports, for the reference's header."""
    r = subprocess.run([svo, "glinfo"], env=env, cwd=cwd, capture_output=True, text=True)
    fields = dict(line.split(None, 1) for line in r.stdout.splitlines() if len(line.split(None, 1)) == 2)
    return f"{fields.get('renderer', '?')} | {fields.get('version', '?')}"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--svo", required=True, help="the svo binary")
    p.add_argument("--work", required=True, help="scratch folder (its outputs/ is emptied first)")
    p.add_argument("--hashes", required=True, help="reference file, tests/outputs_unchanged.sha256")
    p.add_argument("--update", action="store_true", help="rewrite the reference instead of comparing")
    p.add_argument("--skip-vtk", action="store_true", help="leave out `svo vtk` (SVO_WITH_VTK=OFF)")
    p.add_argument("--skip-validate", action="store_true", help="leave out `svo validate` (SVO_WITH_VALIDATE=OFF)")
    args = p.parse_args()
    skip = {need for need, on in (("vtk", args.skip_vtk), ("validate", args.skip_validate)) if on}
    if args.update and skip:
        p.error("--update needs every command: leave out --skip-vtk and --skip-validate")

    svo = os.path.abspath(args.svo)
    out = os.path.join(os.path.abspath(args.work), "outputs")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    env = environment(out)
    started = time.monotonic()

    if not args.update and not os.path.isfile(args.hashes):
        raise Failure(f"no reference file {args.hashes} (write one with --update)")
    expected, header = ({}, []) if args.update else read_reference(args.hashes)
    here = renderer(svo, env, out)
    actual, failures, mismatches, skipped = {}, [], [], []
    for name, command, outputs, need in COMMANDS:
        line = "svo " + " ".join(command)
        if need in skip:
            skipped += outputs
            print(f"skip      {name}: {line}")
            continue
        t0 = time.monotonic()
        r = subprocess.run([svo, *command], env=env, cwd=out, capture_output=True)
        seconds = time.monotonic() - t0
        if r.returncode != 0:
            failures.append(f"FAILED    {name}: `{line}` exited {r.returncode}\n"
                            + r.stdout.decode(errors="replace") + r.stderr.decode(errors="replace"))
            print(failures[-1])
            continue
        for output in outputs:
            try:
                if output == "stdout":
                    key, data = f"{name}.stdout", r.stdout
                else:
                    key = output
                    with open(os.path.join(out, output), "rb") as f:
                        data = f.read()
                digest = hashlib.sha256(normalise(command, output, data)).hexdigest()
            except (OSError, Failure) as e:
                failures.append(f"FAILED    {name}: `{line}`: {e}")
                print(failures[-1])
                continue
            actual[key] = digest
            want = expected.get(key)
            if args.update or want == digest:
                print(f"{'ok' if not args.update else 'hashed':9s} {digest}  {key}  ({seconds:.2f} s: {line})")
            else:
                mismatches.append(key)
                print(f"MISMATCH  {key} from `{line}`: expected {want or '(not in the reference)'}, got {digest}")

    if args.update:
        if failures:
            print(f"{len(failures)} command(s) failed: the reference is left as it was", file=sys.stderr)
            return 1
        with open(args.hashes, "w", encoding="ascii") as f:
            f.write("# SHA-256 of svo's outputs, written by tests/outputs_unchanged.py --update (see its header\n"
                    "# for the commands and what is normalised). Rewrite only when an output is meant to change.\n"
                    f"# renderer: {here}\n")
            for key in sorted(actual):
                f.write(f"{actual[key]}  {key}\n")
        print(f"wrote {len(actual)} hashes to {args.hashes} in {time.monotonic() - started:.1f} s")
        return 0

    produced = set(actual) | {f"{n}.stdout" if o == "stdout" else o for n, _, os_, _ in COMMANDS for o in os_}
    for key in sorted(set(expected) - produced):
        mismatches.append(key)
        print(f"MISMATCH  {key}: in the reference, but no command of this test writes it")
    made_on = next((h.split(":", 1)[1].strip() for h in header if h.startswith("# renderer:")), None)
    if (failures or mismatches) and made_on and made_on != here:
        print(f"note: the reference was made on '{made_on}', this run is on '{here}': "
              "different rendering software alone changes these bytes")
    print(f"{len(actual)} outputs hashed, {len(mismatches)} mismatched, {len(failures)} failed, "
          f"{len(skipped)} skipped, in {time.monotonic() - started:.1f} s")
    return 1 if failures or mismatches else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as e:
        print(f"outputs_unchanged: {e}", file=sys.stderr)
        sys.exit(1)
