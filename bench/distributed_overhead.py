"""svo.distributed's overhead: a 1-worker local cluster against one process,
the same job (issue 43; target written before measuring: within 1.2x the
one process's wall time at 512^3 and up).

    PYTHONPATH=build/python /usr/bin/python3 bench/distributed_overhead.py MESH [N ...] [--kinds surface,sdf]

One process: svo.read_mesh, then a warm Voxelizer's call (the best of
--repeat). Cluster: the arrays given to svo.distributed.voxelize on a
LocalCluster of one one-thread worker process started beforehand (the
cluster's start is printed apart), the best of --repeat, tiles as
svo.distributed plans them (default) or --tile. Prints a Markdown table.
"""
import argparse
import time

import svo
import svo.distributed


def one_process(voxelizer, v, t, kind, n):
    if kind == "surface":
        return voxelizer.voxelize(v, t, resolution=n).grid
    if kind == "sdf":
        return voxelizer.level_set(v, t, resolution=n).grid
    if kind == "udf":
        return voxelizer.level_set(v, t, resolution=n, unsigned=True).grid
    return voxelizer.solid(v, t, resolution=n).grid


def best(f, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - start)
    return min(times), out


def main():
    from distributed import Client, LocalCluster

    p = argparse.ArgumentParser()
    p.add_argument("mesh")
    p.add_argument("sizes", nargs="*", type=int, default=[256, 512])
    p.add_argument("--kinds", default="surface,sdf")
    p.add_argument("--repeat", type=int, default=2)
    p.add_argument("--tile", type=int)
    p.add_argument("--workers", type=int, default=1)
    a = p.parse_args()
    v, t = svo.read_mesh(a.mesh)
    print(f"mesh {a.mesh}: {len(t)} triangles; workers {a.workers}")
    start = time.perf_counter()
    with LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        client.wait_for_workers(a.workers)
        print(f"cluster start {time.perf_counter() - start:.2f} s")
        voxelizer = svo.Voxelizer()
        print("| kind | N | one process s | cluster s | ratio | tiles | active voxels |")
        print("|---|---|---|---|---|---|---|")
        for kind in a.kinds.split(","):
            for n in a.sizes:
                one_process(voxelizer, v, t, kind, 64)  # warm
                t1, g1 = best(lambda: one_process(voxelizer, v, t, kind, n), a.repeat)
                tiles = []
                t2, g2 = best(lambda: svo.distributed.voxelize(
                    (v, t), client=client, kind=kind, resolution=n, tile=a.tile,
                    progress=lambda done, total: tiles.append(total)), a.repeat)
                assert g1.activeVoxelCount() == g2.activeVoxelCount()
                print(f"| {kind} | {n} | {t1:.2f} | {t2:.2f} | {t2 / t1:.2f} | {tiles[-1]} | {g1.activeVoxelCount()} |",
                      flush=True)


if __name__ == "__main__":
    main()
