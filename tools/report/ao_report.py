"""The ambient occlusion report: the paper's Figure 6 on udm1-ao's default scene.

Every sampler with two dimensions renders the scene at 64 spp; each image is
compared with a high-spp reference (sobol-owen, 8192 spp by default, rendered
once by `udm1-ao reference` and reused while the scene and settings are the
same). The report gives a table of PSNR (peak 1 on linear AO) and render time,
with the PSNR's spread over seeds, a contact sheet of the images with their
PSNR, an equal-time comparison (each sampler gets the time EPISWR takes at
64 spp) and an spp sweep (16 to 256; 1024 with --sweep-spps) plotted as error against spp and
against time.

Writes OUT/ao.md, OUT/ao.html, OUT/ao_*.png, OUT/ao.csv and OUT/ao.json;
the images and the reference go to OUT/ao/.

    python tools/report/ao_report.py --ao build/bin/udm1-ao --out report
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from report_common import RendererTool, log, md_table, md_to_html, reference_cache, writable_folder  # noqa: E402

# The paper's set for ambient occlusion (section 4.2.3), in its order, then the other samplers.
PAPER_SET = ["pcg32", "cmj", "grps", "hammersley", "lp", "halton", "sobol", "wr-ao", "we", "wgr", "episwr"]
OTHERS = ["drand48", "halton-owen", "sobol-owen", "pmj02", "wr", "wmmr", "hwmmr", "rd", "wopt", "lattice", "wr+tent",
          "lattice+tent"]
WEYL = {"wr-ao", "we", "wgr", "episwr", "wr", "wmmr", "hwmmr", "rd", "wopt"}
NAMES = {"pcg32": "PRNG (pcg32)", "cmj": "CMJ", "grps": "GRPS", "hammersley": "Hammersley", "lp": "LP",
         "halton": "Halton", "sobol": "Sobol", "wr-ao": "WR (sqrt2, sqrt13)", "we": "WE", "wgr": "WGR",
         "episwr": "EPISWR"}


def AoTool(path: str, scene: str, size: str, maxdist: str | None, cache: Path | None = None) -> RendererTool:
    return RendererTool(path, "udm1-ao", ["--scene", scene, "--size", size] + (["--maxdist", maxdist] if maxdist else []),
                        ms=True, cache=cache)


def summarize(rows, spp: int, seeds: int) -> list[dict]:
    out = []
    for s in dict.fromkeys(r["sampler"] for r in rows):
        rs = [r for r in rows if r["sampler"] == s and r["spp"] == spp]
        ps = [r["psnr"] for r in rs]
        out.append({"sampler": s, "spp": spp, "n_seeds": len(ps), "psnr_seed1": rs[0]["psnr"], "psnr_mean": float(np.mean(ps)),
                    "psnr_sd": float(np.std(ps, ddof=1)) if seeds > 1 else 0.0,
                    "rmse_mean": float(np.sqrt(np.mean([r["rmse"] ** 2 for r in rs]))),
                    "seconds": float(np.median([r["seconds"] for r in rs])), "paper_set": s in PAPER_SET})
    return out


def contact_sheet(rows, folder: Path, out: Path, name: str, title: str, label) -> str:
    cols = 4 if len(rows) > 9 else 3
    nrows = math.ceil(len(rows) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(3.1 * cols, 3.6 * nrows))
    for ax in np.ravel(axes):
        ax.axis("off")
    for ax, r in zip(np.ravel(axes), rows):
        img = mpimg.imread(folder / r["png"])
        img = img if img.ndim == 2 else img[..., 0]  # linear AO, shown with gamma 2.2 (PSNR is on linear values)
        ax.imshow(img ** (1 / 2.2), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
        ax.set_title(label(r), fontsize=9, color="#a00" if r["sampler"] in WEYL else "black")
    fig.suptitle(title + "; shown with gamma 2.2")
    fig.tight_layout()
    fig.savefig(out / name, dpi=110)
    plt.close(fig)
    return name


def plot_sweep(rows, out: Path) -> str:
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    samplers = list(dict.fromkeys(r["sampler"] for r in rows))
    cmap = plt.get_cmap("tab20")
    for k, s in enumerate(samplers):
        pts = [r for r in rows if r["sampler"] == s]
        style = dict(color=cmap(k % 20), lw=2.2 if s in WEYL else 1.2, ls="-" if s in WEYL else "--",
                     marker="o" if s in WEYL else ".", label=s)
        axes[0].loglog([p["spp"] for p in pts], [p["rmse"] for p in pts], **style)
        axes[1].loglog([p["seconds"] for p in pts], [p["rmse"] for p in pts], **style)
    spps = sorted({r["spp"] for r in rows})
    ref = [rows[0]["rmse"] * (spps[0] / n) ** 0.5 for n in spps]
    axes[0].loglog(spps, ref, color="grey", lw=0.8, ls=":", label="N^-1/2")
    axes[0].set(xlabel="samples per pixel", ylabel="RMSE against the reference", title="error against spp")
    axes[1].set(xlabel="render time (s)", ylabel="RMSE against the reference", title="error against time")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
    axes[1].legend(fontsize=7, ncol=2)
    fig.suptitle("Ambient occlusion: the paper's Weyl sets solid, baselines dashed")
    fig.tight_layout()
    fig.savefig(out / "ao_sweep.png", dpi=110)
    plt.close(fig)
    return "ao_sweep.png"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ao", required=True, help="path of udm1-ao")
    ap.add_argument("--out", default="report")
    ap.add_argument("--scene", default="builtin:cornell")
    ap.add_argument("--size", default="256x256")
    ap.add_argument("--maxdist", default=None, help="occlusion ray length (default: unbounded)")
    ap.add_argument("--spp", type=int, default=64, help="samples per pixel of Figure 6 (default 64)")
    ap.add_argument("--ref-spp", type=int, default=8192, help="Figure 6's reference spp (default 8192, as the paper)")
    ap.add_argument("--sweep-ref-spp", type=int, default=8192,
                    help="the sweep's reference spp (default 8192: the screen step's reference too)")
    ap.add_argument("--seeds", type=int, default=4, help="seeds per PSNR (default 4; the sheets show seed 1)")
    ap.add_argument("--sweep-size", default="128x128", help="image size of the spp sweep (default 128x128)")
    ap.add_argument("--sweep-spps", default="16,32,64,128,256",
                    help="spp of the sweep (default 16,32,64,128,256; the main report's --full adds 512,1024)")
    ap.add_argument("--quick", action="store_true", help="a small image and few spp, for tests")
    args = ap.parse_args(argv)
    if not Path(args.ao).exists():
        print(f"ao_report: no udm1-ao at '{args.ao}' (build it first)", file=sys.stderr)
        return 2
    if not (1 <= args.spp <= 1 << 20 and 4 <= args.ref_spp <= 1 << 20 and 1 <= args.sweep_ref_spp <= 1 << 20
            and 1 <= args.seeds <= 1000):
        print("ao_report: --spp and --sweep-ref-spp must be in 1..1048576, --ref-spp in 4..1048576 and --seeds in "
              "1..1000", file=sys.stderr)
        return 2
    out = writable_folder(args.out, "ao_report")
    if out is None:
        return 1
    if args.quick:
        args.size, args.sweep_size, args.ref_spp, args.seeds, args.spp = "48x48", "32x32", 1024, 2, 16
        args.sweep_ref_spp = 1024
    try:
        spps = [4, 16, 64] if args.quick else sorted({int(x) for x in args.sweep_spps.split(",")})
    except ValueError:
        spps = []
    if not spps or not all(1 <= n <= 1 << 20 for n in spps):
        print(f"ao_report: --sweep-spps '{args.sweep_spps}' is not a list of spp in 1..1048576", file=sys.stderr)
        return 2
    folder = out / "ao"
    folder.mkdir(exist_ok=True)
    cache = reference_cache(out)
    tool = AoTool(args.ao, args.scene, args.size, args.maxdist, cache)
    t0 = time.time()
    samplers = PAPER_SET + OTHERS
    ref = folder / f"reference-{args.size}-{args.ref_spp}spp.exr"
    log(f"reference: {args.ref_spp} spp, sobol-owen (reused if it was made by the same scene and settings)")
    ref_line = tool.reference(args.ref_spp, ref, folder / "reference.png")
    # the reference's own error, estimated: half its RMSE against the render of a quarter of its samples (from there
    # to the reference the error falls at least as N^-1/2 does: by half or more)
    quarter = folder / f"reference-{args.size}-{args.ref_spp // 4}spp.exr"
    tool.reference(args.ref_spp // 4, quarter, folder / "reference-quarter.png")
    ref_error = 0.5 * float(re.search(r"rmse (\S+)", tool.run("compare", str(quarter), str(ref))).group(1))
    log(f"Figure 6: {len(samplers)} samplers at {args.spp} spp, {args.seeds} seeds each")
    fig6 = summarize(tool.sweep(samplers, [args.spp], args.seeds, ref, folder), args.spp, args.seeds)
    for r in fig6:
        r["png"] = f"{r['sampler']}-{args.spp}spp.png"
    budget = next(r["seconds"] for r in fig6 if r["sampler"] == "episwr")
    # the sweep on a smaller image with its own reference, so that it fits in the main job
    small = AoTool(args.ao, args.scene, args.sweep_size, args.maxdist, cache)
    small_ref = folder / f"reference-{args.sweep_size}-{args.sweep_ref_spp}spp.exr"
    log(f"spp sweep {spps[0]}..{spps[-1]} at {args.sweep_size} (reference: {args.sweep_ref_spp} spp, reused if made "
        "before)")
    small.reference(args.sweep_ref_spp, small_ref, folder / f"reference-{args.sweep_size}.png")
    sw = [{k: v for k, v in r.items() if k in ("sampler", "spp", "seconds")} | {"rmse": r["rmse_mean"]}
          for spp in spps for r in summarize(small.sweep(samplers, [spp], 1, small_ref, note=f"{spp} spp "), spp, 1)]
    log(f"equal time: every sampler given EPISWR's {args.spp}-spp time, {budget * 1e3:.1f} ms")
    eq_folder = folder / "equal_time"
    eq_folder.mkdir(exist_ok=True)
    eq = []
    for r in fig6:  # time is proportional to spp at a fixed image size (the sweep's times show it)
        s, spp = r["sampler"], max(1, int(round(args.spp * budget / r["seconds"])))
        eq += summarize(tool.sweep([s], [spp], args.seeds, ref, eq_folder), spp, args.seeds)
        eq[-1]["png"] = f"equal_time/{s}-{spp}spp.png"

    fig6_rows = [{"sampler": "reference", "png": "reference.png", "psnr_seed1": float("inf"), "seconds": 0}]
    sheet = contact_sheet(fig6_rows + [r for r in fig6 if r["paper_set"]], folder, out, "ao_figure6.png",
                          f"Figure 6: ambient occlusion at {args.spp} spp (PSNR against {args.ref_spp} spp, seed 1)",
                          lambda r: f"reference, {args.ref_spp} spp (Figure 4)" if r["sampler"] == "reference" else
                          f"{NAMES.get(r['sampler'], r['sampler'])}\n{r['psnr_seed1']:.2f} dB, {r['seconds'] * 1e3:.0f} ms")
    sheet_all = contact_sheet(fig6, folder, out, "ao_all.png", f"every sampler at {args.spp} spp",
                              lambda r: f"{r['sampler']}\n{r['psnr_seed1']:.2f} dB")
    sheet_eq = contact_sheet([r for r in eq if r["sampler"] in PAPER_SET], folder, out, "ao_equal_time.png",
                             f"equal time ({budget * 1e3:.0f} ms each, EPISWR's {args.spp}-spp time)",
                             lambda r: f"{r['sampler']}: {r['spp']} spp\n{r['psnr_seed1']:.2f} dB, "
                                       f"{r['seconds'] * 1e3:.0f} ms")
    sweep_png = plot_sweep(sw, out)

    with open(out / "ao.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["table", "sampler", "spp", "psnr_seed1", "psnr_mean", "psnr_sd", "rmse",
                                          "seconds"], extrasaction="ignore")
        w.writeheader()
        for r in fig6:
            w.writerow({"table": "figure6", "rmse": r["rmse_mean"], **r})
        for r in sw:
            w.writerow({"table": "sweep", **r})
        for r in eq:
            w.writerow({"table": "equal_time", **r})
    smallest = min(r["rmse_mean"] for r in fig6 + eq)
    below = f"{smallest / ref_error:.0f}" if ref_error > 0 else "infinitely many"
    (out / "ao.json").write_text(json.dumps({"figure6": fig6, "sweep": sw, "equal_time": eq, "reference": ref_line,
                                             "reference_spp": args.ref_spp, "reference_error": ref_error,
                                             "smallest_rmse": smallest, "budget_seconds": budget,
                                             "seconds": time.time() - t0}, indent=1))
    best = max(fig6, key=lambda r: r["psnr_mean"])
    best_eq = max(eq, key=lambda r: r["psnr_mean"])
    ranked = sorted(fig6, key=lambda r: -r["psnr_mean"])
    rank_of = {r["sampler"]: k + 1 for k, r in enumerate(ranked)}
    table = [[r["sampler"] + (" *" if r["paper_set"] else ""), f"{r['psnr_seed1']:.2f}",
              f"{r['psnr_mean']:.2f} +- {r['psnr_sd']:.2f}", rank_of[r["sampler"]], f"{r['seconds'] * 1e3:.1f}"]
             for r in fig6]
    eq_table = [[r["sampler"], r["spp"], f"{r['seconds'] * 1e3:.1f}", f"{r['psnr_seed1']:.2f}", f"{r['psnr_mean']:.2f}"]
                for r in sorted(eq, key=lambda r: -r["psnr_mean"])]
    epis = next(r for r in fig6 if r["sampler"] == "episwr")
    paper_rank = {r["sampler"]: k + 1 for k, r in enumerate(sorted((r for r in fig6 if r["paper_set"]),
                                                                    key=lambda r: -r["psnr_mean"]))}
    eq_rank = {r["sampler"]: k + 1 for k, r in enumerate(sorted((r for r in eq if r["sampler"] in PAPER_SET),
                                                                 key=lambda r: -r["psnr_mean"]))}
    md = f"""# udm1 ambient occlusion report

The paper's Figure 6 (section 4.2) on `{args.scene}` at {args.size}: AO = (1/pi) * integral of V cos(theta),
{args.spp} cosine-weighted directions per pixel from each sampler's 2D points, per-pixel randomization as
the library provides it (each sampler's default), compared with a {args.ref_spp}-spp reference
(`{ref_line}`), whose own error is about {ref_error:.2g} (half its RMSE against its first {args.ref_spp // 4}
spp), {below} times below the smallest RMSE compared here ({smallest:.2g}): its share of a
compared MSE is at most {100 * (ref_error / smallest) ** 2:.1f} %. PSNR has peak 1 on linear AO values (10 log10(1/MSE)). Times are udm1-ao's render time
(median of the seeds, all cores, scene loading excluded). Made in {time.time() - t0:.0f} s by
`python tools/report/ao_report.py --ao build/bin/udm1-ao --out report`. Raw numbers: [ao.csv](ao.csv), [ao.json](ao.json).

## Verdict
At {args.spp} spp the best mean PSNR over {args.seeds} seeds is **{best['sampler']}** ({best['psnr_mean']:.2f} dB);
EPISWR, the paper's choice, is {epis['psnr_mean']:.2f} dB (rank {rank_of['episwr']} of {len(fig6)}). At equal time
({budget * 1e3:.0f} ms) the best is **{best_eq['sampler']}** ({best_eq['psnr_mean']:.2f} dB at {best_eq['spp']} spp).
The paper (Figure 6) reports EPISWR first of its {len(PAPER_SET)} and Halton and Sobol last; here, among the same
{len(PAPER_SET)}, EPISWR ranks {paper_rank['episwr']}, Halton {paper_rank['halton']} and Sobol {paper_rank['sobol']} at equal spp, and
EPISWR ranks {eq_rank['episwr']}, Halton {eq_rank['halton']} and Sobol {eq_rank['sobol']} at equal time. The paper's Weyl pairs
WR (sqrt2, sqrt13) and WE rank {paper_rank['wr-ao']} and {paper_rank['we']}: without the EPIS first coordinate
(a stratified 1D set), a 2D Weyl sequence is a lattice-like set whose quality depends on its pair.

![Figure 6](ao_figure6.png)

## Every sampler at {args.spp} spp
`*` marks the paper's set for AO. PSNR of seed 1 (the image shown), and mean +- sd over {args.seeds} seeds.

{md_table(["sampler", "PSNR seed 1 (dB)", f"PSNR over {args.seeds} seeds (dB)", "rank", "time (ms)"], table)}

![every sampler](ao_all.png)

## Error against spp and against time
RMSE against a {args.sweep_ref_spp}-spp reference of the same size, at {args.sweep_size} (a smaller image, so the
sweep fits in the main job), spp {", ".join(map(str, spps))}, one seed each.

![sweep]({sweep_png})

## Equal time
Each sampler renders at the spp that takes EPISWR's {args.spp}-spp time ({budget * 1e3:.0f} ms): {args.spp} x the
budget / its own {args.spp}-spp time (render time is proportional to spp, as the sweep shows); the time column is
what the render then took. Point sets (Hammersley, LP, GRPS, CMJ, PMJ02's prefixes) are then used at spp that
are not powers of two, which is part of the price of their time.

{md_table(["sampler", "spp", "time (ms)", "PSNR seed 1 (dB)", f"PSNR over {args.seeds} seeds (dB)"], eq_table)}

![equal time](ao_equal_time.png)
"""
    (out / "ao.md").write_text(md)
    (out / "ao.html").write_text(md_to_html(md, "udm1 ambient occlusion report"))
    log(f"wrote {out / 'ao.html'} in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
