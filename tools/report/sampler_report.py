"""The sampler report: every udm1 sampler, the paper's Weyl sets and the
baselines, measured the same way: discrepancy against N, integration RMSE
against N and against time for smooth and discontinuous integrands (2D) and
the Genz families (8D), fitted convergence slopes, spectra and point plots,
and a plain statement of where the paper's sequences win and where they lose.

Writes OUT/samplers.md, OUT/samplers.html, OUT/samplers_*.png,
OUT/samplers_error.csv and OUT/samplers.json. The error table comes from the
C benchmark `udm1_bench_samplers error` (timing in C, one thread).

    PYTHONPATH=python python tools/report/sampler_report.py --bench build/bin/udm1_bench_samplers --out report
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import udm1  # noqa: E402
from report_common import log, md_table, md_to_html, writable_folder  # noqa: E402

PAPER = ["wr-ao", "we", "wgr", "episwr", "wr", "wmmr", "hwmmr", "rd"]
BASELINES = ["pcg32", "drand48", "halton", "halton-owen", "sobol", "sobol-owen", "hammersley", "lp", "cmj", "grps",
             "pmj02"]
BEYOND = ["wopt", "lattice"]  # udm1's own sets beyond the paper: shown everywhere, not counted in the paper's verdicts
SMOOTH = {"gaussian", "product-peak", "bilinear", "genz-oscillatory", "genz-product-peak", "genz-corner-peak",
          "genz-gaussian", "genz-continuous"}


def style(name: str) -> dict:
    """Paper sets solid, baselines dashed; a stable colour per sampler."""
    names = PAPER + BASELINES + BEYOND
    cmap = plt.get_cmap("tab20")
    return {"color": cmap(names.index(name) % 20) if name in names else "k",
            "linestyle": "-" if name in PAPER + BEYOND else "--", "marker": "o" if name in PAPER + BEYOND else "s", "ms": 3}


def run_bench(bench: str, reps: int, quick: bool, ns: str | None = None) -> list[dict]:
    cmd = [bench, "error", "--reps", str(reps)] + (["--ns", ns] if ns else []) + (["--quick"] if quick else [])
    log("integration error of every sampler: " + " ".join(cmd))
    with tempfile.TemporaryFile(mode="w+") as table:  # a file, not a pipe: no deadlock on large output
        proc = subprocess.Popen(cmd, stdout=table, stderr=subprocess.PIPE, text=True)
        for line in proc.stderr:  # progress, one line per sampler
            log(line.strip())
        if proc.wait() != 0:
            raise RuntimeError(f"{bench} failed with exit code {proc.returncode}")
        table.seek(0)
        rows = list(csv.DictReader(table))
    for r in rows:
        for k in ("d", "n", "reps"):
            r[k] = int(r[k])
        for k in ("rmse", "relative_rmse", "seconds_per_estimate", "create_seconds"):
            r[k] = float(r[k])
    return rows


def timed_rows(rows: list[dict], path: str) -> None:
    """Each row's seconds_per_estimate and create_seconds from `path`, a CSV of the same benchmark run alone on
    the machine (the RMSE run may share it with other work); every row must be there."""
    with open(path) as f:
        times = {(r["sampler"], r["integrand"], int(r["n"])): r for r in csv.DictReader(f)}
    for r in rows:
        t = times.get((r["sampler"], r["integrand"], r["n"]))
        if t is None:
            raise ValueError(f"no time for {r['sampler']} on {r['integrand']} at N = {r['n']}")
        r["seconds_per_estimate"], r["create_seconds"] = float(t["seconds_per_estimate"]), float(t["create_seconds"])
        r["time_reps"] = int(t["reps"])


def slope(ns, errs) -> float:
    ns, errs = np.asarray(ns, float), np.asarray(errs, float)
    keep = (ns >= 256) & (errs > 0)
    if keep.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(ns[keep]), np.log(errs[keep]), 1)[0])


def plot_grid(rows, integrands, x_key, out: Path, name: str, title: str) -> str:
    cols = 4
    nrows = math.ceil(len(integrands) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.4 * nrows))
    for ax, integ in zip(axes.ravel(), integrands):
        rs = [r for r in rows if r["integrand"] == integ]
        for s in dict.fromkeys(r["sampler"] for r in rs):
            pts = sorted((r[x_key], r["relative_rmse"]) for r in rs if r["sampler"] == s)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], label=s, lw=1, **style(s))
        xs = sorted({r[x_key] for r in rs})
        if x_key == "n" and xs:  # slope guides N^-1/2, N^-1, N^-1.5 through the first random point
            x0, x1 = xs[0], xs[-1]
            for p, lab in [(0.5, "N^-1/2"), (1.0, "N^-1"), (1.5, "N^-3/2")]:
                y0 = 0.05
                ax.loglog([x0, x1], [y0, y0 * (x1 / x0) ** -p], color="0.75", lw=0.8, zorder=0)
                ax.text(x1, y0 * (x1 / x0) ** -p, lab, fontsize=6, color="0.5")
        ax.set_title(f"{integ} (d={rs[0]['d'] if rs else '?'})", fontsize=9)
        ax.set_xlabel("points N" if x_key == "n" else "seconds per estimate", fontsize=8)
        ax.set_ylabel("relative RMSE", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="both", alpha=0.2)
    for ax in axes.ravel()[len(integrands):]:
        ax.axis("off")
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=10, fontsize=7)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.06, 1, 0.97))
    fig.savefig(out / name, dpi=90)
    plt.close(fig)
    return name


def make(name: str, d: int, n: int, seed: int):
    info = {p.name: p for p in udm1.presets()}[name]
    return udm1.Sequence(name, d, point_count=n if info.point_set else 0, seed=seed)


def discrepancy_rows(samplers, ns, seeds) -> list[dict]:
    rows = []
    for s in samplers:
        for n in ns:
            vals = {"CD": [], "L2-star": []}
            for seed in range(seeds):
                pts = make(s, 2, n, seed + 1).points(n, stream=seed)
                for m in vals:
                    vals[m].append(udm1.discrepancy(pts, m))
            rows.append({"sampler": s, "n": n, **{m: float(np.mean(v)) for m, v in vals.items()}})
    rows += [{"sampler": "random, expected", "n": n, "CD": udm1.discrepancy_random(n, 2, "CD"),
              "L2-star": udm1.discrepancy_random(n, 2, "L2-star")} for n in ns]
    return rows


def plot_discrepancy(rows, out: Path) -> str:
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for ax, m in zip(axes, ["CD", "L2-star"]):
        for s in dict.fromkeys(r["sampler"] for r in rows):
            rs = [r for r in rows if r["sampler"] == s]
            kw = style(s) if s != "random, expected" else {"color": "k", "linestyle": ":"}
            ax.loglog([r["n"] for r in rs], [r[m] for r in rs], label=s, lw=1, **kw)
        ax.set_xlabel("points N")
        ax.set_ylabel(m + (" (squared)" if m == "CD" else ""))
        ax.set_title(f"2D {m} discrepancy, mean over randomizations")
        ax.grid(True, which="both", alpha=0.2)
    axes[1].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out / "samplers_discrepancy.png", dpi=90)
    plt.close(fig)
    return "samplers_discrepancy.png"


def image_grid(samplers, make_image, out: Path, name: str, title: str, cmap="gray", vmin=None, vmax=None) -> str:
    cols = 7
    nrows = math.ceil(len(samplers) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(2.3 * cols, 2.5 * nrows))
    for ax, s in zip(axes.ravel(), samplers):
        img = make_image(s)
        if img.ndim == 2 and img.shape[1] == 2 and img.shape[0] != img.shape[1]:  # points
            ax.scatter(img[:, 0], img[:, 1], s=1.5, c="#1f4e79")
            ax.set_xlim(0, 1)
            ax.set_ylim(0, 1)
        else:
            ax.imshow(img, cmap=cmap, vmin=vmin, vmax=vmax, interpolation="nearest")
        ax.set_title(s, fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_aspect("equal")
    for ax in axes.ravel()[len(samplers):]:
        ax.axis("off")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out / name, dpi=90)
    plt.close(fig)
    return name


def cost(r: dict, per_time: bool) -> float:
    """The figure compared: RMSE at equal N, or RMSE^2 x time (inverse efficiency) at equal time."""
    return r["rmse"] ** 2 * r["seconds_per_estimate"] if per_time else r["rmse"]


def verdicts(rows, per_time: bool = False) -> tuple[list[list], list[str]]:
    """For each integrand and N: the best paper set against the best baseline,
    by RMSE (equal N) or by RMSE^2 x time (equal time)."""
    table, lines = [], []
    integrands = list(dict.fromkeys(r["integrand"] for r in rows))
    ns = sorted({r["n"] for r in rows})
    for integ in integrands:
        for n in ns:
            rs = [r for r in rows if r["integrand"] == integ and r["n"] == n]
            paper = [r for r in rs if r["sampler"] in PAPER]
            base = [r for r in rs if r["sampler"] in BASELINES]
            if not paper or not base:
                continue
            bp = min(paper, key=lambda r: cost(r, per_time))
            bb = min(base, key=lambda r: cost(r, per_time))
            ratio = cost(bp, per_time) / cost(bb, per_time) if cost(bb, per_time) > 0 else float("inf")
            verdict = "paper set wins" if ratio < 0.95 else ("tie" if ratio <= 1.05 else "paper set loses")
            table.append([integ, rs[0]["d"], n, f"{bp['sampler']} {bp['relative_rmse']:.3g}",
                          f"{bb['sampler']} {bb['relative_rmse']:.3g}", f"{ratio:.3g}", verdict])
    for integ in integrands:
        sub = [t for t in table if t[0] == integ]
        wins = [t[2] for t in sub if t[6] == "paper set wins"]
        losses = [t[2] for t in sub if t[6] == "paper set loses"]
        kind = "smooth" if integ in SMOOTH else "discontinuous"
        lines.append(f"- **{integ}** ({kind}): the best of the paper's sets "
                     + (f"wins at N = {', '.join(map(str, wins))}" if wins else "never wins")
                     + (f"; loses at N = {', '.join(map(str, losses))}" if losses else "")
                     + ".")
    return table, lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", required=True, help="path of udm1_bench_samplers")
    ap.add_argument("--out", default="report")
    ap.add_argument("--reps", type=int, default=32, help="randomizations per RMSE (default 32)")
    ap.add_argument("--ns", help="the point counts N (comma list; default the benchmark's: 64 .. 16384)")
    ap.add_argument("--times", help="seconds per estimate (and creation) from this CSV of `udm1_bench_samplers error`, "
                                    "run alone on the machine (the main report's sampler-times step: fewer "
                                    "randomizations, the same N); default: the RMSE run's own times")
    ap.add_argument("--quick", action="store_true", help="small sizes, for tests")
    args = ap.parse_args(argv)
    if not 2 <= args.reps <= 10000:
        print(f"sampler_report: --reps {args.reps} is outside 2..10000", file=sys.stderr)
        return 2
    if not Path(args.bench).exists():
        print(f"sampler_report: no benchmark program at '{args.bench}' (build it first)", file=sys.stderr)
        return 2
    out = writable_folder(args.out, "sampler_report")
    if out is None:
        return 1
    t0 = time.time()
    rows = run_bench(args.bench, args.reps, args.quick, args.ns)
    if args.times:
        try:
            timed_rows(rows, args.times)
        except (OSError, KeyError, ValueError) as exc:  # (KeyError: a column the file lacks)
            print(f"sampler_report: --times '{args.times}': {exc}", file=sys.stderr)
            return 1
    with open(out / "samplers_error.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    two_d = [i for i in dict.fromkeys(r["integrand"] for r in rows) if not i.startswith("genz")]
    genz = [i for i in dict.fromkeys(r["integrand"] for r in rows) if i.startswith("genz")]
    figs = {
        "rmse_2d": plot_grid(rows, two_d, "n", out, "samplers_rmse_2d.png",
                             "2D integrands: relative RMSE against N (paper sets solid, baselines dashed)"),
        "time_2d": plot_grid(rows, two_d, "seconds_per_estimate", out, "samplers_time_2d.png",
                             "2D integrands: relative RMSE against time per estimate (C, one thread)"),
        "rmse_genz": plot_grid(rows, genz, "n", out, "samplers_rmse_genz.png",
                               "Genz families, d = 8: relative RMSE against N"),
        "time_genz": plot_grid(rows, genz, "seconds_per_estimate", out, "samplers_time_genz.png",
                               "Genz families, d = 8: relative RMSE against time per estimate"),
    }
    log("discrepancy against N")
    samplers_2d = [s for s in PAPER + BASELINES + BEYOND]
    disc_ns = [64, 256] if args.quick else [64, 256, 1024, 4096]
    disc = discrepancy_rows(samplers_2d, disc_ns, 2 if args.quick else 4)
    figs["disc"] = plot_discrepancy(disc, out)
    log("point plots, spectra and zone plates")
    n_img = 256 if args.quick else 1024
    figs["points"] = image_grid(samplers_2d, lambda s: make(s, 2, 256, 1).points(256), out, "samplers_points.png",
                                "256 points of each sampler (dimensions 0, 1)")
    figs["spectra"] = image_grid(
        samplers_2d, lambda s: np.log10(np.maximum(make(s, 2, n_img, 1).spectrum(n_img, 64, 2 if args.quick else 8),
                                                   1e-3)),
        out, "samplers_spectra.png", f"power spectra, {n_img} points, log10 (white noise = 0)", vmin=-2, vmax=1)
    figs["zoneplates"] = image_grid(
        samplers_2d, lambda s: make(s, 2, 4, 1).zoneplate(96, 96, 4), out, "samplers_zoneplates.png",
        "zone plate, 96 x 96 pixels, 4 samples per pixel (false rings = aliasing)", vmin=0, vmax=1)

    # slopes and tables
    slopes = {}
    for integ in two_d + genz:
        for s in dict.fromkeys(r["sampler"] for r in rows if r["integrand"] == integ):
            pts = sorted((r["n"], r["rmse"]) for r in rows if r["integrand"] == integ and r["sampler"] == s)
            slopes[(s, integ)] = slope([p[0] for p in pts], [p[1] for p in pts])
    samplers = list(dict.fromkeys(r["sampler"] for r in rows))
    slope_rows = [[s] + [f"{slopes.get((s, i), float('nan')):.2f}" for i in two_d + genz] for s in samplers]
    check_ns = sorted({r["n"] for r in rows})
    n_hi = 10000 if 10000 in check_ns else check_ns[-1]
    n_lo = 1000 if 1000 in check_ns else check_ns[0]
    at = {(r["sampler"], r["integrand"], r["n"]): r for r in rows}
    err_rows = [[s] + [f"{at[(s, i, n_lo)]['relative_rmse']:.2g} / {at[(s, i, n_hi)]['relative_rmse']:.2g}"
                       if (s, i, n_lo) in at and (s, i, n_hi) in at else "-" for i in two_d + genz] for s in samplers]
    table, lines = verdicts(rows)
    table_t, lines_t = verdicts(rows, per_time=True)
    timing = (f"measured alone on the machine by a separate run of the benchmark with {rows[0]['time_reps']} "
              f"randomizations per N (`--times`; the RMSE run, with {args.reps}, may have shared the machine)"
              if args.times else f"the RMSE run's own, over its {args.reps} randomizations")
    data = {"error": rows, "discrepancy": disc, "timing": timing, "slopes": {f"{k[0]}|{k[1]}": v for k, v in slopes.items()},
            "verdicts": table, "verdicts_equal_time": table_t, "reps": args.reps, "seconds": time.time() - t0}
    (out / "samplers.json").write_text(json.dumps(data, indent=1))

    md = f"""# udm1 sampler report

Every sampler of libudm1, measured the same way: the paper's Weyl sets ({", ".join(PAPER)}) and the
baselines ({", ".join(BASELINES)}). Each RMSE is over {args.reps} randomizations (independent streams
of the sampler's default randomization); N includes the non-powers of two 1000 and 10000. Made in
{time.time() - t0:.0f} s. Raw numbers: [samplers_error.csv](samplers_error.csv), [samplers.json](samplers.json).

## Where the paper's sequences win and where they lose
At equal N: the best of the paper's sets against the best baseline by RMSE, per integrand and N (a ratio
below 1 is a win):

{chr(10).join(lines)}

At equal time: the same by RMSE^2 x time per estimate (the inverse of efficiency; C, one thread), which
counts the Weyl sequences' speed:

{chr(10).join(lines_t)}

Equal N:

{md_table(["integrand", "d", "N", "best paper set (rel. RMSE)", "best baseline (rel. RMSE)", "RMSE ratio", "verdict"], table)}

Equal time:

{md_table(["integrand", "d", "N", "best paper set (rel. RMSE)", "best baseline (rel. RMSE)", "RMSE^2 x time ratio", "verdict"], table_t)}

## Integration error against N
![rmse 2d]({figs['rmse_2d']})

![rmse genz]({figs['rmse_genz']})

Fitted convergence slopes (log RMSE against log N, N >= 256):

{md_table(["sampler"] + two_d + genz, slope_rows)}

Relative RMSE at N = {n_lo} / N = {n_hi}:

{md_table(["sampler"] + two_d + genz, err_rows)}

## Integration error against time
Time of one estimate: filling N points and evaluating the integrand, in C on one thread (the
sampler's creation apart: PMJ02 builds its tables then, see the CSV's create_seconds); {timing}.

![time 2d]({figs['time_2d']})

![time genz]({figs['time_genz']})

## Discrepancy against N (2D)
![discrepancy]({figs['disc']})

## Points, spectra, zone plates
![points]({figs['points']})

![spectra]({figs['spectra']})

![zone plates]({figs['zoneplates']})
"""
    (out / "samplers.md").write_text(md)
    (out / "samplers.html").write_text(md_to_html(md, "udm1 sampler report"))
    log(f"wrote {out}/samplers.html and samplers.md in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
