"""udm1-pt against pbrt-v4 and Mitsuba 3 on the shared scenes, at equal error.

Every shared scene (../shared/scenes: cornell-box, veach-mis, crown; skipped with a message where absent) at a
benchmark size with a box pixel filter (bench_accuracy.prepare) is rendered, at each spp and seed, by:

- udm1-pt (its default loop), with each of --samplers; time: its render seconds (the scene's load apart);
- pbrt-v4, the renderer the files are written for (built from ../shared/anchors by scripts/anchors.sh; skipped
  with a message where absent), with each of its samplers in --pbrt-samplers (zsobol is its default;
  pmj02bn is left out: its tables are stubs in the snapshot); time: the process's wall time less its load
  (the least wall time of two 1-spp runs, which also hold one spp of rendering: pbrt-v4's time is, if
  anything, underestimated);
- Mitsuba 3, variants scalar_rgb and llvm_ad_rgb (its vectorized JIT variant; libllvm19, skipped with a
  message without it), where the scene can be given to it (`udm1-pt export` and bench/mitsuba_scene.py,
  which states the materials' correspondence and refuses the rest: the Crown's textures and mixes), with
  each of --mitsuba-samplers; time: mi.render with the image evaluated, its JIT kernels compiled by an
  untimed render of the same configuration first.

Each renderer's error is the RMSE of its linear RGB, clamped to [0, 1], against its own converged reference
(its default sampler at --ref-spp, cached in DIR: udm1-pt sobol-owen, pbrt-v4 zsobol, Mitsuba independent),
the MSE averaged over --seeds seeds; so each is measured on its own model of the scene (spectral or RGB,
Mitsuba's analytic plastic or pbrt-v4's layered coat). The renders alternate renderer by renderer at every
(spp, seed), in one order and then the other, and a sampler's time is its fastest render of the seeds (on a
shared machine the least disturbed; every render's time is in the JSON), so that the machine's drift falls on
all alike.

Equal error: the targets are the errors pbrt-v4's default sampler (zsobol) reaches at each spp but the first
(which is there so that every curve brackets the targets); for each renderer, the seconds its best sampler needs to reach a target (log-log interpolation between measured
points); the speed-up is the fastest other renderer's time over udm1-pt's.

Writes DIR/pt_scenes.json, DIR/pt_scenes.md and DIR/<scene>_error_vs_time.png.

    python bench/bench_pt_scenes.py [--tool build/bin/udm1-pt] [--pbrt PATH] [--only crown,veach-mis]
                                    [--spps 16,64,256] [--ref-spp 4096] [--seeds 2] [--out build/bench_pt_scenes]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_accuracy import SHARED, Case, find_pbrt, prepare, read_exr  # noqa: E402
from bench_pt import LLVM_PATH, llvm_available, time_to  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
# (scene, size, spps): the first spp is below the targets', so that every renderer's curve brackets them
SCENES = [("cornell-box", (128, 128), [4, 16, 64, 256, 1024]), ("veach-mis", (192, 144), [4, 16, 64, 256]),
          ("crown", (100, 140), [4, 16, 64, 256])]
SECONDS = re.compile(r"\bseconds ([0-9.]+)")
LOADED = re.compile(r"loaded \(parse, meshes, textures, BVH\) in ([0-9.]+) s")
SAMPLER_BLOCK = r'(?m)^Sampler "[^"]+"[^\n]*\n(?:[ \t]+"[^\n]*\n)*'


def log(msg: str) -> None:
    print(f"[bench_pt_scenes {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def rmse(img: np.ndarray, ref: np.ndarray) -> float:
    return float(np.sqrt(np.mean((np.clip(img, 0, 1) - np.clip(ref, 0, 1)) ** 2)))


class Udm1:
    name = "udm1-pt"

    def __init__(self, tool: str, scene: Path, threads: int):
        self.tool, self.scene, self.threads = tool, scene, threads
        self.load = None

    def render(self, sampler: str, spp: int, seed: int) -> tuple[np.ndarray, float]:
        out = self.scene.with_name(f"udm1-{sampler}-{spp}-{seed}.exr")
        cmd = [self.tool, "--scene", str(self.scene), "--sampler", sampler, "--spp", str(spp), "--seed", str(seed),
               "--threads", str(self.threads), "-o", str(out)]
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=self.scene.parent)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip()[-400:]}")
        self.load = float(LOADED.search(r.stdout).group(1))
        img = read_exr(out)
        out.unlink()
        return img, float(SECONDS.search(r.stdout).group(1))


class Pbrt:
    name = "pbrt-v4"

    def __init__(self, pbrt: str, case: Case, work: Path, threads: int):
        self.pbrt, self.case, self.work, self.threads = pbrt, case, work, threads
        self.files: dict = {}
        self.load = min(self.wall("zsobol", 1, 1)[1] for _ in range(2))

    def file(self, sampler: str) -> Path:
        """The prepared scene with its Sampler directive (if any) replaced by the sampler's."""
        if sampler not in self.files:
            base = prepare(self.case, None, self.work)
            text = re.sub(SAMPLER_BLOCK, "", base.read_text())
            path = base.with_name(f"{base.stem}-pbrt-{sampler}.pbrt")
            path.write_text(f'Sampler "{sampler}"\n' + text)
            self.files[sampler] = path
        return self.files[sampler]

    def wall(self, sampler: str, spp: int, seed: int) -> tuple[np.ndarray, float]:
        scene = self.file(sampler)
        out = scene.with_name(f"{scene.stem}-{spp}-{seed}.exr")
        cmd = [self.pbrt, "--spp", str(spp), "--seed", str(seed), "--nthreads", str(self.threads), "--quiet",
               "--outfile", str(out), str(scene)]
        t0 = time.perf_counter()
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=scene.parent)
        seconds = time.perf_counter() - t0
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip()[-400:]}")
        img = read_exr(out)
        out.unlink()
        return img, seconds

    def render(self, sampler: str, spp: int, seed: int) -> tuple[np.ndarray, float]:
        img, seconds = self.wall(sampler, spp, seed)
        return img, max(seconds - self.load, 1e-3)


class Mitsuba:
    def __init__(self, folder: Path, variant: str):
        self.folder, self.variant, self.name = folder, variant, f"mitsuba {variant}"
        self.compiled: set = set()
        self.load = None

    def render(self, sampler: str, spp: int, seed: int) -> tuple[np.ndarray, float]:
        import mitsuba as mi
        import mitsuba_scene

        mi.set_variant(self.variant)
        if self.variant != "scalar_rgb" and (sampler, spp) not in self.compiled:  # kernels compiled, not timed
            mitsuba_scene.render(self.folder, spp, sampler, 0)
            self.compiled.add((sampler, spp))
        if self.load is None:
            t0 = time.perf_counter()
            mitsuba_scene.load(self.folder, spp, sampler, seed)
            self.load = time.perf_counter() - t0
        img, seconds = mitsuba_scene.render(self.folder, spp, sampler, seed)
        mi.set_variant("scalar_rgb")
        return img, seconds


def reference(who, sampler: str, spp: int, path: Path) -> np.ndarray:
    if path.exists():
        return np.load(path)
    log(f"  reference: {who.name} {sampler} {spp} spp -> {path.name}")
    img, seconds = who.render(sampler, spp, 1000)
    log(f"  ({seconds:.1f} s)")
    np.save(path, img)
    return img


def run_scene(name: str, size: tuple, spps: list, args, pbrt: str | None, variants: list, out: Path) -> dict:
    case = Case(name, SHARED / name / f"{name}.pbrt", size, 0)
    scene = prepare(case, None, out)
    w, h = size
    tag = f"{name}-{w}x{h}"
    renderers = [(Udm1(args.tool, scene, args.threads), args.samplers.split(","), "sobol-owen")]
    if pbrt:
        renderers.append((Pbrt(pbrt, case, out, args.threads), args.pbrt_samplers.split(","), "zsobol"))
    mitsuba_note = ""
    if variants:
        folder = out / f"{tag}-mitsuba"
        r = subprocess.run([args.tool, "export", str(folder), "--scene", str(scene)], capture_output=True, text=True)
        try:
            if r.returncode != 0:
                raise ValueError(r.stderr.strip())
            import mitsuba_scene

            mitsuba_scene.load(folder, 1)  # raises ValueError for a material Mitsuba has no counterpart of
            for v in variants:
                renderers.append((Mitsuba(folder, v), args.mitsuba_samplers.split(","), "independent"))
        except ValueError as e:
            mitsuba_note = f"not given to Mitsuba: {e}"
            log(f"{name}: {mitsuba_note}")
    refs, ref_means = {}, {}
    for who, _, default in renderers:
        family = "mitsuba" if who.name.startswith("mitsuba") else who.name
        if family not in refs:
            if family == "mitsuba":  # one reference for both variants: the fastest variant renders it
                who = next(x for x, _, _ in reversed(renderers) if x.name.startswith("mitsuba"))
            refs[family] = reference(who, default, args.ref_spp, out / f"ref-{tag}-{family}-{args.ref_spp}.npy")
            ref_means[family] = refs[family].reshape(-1, 3).mean(axis=0).tolist()
    rows = []
    for spp in spps:
        acc: dict = {}
        for seed in range(1, args.seeds + 1):
            turns = [(k, r) for k in range(max(len(s) for _, s, _ in renderers)) for r in renderers]
            for k, (who, samplers, _) in (turns if seed % 2 else turns[::-1]):  # both ways round
                if k < len(samplers):
                    s = samplers[k]
                    img, seconds = who.render(s, spp, seed)
                    family = "mitsuba" if who.name.startswith("mitsuba") else who.name
                    a = acc.setdefault((who.name, s), {"mse": [], "seconds": []})
                    a["mse"].append(rmse(img, refs[family]) ** 2)
                    a["seconds"].append(seconds)
        for (renderer, s), a in acc.items():
            rows.append({"renderer": renderer, "sampler": s, "spp": spp, "rmse": float(np.sqrt(np.mean(a["mse"]))),
                         "seconds": float(min(a["seconds"])), "all_seconds": a["seconds"]})
            log(f"{name} {spp} spp: {renderer} {s}: RMSE {rows[-1]['rmse']:.5f}, {rows[-1]['seconds']:.3f} s")
    loads = {who.name: who.load for who, _, _ in renderers}

    def curve(renderer, s):
        return [(r["seconds"], r["rmse"]) for r in rows if r["renderer"] == renderer and r["sampler"] == s]

    equal = []
    if pbrt:
        targets = [r["rmse"] for r in rows if r["renderer"] == "pbrt-v4" and r["sampler"] == "zsobol"][1:]
        for target in targets:
            rec = {"rmse": target, "best": {}}
            for who, samplers, _ in renderers:
                times = [(time_to(curve(who.name, s), target), s) for s in samplers]
                times = [x for x in times if x[0]]
                rec["best"][who.name] = min(times) if times else None
            ours = rec["best"].get("udm1-pt")
            others = [(t[0], n, t[1]) for n, t in rec["best"].items() if n != "udm1-pt" and t]
            if ours and others:
                fastest = min(others)
                rec["fastest_other"] = fastest[1]
                rec["speedup"] = fastest[0] / ours[0]
                rec["speedup_each"] = {n: t[0] / ours[0] for n, t in rec["best"].items() if n != "udm1-pt" and t}
            equal.append(rec)
    plot(name, size, renderers, curve, out / f"{name}_error_vs_time.png")
    return {"scene": name, "size": list(size), "spps": spps, "seeds": args.seeds, "ref_spp": args.ref_spp,
            "reference_means": ref_means, "load_seconds": loads, "mitsuba": mitsuba_note, "runs": rows,
            "equal_error": equal, "renderers": [[who.name, samplers] for who, samplers, _ in renderers]}


def plot(name, size, renderers, curve, path: Path) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, ax = plt.subplots(figsize=(7.5, 5))
    styles = {"udm1-pt": "-", "pbrt-v4": "--", "mitsuba scalar_rgb": ":", "mitsuba llvm_ad_rgb": "-."}
    for who, samplers, _ in renderers:
        for s in samplers:
            c = sorted(curve(who.name, s))
            ax.loglog([t for t, _ in c], [e for _, e in c], styles.get(who.name, "-"), marker="o", ms=3,
                      label=f"{who.name} {s}")
    ax.set_xlabel("render seconds (both threads; loading apart)")
    ax.set_ylabel("RMSE against the renderer's own reference")
    ax.set_title(f"{name} {size[0]}x{size[1]}: error against time")
    ax.legend(fontsize=6, ncol=2)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def markdown(res: dict, args) -> str:
    md = ["# udm1-pt against pbrt-v4 and Mitsuba 3 on the shared scenes", "",
          f"`python bench/bench_pt_scenes.py --ref-spp {args.ref_spp} --seeds {args.seeds}`, {res['date']}, "
          f"{res['machine']}; {args.threads} threads for every renderer.", ""]
    for sc in res["scenes"]:
        md += [f"## {sc['scene']} {sc['size'][0]}x{sc['size'][1]}", ""]
        if sc["mitsuba"]:
            md += [f"Mitsuba: {sc['mitsuba']}", ""]
        loads = ", ".join(f"{n} {t:.2f} s" for n, t in sc["load_seconds"].items() if t is not None)
        md += [f"Loading (not in the times below): {loads}. Reference means (R, G, B): " +
               "; ".join(f"{n} {m[0]:.4f} {m[1]:.4f} {m[2]:.4f}" for n, m in sc["reference_means"].items()), ""]
        spps = sc["spps"]
        md += ["| renderer | sampler | " + " | ".join(f"{n} spp" for n in spps) + " |", "|---|---|" + "---|" * len(spps)]
        for name, samplers in sc["renderers"]:
            for s in samplers:
                cells = [next((f"{r['rmse']:.5f} ({r['seconds']:.3f} s)" for r in sc["runs"]
                               if r["renderer"] == name and r["sampler"] == s and r["spp"] == n), "") for n in spps]
                md.append(f"| {name} | {s} | " + " | ".join(cells) + " |")
        if sc["equal_error"]:
            names = [n for n, _ in sc["renderers"]]
            md += ["", "Equal error: seconds of each renderer's best sampler to reach pbrt-v4 zsobol's RMSE at each spp",
                   "", "| target RMSE | " + " | ".join(names) + " | fastest other / udm1-pt |",
                   "|---|" + "---|" * (len(names) + 1)]
            for rec in sc["equal_error"]:
                cells = [f"{rec['best'][n][0]:.3g} ({rec['best'][n][1]})" if rec["best"].get(n) else "-" for n in names]
                sp = f"**{rec['speedup']:.2f}** ({rec['fastest_other']})" if "speedup" in rec else "-"
                md.append(f"| {rec['rmse']:.5f} | " + " | ".join(cells) + f" | {sp} |")
        md += ["", f"Plot: `{sc['scene']}_error_vs_time.png`.", ""]
    return "\n".join(md)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tool", default=str(ROOT / "build" / "bin" / "udm1-pt"))
    ap.add_argument("--pbrt", default="", help="a pbrt-v4 binary (default: scripts/anchors.sh pbrt-v4)")
    ap.add_argument("--samplers", default="sobol-owen,sobol,pmj02,wr")
    ap.add_argument("--pbrt-samplers", default="zsobol,paddedsobol,sobol,halton,independent")
    ap.add_argument("--mitsuba-samplers", default="independent,multijitter,ldsampler")
    ap.add_argument("--mitsuba-variants", default="scalar_rgb,llvm_ad_rgb")
    ap.add_argument("--spps", default="", help="comma-separated spps for every scene (default: per scene)")
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--only", default="", help="comma-separated scene names")
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_pt_scenes"))
    args = ap.parse_args(argv)
    args.tool = str(Path(args.tool).resolve())
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    if not SHARED.is_dir():
        log(f"skipped: the shared scenes ({SHARED}) are absent")
        (out / "pt_scenes.json").write_text(json.dumps({"skipped": f"{SHARED} is absent", "scenes": []}))
        return 0
    pbrt = find_pbrt(args.pbrt)
    if not pbrt:
        log("pbrt-v4 skipped: its snapshot (../shared/anchors) is absent")
    variants = [v for v in args.mitsuba_variants.split(",") if v]
    if "llvm_ad_rgb" in variants and not llvm_available():
        log(f"Mitsuba's llvm_ad_rgb skipped: no LLVM library ({LLVM_PATH}; Debian: apt-get install libllvm19)")
        variants.remove("llvm_ad_rgb")
    try:
        import mitsuba as mi

        mi.set_variant("scalar_rgb")
    except ImportError:
        log("Mitsuba skipped: mitsuba is not installed")
        variants = []
    res = {"machine": f"{platform.machine()}, {os.cpu_count()} logical cores, {platform.platform()}",
           "date": time.strftime("%Y-%m-%d"), "pbrt": pbrt, "mitsuba_variants": variants, "scenes": []}
    for name, size, spps in SCENES:
        if args.only and name not in args.only.split(","):
            continue
        if args.spps:
            spps = [int(s) for s in args.spps.split(",")]
        log(f"{name} {size[0]}x{size[1]}: spps {spps}")
        res["scenes"].append(run_scene(name, size, spps, args, pbrt, variants, out))
        (out / "pt_scenes.json").write_text(json.dumps(res, indent=1))
    md = markdown(res, args)
    (out / "pt_scenes.md").write_text(md + "\n")
    print(md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
