"""The path tracing report: the paper's Figure 8/10 protocol (section 5) on udm1-pt.

The paper renders San Miguel (Figure 8) and the Crown (Figure 10) in pbrt-v3 at 4096 spp with PRNG,
Halton, Sobol, WR, WMMR and HWMMR, and gives each image's PSNR against a 32768 / 16384 spp
reference. This report does the same on the scenes this machine can afford, at a stated size, spp and
reference spp, with every sampler the issue names: PRNG (pcg32), Halton, Sobol (plain and Owen-
scrambled), PMJ02, WR, WMMR, HWMMR and R_d. Per scene:

- a reference (sobol-owen, rendered once by `udm1-pt reference` and reused while the scene and
  settings are the same);
- every sampler at the figure's spp, PSNR (peak 1 on linear RGB clamped to [0, 1]) and render time,
  mean and spread over seeds, and a contact sheet of the images with their PSNR and time;
- an equal-time table (every sampler given PRNG's time at the figure's spp);
- an spp sweep (error against spp and against time, one seed), and from it the time each sampler
  needs to reach the error PRNG has at the figure's spp;
- the paper's numbers next to ours as PSNR gains over PRNG, and a verdict per claim.

Scenes: the built-in Cornell box by default (no files needed); --full adds the shared pbrt-v4 scenes
cornell-box and veach-mis (skipped with a message where ../shared is absent) at larger sizes; --scene
renders one given scene instead (the paper's Crown as distributed: --scene
../shared/scenes/crown/crown-volpath.pbrt, into its own --out folder).

Writes OUT/pt.md, OUT/pt.html, OUT/pt_*.png, OUT/pt.csv and OUT/pt.json; images go to OUT/pt/.

    python tools/report/pt_report.py --pt build/bin/udm1-pt --out report [--full]
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from report_common import RendererTool, log, md_table, md_to_html, reference_cache, writable_folder  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "scenes"
SAMPLERS = ["pcg32", "halton", "sobol", "sobol-owen", "pmj02", "wr", "wmmr", "hwmmr", "rd", "wopt", "lattice"]
WEYL = {"wr", "wmmr", "hwmmr", "rd", "wopt"}
NAMES = {"pcg32": "PRNG (pcg32)", "halton": "Halton", "sobol": "Sobol", "sobol-owen": "Sobol (Owen)",
         "pmj02": "PMJ02", "wr": "WR", "wmmr": "WMMR", "hwmmr": "HWMMR", "rd": "R_d", "wopt": "WOPT (udm1's search)",
         "lattice": "rank-1 lattice (CBC)"}
# The paper's PSNR (dB) at 4096 spp: Figure 8 (San Miguel, 32768 spp reference), Figure 10 (Crown, 16384)
PAPER = {"Figure 8 (San Miguel)": {"pcg32": 25.509749, "halton": 26.980754, "sobol": 25.815170, "wr": 27.238521,
                                   "wmmr": 27.355182, "hwmmr": 27.362858},
         "Figure 10 (Crown)": {"pcg32": 22.751059, "halton": 23.687158, "sobol": 23.748147, "wr": 23.571509,
                               "wmmr": 23.553944, "hwmmr": 23.677106}}


def PtTool(path: str, scene: str, size: str, cache: Path | None = None) -> RendererTool:
    return RendererTool(path, "udm1-pt", ["--scene", scene, "--size", size], ms=False, cache=cache)


def summarize(rows, spp: int) -> list[dict]:
    out = []
    for s in dict.fromkeys(r["sampler"] for r in rows):
        rs = [r for r in rows if r["sampler"] == s and r["spp"] == spp]
        ps = [r["psnr"] for r in rs]
        secs = sum(r["seconds"] for r in rs)
        out.append({"sampler": s, "spp": spp, "n_seeds": len(ps), "psnr_seed1": rs[0]["psnr"],
                    "psnr_mean": float(np.mean(ps)),
                    "psnr_sd": float(np.std(ps, ddof=1)) if len(ps) > 1 else 0.0,
                    "rmse_mean": float(np.sqrt(np.mean([r["rmse"] ** 2 for r in rs]))),
                    "seconds": float(np.median([r["seconds"] for r in rs])),
                    "paths_per_second": sum(r["paths"] for r in rs) / secs,
                    "rays_per_second": sum(r["rays"] for r in rs) / secs})
    return out


def time_to(points, target: float):
    """Seconds to reach RMSE target along (seconds, rmse) points, log-log interpolated; None if not reached."""
    pts = sorted(points)
    if pts and pts[0][1] <= target:
        return pts[0][0] * (pts[0][1] / target) ** 2  # below the first point: extrapolated at N^-1/2
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e0 > e1:
            a = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    return None


def contact_sheet(rows, folder: Path, out: Path, name: str, title: str) -> str:
    cols = 5
    nrows = math.ceil(len(rows) / cols)
    first = mpimg.imread(folder / rows[0]["png"])
    aspect = first.shape[1] / first.shape[0]
    fig, axes = plt.subplots(nrows, cols, figsize=(2.9 * cols * max(1.0, aspect) ** 0.5, 3.5 * nrows / max(1.0, aspect) ** 0.5))
    for ax in np.ravel(axes):
        ax.axis("off")
    for ax, r in zip(np.ravel(axes), rows):
        ax.imshow(mpimg.imread(folder / r["png"]), interpolation="nearest")  # sRGB PNGs, as udm1-pt writes them
        label = r.get("label") or f"{NAMES.get(r['sampler'], r['sampler'])}\n{r['psnr_seed1']:.2f} dB, {r['seconds']:.2f} s"
        ax.set_title(label, fontsize=9, color="#a00" if r["sampler"] in WEYL else "black")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out / name, dpi=100)
    plt.close(fig)
    return name


def plot_sweep(rows, out: Path, name: str, title: str) -> str:
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    cmap = plt.get_cmap("tab10")
    for k, s in enumerate(dict.fromkeys(r["sampler"] for r in rows)):
        pts = sorted((r for r in rows if r["sampler"] == s), key=lambda r: r["spp"])
        style = dict(color=cmap(k % 10), lw=2.2 if s in WEYL else 1.2, ls="-" if s in WEYL else "--",
                     marker="o" if s in WEYL else ".", label=NAMES.get(s, s))
        axes[0].loglog([p["spp"] for p in pts], [p["rmse"] for p in pts], **style)
        axes[1].loglog([p["seconds"] for p in pts], [p["rmse"] for p in pts], **style)
    spps = sorted({r["spp"] for r in rows})
    first = min((r for r in rows if r["spp"] == spps[0]), key=lambda r: r["rmse"])["rmse"]
    axes[0].loglog(spps, [first * (spps[0] / n) ** 0.5 for n in spps], color="grey", lw=0.8, ls=":", label="N^-1/2")
    axes[0].set(xlabel="samples per pixel", ylabel="RMSE against the reference", title="error against spp")
    axes[1].set(xlabel="render time (s, all cores)", ylabel="RMSE against the reference", title="error against time")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
    axes[1].legend(fontsize=8, ncol=2)
    fig.suptitle(title + ": the Weyl sets solid, the others dashed")
    fig.tight_layout()
    fig.savefig(out / name, dpi=100)
    plt.close(fig)
    return name


def compare(rows: list[dict], a: str, b: str) -> str:
    """Whether sampler a beats b in mean PSNR over seeds: "holds", "tie" or "fails". A difference within two
    standard errors of the difference of the means (at least 0.05 dB) is a tie."""
    r = {x["sampler"]: x for x in rows}
    d = r[a]["psnr_mean"] - r[b]["psnr_mean"]
    tol = max(0.05, 2 * math.sqrt((r[a]["psnr_sd"] ** 2 + r[b]["psnr_sd"] ** 2) / r[a]["n_seeds"]))
    return "holds" if d > tol else ("tie" if abs(d) <= tol else "fails")


def verdicts(fig: list[dict]) -> list[list[str]]:
    """The paper's claims, checked on this scene's mean PSNR."""
    p = {r["sampler"]: r["psnr_mean"] for r in fig}

    def cmp(a, b):
        return compare(fig, a, b)

    weyl = ["wr", "wmmr", "hwmmr"]
    rows = [[f"{NAMES[w]} beats PRNG", f"{p[w] - p['pcg32']:+.2f} dB", cmp(w, "pcg32")] for w in weyl]
    for w in weyl:
        for q in ("halton", "sobol"):
            rows.append([f"{NAMES[w]} matches or beats {NAMES[q]} (Figure 8: by 0.3-1.5 dB)", f"{p[w] - p[q]:+.2f} dB",
                         {"holds": "holds", "tie": "holds (tie)", "fails": "fails"}[cmp(w, q)]])
    best_w = max(weyl + ["rd"], key=lambda s: p[s])
    best_o = max((s for s in p if s not in WEYL), key=lambda s: p[s])
    rows.append([f"the best Weyl set ({NAMES[best_w]}) against the best other ({NAMES[best_o]})",
                 f"{p[best_w] - p[best_o]:+.2f} dB", cmp(best_w, best_o)])
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pt", required=True, help="path of udm1-pt")
    ap.add_argument("--out", default="report")
    ap.add_argument("--full", action="store_true", help="also the shared pbrt-v4 scenes, larger sizes and spp")
    ap.add_argument("--spp", type=int, default=None, help="the figure's spp (default 256; --full 512)")
    ap.add_argument("--ref-spp", type=int, default=None, help="reference spp (default 4096; --full 8192)")
    ap.add_argument("--seeds", type=int, default=2, help="seeds per PSNR (default 2)")
    ap.add_argument("--scene", help="this scene only (a .pbrt file or builtin:NAME), e.g. the Crown")
    ap.add_argument("--size", default="100x140", help="with --scene: image size (default 100x140)")
    ap.add_argument("--sweep-size", default="50x70", help="with --scene: the sweep's image size (default 50x70)")
    ap.add_argument("--sweep-spps", default=None, help="spp of the sweep (default 16,64,256; --full 16,64,256,1024)")
    ap.add_argument("--quick", action="store_true", help="tiny sizes and spp, for tests")
    args = ap.parse_args(argv)
    if not Path(args.pt).exists():
        print(f"pt_report: no udm1-pt at '{args.pt}' (build it first)", file=sys.stderr)
        return 2
    out = writable_folder(args.out, "pt_report")
    if out is None:
        return 1
    spp = args.spp or (512 if args.full else 256)
    ref_spp = args.ref_spp or (8192 if args.full else 4096)
    seeds = args.seeds
    try:
        sweep_spps = sorted({int(x) for x in args.sweep_spps.split(",")}) if args.sweep_spps else \
            ([16, 64, 256, 1024] if args.full else [16, 64, 256])
    except ValueError:
        sweep_spps = []
    if not sweep_spps or not all(1 <= n <= 1 << 20 for n in sweep_spps):
        print(f"pt_report: --sweep-spps '{args.sweep_spps}' is not a list of spp in 1..1048576", file=sys.stderr)
        return 2
    scenes = [("builtin:cornell", "Cornell box (built in)", "128x128" if args.full else "96x96", "64x64")]
    if args.full:
        for name, size, small in (("cornell-box", "128x128", "64x64"), ("veach-mis", "192x120", "96x60")):
            path = SHARED / name / f"{name}.pbrt"
            if path.exists():
                scenes.append((str(path), f"{name} (pbrt-v4 scenes)", size, small))
            else:
                log(f"{path} is absent: the shared scene {name} is skipped")
    if args.scene:
        scenes = [(args.scene, Path(args.scene).stem, args.size, args.sweep_size)]
    if args.quick:
        spp, ref_spp, seeds, sweep_spps = 16, 256, 2, [4, 16]
        scenes = [(s, t, "24x24", "16x16") for s, t, _, _ in scenes]
    if not (1 <= spp <= 1 << 20 and 1 <= ref_spp <= 1 << 20 and 1 <= seeds <= 1000):
        print("pt_report: --spp and --ref-spp must be in 1..1048576 and --seeds in 1..1000", file=sys.stderr)
        return 2
    folder = out / "pt"
    folder.mkdir(exist_ok=True)
    t0 = time.time()
    results, sections, csv_rows = [], [], []
    for k, (scene, title, size, small_size) in enumerate(scenes):
        tag = f"s{k}"
        cache = reference_cache(out)
        tool, small = PtTool(args.pt, scene, size, cache), PtTool(args.pt, scene, small_size, cache)
        ref = folder / f"{tag}-reference-{size}-{ref_spp}spp.exr"
        log(f"{title}: reference {ref_spp} spp at {size}, sobol-owen (reused if made by the same scene and settings)")
        ref_line = tool.reference(ref_spp, ref, folder / f"{tag}-reference.png")
        images = folder / tag
        images.mkdir(exist_ok=True)
        log(f"{title}: {len(SAMPLERS)} samplers at {spp} spp, {seeds} seeds each")
        fig = summarize(tool.sweep(SAMPLERS, [spp], seeds, ref, images, note=f"{tag} ", extra=("paths", "rays")), spp)
        for r in fig:
            r["png"] = f"{tag}/{r['sampler']}-{spp}spp.png"
        # equal time: every sampler given PRNG's time at the figure's spp (render time is proportional to spp)
        budget = next(r["seconds"] for r in fig if r["sampler"] == "pcg32")
        log(f"{title}: equal time, every sampler given PRNG's {budget:.2f} s")
        eq = []
        for r in fig:
            n = max(1, int(round(spp * budget / r["seconds"])))
            eq += summarize(tool.sweep([r["sampler"]], [n], seeds, ref, note=f"{tag} equal time ",
                                       extra=("paths", "rays")), n)
        small_ref = folder / f"{tag}-reference-{small_size}-{ref_spp}spp.exr"
        log(f"{title}: spp sweep {sweep_spps[0]}..{sweep_spps[-1]} at {small_size}")
        small.reference(ref_spp, small_ref, folder / f"{tag}-reference-{small_size}.png")
        sw = [{"sampler": r["sampler"], "spp": r["spp"], "seconds": r["seconds"], "rmse": r["rmse"]}
              for r in small.sweep(SAMPLERS, sweep_spps, 1, small_ref, note=f"{tag} sweep ")]
        prng_spp = min(sweep_spps, key=lambda n: abs(math.log(n / spp)))
        target = next(r["rmse"] for r in sw if r["sampler"] == "pcg32" and r["spp"] == prng_spp)
        reach = {s: time_to([(r["seconds"], r["rmse"]) for r in sw if r["sampler"] == s], target) for s in SAMPLERS}
        sheet = contact_sheet([{"sampler": "reference", "png": f"{tag}-reference.png",
                                "label": f"reference\n{ref_spp} spp"}] + fig, folder, out, f"pt_{tag}_sheet.png",
                              f"{title}, {size}: every sampler at {spp} spp (PSNR against {ref_spp} spp, seed 1)")
        sweep_png = plot_sweep(sw, out, f"pt_{tag}_sweep.png", f"{title}, {small_size}")
        results.append({"scene": scene, "title": title, "size": size, "spp": spp, "ref_spp": ref_spp, "seeds": seeds,
                        "reference": ref_line, "figure": fig, "sweep_size": small_size, "sweep": sw,
                        "target_rmse": target, "target_spp": prng_spp, "time_to_target": reach,
                        "equal_time": eq, "budget_seconds": budget})
        for r in fig:
            csv_rows.append({"scene": title, "table": "figure", "sampler": r["sampler"], "spp": spp,
                             "psnr_seed1": r["psnr_seed1"], "psnr_mean": r["psnr_mean"], "psnr_sd": r["psnr_sd"],
                             "rmse": r["rmse_mean"], "seconds": r["seconds"]})
        for r in sw:
            csv_rows.append({"scene": title, "table": "sweep", **r})
        for r in eq:
            csv_rows.append({"scene": title, "table": "equal_time", "sampler": r["sampler"], "spp": r["spp"],
                             "psnr_seed1": r["psnr_seed1"], "psnr_mean": r["psnr_mean"], "psnr_sd": r["psnr_sd"],
                             "rmse": r["rmse_mean"], "seconds": r["seconds"]})
        prng_eq = next(r for r in eq if r["sampler"] == "pcg32")
        eq_table = [[NAMES[r["sampler"]], r["spp"], f"{r['seconds']:.2f}", f"{r['psnr_mean']:.2f} +- {r['psnr_sd']:.2f}",
                     f"{r['psnr_mean'] - prng_eq['psnr_mean']:+.2f}"] for r in sorted(eq, key=lambda r: -r["psnr_mean"])]
        ranked = sorted(fig, key=lambda r: -r["psnr_mean"])
        rank = {r["sampler"]: i + 1 for i, r in enumerate(ranked)}
        prng = next(r for r in fig if r["sampler"] == "pcg32")
        table = [[NAMES[r["sampler"]], f"{r['psnr_seed1']:.2f}", f"{r['psnr_mean']:.2f} +- {r['psnr_sd']:.2f}",
                  f"{r['psnr_mean'] - prng['psnr_mean']:+.2f}", rank[r["sampler"]], f"{r['seconds']:.2f}",
                  f"{r['paths_per_second']:.3g}", f"{r['rays_per_second']:.3g}",
                  f"{reach[r['sampler']]:.3g}" if reach[r["sampler"]] else "not reached"] for r in fig]
        sections.append(f"""## {title}

`{scene}` at {size}, {spp} spp against a {ref_spp}-spp reference (`{ref_line}`), {seeds} seeds. The spp sweep
runs at {small_size} against its own {ref_spp}-spp reference; "time to PRNG's error" is the time each sampler needs
there to reach the RMSE PRNG has at {prng_spp} spp ({target:.4g}), log-log interpolated between sweep points.

{md_table(["sampler", "PSNR seed 1 (dB)", f"PSNR over {seeds} seeds (dB)", "gain over PRNG (dB)", "rank",
           "time (s)", "paths/s", "rays/s", "time to PRNG's error (s)"], table)}

![contact sheet]({sheet})

### Equal time
Every sampler at the spp that takes PRNG's {spp}-spp time ({budget:.2f} s): {spp} x that time / its own {spp}-spp
time; the time column is what the render then took.

{md_table(["sampler", "spp", "time (s)", f"PSNR over {seeds} seeds (dB)", "gain over PRNG (dB)"], eq_table)}

![sweep]({sweep_png})

### The paper's claims on this scene
A difference within two standard errors of the difference of the mean PSNRs (over {seeds} seeds; at least
0.05 dB) is a tie.

{md_table(["claim", "ours", "verdict"], verdicts(fig))}
""")
    paper_rows = []
    for figname, vals in PAPER.items():
        paper_rows.append([figname, "4096"] + [f"{vals[s] - vals['pcg32']:+.2f}" if s in vals else "-" for s in SAMPLERS])
    for res in results:
        p = {r["sampler"]: r["psnr_mean"] for r in res["figure"]}
        paper_rows.append([f"ours: {res['title']}", str(res["spp"])] + [f"{p[s] - p['pcg32']:+.2f}" for s in SAMPLERS])
    with open(out / "pt.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["scene", "table", "sampler", "spp", "psnr_seed1", "psnr_mean", "psnr_sd",
                                          "rmse", "seconds"], extrasaction="ignore")
        w.writeheader()
        w.writerows(csv_rows)
    (out / "pt.json").write_text(json.dumps({"scenes": results, "paper": PAPER, "seconds": time.time() - t0}, indent=1))
    cmd = "python tools/report/pt_report.py --pt build/bin/udm1-pt --out report" + (" --full" if args.full else "")
    md = f"""# udm1 path tracing report

The paper's Figure 8/10 protocol (section 5) on udm1-pt: unidirectional path tracing with next-event
estimation and MIS, maximum depth from the scene (pbrt's 5 by default), one sampler point per path in the
documented dimension layout (pt/integrator.h), each sampler's default per-pixel randomization. PSNR has peak 1
on linear RGB clamped to [0, 1]. Times are udm1-pt's render time (median over seeds, all cores, scene loading
excluded). The paper used 4096 spp against 16384-32768 spp references on San Miguel and the Crown; here the
sizes and spp are stated per scene. Made in {time.time() - t0:.0f} s by `{cmd}`. Raw numbers: [pt.csv](pt.csv),
[pt.json](pt.json).

## The paper's numbers next to ours
PSNR gain over PRNG (dB) at equal spp. The paper's absolute PSNRs (Figure 8: PRNG 25.51 dB; Figure 10: 22.75 dB)
depend on its scenes and tone mapping, so the gains are what compares.

{md_table(["figure / scene", "spp"] + [NAMES[s] for s in SAMPLERS], paper_rows)}

{chr(10).join(sections)}"""
    (out / "pt.md").write_text(md)
    (out / "pt.html").write_text(md_to_html(md, "udm1 path tracing report"))
    log(f"wrote {out / 'pt.html'} in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
