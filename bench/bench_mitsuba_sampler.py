"""udm1's samplers inside Mitsuba 3 (udm1.mitsuba) against Mitsuba's own, in one run, on Mitsuba's
Cornell box (mi.cornell_box(), its path integrator) or, with --scene, a pbrt-v4 scene given to Mitsuba
(`udm1-pt export` and bench/mitsuba_scene.py: veach-mis of ../shared/scenes, skipped with a message where
it is absent; --size is then the film's width, its height from the scene's aspect):

1. Equal spp: RMSE against a reference (Mitsuba's independent sampler at --ref-spp, cached in --out)
   of every sampler at each spp, root of the MSE averaged over --seeds renders (linear RGB clamped to
   [0, 1], what a display shows, as bench_pt_scenes.py measures: a visible light's pixels would otherwise
   weigh more than the rest of the image), and the render time
   (scene loaded once per sampler; the JIT variant's kernels compiled by an untimed render first; the
   time includes evaluating the image and, for udm1's table presets, filling the table). The renders
   alternate: per (spp, seed) every sampler in turn, in one order and then the other, and a sampler's time
   is its fastest render of the seeds (on a shared machine the least disturbed: a passing load then slows
   no sampler's figure; every render's time is in the JSON), so the machine's drift falls on all alike.
   Mitsuba's orthogonal sampler renders the square of a prime at or above the spp asked (25, 67^2...):
   its row names the count it took.
2. Equal error: for each target RMSE (what the independent sampler reaches at each spp) the time each
   sampler needs, interpolated log-log between its measured points; the best udm1 sampler against the
   best Mitsuba sampler.

Variants: llvm_ad_rgb (the vectorized JIT variant a speed-minded user picks; needs libllvm19, skipped
with a message without it) at --size, and scalar_rgb at --scalar-size (a smaller image: the scalar variant is
slower for every sampler; where udm1's rows are the Python sampler, a Python call per draw, they render on one
thread: Mitsuba's render threads calling Python contend for the GIL, which costs more than they gain).

udm1's rows are the native plugin (integrations/mitsuba3), built first (python -m udm1.mitsuba build, up to
date in a second); where it cannot be built and is not, udm1.mitsuba's Python sampler, said on stderr.

3. --speed: render time only, the native plugin against Mitsuba's independent sampler, --size (128) Cornell
   box at --speed-spps (4..1024), in scalar_rgb on 1 and on 2 render threads and in llvm_ad_rgb: per spp
   the samplers alternate, --repeats times (in llvm_ad_rgb after an untimed render each, which compiles the
   kernels); the fastest wall time of each (on a shared machine the least disturbed; the median is reported
   beside it) and its ratio to the independent sampler's, and the ratio of their processor times (every
   thread's: what a render costs, not counting the time its threads wait for a core).

    python bench/bench_mitsuba_sampler.py [--size 128] [--spps 4,16,64,256] [--seeds 4] [--out DIR]
    python bench/bench_mitsuba_sampler.py --scene veach-mis [--size 192 --scalar-size 96]
    python bench/bench_mitsuba_sampler.py --speed [--speed-spps 4,16,64,256,1024] [--repeats 3]

4. --instructions: the sampler's own work counted instead of timed (for differences the clock of a shared
   machine cannot resolve): one render on one thread of a --instructions-size Cornell box at --instructions-spp,
   per sampler, under valgrind's callgrind, in millions of instructions executed. scalar_rgb: in the sampler's
   plugin (udm1.so, the library's stream set-up it links included; independent.so and the PCG32 sampler's
   functions in libmitsuba) and in the whole render (Mitsuba, Embree, the integrator). llvm_ad_rgb
   (--instructions-variant): in the kernels Dr.Jit compiled (code valgrind finds in no file; their compilation
   is LLVM's and not counted) and in Embree; valgrind runs them at AVX2 at most.

    python bench/bench_mitsuba_sampler.py --instructions [--instructions-variant scalar_rgb] [--instructions-size 32]
                                          [--instructions-spp 16]
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
SHARED_SCENES = ROOT.parent / "shared" / "scenes"
sys.path.insert(0, str(ROOT / "python"))
sys.path.insert(0, str(ROOT / "bench"))

MITSUBA = [("independent", {"type": "independent"}), ("stratified", {"type": "stratified"}),
           ("multijitter", {"type": "multijitter"}), ("orthogonal", {"type": "orthogonal"}),
           ("ldsampler", {"type": "ldsampler"})]


def use_native(mi) -> bool:
    """udm1's samplers for Mitsuba's current variant: the native plugin (built here when it is not), else the
    Python sampler with a note; True for the native plugin."""
    import udm1.mitsuba
    from udm1 import mitsuba_build
    try:  # (CMake's incremental build: the plugin of this checkout's source, in a second when it is up to date)
        print("bench_mitsuba_sampler: building the native plugin (python -m udm1.mitsuba build) ...", flush=True)
        mitsuba_build.build()
    except mitsuba_build.BuildError as exc:
        print(f"bench_mitsuba_sampler: the native plugin cannot be built ({exc})", file=sys.stderr)
    return not isinstance(udm1.mitsuba.register(), type)


class Scene:
    """What is rendered: Mitsuba's Cornell box, or a pbrt-v4 scene exported by udm1-pt for Mitsuba."""

    def __init__(self, name: str, tool: str, out: Path):
        self.name, self.folder, self.aspect = name, None, 1.0
        if name == "cornell-box":
            return
        path = Path(name) if name.endswith(".pbrt") else SHARED_SCENES / name / f"{name}.pbrt"
        if not path.is_file():
            raise FileNotFoundError(f"{path} is absent (the shared scenes)")
        self.name = path.stem
        self.folder = out / f"{self.name}-export"
        import subprocess
        r = subprocess.run([tool, "export", str(self.folder), "--scene", str(path)], capture_output=True, text=True)
        if r.returncode != 0:
            raise ValueError(f"udm1-pt export {path}: {r.stderr.strip()}")
        js = json.loads((self.folder / "scene.json").read_text())
        self.aspect = js["height"] / js["width"]

    def film(self, width: int) -> tuple[int, int]:
        return width, max(1, round(width * self.aspect))

    def load(self, mi, sampler: dict, film: tuple[int, int], spp: int):
        if self.folder is None:
            d = mi.cornell_box()
            d["sensor"]["film"]["width"], d["sensor"]["film"]["height"] = film
            d["sensor"]["sampler"] = dict(sampler, sample_count=spp)
            return mi.load_dict(d)
        import mitsuba_scene
        return mitsuba_scene.load(self.folder, spp, sampler, 0, film)


def udm1_samplers(film: tuple[int, int], vector: bool):
    """udm1's rows: wr (D = 64), the table presets at D = 32, and (vector variants only) screen; each with
    the film's size (the vector variants need it)."""
    film = {"film_width": film[0], "film_height": film[1]}
    rows = [("udm1 wr", {"type": "udm1", "preset": "wr", **film}),
            ("udm1 sobol-owen", {"type": "udm1", "preset": "sobol-owen", "dimensions": 32, **film}),
            ("udm1 pmj02", {"type": "udm1", "preset": "pmj02", "dimensions": 32, **film})]
    if vector:
        rows.append(("udm1 wr screen", {"type": "udm1", "preset": "wr", "randomize": "screen", **film}))
    return rows


def render(mi, scene, spp: int, seed: int, threads: int = 0, cpu: list | None = None) -> tuple[np.ndarray, float]:
    """One render, timed (wall clock; its processor time, every thread's, appended to `cpu` when given);
    threads > 0 caps Mitsuba's render threads for it."""
    import drjit as dr
    before = dr.thread_count()
    if threads:
        dr.set_thread_count(threads)
    try:
        t0, c0 = time.perf_counter(), time.process_time()
        img = mi.render(scene, spp=spp, seed=seed)
        arr = np.array(img)  # evaluates the image
        dr.sync_thread()
        if cpu is not None:
            cpu.append(time.process_time() - c0)
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


def run_variant(source: Scene, variant: str, size: int, spps, seeds: int, ref_spp: int, out: Path) -> dict:
    import mitsuba as mi
    mi.set_variant(variant)
    native = use_native(mi)
    film = source.film(size)
    tag = "" if source.name == "cornell-box" else f"{source.name}_"
    ref_path = out / f"reference_{tag}{variant}_{film[0]}x{film[1]}_{ref_spp}.npy"
    if ref_path.exists():
        ref = np.load(ref_path)
    else:
        print(f"[{variant}] reference: independent at {ref_spp} spp ({film[0]}x{film[1]}) ...", flush=True)
        ref_scene = source.load(mi, {"type": "independent"}, film, ref_spp)
        ref, t = render(mi, ref_scene, ref_spp, 12345)
        np.save(ref_path, ref)
        print(f"[{variant}] reference in {t:.1f} s", flush=True)
    samplers = MITSUBA + udm1_samplers(film, not variant.startswith("scalar"))
    # a Python sampler in a scalar variant serializes Mitsuba's render threads on the GIL, and their contention
    # costs more than one thread: udm1's rows there render on one thread (Mitsuba's on all)
    # (the Python sampler, in a scalar variant, on one thread)
    threads = {name: (1 if variant.startswith("scalar") and name.startswith("udm1") and not native else 0)
               for name, _ in samplers}
    rows = []
    for spp in spps:
        scenes = {}
        for name, s in samplers:
            scenes[name] = source.load(mi, s, film, spp)
            render(mi, scenes[name], spp, 999, threads[name])  # compile (JIT) / warm up
        mse = {n: [] for n in scenes}
        secs = {n: [] for n in scenes}
        for seed in range(seeds):
            order = list(scenes.items()) if seed % 2 == 0 else list(scenes.items())[::-1]  # both ways round
            for name, scene in order:
                img, t = render(mi, scene, spp, seed, threads[name])
                mse[name].append(float(np.mean((np.clip(img, 0, 1) - np.clip(ref, 0, 1)) ** 2)))
                secs[name].append(t)
            print(f"[{variant}] {spp} spp, seed {seed + 1}/{seeds} done", flush=True)
        for name in scenes:
            taken = scenes[name].sensors()[0].sampler().sample_count()
            rows.append({"variant": variant, "sampler": name, "spp": spp, "spp_taken": taken,
                         "threads": threads[name] or os.cpu_count(),
                         "rmse": math.sqrt(sum(mse[name]) / seeds), "seconds": min(secs[name]),
                         "all_seconds": secs[name]})
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
    return {"variant": variant, "scene": source.name, "rows": rows, "equal_error": equal, "size": size,
            "film": list(film), "seeds": seeds, "ref_spp": ref_spp, "udm1": "native plugin" if native else "Python sampler"}


def run_speed(source: Scene, variant: str, threads: int, size: int, spps, repeats: int) -> dict:
    """--speed: the native plugin's render time against the independent sampler's (see the docstring)."""
    import statistics

    import mitsuba as mi
    mi.set_variant(variant)
    if not use_native(mi):
        return {"variant": variant, "threads": threads, "skipped": "the native plugin is not built"}
    film = source.film(size)
    samplers = [("independent", {"type": "independent"})] + udm1_samplers(film, not variant.startswith("scalar"))
    rows = []
    for spp in spps:
        scenes = {name: source.load(mi, s, film, spp) for name, s in samplers}
        if not variant.startswith("scalar"):
            for name, scene in scenes.items():
                render(mi, scene, spp, 999, threads)  # compile the kernels
        secs = {name: [] for name in scenes}
        cpu = {name: [] for name in scenes}
        for rep in range(repeats):
            order = list(scenes) if rep % 2 == 0 else list(scenes)[::-1]  # alternating, both ways round
            for name in order:
                secs[name].append(render(mi, scenes[name], spp, rep, threads, cpu[name])[1])
        # the fastest of the repeats: on a shared machine the least disturbed render (the median beside it);
        # and the processor time, which does not count the time a render thread waits for a core
        base, base_med, base_cpu = min(secs["independent"]), statistics.median(secs["independent"]), min(cpu["independent"])
        for name in scenes:
            best, med = min(secs[name]), statistics.median(secs[name])
            rows.append({"variant": variant, "threads": threads, "sampler": name, "spp": spp, "seconds": best,
                         "median_seconds": med, "all_seconds": secs[name], "x_independent_time": best / base,
                         "x_independent_median": med / base_med, "cpu_seconds": min(cpu[name]),
                         "all_cpu_seconds": cpu[name], "x_independent_cpu": min(cpu[name]) / base_cpu})
        print(f"[{variant}, {threads or 'every'} thread(s)] {spp} spp: " +
              ", ".join(f"{r['sampler']} {r['x_independent_time']:.3f}x (cpu {r['x_independent_cpu']:.3f}x)"
                      for r in rows[-len(scenes):]), flush=True)
    return {"variant": variant, "scene": source.name, "threads": threads, "size": size, "film": list(film),
            "repeats": repeats, "rows": rows}


def print_speed(res: dict):
    if res.get("skipped"):
        print(f"\n{res['variant']} ({res['threads']} threads): skipped: {res['skipped']}")
        return
    w, h = res["film"]
    print(f"\n{res['scene']}, {res['variant']}, {res['threads'] or 'every'} render thread(s), {w}x{h}, fastest of "
          f"{res['repeats']}: wall time over the independent sampler's (the medians' ratio, then the processor "
          "times', in brackets)")
    names = list(dict.fromkeys(r["sampler"] for r in res["rows"]))
    spps = list(dict.fromkeys(r["spp"] for r in res["rows"]))
    print(f"{'sampler':<18}" + "".join(f"{s:>20}" for s in spps))
    for n in names:
        cells = {r["spp"]: r for r in res["rows"] if r["sampler"] == n}
        if n == "independent":
            print(f"{n + ' (s)':<18}" + "".join(f"{cells[s]['seconds']:20.3f}" for s in spps))
        else:
            print(f"{n:<18}" + "".join(f"{cells[s]['x_independent_time']:6.3f} ({cells[s]['x_independent_median']:.2f}, "
                                       f"{cells[s]['x_independent_cpu']:.2f})" for s in spps))


def print_result(res: dict):
    w, h = res["film"]
    print(f"\n{res['scene']}, {res['rows'][0]['variant']}: {w}x{h}, {res['seeds']} seeds, reference "
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


def render_one(variant: str, sampler: str, size: int, spp: int) -> None:
    """--render-one (the process --instructions runs under callgrind): one render on one thread."""
    if variant.startswith("llvm"):
        os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM_PATH)
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(variant)
    use_native(mi)
    film = (size, size)
    rows = dict([("independent", {"type": "independent"})] + udm1_samplers(film, False))
    dr.set_thread_count(1)
    scene = Scene("cornell-box", "", Path(".")).load(mi, rows[sampler], film, spp)
    print(float(np.array(mi.render(scene, spp=spp)).sum()))


def run_instructions(variant: str, size: int, spp: int, out: Path) -> dict:
    """--instructions (see the docstring): per sampler, the instructions of its plugin and of the render."""
    import callgrind_counts
    if callgrind_counts.missing_tool():
        return {"skipped": "valgrind is not installed (Debian package valgrind)"}
    if variant.startswith("llvm") and not Path(LLVM_PATH).exists():
        return {"skipped": f"{LLVM_PATH} is missing"}
    import mitsuba as mi
    mi.set_variant(variant)
    if not use_native(mi):
        return {"skipped": "the native plugin is not built"}
    jit = not variant.startswith("scalar")
    rows = []
    for name in ["independent"] + [n for n, _ in udm1_samplers((size, size), False)]:
        cg = out / f"callgrind-{variant}-{name.replace(' ', '-')}.out"
        try:
            counted = callgrind_counts.count([sys.executable, __file__, "--render-one", name, "--instructions-variant",
                                              variant, "--instructions-size", str(size), "--instructions-spp", str(spp)],
                                             str(cg))
        except RuntimeError as e:
            raise SystemExit(f"bench_mitsuba_sampler: {name}: {e}")
        sampler = render_total = 0
        for n, fn, path in counted:
            obj = os.path.basename(path)
            if jit:  # the compiled kernels (in no file) hold the sampler's arithmetic
                sampler += n if obj == "???" else 0
                render_total += n if obj == "???" or obj.startswith("libembree") else 0
                continue
            mine = obj in ("udm1.so", "independent.so") or (obj == "libmitsuba.so" and "PCG32Sampler" in fn)
            sampler += n if mine else 0
            if mine or obj in ("libmitsuba.so", "libembree3.so", "path.so") or "/plugins/" in path:
                render_total += n
        rows.append({"sampler": name, "sampler_minstr": sampler / 1e6, "render_minstr": render_total / 1e6})
        print(f"[instructions] {name}: sampler {sampler / 1e6:.1f} M, render {render_total / 1e6:.1f} M", flush=True)
    return {"variant": variant, "size": size, "spp": spp, "rows": rows}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="cornell-box",
                    help="cornell-box (Mitsuba's), a shared scene's name (veach-mis) or a .pbrt file")
    ap.add_argument("--tool", default=str(ROOT / "build" / "bin" / "udm1-pt"), help="udm1-pt, which exports --scene")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spps", default="4,16,64,256")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--scalar-size", type=int, default=48)
    ap.add_argument("--scalar-spps", default="4,16,64")
    ap.add_argument("--scalar-seeds", type=int, default=2)
    ap.add_argument("--variants", default="llvm_ad_rgb,scalar_rgb")
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_mitsuba_sampler"))
    ap.add_argument("--speed", action="store_true", help="render time only: the native plugin against independent")
    ap.add_argument("--speed-spps", default="4,16,64,256,1024")
    ap.add_argument("--speed-runs", default="scalar_rgb:1,scalar_rgb:2,llvm_ad_rgb:0",
                    help="variant:threads pairs (0: Mitsuba's default, every core)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--instructions", action="store_true", help="count the samplers' instructions (scalar_rgb, callgrind)")
    ap.add_argument("--instructions-variant", default="scalar_rgb")
    ap.add_argument("--instructions-size", type=int, default=32)
    ap.add_argument("--instructions-spp", type=int, default=16)
    ap.add_argument("--render-one", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.render_one:
        render_one(args.instructions_variant, args.render_one, args.instructions_size, args.instructions_spp)
        return 0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    results = []
    suffix = "" if args.scene == "cornell-box" else "-" + Path(args.scene).stem
    try:
        source = Scene(args.scene, args.tool, out)
    except (FileNotFoundError, ValueError) as exc:
        print(f"bench_mitsuba_sampler: {exc}: skipped", file=sys.stderr)
        name = "speed" if args.speed else "results"
        (out / f"{name}{suffix}.json").write_text(json.dumps([{"skipped": str(exc)}]))
        return 0
    if args.instructions:
        res = run_instructions(args.instructions_variant, args.instructions_size, args.instructions_spp, out)
        if "skipped" in res:
            print(f"bench_mitsuba_sampler: {res['skipped']}: skipped", file=sys.stderr)
        else:
            base = res["rows"][0]
            print(f"\n{res['variant']}, Cornell box {res['size']} x {res['size']}, {res['spp']} spp, one thread: instructions "
                  "executed (callgrind), millions")
            first = "in the compiled kernels" if res["variant"] != "scalar_rgb" else "in the sampler"
            second = "kernels and Embree" if res["variant"] != "scalar_rgb" else "in the render"
            print(f"| sampler | {first} | {second} | that over the independent sampler's |\n|---|---|---|---|")
            for r in res["rows"]:
                print(f"| {r['sampler']} | {r['sampler_minstr']:.1f} | {r['render_minstr']:.1f} | "
                      f"{r['render_minstr'] / base['render_minstr']:.3f} |")
        (out / f"instructions-{args.instructions_variant}.json").write_text(json.dumps(res, indent=1))
        return 0
    if args.speed:
        for run in args.speed_runs.split(","):
            variant, threads = run.split(":")
            if variant.startswith("llvm") and not Path(LLVM_PATH).exists():
                results.append({"variant": variant, "threads": int(threads), "skipped": f"{LLVM_PATH} is missing"})
                continue
            res = run_speed(source, variant, int(threads), args.size, [int(s) for s in args.speed_spps.split(",")],
                            args.repeats)
            results.append(res)
        for res in results:
            print_speed(res)
        (out / f"speed{suffix}.json").write_text(json.dumps(results, indent=1))
        print(f"\nwrote {out / f'speed{suffix}.json'}")
        return 0
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
        res = run_variant(source, variant, args.scalar_size if scalar else args.size,
                          [int(s) for s in (args.scalar_spps if scalar else args.spps).split(",")],
                          args.scalar_seeds if scalar else args.seeds, 1024 if scalar else args.ref_spp, out)
        print_result(res)
        results.append(res)
    (out / f"results{suffix}.json").write_text(json.dumps(results, indent=1))
    print(f"\nwrote {out / f'results{suffix}.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
