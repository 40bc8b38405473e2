#!/usr/bin/env python3
"""Start-up of one `svo voxelize` process: EGL set-up and programs, with the
program cache (SVO_PROGRAM_CACHE) and the driver's own shader cache each empty
or warm.

Each run is a new process on a small mesh, so start-up is most of it. The
driver's cache is pointed at a folder of the script's (Mesa:
MESA_SHADER_CACHE_DIR; NVIDIA: __GL_SHADER_DISK_CACHE_PATH), "empty" meaning a
fresh folder per run. Reports medians of --runs runs per case as JSON and a
markdown table.

  python3 bench/startup.py --svo build/bin/svo --machine cpu-2core-llvmpipe
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
from pathlib import Path

CASES = [
    # name, program cache, driver cache
    ("cold: both caches empty", "empty", "empty"),
    ("program cache empty, driver cache warm", "empty", "warm"),
    ("program cache warm, driver cache empty", "warm", "empty"),
    ("warm: both caches warm", "warm", "warm"),
    ("program cache off, driver cache warm", "off", "warm"),
]


def run(svo, args, program_cache, driver_cache, out_json):
    env = dict(os.environ)
    env["SVO_PROGRAM_CACHE"] = program_cache
    env["MESA_SHADER_CACHE_DIR"] = driver_cache
    env["__GL_SHADER_DISK_CACHE_PATH"] = driver_cache
    env["__GL_SHADER_DISK_CACHE_SKIP_CLEANUP"] = "1"
    cmd = [svo, "voxelize"] + args + ["--repeat", "1", "-o", str(out_json.with_suffix(".vdb")), "--json", str(out_json)]
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
    return json.loads(out_json.read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--mesh", default="", help="mesh file (default: the built-in Cornell box)")
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--machine", required=True, help="results go to bench/results/MACHINE/startup.*")
    ap.add_argument("--out", default="", help="write startup.* here instead")
    a = ap.parse_args()
    args = ([a.mesh] if a.mesh else []) + ["-r", str(a.res)]
    out_dir = Path(a.out) if a.out else Path(__file__).resolve().parent / "results" / a.machine
    out_dir.mkdir(parents=True, exist_ok=True)

    rows = []
    renderer = ""
    with tempfile.TemporaryDirectory(prefix="svo_startup_") as tmp:
        tmp = Path(tmp)
        warm_programs, warm_driver = tmp / "warm_programs", tmp / "warm_driver"
        run(a.svo, args, str(warm_programs), str(warm_driver), tmp / "prime.json")  # fills both warm caches
        for name, programs, driver in CASES:
            samples = []
            for i in range(a.runs):
                fresh = tmp / f"{len(rows)}_{i}"
                fresh.mkdir()  # Mesa makes only the last folder of its cache path
                p = {"empty": str(fresh / "programs"), "warm": str(warm_programs), "off": "off"}[programs]
                d = str(fresh / "driver") if driver == "empty" else str(warm_driver)
                r = run(a.svo, args, p, d, tmp / "run.json")
                renderer = r["renderer"]
                stage = {s["name"]: s["wall_ms"] for s in r["stages"]}
                s = r["startup"]
                samples.append({
                    "egl_ms": s["egl_ms"],
                    "program_ms": s["program_ms"],
                    "compiled": s["programs_compiled"],
                    "loaded": s["programs_loaded"],
                    "first_gpu_stages_ms": stage.get("voxelize", 0) + stage.get("octree build", 0),
                    "total_ms": r["total_wall_ms"],
                })
            med = {k: statistics.median(x[k] for x in samples) for k in samples[0]}
            rows.append({"case": name, "runs": a.runs, "median": med, "samples": samples})

    (out_dir / "startup.json").write_text(json.dumps({"renderer": renderer, "args": args, "rows": rows}, indent=2) + "\n")
    lines = [
        f"Start-up of `svo voxelize {' '.join(args)}` in a new process, {renderer}; medians of {a.runs} runs.",
        "",
        "| case | EGL set-up ms | programs ms | compiled / loaded | voxelize + octree build ms | command total ms |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        m = r["median"]
        lines.append(f"| {r['case']} | {m['egl_ms']:.1f} | {m['program_ms']:.1f} | {m['compiled']:.0f} / {m['loaded']:.0f} "
                     f"| {m['first_gpu_stages_ms']:.1f} | {m['total_ms']:.1f} |")
    lines += [
        "",
        "EGL set-up and programs: `VoxelizeStats::startup`. Voxelize + octree build: the first call's GPU stages",
        "(wall), where a driver that compiles machine code at the first draw or dispatch (llvmpipe) pays for it;",
        "only the driver's own cache keeps that. Command total: `svo voxelize`'s total (mesh, call, .vdb write),",
        "without loading the process. Run by `bench/startup.py`.",
    ]
    (out_dir / "startup.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
