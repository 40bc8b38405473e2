"""The city benchmark of svo.distributed (issue 43): `svo scene city` of N
triangles voxelized at R^3 on a LocalCluster, one .vdb per tile (output_dir)
so that no process holds the whole grid.

    PYTHONPATH=build/python /usr/bin/python3 bench/distributed_city.py \
        --svo build/bin/svo --triangles 10000000 --resolution 8192 --kinds surface,sdf --workers 2 --out /tmp/city

Per kind: wall seconds of svo.distributed.voxelize (the cluster started
beforehand, its start printed apart), the tiles, the active voxels, the
bytes of the tile files and per active voxel, and the peak resident memory
of each worker and of the client (ru_maxrss of each process, so the peak
over the whole run so far: kinds are run in the order given, each on a
fresh cluster). The mesh is read once on the client and given as arrays, so
a surface's triangles are cut to the tiles on the workers. Prints a
Markdown table.
"""
import argparse
import os
import resource
import shutil
import subprocess
import time

import svo
import svo.distributed


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def folder_bytes(path):
    return sum(os.path.getsize(os.path.join(path, f)) for f in os.listdir(path) if f.endswith(".vdb"))


def main():
    from distributed import Client, LocalCluster

    p = argparse.ArgumentParser()
    p.add_argument("--svo", default="build/bin/svo")
    p.add_argument("--triangles", type=int, default=10_000_000)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--resolution", type=int, default=8192)
    p.add_argument("--kinds", default="surface,sdf")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--tile", type=int)
    p.add_argument("--out", default="/tmp/svo-city")
    p.add_argument("--keep", action="store_true", help="keep the tile folders")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    mesh = os.path.join(a.out, f"city-{a.triangles}-{a.seed}.obj")
    if not os.path.exists(mesh):
        start = time.perf_counter()
        subprocess.run([a.svo, "scene", "city", "--triangles", str(a.triangles), "--seed", str(a.seed), "-o", mesh,
                        "-q"], check=True)
        print(f"scene: {time.perf_counter() - start:.1f} s, {os.path.getsize(mesh) / 1e6:.0f} MB")
    start = time.perf_counter()
    v, t = svo.read_mesh(mesh)
    print(f"mesh {mesh}: {len(t)} triangles, read in {time.perf_counter() - start:.1f} s; "
          f"{a.workers} workers; {a.resolution}^3")
    rows = []
    for kind in a.kinds.split(","):
        folder = os.path.join(a.out, f"tiles-{kind}-{a.resolution}")
        shutil.rmtree(folder, ignore_errors=True)
        start = time.perf_counter()
        with LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                          dashboard_address=":0") as cluster, Client(cluster) as client:
            client.wait_for_workers(a.workers)
            print(f"{kind}: cluster start {time.perf_counter() - start:.1f} s", flush=True)
            start = time.perf_counter()
            index = svo.distributed.voxelize((v, t), client=client, kind=kind, resolution=a.resolution,
                                             tile=a.tile, output_dir=folder, timeout=None,
                                             progress=lambda done, total, left: print(
                                                 f"  tiles {done}/{total}" + (f", {left:.0f} s left" if left else ""),
                                                 flush=True))
            wall = time.perf_counter() - start
            workers = client.run(peak_mib)
        size = folder_bytes(folder)
        voxels = index["active_voxels"]
        rows.append((kind, wall, len(index["tiles"]), sum(1 for e in index["tiles"] if e["file"]), voxels, size,
                     size / max(voxels, 1), max(workers.values()), peak_mib()))
        if not a.keep:
            shutil.rmtree(folder, ignore_errors=True)
    print("| kind | wall s | tiles (files) | active voxels | tile files MB | bytes/voxel | worker peak MiB | "
          "client peak MiB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for kind, wall, tiles, files, voxels, size, per, worker, client in rows:
        print(f"| {kind} | {wall:.1f} | {tiles} ({files}) | {voxels:,} | {size / 1e6:.0f} | {per:.2f} | "
              f"{worker:.0f} | {client:.0f} |")


if __name__ == "__main__":
    main()
