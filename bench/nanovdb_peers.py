#!/usr/bin/env python3
"""svo's NanoVDB grids against NanoVDB's own CUDA MeshToGrid, in one run.

For every mesh and resolution N (svo's --resolution; the harness takes the
same voxel size, bench/nanovdb_mesh_to_grid.cu):
  topology, band 3   MeshToGrid getHandle()            svo --fill band --band 3 --topology mask
  UDF, band 3        MeshToGrid getHandleAndUDF()      svo --udf --band 3
  surface            MeshToGrid band 0                 svo's conservative surface
  surface's ball     MeshToGrid band 0.867 (sqrt(3)/2) svo's conservative surface (must be a subset)
GPU ms: MeshToGrid's CUDA events around the call, median of --runs after a
warm-up; svo's stage GPU times (timer queries), medians of --repeat after a
warm-up. End to end: one process each, mesh file to .nvdb (svo) or the
harness's read + upload + convert + download + write. "before": svo's host
path of today's main for the same .nvdb, a .vdb written and converted by
`svo convert` (NanoVDB's openToNanoVDB). Voxel sets: voxels in both, only in
svo, only in MeshToGrid (the harness reads svo's .nvdb).

  python3 bench/nanovdb_peers.py --svo BIN/svo --m2g BIN/m2g --res 256 512 --md out.md MESH.obj ...
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time


def run(cmd, timeout):
    """(returncode, wall ms, stdout) of one child process."""
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, timeout * 1000.0, ""
    if p.returncode != 0:
        sys.stderr.write(f"{' '.join(cmd)}: exit {p.returncode}: {p.stderr.strip()[-400:]}\n")
    return p.returncode, (time.perf_counter() - t0) * 1000.0, p.stdout


def svo_gpu_ms(report):
    """Sum of the stages' GPU times (null where a stage is not on the GPU)."""
    return sum(s["gpu_ms"] for s in report["stages"] if s.get("gpu_ms") is not None)


def svo_run(a, mesh, res, args, out, tmp):
    """svo timed (--repeat) and end to end (one cold process); its report."""
    js = os.path.join(tmp, "svo.json")
    rc, _, _ = run([a.svo, "voxelize", mesh, "-r", str(res)] + args + ["--repeat", str(a.runs), "-o", out, "--json", js],
                   a.timeout)
    if rc != 0:
        return None
    with open(js) as f:
        report = json.load(f)
    rc, wall, _ = run([a.svo, "voxelize", mesh, "-r", str(res)] + args + ["-o", out], a.timeout)
    report["end_to_end_ms"] = wall if rc == 0 else None
    return report


def m2g_run(a, mesh, res, band, udf, compare, tmp):
    cmd = [a.m2g, mesh, "-r", str(res), "--band", str(band), "--runs", str(a.runs), "--out", os.path.join(tmp, "m2g.nvdb")]
    if udf:
        cmd.append("--udf")
    if compare:
        cmd += ["--compare", compare]
    rc, wall, out = run(cmd, a.timeout)
    if rc != 0 or not out.strip():
        return None
    r = json.loads(out.strip().splitlines()[-1])
    r["process_ms"] = wall
    return r


def before_ms(a, mesh, res, args, tmp):
    """Today's host path to the same .nvdb: .vdb, then svo convert (openToNanoVDB)."""
    vdb, nvdb = os.path.join(tmp, "before.vdb"), os.path.join(tmp, "before.nvdb")
    rc1, w1, _ = run([a.svo, "voxelize", mesh, "-r", str(res)] + args + ["-o", vdb], a.timeout)
    rc2, w2, _ = run([a.svo, "convert", vdb, "-o", nvdb], a.timeout)
    return w1 + w2 if rc1 == 0 and rc2 == 0 else None


HALF_DIAGONAL = 0.867  # a voxel's circumscribed sphere, sqrt(3)/2 voxels, and a margin for float rounding


def stage_gpu_ms(report, name):
    return next((s["gpu_ms"] for s in report["stages"] if s["name"] == name and s.get("gpu_ms") is not None), None)


def fmt(v, digits=1):
    return "—" if v is None else f"{v:.{digits}f}"


def ratio(num, den):
    return "—" if not num or not den else f"{num / den:.2f}×"


def write_md(path, title, band, runs, rows):
    """The tables of every row so far (rewritten after each row, so a run cut
    short by its time limit still leaves its table)."""
    with open(path + ".tmp", "w") as f:
        f.write(f"# {title}\n\nBand {band:g}, medians of {runs} runs after a warm-up; "
                "ratio = MeshToGrid / svo (above 1: svo faster). GPU ms: the mesh already on the GPU.\n\n")
        f.write("## Topology: svo's `--fill band` (ValueMask) against MeshToGrid's getHandle()\n\n"
                "| mesh | N | svo band GPU ms | of which band distance / grid | MeshToGrid topology GPU ms | ratio "
                "| voxels both / only svo / only MeshToGrid | svo band .nvdb end to end ms |\n|" + "---|" * 8 + "\n")
        for r in rows:
            b, t = r.get("svo_band"), r["m2g_topology"]
            g = svo_gpu_ms(b) if b else None
            sets = f"{t['both']} / {t['only_svo']} / {t['only_meshtogrid']}" if t and "both" in t else "—"
            split = (f"{fmt(stage_gpu_ms(b, 'band distance'))} / {fmt(stage_gpu_ms(b, 'nanovdb grid (gpu)'))}"
                     if b else "—")
            f.write(f"| {r['mesh']} | {r['res']} | {fmt(g)} | {split} | {fmt(t and t['gpu_ms_median'])} "
                    f"| {ratio(t and t['gpu_ms_median'], g)} | {sets} | {fmt(b and b['end_to_end_ms'])} |\n")
        f.write("\n## Unsigned distances: svo's `--udf` against MeshToGrid's getHandleAndUDF()\n\n"
                "| mesh | N | svo UDF GPU ms | of which band distance / grid | MeshToGrid UDF GPU ms | ratio "
                "| UDF max diff | svo .nvdb end to end ms | before ms | gain | MeshToGrid end to end ms |\n|" + "---|" * 11 + "\n")
        for r in rows:
            s, u = r["svo_udf"], r["m2g_udf"]
            g = svo_gpu_ms(s) if s else None
            e2e = s["end_to_end_ms"] if s else None
            split = (f"{fmt(stage_gpu_ms(s, 'band distance'))} / {fmt(stage_gpu_ms(s, 'nanovdb grid (gpu)'))}"
                     if s else "—")
            f.write(f"| {r['mesh']} | {r['res']} | {fmt(g)} | {split} "
                    f"| {fmt(u and u['gpu_ms_median'])} | {ratio(u and u['gpu_ms_median'], g)} "
                    f"| {fmt(u and u.get('udf_max_abs_diff'), 6)} | {fmt(e2e)} | {fmt(r['before_udf_ms'])} "
                    f"| {ratio(r['before_udf_ms'], e2e)} | {fmt(u and u['end_to_end_ms'])} |\n")
        f.write("\n## Surface: svo's conservative surface against MeshToGrid with band 0\n\n")
        f.write("| mesh | N | svo GPU ms | MeshToGrid GPU ms | ratio | voxels both / only svo / only MeshToGrid "
                "| band 0.867 (√3/2): both / only svo / only MeshToGrid |\n|---|---|---|---|---|---|---|\n")
        for r in rows:
            s, m = r["svo_surface"], r["m2g_surface"]
            g = svo_gpu_ms(s) if s else None
            sets = f"{m['both']} / {m['only_svo']} / {m['only_meshtogrid']}" if m and "both" in m else "—"
            h = r.get("m2g_half_diagonal")
            ball = f"{h['both']} / {h['only_svo']} / {h['only_meshtogrid']}" if h and "both" in h else "—"
            f.write(f"| {r['mesh']} | {r['res']} | {fmt(g)} | {fmt(m and m['gpu_ms_median'])} "
                    f"| {ratio(m and m['gpu_ms_median'], g)} | {sets} | {ball} |\n")
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--svo", default="build/bin/svo")
    ap.add_argument("--m2g", required=True, help="bench/nanovdb_mesh_to_grid.cu built with nvcc")
    ap.add_argument("--res", type=int, nargs="+", default=[256, 512, 1024, 2048, 4096])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--band", type=float, default=3.0)
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--md", required=True)
    ap.add_argument("--json", help="every measurement, one object per line")
    ap.add_argument("--title", default="svo NanoVDB output against NanoVDB's MeshToGrid")
    ap.add_argument("--from-jsonl", help="write --md from the JSON lines of an earlier run, running nothing")
    a = ap.parse_args()
    if a.from_jsonl:
        with open(a.from_jsonl) as f:
            write_md(a.md, a.title, a.band, a.runs, [json.loads(l) for l in f if l.strip()])
        return 0
    rows = []
    log = open(a.json, "w") if a.json else None
    for mesh in a.meshes:
        for res in a.res:
            with tempfile.TemporaryDirectory() as tmp:
                udf_nvdb, surf_nvdb = os.path.join(tmp, "udf.nvdb"), os.path.join(tmp, "surface.nvdb")
                band_nvdb = os.path.join(tmp, "band.nvdb")
                udf_args = ["--udf", "--band", str(a.band)]
                s_udf = svo_run(a, mesh, res, udf_args, udf_nvdb, tmp)
                s_band = svo_run(a, mesh, res, ["--fill", "band", "--band", str(a.band), "--topology", "mask"],
                                 band_nvdb, tmp)
                # ValueMask topology: the harness compares mask or float grids.
                s_surf = svo_run(a, mesh, res, ["--topology", "mask"], surf_nvdb, tmp)
                m_top = m2g_run(a, mesh, res, a.band, False, band_nvdb if s_band else None, tmp)
                m_udf = m2g_run(a, mesh, res, a.band, True, udf_nvdb if s_udf else None, tmp)
                m_surf = m2g_run(a, mesh, res, 0.0, False, surf_nvdb if s_surf else None, tmp)
                # Every voxel whose cube meets a triangle has its centre within
                # half the cube's diagonal of it: MeshToGrid's band sqrt(3)/2
                # must hold svo's conservative surface (none only in svo's).
                m_ball = m2g_run(a, mesh, res, HALF_DIAGONAL, False, surf_nvdb if s_surf else None, tmp)
                b_udf = before_ms(a, mesh, res, udf_args, tmp)
                row = dict(mesh=os.path.basename(mesh), res=res, svo_udf=s_udf, svo_band=s_band, svo_surface=s_surf, m2g_topology=m_top,
                           m2g_udf=m_udf, m2g_surface=m_surf, m2g_half_diagonal=m_ball,
                           before_udf_ms=b_udf)
                rows.append(row)
                if log:
                    log.write(json.dumps(row) + "\n")
                    log.flush()
                print(f"{row['mesh']} {res}: svo udf {fmt(s_udf and svo_gpu_ms(s_udf))} GPU ms, "
                      f"band {fmt(s_band and svo_gpu_ms(s_band))}, "
                      f"m2g topology {fmt(m_top and m_top['gpu_ms_median'])}, udf {fmt(m_udf and m_udf['gpu_ms_median'])}",
                      flush=True)
                write_md(a.md, a.title, a.band, a.runs, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
