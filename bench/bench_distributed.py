"""Scale-out on this machine: udm1.distributed against single-process runs of the same work,
side by side in one run, and the per-task overhead that bounds it.

1. A path-tracing render (udm1-pt, built-in Cornell box, --size, --spp, sobol-owen), split into
   --tasks sample ranges, on a LocalCluster of 1 and 2 worker processes (1 thread each), against
   the tool alone with --threads 1 and 2 (the anchors). Every distributed image is checked equal
   to the tool's own, bit for bit.
2. A Monte Carlo integral (udm1.integrate, genz-gaussian in 8D, wr, --n points) the same way.
3. Overheads: a Dask round trip per task (a no-op task, 1 worker: the scheduler, the transport
   and the Python call), and the fixed cost of one render task (the tool's start, scene load and
   BVH: one pixel, one sample), and the merge of the parts.
4. The projection for N machines of c = 2 cores that follows from them, with the tree merge of
   udm1.distributed.render (see project()).

Writes JSON and a plot (time against workers, measured and projected) to --out.

    python bench/bench_distributed.py [--size 256x256] [--spp 256] [--tasks 16] [--n 16777216] [--out DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

import udm1  # noqa: E402
import udm1.distributed as ud  # noqa: E402


def log(msg: str) -> None:
    print(f"[bench_distributed] {msg}", file=sys.stderr, flush=True)


def timed(fn, reps: int = 1):
    best, out = float("inf"), None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def gauss(x):
    return udm1.integrand("genz-gaussian", x)


def noop(k):
    return k


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tool", default=str(ROOT / "build" / "bin" / "udm1-pt"))
    ap.add_argument("--size", default="256x256")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--tasks", type=int, default=16)
    ap.add_argument("--n", type=int, default=1 << 24)
    ap.add_argument("--reps", type=int, default=2, help="best of this many runs per configuration")
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_distributed"))
    ap.add_argument("--replot", action="store_true", help="only redo the projection and plot from OUT/distributed.json")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.replot:
        report(json.loads((out / "distributed.json").read_text()), out)
        return 0
    tool = a.tool
    args = ["--size", a.size, "--sampler", "sobol-owen"]
    res = {"machine": {"cpu": platform.processor() or platform.machine(), "cores": os.cpu_count(),
                       "python": platform.python_version()},
           "config": {"size": a.size, "spp": a.spp, "tasks": a.tasks, "n": a.n, "reps": a.reps}}
    import dask
    import distributed

    res["machine"]["dask"] = dask.__version__
    res["machine"]["distributed"] = distributed.__version__
    try:
        res["machine"]["cpu"] = next(l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name"))
    except (OSError, StopIteration):
        pass

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # anchors: the tool alone
        render = {}
        for threads in (1, 2):
            log(f"render: udm1-pt alone, {threads} thread(s)")
            secs, _ = timed(lambda: subprocess.run([tool, *args, "--spp", str(a.spp), "--threads", str(threads), "-o",
                                                    str(tmp / f"one{threads}.exr")], check=True, capture_output=True),
                            a.reps)
            render[f"alone-{threads}"] = secs
        log("integral: udm1.integrate in this process")
        secs, whole = timed(lambda: udm1.integrate(gauss, "wr", 8, a.n, seed=1), a.reps)
        integral = {"alone-1": secs}
        overhead = {}
        log("task overhead: the tool on one pixel and one sample")
        overhead["tool_task_seconds"], _ = timed(lambda: ud.probe(tool, args, a.spp), 5)
        for workers in (1, 2):
            log(f"LocalCluster of {workers} worker(s): starting")
            t0 = time.perf_counter()
            with ud.connect(n_workers=workers, threads_per_worker=1) as client:
                client.wait_for_workers(workers)
                res.setdefault("cluster_start_seconds", {})[workers] = time.perf_counter() - t0
                log(f"render over {workers} worker(s), {a.tasks} tasks")
                secs, r = timed(lambda: ud.render(tool, str(tmp / f"d{workers}.exr"), spp=a.spp, args=args,
                                                  tasks=a.tasks, client=client, progress=True), a.reps)
                same = (tmp / f"d{workers}.exr").read_bytes() == (tmp / "one1.exr").read_bytes()
                if not same:
                    raise SystemExit("bench_distributed: the distributed render differs from the tool's own")
                render[f"dask-{workers}"] = secs
                render[f"dask-{workers}-task-mean"] = float(np.mean([p["seconds"] for p in r.parts]))
                log(f"integral over {workers} worker(s), {a.tasks} tasks")
                secs, est = timed(lambda: ud.integrate(gauss, "wr", 8, a.n, seed=1, tasks=a.tasks, client=client,
                                                       progress=False), a.reps)
                if est.sum != whole.sum:
                    raise SystemExit("bench_distributed: the distributed integral differs from the single-process one")
                integral[f"dask-{workers}"] = secs
                if workers == 1:
                    log("Dask round trip per task: 400 no-op tasks on 1 worker")
                    k = 400
                    secs, _ = timed(lambda: client.gather(client.map(noop, range(k), pure=False)), 3)
                    overhead["dask_task_seconds"] = secs / k
                    secs, _ = timed(lambda: client.submit(noop, 1, pure=False).result(), 20)
                    overhead["dask_single_roundtrip_seconds"] = secs
        # the merge alone
        parts = []
        for k, (first, count) in enumerate(ud.split_range(a.spp, a.tasks)):
            p = tmp / f"p{k}.exr"
            subprocess.run([tool, *args, "--spp", str(a.spp), "--spp-first", str(first), "--spp-count", str(count),
                            "-o", str(p)], check=True, capture_output=True)
            parts.append(str(p))
        overhead["merge_seconds"], _ = timed(lambda: subprocess.run([tool, "merge", *parts, "-o", str(tmp / "m.exr")],
                                                                    check=True, capture_output=True), 3)
    res["render_seconds"] = render
    res["integral_seconds"] = integral
    res["overhead"] = overhead
    report(res, out)
    return 0


def project(res: dict, fan_in: int = 16) -> dict:
    """Time on N machines of c = 2 cores (S = 2N slots) for T = 4 S tasks over one tile:
    rendering ceil(T / S) (W / T + o); the merge tree on the workers, each level r -> ceil(r / G) merges of
    G = fan_in parts taking ceil(merges / S) (o + G m); the client's last merge o_tool + r m. W is the
    one-thread work, o = Dask's round trip + the tool's start per task, m the merge's cost per part
    (measured: the client's merge of the 16 parts less one tool start, over 16). For this render's W and
    for 100 W."""
    ov, cfg = res["overhead"], res["config"]
    o = ov["dask_task_seconds"] + ov["tool_task_seconds"]
    m = max(0.0, (ov["merge_seconds"] - ov["tool_task_seconds"]) / cfg["tasks"])
    out = {}
    for scale in (1, 100):
        W = res["render_seconds"]["alone-1"] * scale
        for machines in (1, 2, 4, 8, 16, 64, 256, 1024):
            slots = 2 * machines
            tasks = 4 * slots
            t, r, levels = -(-tasks // slots) * (W / tasks + o), tasks, 0
            while r > fan_in:
                r = -(-r // fan_in)
                t += -(-r // slots) * (o + fan_in * m)
                levels += 1
            t += ov["tool_task_seconds"] + r * m
            out[f"{scale}W-{machines}"] = {"work": W, "machines": machines, "tasks": tasks, "merge_levels": levels,
                                           "seconds": t, "speedup": W / t, "efficiency": W / t / slots}
    return out


def report(res: dict, out: Path) -> None:
    res["projection"] = proj = project(res)
    (out / "distributed.json").write_text(json.dumps(res, indent=1))
    print(json.dumps({k: res[k] for k in ("render_seconds", "integral_seconds", "overhead")}, indent=1))
    print("projection (2-core machines, 4 tasks per core): work, machines, tasks, merge levels, seconds, speed-up, "
          "efficiency")
    for v in proj.values():
        print(f"  {v['work']:8.1f} {v['machines']:5d} {v['tasks']:5d} {v['merge_levels']:2d} {v['seconds']:9.3f} "
              f"{v['speedup']:8.2f} {v['efficiency']:6.2f}")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log(f"wrote {out / 'distributed.json'} (no matplotlib: no plot)")
        return
    render, cfg = res["render_seconds"], res["config"]
    W = render["alone-1"]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot([1, 2], [render["alone-1"], render["alone-2"]], "o-", label="udm1-pt alone (1, 2 threads)")
    ax.plot([1, 2], [render["dask-1"], render["dask-2"]], "s-", label=f"udm1.distributed ({cfg['tasks']} tasks; 1, 2 workers)")
    for scale, style in ((1, "k--"), (100, "k-.")):
        m = [v for v in proj.values() if abs(v["work"] - W * scale) < 1e-9]
        ax.plot([2 * v["machines"] for v in m], [v["seconds"] for v in m], style,
                label=f"projection, {'this render' if scale == 1 else '100x its spp'}, 2-core machines")
        ax.plot([1, 2048], [W * scale, W * scale / 2048], ":", color="grey")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("worker cores")
    ax.set_ylabel("seconds")
    ax.set_title(f"udm1-pt {cfg['size']} {cfg['spp']} spp over Dask (dotted: perfect scaling)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "distributed.png", dpi=110)
    log(f"wrote {out / 'distributed.json'} and {out / 'distributed.png'}")


if __name__ == "__main__":
    sys.exit(main())
