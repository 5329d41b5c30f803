"""The sequence report: point plots, discrepancy tables and the constant-set
check for the paper's Weyl sets, next to random points and scrambled Sobol,
and the exactness of udm1's integer arithmetic against fmod(n*alpha, 1).

Writes OUT/sequences.html, OUT/sequences.md, OUT/*.png, OUT/sequences.json and
OUT/discrepancy.csv; a step of the main report (tools/report/main_report.py,
which writes OUT/index.html). On its own:

    PYTHONPATH=python python tools/report/sequence_report.py --out report
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import platform
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.stats import qmc  # noqa: E402

import udm1  # noqa: E402
from report_common import log, md_table, md_to_html, writable_folder  # noqa: E402

# The paper's 2D sets (section 4.2), the first two dimensions of its
# many-dimensional sets (section 5.1), R_2, and the anchors.
PLOT_SETS = [
    ("WR (sqrt2, sqrt13)", "wr-ao", {}),
    ("WE (e, e^2)", "we", {}),
    ("WGR", "wgr", {}),
    ("EPISWR", "episwr", {"point_count": True}),
    ("WR primes, dims 0-1", "wr", {}),
    ("WMMR, dims 0-1", "wmmr", {}),
    ("HWMMR, dims 0-1", "hwmmr", {}),
    ("R_2", "rd", {}),
]
METHODS = ["L2-star", "CD", "WD"]


def udm1_points(preset: str, n: int, seed: int, point_count: bool = False, dims: int = 2) -> np.ndarray:
    max_d = {p.name: p.max_dimensions for p in udm1.presets()}[preset]
    d = min(max_d, dims)
    seq = udm1.Sequence(preset, d, seed=seed, point_count=n if point_count else 0)
    return seq.points(n, stream=seed)[:, :2]


def anchor_points(kind: str, n: int, seed: int) -> np.ndarray:
    if kind == "random":
        return np.random.default_rng(seed).random((n, 2))
    engine = qmc.Sobol(2, scramble=True, rng=np.random.default_rng(seed))
    return engine.random(n)


def plot_points(out: Path, n: int) -> str:
    sets = [(t, lambda p=p, e=e: udm1_points(p, n, 1, bool(e.get("point_count")))) for t, p, e in PLOT_SETS]
    sets += [("random (PCG64)", lambda: anchor_points("random", n, 1)),
             ("Sobol, Owen-scrambled (scipy)", lambda: anchor_points("sobol", n, 1))]
    cols = 5
    rows = math.ceil(len(sets) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.1 * cols, 3.3 * rows))
    for ax, (title, make) in zip(axes.ravel(), sets):
        pts = make()
        ax.scatter(pts[:, 0], pts[:, 1], s=4, c="#1f4e79" if "random" not in title and "Sobol" not in title else "#a33")
        ax.set_title(title, fontsize=9)
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1)
        ax.set_aspect("equal")
        ax.set_xticks([0, 0.5, 1])
        ax.set_yticks([0, 0.5, 1])
        ax.tick_params(labelsize=7)
    for ax in axes.ravel()[len(sets):]:
        ax.axis("off")
    fig.suptitle(f"{n} points, randomly shifted (seed 1); anchors in red", fontsize=11)
    fig.tight_layout()
    name = f"points_{n}.png"
    fig.savefig(out / name, dpi=110)
    plt.close(fig)
    return name


def discrepancy_table(ns: list[int], seeds: int) -> list[dict]:
    rows = []
    entries = [(t, "udm1", p, e) for t, p, e in PLOT_SETS] + [
        ("random (PCG64)", "anchor", "random", {}), ("Sobol, Owen-scrambled (scipy)", "anchor", "sobol", {})]
    for n in ns:
        for title, kind, key, extra in entries:
            row = {"set": title, "n": n}
            for m in METHODS:
                vals = []
                for s in range(seeds):
                    if kind == "udm1":
                        pts = udm1_points(key, n, 100 + s, bool(extra.get("point_count")))
                    else:
                        pts = anchor_points(key, n, 100 + s)
                    vals.append(udm1.discrepancy(pts, m))
                row[m] = float(np.mean(vals))
            rows.append(row)
        rows.append({"set": "random, expected", "n": n, **{m: udm1.discrepancy_random(n, 2, m) for m in METHODS}})
        log(f"discrepancy at n = {n} done")
    return rows


def plot_discrepancy(out: Path, rows: list[dict], method: str) -> str:
    fig, ax = plt.subplots(figsize=(7.5, 5))
    sets = list(dict.fromkeys(r["set"] for r in rows))
    for s in sets:
        rs = [r for r in rows if r["set"] == s]
        style = "--" if "random" in s or "Sobol" in s else "-"
        ax.loglog([r["n"] for r in rs], [r[method] for r in rs], style, marker="o", ms=3, label=s)
    ax.set_xlabel("number of points n")
    ax.set_ylabel(f"{method} discrepancy" + (" (squared)" if method != "L2-star" else ""))
    ax.set_title(f"{method} discrepancy of 2D sets, mean over randomizations")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    name = f"discrepancy_{method}.png"
    fig.savefig(out / name, dpi=110)
    plt.close(fig)
    return name


def check_table(ns: list[int], full: bool = True) -> list[dict]:
    """The constant-set check (its cost grows as d^2 n^2: d = 64 at n above 256 is --full's, two thirds of it)."""
    rows = []
    for preset, dims in [("wr", [8, 16, 22, 32, 64]), ("wmmr", [8, 16, 22]), ("hwmmr", [8, 16, 22]),
                         ("rd", [8, 16, 22, 32, 64]), ("wopt", [8, 16, 22, 32, 64])]:
        for d in dims:
            seq = udm1.Sequence(preset, d, randomize=False)
            for n in (n for n in ns if full or d <= 32 or n <= 256):
                r = seq.check(n)
                rows.append({"preset": preset, "d": d, "n": n, "worst_dims": list(r["worst_dims"]),
                             "worst_l2_star": r["worst_l2_star"], "random_l2_star": r["random_l2_star"],
                             "ratio": r["worst_l2_star"] / r["random_l2_star"], "dependent": r["dependent"]})
        log(f"constant-set check of {preset} done")
    pair = udm1.check_alphas([udm1.Sqrt(487), udm1.Sqrt(237173)], 256)
    rows.append({"preset": "pair (sqrt487, sqrt237173)", "d": 2, "n": 256, "worst_dims": [0, 1],
                 "worst_l2_star": pair["worst_l2_star"], "random_l2_star": pair["random_l2_star"],
                 "ratio": pair["worst_l2_star"] / pair["random_l2_star"], "dependent": pair["dependent"]})
    return rows


def exactness(out: Path) -> tuple[str, list[dict]]:
    """Error of double fmod(n*alpha, 1) and of udm1 against the exact value, alpha = sqrt(237173)."""
    seq = udm1.Sequence("wmmr", 22, randomize=False)
    k = 237173
    frac = math.isqrt(k << 512) % (1 << 256)  # frac(sqrt k) * 2^256, exact floor
    rows = []
    for e in range(10, 64, 2):
        n = 1 << e
        exact = (n * frac) % (1 << 256)  # 0.256 fixed point
        naive = math.fmod(n * math.sqrt(k), 1.0)
        ours = int(seq.sample(n, 21, dtype=np.uint64)) << 192  # 0.64 -> 0.256, exact

        def err(v: int) -> float:  # circular distance, computed in integers
            d = (v - exact) % (1 << 256)
            return min(d, (1 << 256) - d) / 2**256

        naive_fixed = int(naive * 2**64) << 192  # the double is exact in 0.64
        rows.append({"n": n, "exact": exact / 2**256, "fmod_error": err(naive_fixed), "udm1_error": err(ours)})
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    ax.loglog([r["n"] for r in rows], [max(r["fmod_error"], 1e-20) for r in rows], "o-", c="#a33",
              label="fmod(n * sqrt(237173), 1) in double")
    ax.loglog([r["n"] for r in rows], [max(r["udm1_error"], 1e-30) for r in rows], "s-", c="#1f4e79",
              label="udm1 (0.128 fixed point, integer arithmetic)")
    ax.axhline(2**-60, ls=":", c="gray")
    ax.text(2**10, 2**-60 * 2, "2^-60", fontsize=8, color="gray")
    ax.set_xlabel("index n")
    ax.set_ylabel("|value - exact| (mod 1)")
    ax.set_title("Exactness at large indices: the paper's worst WMMR generator")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    name = "exactness.png"
    fig.savefig(out / name, dpi=110)
    plt.close(fig)
    return name, rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="report", help="output folder (default: report)")
    ap.add_argument("--seeds", type=int, default=8, help="randomizations averaged per discrepancy (default 8)")
    ap.add_argument("--quick", action="store_true", help="small sizes, for tests")
    ap.add_argument("--full", action="store_true", help="the constant-set check at d = 64 to n = 1024 too")
    args = ap.parse_args(argv)
    if args.seeds < 1 or args.seeds > 1000:
        print(f"sequence_report: --seeds {args.seeds} is outside 1..1000", file=sys.stderr)
        return 2
    out = writable_folder(args.out, "sequence_report")
    if out is None:
        return 1
    t0 = time.time()
    ns = [64, 256] if args.quick else [64, 256, 1024, 4096]
    check_ns = [256] if args.quick else [256, 1024]

    log("point plots")
    fig_points = plot_points(out, 256)
    log("discrepancy tables")
    disc = discrepancy_table(ns, args.seeds)
    fig_disc = {m: plot_discrepancy(out, disc, m) for m in METHODS}
    log("constant-set check (worst 2D projections)")
    checks = check_table(check_ns, args.full)
    log("exactness against fmod")
    fig_exact, exact_rows = exactness(out)

    with open(out / "discrepancy.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["set", "n"] + METHODS)
        w.writeheader()
        w.writerows(disc)
    machine = {"python": platform.python_version(), "platform": platform.platform(), "processor": platform.processor(),
               "udm1": udm1.version(), "numpy": np.__version__}
    data = {"discrepancy": disc, "check": checks, "exactness": exact_rows, "machine": machine,
            "seeds": args.seeds, "seconds": time.time() - t0}
    (out / "sequences.json").write_text(json.dumps(data, indent=1))

    # ---- report.md ----
    big_n = ns[-1]
    disc_rows = [[r["set"]] + [f"{r[m]:.3g}" for m in METHODS] for r in disc if r["n"] == big_n]
    chk_rows = [[c["preset"], c["d"], c["n"], f"({c['worst_dims'][0]}, {c['worst_dims'][1]})", f"{c['worst_l2_star']:.3g}",
                 f"{c['ratio']:.2f}x"] for c in checks]
    ex_rows = [[f"2^{int(math.log2(r['n']))}", f"{r['fmod_error']:.2g}", f"{r['udm1_error']:.2g}"]
               for r in exact_rows if int(math.log2(r["n"])) % 10 in (0, 2)]
    wins = [r["set"] for r in disc if r["n"] == big_n and r["set"] in [t for t, _, _ in PLOT_SETS]
            and r["CD"] < [x for x in disc if x["n"] == big_n and x["set"].startswith("Sobol")][0]["CD"]]
    md = f"""# udm1 sequence report

udm1 {udm1.version()}; {len(ns)} sizes, {args.seeds} randomizations each; made in {time.time() - t0:.0f} s.
The comparison of every sampler (integration error against N and time, spectra, zone plates, and where
the paper's sequences win and lose) is in [the sampler report](samplers.html); the paper's noise figures,
re-made with udm1 tables beside drand48, in [noise/](noise/figures.md); the paper's ambient occlusion
comparison (its Figure 6: every sampler at 64 spp against an 8192-spp reference, equal time, error against
spp and time) in [the ambient occlusion report](ao.html); the paper's path tracing protocol (its Figures 8
and 10: every sampler at equal spp against a high-spp reference, error against spp and time) with udm1-pt
in [the path tracing report](pt.html).

## Points
![points]({fig_points})

The paper's 2D sets and the first two dimensions of its many-dimensional sets, 256 points each, with a
random shift, beside independent random points and Owen-scrambled Sobol.

## Discrepancy (2D, mean over {args.seeds} randomizations, n = {big_n})
{md_table(["set"] + METHODS, disc_rows)}

CD, WD are squared and L2-star square-rooted, as scipy.stats.qmc.discrepancy. "random, expected" is the
exact expectation for n independent uniform points.

![CD]({fig_disc['CD']}) ![WD]({fig_disc['WD']}) ![L2-star]({fig_disc['L2-star']})

Verdict at n = {big_n} (CD): sets below Owen-scrambled Sobol: {", ".join(wins) if wins else "none"}.

## Constant-set check: worst 2D projection of the many-dimensional sets
{md_table(["set", "d", "n", "worst pair", "L2-star", "x random"], chk_rows)}

A ratio above 1 means that some pair of dimensions is worse than independent random points.

## Exactness: the paper's generator sqrt(237173) at large indices
![exactness]({fig_exact})

{md_table(["n", "fmod(n a, 1) error", "udm1 error"], ex_rows)}

## Machine
{md_table(["key", "value"], [[k, v] for k, v in machine.items()])}
"""
    (out / "sequences.md").write_text(md)
    (out / "sequences.html").write_text(md_to_html(md, "udm1 sequence report"))
    log(f"wrote {out}/sequences.html, sequences.md, sequences.json, discrepancy.csv and {len(METHODS) + 2} figures "
        f"in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
