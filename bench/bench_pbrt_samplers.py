"""The paper's experiment in its own renderer family: samplers swapped inside pbrt-v4 on the paper's scenes.

pbrt-v4 (built from the snapshot in ../shared/anchors by scripts/anchors.sh, with udm1's sampler added by
integrations/pbrt-v4/udm1-sampler.patch; skipped with a message where the snapshot or the shared scenes
are absent) renders the Crown (the paper's Figure 10 scene) and veach-mis with each sampler at equal spp:
its own `zsobol` (its default), `halton`, `sobol` and `independent`, and `Sampler "udm1"` with the presets
`wr`, `wmmr`, `hwmmr`, `sobol-owen` and `wr` with screen-space randomization. Every render is compared
with one high-spp pbrt-v4 reference (zsobol) of the same scene: PSNR (peak 1, linear RGB clamped to
[0, 1], as udm1-pt's reports), averaged over --seeds seeds, the gain over `independent` (the paper's
PRNG), and the time per render (pbrt-v4's whole process: its scene load included; the load alone is
timed with --spp 1 and reported beside it). The samplers' renders alternate seed by seed.

Writes DIR/pbrt_samplers.json and DIR/pbrt_samplers.md.

    python bench/bench_pbrt_samplers.py [--pbrt PATH] [--spp 256] [--ref-spp 4096] [--seeds 2]
                                        [--only crown,veach-mis] [--out build/bench_pbrt]
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
from bench_accuracy import SHARED, Case, Variant, find_pbrt, prepare, read_exr  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

# (label, pbrt-v4 Sampler directive); the paper's PRNG is pbrt-v4's independent sampler
SAMPLERS = [
    ("pbrt independent (PRNG)", 'Sampler "independent"'),
    ("pbrt halton", 'Sampler "halton"'),
    ("pbrt sobol", 'Sampler "sobol"'),
    ("pbrt zsobol (default)", 'Sampler "zsobol"'),
    ("udm1 wr", 'Sampler "udm1" "string preset" "wr"'),
    ("udm1 wmmr", 'Sampler "udm1" "string preset" "wmmr"'),
    ("udm1 hwmmr", 'Sampler "udm1" "string preset" "hwmmr"'),
    ("udm1 sobol-owen", 'Sampler "udm1" "string preset" "sobol-owen"'),
    ("udm1 wr, screen", 'Sampler "udm1" "string preset" "wr" "string randomization" "screen"'),
]
# the paper's PSNR gains over PRNG at 4096 spp (Figure 10, the Crown; Figure 8 is San Miguel, not shared)
PAPER_CROWN = {"pbrt independent (PRNG)": 0.0, "pbrt halton": 23.687158 - 22.751059, "pbrt sobol": 23.748147 - 22.751059,
               "udm1 wr": 23.571509 - 22.751059, "udm1 wmmr": 23.553944 - 22.751059, "udm1 hwmmr": 23.677106 - 22.751059}
SAMPLER_BLOCK = r'(?m)^Sampler "[^"]+"[^\n]*\n(?:[ \t]+"[^\n]*\n)*'


def log(msg: str) -> None:
    print(f"[bench_pbrt_samplers {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def scenes() -> list[Case]:
    return [Case("crown", SHARED / "crown" / "crown.pbrt", (100, 140), 0),
            Case("veach-mis", SHARED / "veach-mis" / "veach-mis.pbrt", (192, 144), 0)]


def scene_with(case: Case, label: str, directive: str, work: Path) -> Path:
    """The scene's file with its Sampler directive replaced (bench_accuracy.prepare: a box filter, the case's
    size, the scene's folder linked)."""
    return prepare(case, Variant(label, [(SAMPLER_BLOCK, directive + "\n")]), work)


def render(pbrt: str, scene: Path, spp: int, seed: int, threads: int) -> tuple[np.ndarray, float]:
    out = scene.with_name(f"{scene.stem}-{spp}-{seed}.exr")
    cmd = [pbrt, "--spp", str(spp), "--seed", str(seed), "--nthreads", str(threads), "--quiet", "--outfile",
           str(out), str(scene)]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=scene.parent)
    seconds = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip()[-400:]}")
    img = read_exr(out)
    out.unlink()
    return img, seconds


def psnr(img: np.ndarray, ref: np.ndarray) -> float:
    mse = float(np.mean((np.clip(img, 0, 1) - np.clip(ref, 0, 1)) ** 2))
    return float("inf") if mse == 0 else -10.0 * np.log10(mse)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pbrt", default="", help="a pbrt-v4 binary with udm1's sampler (default: scripts/anchors.sh pbrt-v4)")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--only", default="", help="comma-separated scene names (crown, veach-mis)")
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_pbrt"))
    args = ap.parse_args()
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    if not SHARED.is_dir():
        why = f"the shared scenes ({SHARED}) are absent"
        log(f"skipped: {why}")
        (out / "pbrt_samplers.json").write_text(json.dumps({"skipped": why, "rows": []}))
        return 0
    pbrt = find_pbrt(args.pbrt)
    if not pbrt:
        why = "no pbrt-v4 (its snapshot, ../shared/anchors, is absent)"
        log(f"skipped: {why}")
        (out / "pbrt_samplers.json").write_text(json.dumps({"skipped": why, "rows": []}))
        return 0
    rows = []
    for case in scenes():
        if args.only and case.name not in args.only.split(","):
            continue
        ref_scene = scene_with(case, "reference", 'Sampler "zsobol"', out)
        ref_path = out / f"{case.name}-reference-{args.ref_spp}.npy"
        if ref_path.exists():
            ref = np.load(ref_path)
        else:
            log(f"{case.name}: reference, zsobol at {args.ref_spp} spp")
            ref, secs = render(pbrt, ref_scene, args.ref_spp, 1000, args.threads)
            np.save(ref_path, ref)
            log(f"  {secs:.1f} s")
        _, load = render(pbrt, ref_scene, 1, 1, args.threads)  # the load: a 1-spp render is nearly all load
        files = {label: scene_with(case, label, directive, out) for label, directive in SAMPLERS}
        results = {label: {"psnr": [], "seconds": []} for label, _ in SAMPLERS}
        for seed in range(1, args.seeds + 1):
            for label, _ in SAMPLERS:
                img, secs = render(pbrt, files[label], args.spp, seed, args.threads)
                results[label]["psnr"].append(psnr(img, ref))
                results[label]["seconds"].append(secs)
                log(f"{case.name} seed {seed}: {label}: {results[label]['psnr'][-1]:.2f} dB, {secs:.1f} s")
        base = float(np.mean(results[SAMPLERS[0][0]]["psnr"]))
        for label, _ in SAMPLERS:
            p = float(np.mean(results[label]["psnr"]))
            rows.append({"scene": case.name, "sampler": label, "spp": args.spp, "seeds": args.seeds, "psnr": p,
                         "psnr_seeds": results[label]["psnr"], "gain": p - base,
                         "paper_gain": PAPER_CROWN.get(label) if case.name == "crown" else None,
                         "seconds": float(np.mean(results[label]["seconds"])), "load_seconds": load,
                         "size": list(case.size), "ref_spp": args.ref_spp})
    md = ["# Samplers inside pbrt-v4: the paper's experiment", "",
          f"`python bench/bench_pbrt_samplers.py --spp {args.spp} --ref-spp {args.ref_spp} --seeds {args.seeds}` on "
          f"{platform.node()} ({os.cpu_count()} cores, {args.threads} threads), {time.strftime('%Y-%m-%d')}. PSNR against a "
          f"{args.ref_spp}-spp pbrt-v4 zsobol reference, mean over {args.seeds} seeds; seconds per render (the whole "
          "process, the scene's load included).", "",
          "| scene | sampler | PSNR (dB) | each seed's | gain over PRNG | the paper's gain (Crown, Figure 10) | seconds | of which load |",
          "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        paper = "" if r["paper_gain"] is None else f"{r['paper_gain']:+.2f}"
        seeds = " / ".join(f"{x:.2f}" for x in r["psnr_seeds"])
        md.append(f"| {r['scene']} {r['size'][0]}x{r['size'][1]} | {r['sampler']} | {r['psnr']:.2f} | {seeds} | {r['gain']:+.2f} | "
                  f"{paper} | {r['seconds']:.2f} | {r['load_seconds']:.2f} |")
    (out / "pbrt_samplers.md").write_text("\n".join(md) + "\n")
    (out / "pbrt_samplers.json").write_text(json.dumps({"rows": rows, "pbrt": pbrt, "machine": platform.node(),
                                                        "date": time.strftime("%Y-%m-%d")}, indent=1))
    print("\n".join(md))
    return 0


if __name__ == "__main__":
    sys.exit(main())
