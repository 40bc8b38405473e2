#!/usr/bin/python3
"""The README's "Use" block, run as written, top to bottom, in a fresh folder.

What it proves: every command line of the block (the ```sh block under
"## Use") exits 0 when run in order in one folder, each in its own bash,
as a user would paste them: the outputs of earlier lines (bunny.svo,
city.obj) are the inputs of later ones, and outputs that exist are replaced.
A line whose comment holds "[GPU host]" needs a real GPU (work a software
renderer cannot do in a test's time); it is run where `svo glinfo` names a
GPU and skipped, and reported as skipped, on Mesa's llvmpipe, softpipe or
where there is no GL at all.

The folder holds what the block names but does not make, small stand-ins
made here: bunny.obj (a closed icosphere), part.stl and mesh.ply (the same
sphere, scaled by 20, as ASCII STL and PLY), mesh.off (the Cornell box, with
its colours), in.vdb and in.svo (the Cornell box voxelized at resolution 64),
and build/bin/svo, a link to the svo under test.

Run (ctest runs it as `readme_use`):
  /usr/bin/python3 tests/readme_use.py --svo build/bin/svo --readme README.md \
      --work /tmp/readme_use
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

GPU_MARK = "[GPU host]"


def use_block(readme):
    """The command lines of the first ```sh block after "## Use"."""
    text = open(readme, encoding="utf-8").read()
    at = text.find("\n## Use\n")
    if at < 0:
        raise SystemExit(f"{readme}: no '## Use' section")
    match = re.search(r"```sh\n(.*?)```", text[at:], re.S)
    if not match:
        raise SystemExit(f"{readme}: no ```sh block under '## Use'")
    return [line for line in match.group(1).splitlines() if line.strip() and not line.lstrip().startswith("#")]


def run(cmd, cwd, env):
    return subprocess.run(cmd, cwd=cwd, env=env, shell=isinstance(cmd, str), executable="/bin/bash" if
                          isinstance(cmd, str) else None, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, errors="replace")


def read_obj(path):
    vertices, faces = [], []
    for line in open(path):
        part = line.split()
        if part and part[0] == "v":
            vertices.append(tuple(float(x) for x in part[1:4]))
        elif part and part[0] == "f":
            faces.append(tuple(int(x.split("/")[0]) - 1 for x in part[1:4]))
    return vertices, faces


def write_stl(path, vertices, faces):
    with open(path, "w") as f:
        f.write("solid part\n")
        for t in faces:
            a, b, c = (vertices[i] for i in t)
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            f.write(f" facet normal {n[0]:g} {n[1]:g} {n[2]:g}\n  outer loop\n")
            for p in (a, b, c):
                f.write(f"   vertex {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")
            f.write("  endloop\n endfacet\n")
        f.write("endsolid part\n")


def write_ply(path, vertices, faces):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(vertices)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        for p in vertices:
            f.write(f"{p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")
        for t in faces:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def on_gpu_host(svo, env):
    """Whether `svo glinfo` names a hardware renderer."""
    r = run([svo, "glinfo"], None, env)
    if r.returncode != 0:
        return False
    renderer = re.search(r"^renderer\s+(.*)$", r.stdout, re.M)
    return bool(renderer) and not re.search(r"llvmpipe|softpipe|swrast", renderer.group(1), re.I)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--svo", required=True)
    ap.add_argument("--readme", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    svo = os.path.abspath(args.svo)
    lines = use_block(args.readme)

    env = dict(os.environ, LC_ALL="C")
    env.pop("DISPLAY", None)  # svo vtk --png draws through an Xvfb of its own
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "build", "bin"))
    os.symlink(svo, os.path.join(work, "build", "bin", "svo"))

    # The stand-ins for the user's files.
    for setup in (["scene", "icosphere", "--level", "3", "-o", "bunny.obj"], ["scene", "cornell", "-o", "mesh.off"],
                  ["voxelize", "-r", "64", "-o", "in.vdb"], ["voxelize", "-r", "64", "-o", "in.svo"]):
        r = run([svo, *setup, "-q"], work, env)
        if r.returncode != 0:
            raise SystemExit(f"setup svo {' '.join(setup)} failed:\n{r.stdout}")
    vertices, faces = read_obj(os.path.join(work, "bunny.obj"))
    big = [tuple(20 * x for x in p) for p in vertices]
    write_stl(os.path.join(work, "part.stl"), big, faces)
    write_ply(os.path.join(work, "mesh.ply"), big, faces)

    gpu = on_gpu_host(svo, env)
    passed, failed, skipped = 0, [], 0
    for n, line in enumerate(lines, 1):
        if GPU_MARK in line and not gpu:
            print(f"[{n:2}] skipped (needs a GPU host): {line}")
            skipped += 1
            continue
        t0 = time.monotonic()
        r = run(line, work, env)
        seconds = time.monotonic() - t0
        if r.returncode == 0:
            passed += 1
            print(f"[{n:2}] ok {seconds:6.1f} s: {line}")
        else:
            failed.append(n)
            print(f"[{n:2}] FAILED (exit {r.returncode}, {seconds:.1f} s): {line}\n{r.stdout}")
    if not lines:
        raise SystemExit("the Use block holds no command")
    print(f"{passed} passed, {len(failed)} failed, {skipped} skipped")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
