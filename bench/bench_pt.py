"""udm1-pt against Mitsuba 3, side by side in one run: throughput, error at equal spp, and time to a
given error.

1. Throughput: paths/s and rays/s of udm1-pt on the built-in Cornell box (the wavefront loop, and
   the scalar loop for comparison) and on the shared pbrt-v4 scenes (cornell-box, veach-mis; skipped
   with a message where ../shared is absent), and Mitsuba 3 (PyPI `mitsuba`, its `path` integrator) on
   the same Cornell box at the same spp, in its scalar_rgb variant and in llvm_ad_rgb, its vectorized
   JIT-compiled CPU variant (the one a speed-minded user picks; it needs libllvm19 on Debian 12, and is
   skipped with a message without it). A JIT variant's kernels are compiled by an untimed render of the
   same configuration first, and its time includes evaluating the image (its render is lazy).
2. Equal spp: RMSE (root of the MSE averaged over --seeds renders; time averaged too) against one
   common reference (udm1-pt, sobol-owen at --ref-spp, cached) for every udm1 sampler and every
   Mitsuba sampler at each spp, the renders interleaved (per spp: a udm1-pt sampler, a Mitsuba
   sampler, and so on), so that the machine's drift during the run falls on both alike. Mitsuba's
   orthogonal sampler renders the square of a prime at or above the spp asked, 25/121/289/1369 for
   16/64/256/1024: the table shows the count it took, and its time and error are those of that
   count. The scenes are matched by `udm1-pt export` (see bench/mitsuba_scene.py); the two
   renderers' high-spp images agree pixel by pixel within their noise. Errors are those of
   `udm1-pt compare` (linear RGB clamped to [0, 1], as the PSNR).
3. Equal error: for each target RMSE (the errors Mitsuba's independent sampler reaches at the spps),
   the time each sampler needs, interpolated log-log between measured points; the ratio of Mitsuba's
   best time to udm1-pt's best time is the speed-up at equal error.

Both renderers use every core of the machine; times are render times (scene loading excluded).

With --estimators it measures udm1-pt's own estimator choices instead, on the same Cornell box and
reference: Russian roulette from vertex 1 (pbrt-v4's rule), 2, 3 (the default) or never, and triangle
lights sampled by solid angle near the light (the default), wherever possible (pbrt-v4) or never; for
each, MSE x time relative to the default (lower is better), per sampler.

    python bench/bench_pt.py [--size 128x128] [--spps 16,64,256,1024] [--ref-spp 8192] [--out DIR]
    python bench/bench_pt.py --estimators [--estimator-spp 256]
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

# Mitsuba's llvm_ad_rgb needs an LLVM that Dr.Jit can drive: on Debian 12 libllvm19 (14 is refused, 15 and 16
# fail in code generation on AVX-512 machines)
LLVM_PATH = os.environ.get("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1")


def llvm_available() -> bool:
    if not Path(LLVM_PATH).exists():
        return False
    os.environ["DRJIT_LIBLLVM_PATH"] = LLVM_PATH
    return True
SHARED = ROOT.parent / "shared" / "scenes"
OURS = ["pcg32", "halton", "sobol", "sobol-owen", "pmj02", "cmj", "wr", "wmmr", "hwmmr", "rd"]
THEIRS = ["independent", "stratified", "multijitter", "orthogonal", "ldsampler"]  # every sampler Mitsuba 3 has
LINE = re.compile(r"loop (\S+) seconds (\S+) paths (\d+) rays (\d+) paths_per_second (\S+) rays_per_second (\S+)")


def log(msg: str) -> None:
    print(f"[bench_pt {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def tool_run(tool: str, *args: str) -> str:
    r = subprocess.run([tool, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"bench_pt: {tool} {' '.join(args)} failed: {r.stderr.strip()}")
    return r.stdout


def throughput(tool: str, scene: str, size: str, spp: int, *extra: str) -> dict:
    out = tool_run(tool, "--scene", scene, "--size", size, "--spp", str(spp), "--sampler", "sobol-owen",
                   "-o", "/tmp/udm1-bench-pt.exr", *extra)
    m = LINE.search(out)
    return {"loop": m.group(1), "seconds": float(m.group(2)), "paths": int(m.group(3)), "rays": int(m.group(4)),
            "paths_per_second": float(m.group(5)), "rays_per_second": float(m.group(6))}


def rmse_of(tool: str, image: Path, ref: Path) -> float:
    out = tool_run(tool, "compare", str(image), str(ref))
    return float(re.match(r"mse \S+ rmse (\S+)", out).group(1))


def time_to(points: list[tuple[float, float]], target: float) -> float | None:
    """Seconds to reach RMSE target along measured (seconds, rmse) points, log-log interpolated
    between the two points that bracket it (None outside the measured range)."""
    pts = sorted(points)
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e0 > e1:
            a = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    if pts and abs(pts[0][1] - target) <= 1e-12:
        return pts[0][0]
    return None


VARIANTS = [("default: roulette from vertex 3, solid angle near lights", []),
            ("roulette from vertex 1 (pbrt-v4)", ["--rr-depth", "1"]),
            ("roulette from vertex 2", ["--rr-depth", "2"]),
            ("no roulette", ["--no-roulette"]),
            ("solid angle wherever possible (pbrt-v4)", ["--solid-angle", "always"]),
            ("solid angle never (area sampling)", ["--solid-angle", "never"])]


def estimators(args) -> int:
    tool, out = args.tool, Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    ref = out / f"ref-cornell-{args.size}-{args.ref_spp}.exr"
    log(f"reference: udm1-pt sobol-owen {args.ref_spp} spp at {args.size} -> {ref} (reused when cached)")
    tool_run(tool, "reference", "-o", str(ref), "--spp", str(args.ref_spp), "--size", args.size, "--seed", "7")
    samplers = ["pcg32", "sobol-owen", "pmj02", "wr"]
    res = {}
    for name, extra in VARIANTS:
        for s in samplers:
            log(f"{name}: {s}")
            csv_out = tool_run(tool, "sweep", "--against", str(ref), "--samplers", s, "--spps",
                               str(args.estimator_spp), "--size", args.size, "--seeds", str(args.seeds), *extra)
            recs = list(csv.DictReader(csv_out.splitlines()))
            res[name, s] = (float(np.mean([float(r["rmse"]) ** 2 for r in recs])),
                            float(np.mean([float(r["seconds"]) for r in recs])),
                            float(np.mean([int(r["rays"]) / int(r["paths"]) for r in recs])))
    print(f"# udm1-pt estimator choices: builtin:cornell {args.size}, {args.estimator_spp} spp, {args.seeds} seeds\n")
    print("MSE x time relative to the default (lower is better); in brackets MSE relative, time relative, rays/path\n")
    print("| variant | " + " | ".join(samplers) + " |\n|---|" + "---|" * len(samplers))
    base = {s: res[VARIANTS[0][0], s] for s in samplers}
    for name, _ in VARIANTS:
        cells = []
        for s in samplers:
            m, t, rpp = res[name, s]
            cells.append(f"**{m * t / (base[s][0] * base[s][1]):.2f}** ({m / base[s][0]:.2f}, {t / base[s][1]:.2f}, {rpp:.2f})")
        print(f"| {name} | " + " | ".join(cells) + " |")
    (out / "estimators.json").write_text(json.dumps({f"{k[0]} | {k[1]}": v for k, v in res.items()}, indent=1))
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tool", default=str(ROOT / "build" / "bin" / "udm1-pt"))
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--spps", default="16,64,256,1024")
    ap.add_argument("--ref-spp", type=int, default=8192)
    ap.add_argument("--samplers", default=",".join(OURS))
    ap.add_argument("--mitsuba-samplers", default=",".join(THEIRS))
    ap.add_argument("--mitsuba-variants", default="scalar_rgb,llvm_ad_rgb",
                    help="Mitsuba variants (llvm_ad_rgb: its vectorized JIT variant; skipped with a message without LLVM)")
    ap.add_argument("--seeds", type=int, default=3, help="renders per point, MSE and time averaged (default 3)")
    ap.add_argument("--throughput-spp", type=int, default=64)
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_pt"))
    ap.add_argument("--estimators", action="store_true", help="measure udm1-pt's estimator choices instead")
    ap.add_argument("--estimator-spp", type=int, default=256)
    args = ap.parse_args(argv)
    if args.estimators:
        return estimators(args)
    variants = [v for v in args.mitsuba_variants.split(",") if v]
    if "llvm_ad_rgb" in variants and not llvm_available():  # (before Dr.Jit starts: it reads the path once)
        log(f"Mitsuba's llvm_ad_rgb skipped: no LLVM library ({LLVM_PATH}; Debian: apt-get install libllvm19)")
        variants.remove("llvm_ad_rgb")
    try:
        import mitsuba as mi
    except ImportError:
        print("bench_pt: mitsuba is not installed (pip install mitsuba)", file=sys.stderr)
        return 2
    mi.set_variant("scalar_rgb")
    sys.path.insert(0, str(ROOT / "bench"))
    import mitsuba_scene

    tool, out = args.tool, Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    spps = [int(s) for s in args.spps.split(",")]
    ours = args.samplers.split(",")
    # Mitsuba's entries: a sampler in its scalar_rgb variant by name, in another variant as "variant:sampler"
    theirs = [s if v == "scalar_rgb" else f"{v}:{s}" for v in variants for s in args.mitsuba_samplers.split(",")]
    w, h = (int(v) for v in args.size.split("x"))
    results: dict = {"machine": f"{platform.machine()}, {os.cpu_count()} logical cores, {platform.platform()}",
                     "mitsuba": mi.__version__, "size": args.size, "spps": spps, "ref_spp": args.ref_spp}

    # 1. throughput
    log("throughput: udm1-pt on each scene, Mitsuba on the Cornell box")
    scenes = [("builtin:cornell", "builtin:cornell", args.size)]
    for name, size in (("cornell-box", args.size), ("veach-mis", f"{w * 3 // 2}x{h}")):
        p = SHARED / name / f"{name}.pbrt"
        if p.exists():
            scenes.append((name, str(p), size))
        else:
            log(f"{p} is absent: {name} skipped")
    results["throughput"] = []
    for name, scene, size in scenes:
        r = throughput(tool, scene, size, args.throughput_spp)
        r.update(renderer=f"udm1-pt sobol-owen ({r['loop']} loop)", scene=name, size=size, spp=args.throughput_spp)
        results["throughput"].append(r)
        if name == "builtin:cornell":  # the same render through the scalar loop (apps/pt/integrator.h)
            r = throughput(tool, scene, size, args.throughput_spp, "--loop", "scalar")
            r.update(renderer="udm1-pt sobol-owen (scalar loop)", scene=name, size=size, spp=args.throughput_spp)
            results["throughput"].append(r)
    scene_dir = out / "cornell-export"
    tool_run(tool, "export", str(scene_dir), "--size", args.size)
    mitsuba_scene.render(scene_dir, 1, "independent", 0)  # warm up: Mitsuba's first render sets up its JIT and threads
    img, secs = mitsuba_scene.render(scene_dir, args.throughput_spp, "independent", 1)
    paths = w * h * args.throughput_spp
    results["throughput"].append({"renderer": "Mitsuba 3 scalar_rgb independent", "scene": "builtin:cornell",
                                  "size": args.size, "spp": args.throughput_spp, "seconds": secs, "paths": paths,
                                  "rays": None, "paths_per_second": paths / secs, "rays_per_second": None})
    for variant in (v for v in variants if v != "scalar_rgb"):
        mi.set_variant(variant)
        mitsuba_scene.render(scene_dir, args.throughput_spp, "independent", 0)  # its kernels compiled, not timed
        img, secs = mitsuba_scene.render(scene_dir, args.throughput_spp, "independent", 1)
        results["throughput"].append({"renderer": f"Mitsuba 3 {variant} independent", "scene": "builtin:cornell",
                                      "size": args.size, "spp": args.throughput_spp, "seconds": secs, "paths": paths,
                                      "rays": None, "paths_per_second": paths / secs, "rays_per_second": None})
        mi.set_variant("scalar_rgb")

    # 2. equal spp
    ref = out / f"ref-cornell-{args.size}-{args.ref_spp}.exr"
    log(f"reference: udm1-pt sobol-owen {args.ref_spp} spp at {args.size} -> {ref} (reused when cached)")
    tool_run(tool, "reference", "-o", str(ref), "--spp", str(args.ref_spp), "--size", args.size, "--seed", "7")
    # interleaved, so that the VM's drift during the run falls on both renderers alike: per spp, one
    # udm1-pt sampler, then one Mitsuba sampler, and so on
    rows = []
    for spp in spps:
        order = []
        for k in range(max(len(ours), len(theirs))):
            order += [("udm1-pt", ours[k])] if k < len(ours) else []
            order += [("mitsuba", theirs[k])] if k < len(theirs) else []
        for renderer, s in order:
            log(f"{renderer} {s}: spp {spp}")
            if renderer == "udm1-pt":
                csv_out = tool_run(tool, "sweep", "--against", str(ref), "--samplers", s, "--spps", str(spp),
                                   "--size", args.size, "--seeds", str(args.seeds))
                recs = list(csv.DictReader(csv_out.splitlines()))
                rows.append({"renderer": "udm1-pt", "sampler": s, "spp": spp,
                             "seconds": float(np.mean([float(r["seconds"]) for r in recs])),
                             "rmse": float(np.sqrt(np.mean([float(r["rmse"]) ** 2 for r in recs])))})
                continue
            variant, _, sampler = s.rpartition(":")
            mi.set_variant(variant or "scalar_rgb")
            if variant:  # a JIT variant compiles its kernels at the first render of a configuration: not timed
                mitsuba_scene.render(scene_dir, spp, sampler, 0)
            secs, mse, counts = [], [], []
            for seed in range(1, args.seeds + 1):
                img, t = mitsuba_scene.render(scene_dir, spp, sampler, seed, counts)
                exr = out / f"mitsuba-{s}-{spp}-{seed}.exr"
                mi.set_variant("scalar_rgb")
                mi.util.write_bitmap(str(exr), img.astype("float32"), write_async=False)
                mi.set_variant(variant or "scalar_rgb")
                secs.append(t)
                mse.append(rmse_of(tool, exr, ref) ** 2)
                exr.unlink()
            rows.append({"renderer": "mitsuba", "sampler": s, "spp": spp, "rendered_spp": counts[0],
                         "seconds": float(np.mean(secs)), "rmse": float(np.sqrt(np.mean(mse)))})
    results["runs"] = rows

    # 3. equal error
    def curve(renderer, s):
        return [(r["seconds"], r["rmse"]) for r in rows if r["renderer"] == renderer and r["sampler"] == s]

    targets = [r["rmse"] for r in rows if r["renderer"] == "mitsuba" and r["sampler"] == "independent"][1:]
    equal = []
    for target in targets:
        rec = {"rmse": target, "udm1-pt": {}, "mitsuba": {}}
        for s in ours:
            rec["udm1-pt"][s] = time_to(curve("udm1-pt", s), target)
        for s in theirs:
            rec["mitsuba"][s] = time_to(curve("mitsuba", s), target)
        best_ours = min((t, s) for s, t in rec["udm1-pt"].items() if t)
        best_theirs = min((t, s) for s, t in rec["mitsuba"].items() if t)
        rec["best_udm1"], rec["best_mitsuba"] = best_ours[1], best_theirs[1]
        rec["speedup"] = best_theirs[0] / best_ours[0]
        equal.append(rec)
    results["equal_error"] = equal
    (out / "bench_pt.json").write_text(json.dumps(results, indent=1))

    # report
    print(f"# udm1-pt against Mitsuba 3 {mi.__version__} ({', '.join(variants)}), {results['machine']}\n")
    print(f"## Throughput ({args.throughput_spp} spp)\n")
    print("| renderer | scene | size | paths/s | rays/s | rays/path |\n|---|---|---|---|---|---|")
    for r in results["throughput"]:
        rays = f"{r['rays_per_second']:.3g}" if r["rays"] else "n/a"
        rpp = f"{r['rays'] / r['paths']:.2f}" if r["rays"] else "n/a"
        print(f"| {r['renderer']} | {r['scene']} | {r['size']} | {r['paths_per_second']:.3g} | {rays} | {rpp} |")
    for m in (r for r in results["throughput"] if r["renderer"].startswith("Mitsuba")):
        base = m["paths_per_second"]
        print(f"\nudm1-pt / {m['renderer']} paths per second on the same Cornell box: "
              f"{results['throughput'][0]['paths_per_second'] / base:.2f} "
              f"(scalar loop: {results['throughput'][1]['paths_per_second'] / base:.2f})")
    print()
    print(f"## Equal spp: RMSE against udm1-pt sobol-owen {args.ref_spp} spp, {args.size}, {args.seeds} seeds "
          "(seconds in brackets)\n")
    print("| renderer | sampler | " + " | ".join(f"{n} spp" for n in spps) + " |")
    print("|---|---|" + "---|" * len(spps))
    for renderer, names in (("mitsuba", theirs), ("udm1-pt", ours)):
        for s in names:
            cells = [next((f"{r['rmse']:.5f} ({r['seconds']:.2f})"
                           + (f" [{r['rendered_spp']} spp]" if r.get("rendered_spp", n) != n else "") for r in rows
                           if r["renderer"] == renderer and r["sampler"] == s and r["spp"] == n), "") for n in spps]
            print(f"| {renderer} | {s} | " + " | ".join(cells) + " |")
    print("\n## Equal error: seconds to reach the RMSE Mitsuba's independent sampler reaches at each spp\n")
    print("| target RMSE | " + " | ".join(f"mitsuba {s}" for s in theirs) + " | "
          + " | ".join(ours) + " | best Mitsuba / best udm1-pt |")
    print("|---|" + "---|" * (len(theirs) + len(ours) + 1))
    for rec in equal:
        cells = [f"{rec['mitsuba'][s]:.3g}" if rec["mitsuba"][s] else "-" for s in theirs]
        cells += [f"{rec['udm1-pt'][s]:.3g}" if rec["udm1-pt"][s] else "-" for s in ours]
        print(f"| {rec['rmse']:.5f} | " + " | ".join(cells)
              + f" | **{rec['speedup']:.2f}** ({rec['best_mitsuba']} / {rec['best_udm1']}) |")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 5))
        for renderer, names, style in (("mitsuba", theirs, "--"), ("udm1-pt", ours, "-")):
            for s in names:
                c = sorted(curve(renderer, s))
                ax.loglog([t for t, _ in c], [e for _, e in c], style, marker="o", ms=3, label=f"{renderer} {s}")
        ax.set_xlabel("render seconds (all cores)")
        ax.set_ylabel("RMSE against the reference")
        ax.set_title(f"Cornell box {args.size}: error against time")
        ax.legend(fontsize=7, ncol=2)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(out / "pt_error_vs_time.png", dpi=110)
        print(f"\nplot: {out / 'pt_error_vs_time.png'}; numbers: {out / 'bench_pt.json'}")
    except ImportError:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
