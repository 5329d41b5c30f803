"""udm1's samplers inside Mitsuba 3 (udm1.mitsuba) against Mitsuba's own, in one run, on Mitsuba's
Cornell box (mi.cornell_box(), its path integrator):

1. Equal spp: RMSE against a reference (Mitsuba's independent sampler at --ref-spp, cached in --out)
   of every sampler at each spp, root of the MSE averaged over --seeds renders, and the render time
   (scene loaded once per sampler; the JIT variant's kernels compiled by an untimed render first; the
   time includes evaluating the image and, for udm1's table presets, filling the table). The renders
   alternate: per (spp, seed) every sampler in turn, so the machine's drift falls on all alike.
   Mitsuba's orthogonal sampler renders the square of a prime at or above the spp asked (25, 67^2...):
   its row names the count it took.
2. Equal error: for each target RMSE (what the independent sampler reaches at each spp) the time each
   sampler needs, interpolated log-log between its measured points; the best udm1 sampler against the
   best Mitsuba sampler.

Variants: llvm_ad_rgb (the vectorized JIT variant a speed-minded user picks; needs libllvm19, skipped
with a message without it) at --size, and scalar_rgb at --scalar-size (udm1's scalar sampler is a
Python call per draw: slower by design there, measured on a smaller image, and on one render thread:
Mitsuba's render threads calling Python contend for the GIL, which costs more than they gain).

    python bench/bench_mitsuba_sampler.py [--size 128] [--spps 4,16,64,256] [--seeds 4] [--out DIR]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

LLVM_PATH = os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

MITSUBA = [("independent", {"type": "independent"}), ("stratified", {"type": "stratified"}),
           ("multijitter", {"type": "multijitter"}), ("orthogonal", {"type": "orthogonal"}),
           ("ldsampler", {"type": "ldsampler"})]


def udm1_samplers(size: int, vector: bool):
    """udm1's rows: wr (D = 64), the table presets at D = 32, and (vector variants only) screen; each with
    the film's size (the vector variants need it)."""
    film = {"film_width": size, "film_height": size}
    rows = [("udm1 wr", {"type": "udm1", "preset": "wr", **film}),
            ("udm1 sobol-owen", {"type": "udm1", "preset": "sobol-owen", "dimensions": 32, **film}),
            ("udm1 pmj02", {"type": "udm1", "preset": "pmj02", "dimensions": 32, **film})]
    if vector:
        rows.append(("udm1 wr screen", {"type": "udm1", "preset": "wr", "randomize": "screen", **film}))
    return rows


def load(mi, sampler: dict, size: int, spp: int):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = size
    d["sensor"]["sampler"] = dict(sampler, sample_count=spp)
    return mi.load_dict(d)


def render(mi, scene, spp: int, seed: int, threads: int = 0) -> tuple[np.ndarray, float]:
    """One render, timed; threads > 0 caps Mitsuba's render threads for it."""
    import drjit as dr
    before = dr.thread_count()
    if threads:
        dr.set_thread_count(threads)
    try:
        t0 = time.perf_counter()
        img = mi.render(scene, spp=spp, seed=seed)
        arr = np.array(img)  # evaluates the image
        dr.sync_thread()
        return arr, time.perf_counter() - t0
    finally:
        dr.set_thread_count(before)


def interp_time(points, target):
    """Time at which a sampler's RMSE reaches target, log-log between measured (time, rmse) points."""
    pts = sorted(points)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e0 > e1:
            a = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    return None


def run_variant(variant: str, size: int, spps, seeds: int, ref_spp: int, out: Path) -> dict:
    import mitsuba as mi
    mi.set_variant(variant)
    import udm1.mitsuba
    udm1.mitsuba.register()
    ref_path = out / f"reference_{variant}_{size}_{ref_spp}.npy"
    if ref_path.exists():
        ref = np.load(ref_path)
    else:
        print(f"[{variant}] reference: independent at {ref_spp} spp ({size}x{size}) ...", flush=True)
        ref_scene = load(mi, {"type": "independent"}, size, ref_spp)
        ref, t = render(mi, ref_scene, ref_spp, 12345)
        np.save(ref_path, ref)
        print(f"[{variant}] reference in {t:.1f} s", flush=True)
    samplers = MITSUBA + udm1_samplers(size, not variant.startswith("scalar"))
    # a Python sampler in a scalar variant serializes Mitsuba's render threads on the GIL, and their contention
    # costs more than one thread: udm1's rows there render on one thread (Mitsuba's on all)
    threads = {name: (1 if variant.startswith("scalar") and name.startswith("udm1") else 0) for name, _ in samplers}
    rows = []
    for spp in spps:
        scenes = {}
        for name, s in samplers:
            scenes[name] = load(mi, s, size, spp)
            render(mi, scenes[name], spp, 999, threads[name])  # compile (JIT) / warm up
        mse = {n: [] for n in scenes}
        secs = {n: [] for n in scenes}
        for seed in range(seeds):
            for name, scene in scenes.items():
                img, t = render(mi, scene, spp, seed, threads[name])
                mse[name].append(float(np.mean((img - ref) ** 2)))
                secs[name].append(t)
            print(f"[{variant}] {spp} spp, seed {seed + 1}/{seeds} done", flush=True)
        for name in scenes:
            taken = scenes[name].sensors()[0].sampler().sample_count()
            rows.append({"variant": variant, "sampler": name, "spp": spp, "spp_taken": taken,
                         "threads": threads[name] or os.cpu_count(),
                         "rmse": math.sqrt(sum(mse[name]) / seeds), "seconds": sum(secs[name]) / seeds})
    base = {r["spp"]: r["seconds"] for r in rows if r["sampler"] == "independent"}
    for r in rows:
        r["x_independent_time"] = r["seconds"] / base[r["spp"]]
    equal = []
    for spp in spps:
        target = next(r["rmse"] for r in rows if r["sampler"] == "independent" and r["spp"] == spp)
        times = {}
        for name, _ in samplers:
            t = interp_time([(r["seconds"], r["rmse"]) for r in rows if r["sampler"] == name], target)
            if t is not None:
                times[name] = t
        ours = {k: v for k, v in times.items() if k.startswith("udm1")}
        theirs = {k: v for k, v in times.items() if not k.startswith("udm1")}
        # a sampler already below the target at the smallest spp has no interpolated time: it may be the
        # fastest, so the comparison at this target is made only when every sampler brackets it
        missing = [name for name, _ in samplers if name not in times]
        if missing:
            equal.append({"variant": variant, "target_rmse": target, "target_of": f"independent at {spp} spp",
                          "not_compared": f"{', '.join(missing)} below it at the smallest spp (or never reach it)",
                          "times": times})
            continue
        if ours and theirs:
            bo, bt = min(ours, key=ours.get), min(theirs, key=theirs.get)
            equal.append({"variant": variant, "target_rmse": target, "target_of": f"independent at {spp} spp",
                          "best_udm1": bo, "udm1_seconds": ours[bo], "best_mitsuba": bt, "mitsuba_seconds": theirs[bt],
                          "speedup": theirs[bt] / ours[bo], "times": times})
    return {"variant": variant, "rows": rows, "equal_error": equal, "size": size, "seeds": seeds, "ref_spp": ref_spp}


def print_result(res: dict):
    print(f"\n{res['rows'][0]['variant']}: {res['size']}x{res['size']}, {res['seeds']} seeds, reference "
          f"{res['ref_spp']} spp")
    print(f"{'sampler':<18} {'spp':>5} {'taken':>6} {'threads':>7} {'RMSE':>10} {'seconds':>9} {'x indep. time':>14}")
    for r in res["rows"]:
        print(f"{r['sampler']:<18} {r['spp']:>5} {r['spp_taken']:>6} {r['threads']:>7} {r['rmse']:10.5f} "
              f"{r['seconds']:9.3f} {r['x_independent_time']:14.2f}")
    for e in res["equal_error"]:
        if e.get("not_compared"):
            print(f"equal error {e['target_rmse']:.5f} ({e['target_of']}): not compared: {e['not_compared']}")
            continue
        print(f"equal error {e['target_rmse']:.5f} ({e['target_of']}): best udm1 {e['best_udm1']} "
              f"{e['udm1_seconds']:.3f} s, best Mitsuba {e['best_mitsuba']} {e['mitsuba_seconds']:.3f} s: "
              f"{e['speedup']:.2f}x")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spps", default="4,16,64,256")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--scalar-size", type=int, default=48)
    ap.add_argument("--scalar-spps", default="4,16,64")
    ap.add_argument("--scalar-seeds", type=int, default=2)
    ap.add_argument("--variants", default="llvm_ad_rgb,scalar_rgb")
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_mitsuba_sampler"))
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    results = []
    try:
        import mitsuba  # noqa: F401
    except ImportError:
        why = "Mitsuba 3 is not installed (pip install mitsuba)"
        print(f"bench_mitsuba_sampler: {why}: skipped", file=sys.stderr)
        (out / "results.json").write_text(json.dumps([{"skipped": why}]))
        return 0
    for variant in args.variants.split(","):
        if variant.startswith("llvm") and not Path(LLVM_PATH).exists():
            why = f"{LLVM_PATH} is missing (apt-get install libllvm19)"
            print(f"bench_mitsuba_sampler: {why}: {variant} skipped", file=sys.stderr)
            results.append({"variant": variant, "skipped": why})
            continue
        scalar = variant.startswith("scalar")
        res = run_variant(variant, args.scalar_size if scalar else args.size,
                          [int(s) for s in (args.scalar_spps if scalar else args.spps).split(",")],
                          args.scalar_seeds if scalar else args.seeds, 1024 if scalar else args.ref_spp, out)
        print_result(res)
        results.append(res)
    (out / "results.json").write_text(json.dumps(results, indent=1))
    print(f"\nwrote {out / 'results.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
