"""Dask only, no svo: the deadlock behind issue 43 (a worker killed in a tile task).

svo.distributed's whole-mesh path in miniature: a mesh held as a task's
result (_hold), a plan task, 125 tile tasks that each depend on _hold. A
worker plugin SIGKILLs the worker running the first tile task. On Dask
2022.11 up to 2024.6.0 (Debian bookworm: 2022.12.1) the tiles are queued on
the scheduler (root-ish), and when _hold dies with its only worker they stay
queued on it (dask/distributed#8702); the job never finishes. The script
then prints the scheduler's and the workers' states (after WATCH seconds)
and faulthandler ends it at 120 s.

    NW=1 python3 bench/distributed_kill_repro.py          # hangs (2 of 2 runs)
    NW=1 FIX=1 python3 bench/distributed_kill_repro.py    # svo's fix: a loose worker restriction; finishes
    NW=2 python3 bench/distributed_kill_repro.py          # hung 1 run in 37

NW: workers; FIX: restrict the tiles (addresses here; svo uses hosts, see
svo.distributed._placement); FIRST: seconds the first tile of a worker
sleeps (a GL context's start).
"""
import faulthandler, logging, os, sys, tempfile, threading, time, pprint
import numpy as np
import distributed
from distributed import as_completed

def _hold(data):
    return data

def _plan_task(mesh, n):
    v, t = mesh
    return [((i, 0, 0), (i + 8, 8, 8)) for i in range(n)]

_first = [True]
def _tile_task(mesh, box):
    if _first[0]:
        _first[0] = False
        time.sleep(float(os.environ.get("FIRST", "0")))
    v, t = mesh
    s = 0.0
    end = time.monotonic() + 0.05
    while time.monotonic() < end:
        s += float(v.sum())
    return np.full(1000, box[0][0])

class KillOnce(distributed.WorkerPlugin):
    name = "kill-once"
    def __init__(self, marker):
        self.marker = marker
    def transition(self, key, start, finish, **kwargs):
        if finish != "executing" or not str(key).startswith("_tile_task"):
            return
        try:
            fd = os.open(self.marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            return
        import signal
        def kill_in_task():
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline:
                for frame in sys._current_frames().values():
                    while frame is not None and frame.f_code.co_name != "_tile_task":
                        frame = frame.f_back
                    if frame is not None:
                        os.write(fd, f"{key} {os.getpid()}".encode())
                        os.close(fd)
                        os.kill(os.getpid(), signal.SIGKILL)
                time.sleep(0.001)
        threading.Thread(target=kill_in_task, daemon=True).start()

def watch(c):
    time.sleep(float(os.environ.get("WATCH", "70")))
    def sched(dask_scheduler):
        out = {"workers": {a: (ws.status.name, sorted(str(t.key) for t in ws.processing)[:5], len(ws.processing), sorted(str(t.key) for t in ws.has_what)[:5], ws.pid)
                           for a, ws in dask_scheduler.workers.items()}}
        states = {}
        for k, ts in dask_scheduler.tasks.items():
            states.setdefault(ts.state, []).append(str(k))
        out["states"] = {k: (len(v), v[:4]) for k, v in states.items()}
        out["hold"] = {str(k): (ts.state, [w.address for w in ts.who_has], ts.processing_on and ts.processing_on.address, ts.suspicious)
                       for k, ts in dask_scheduler.tasks.items() if str(k).startswith("_hold")}
        out["queued"] = len(dask_scheduler.queued)
        out["unrunnable"] = len(dask_scheduler.unrunnable)
        hk = [k for k in dask_scheduler.tasks if str(k).startswith("_hold")]
        out["hold_story"] = [str(x) for x in dask_scheduler.story(*hk)][-40:]
        return out
    print("=== scheduler", pprint.pformat(c.run_on_scheduler(sched), width=220), flush=True)
    def wst(dask_worker):
        s = dask_worker.state
        states = {}
        for k, ts in s.tasks.items():
            states.setdefault(ts.state, []).append(str(k))
        hk = [k for k in s.tasks if str(k).startswith("_hold")]
        return {"states": {k: (len(v), v[:3]) for k, v in states.items()},
                "hold": {str(k): (s.tasks[k].state, sorted(map(str, s.tasks[k].who_has))) for k in hk},
                "executing": [str(t.key) for t in s.executing], "in_flight_workers": {str(k): list(map(str,v)) for k,v in s.in_flight_workers.items()},
                "busy": list(s.busy_workers),
                "story": [str(x) for x in dask_worker.state.story(*hk)][-40:]}
    print("=== workers", pprint.pformat(c.run(wst), width=220), flush=True)

def main():
    faulthandler.dump_traceback_later(120, exit=True)
    marker = tempfile.mktemp()
    rng = np.random.default_rng(0)
    mesh = (rng.random((300, 3)), rng.integers(0, 300, (600, 3)))
    t0 = time.monotonic()
    with distributed.LocalCluster(n_workers=int(os.environ.get("NW", "2")), threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
        c.wait_for_workers(int(os.environ.get("NW", "2")), timeout=60)
        c.register_worker_plugin(KillOnce(marker))
        held = c.submit(_hold, mesh, pure=False)
        boxes = c.submit(_plan_task, held, 125, pure=False).result()
        threading.Thread(target=watch, args=(c,), daemon=True).start()
        extra = {}
        if os.environ.get("FIX"):
            extra = dict(workers=list(c.scheduler_info()["workers"]), allow_other_workers=True)
        futures = [c.submit(_tile_task, held, b, pure=False, **extra) for b in boxes]
        got = []
        for f in as_completed(futures):
            got.append(int(f.result()[0]))
            f.release()
        assert sorted(got) == list(range(125)), got
        print("job done", time.monotonic() - t0, open(marker).read(), flush=True)
        c.wait_for_workers(int(os.environ.get("NW", "2")), timeout=60)
        print("workers back", time.monotonic() - t0, flush=True)
    print("closed", time.monotonic() - t0, flush=True)

if __name__ == "__main__":
    main()
