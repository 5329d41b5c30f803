"""The main report's content: tables and plots made from the steps' JSON and text outputs.

`build(doc, out, steps, state, mode, machine)` adds, in order: the verdict (per application, the best
sampler at equal time and at equal spp, its gain over PRNG and over the best other sampler, and the
machine), the paper's claims with a verdict each, then the details: the steps table, the paper's
path-tracing numbers next to ours, the speed-against-error plots, and one section per application. A step that failed or did not run is shown as such, and none of its (possibly stale) numbers
are read. Every sampler a step ran appears in each table made from that step.
"""

from __future__ import annotations

import csv
import functools
import json
import math
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pt_report import NAMES as PT_NAMES, PAPER as PT_PAPER, compare  # noqa: E402
from ao_report import PAPER_SET as AO_PAPER_SET  # noqa: E402

WEYL = {"wr-ao", "we", "wgr", "episwr", "wr", "wmmr", "hwmmr", "rd", "wopt"}
ORDER = ["wr-ao", "we", "wgr", "episwr", "wr", "wmmr", "hwmmr", "rd", "wopt", "lattice", "pcg32", "drand48", "halton", "halton-owen",
         "sobol", "sobol-owen", "hammersley", "lp", "cmj", "grps", "pmj02"]
SMOOTH_2D, DISCONTINUOUS_2D, SMOOTH_8D = "gaussian", "disk", "genz-oscillatory"


def style(sampler: str) -> dict:
    cmap = plt.get_cmap("tab20")
    k = ORDER.index(sampler) if sampler in ORDER else len(ORDER)
    weyl = sampler in WEYL
    return {"color": cmap(k % 20), "ls": "-" if weyl else "--", "lw": 1.8 if weyl else 1.1,
            "marker": "o" if weyl else ".", "ms": 3, "label": sampler}


def done(state: dict, name: str) -> bool:
    return state.get(name, {}).get("status") in ("ok", "reused")


def not_shown(doc, state: dict, name: str) -> bool:
    """If the step did not finish, say so in its section (and return True: show none of its numbers)."""
    if done(state, name):
        return False
    r = state.get(name, {})
    status = r.get("status", "not run")
    if status == "failed":
        doc.para(f"**This step failed**: {r.get('error', '')}. Its numbers are not shown (any files an earlier run "
                 "left are not read). Run `./run.sh` again to retry it; the finished steps are reused.")
    else:
        doc.para(f"**This step did not run** ({status}).")
    return True


@functools.lru_cache(maxsize=None)
def load(out: Path, name: str) -> dict:
    """A step's JSON, read once per report (several sections use the same file; do not modify the result)."""
    return json.loads((out / name).read_text())


PT_STEPS = (("pt", ""), ("crown", "crown/"))  # the path tracing steps and the folder each writes into


def pt_scenes(out: Path, state) -> list[tuple[str, str, dict]]:
    """(step, folder prefix, scene result) for every scene of the path tracing steps that finished."""
    return [(step, prefix, sc) for step, prefix in PT_STEPS if done(state, step)
            for sc in load(out, prefix + "pt.json")["scenes"]]


# ---- the steps' text outputs ---------------------------------------------------------------------------------

def parse_throughput(text: str) -> list[dict]:
    rows = []
    for line in text.splitlines()[1:]:
        f = line.split()
        if len(f) == 7:
            rows.append({"sampler": f[0], "d": int(f[1]), "bulk": float(f[2]), "bulk_x_wr": float(f[3]),
                         "per_sample": float(f[5]), "per_sample_x_wr": float(f[6])})
        elif len(f) == 5 and f[0] == "(memset)":
            rows.append({"sampler": "(memset)", "d": int(f[1]), "bulk": float(f[2]), "bulk_x_wr": float(f[3]),
                         "per_sample": None, "per_sample_x_wr": None})
    return rows


def parse_libnoise(text: str) -> list[dict]:
    """udm1_bench_noise: a 44-character name column, then evaluations per second and a ratio."""
    rows, anchor = [], None
    for line in text.splitlines():
        m = re.match(r"^(.{44})\s+([0-9.e+-]+)\s+([0-9.]+)\s*$", line)
        if not m:
            continue
        name = m.group(1).strip()
        if name.startswith("image"):
            anchor = "udm1 image, 1 thread"
        elif anchor is None:
            anchor = "libnoise GradientCoherentNoise3D"
        rows.append({"method": name, "per_second": float(m.group(2)), "ratio": float(m.group(3)), "anchor": anchor})
    return rows


def parse_simd_noise(out: Path) -> list[dict]:
    """bench_noise.py's rows (FastNoiseSIMD, or FastNoise Lite where it is absent, and udm1)."""
    rows = load(out, "noise_simd.json")["rows"]
    return [{"method": f"{r['method']} ({r['group']})", "per_second": r["rate"], "ratio": r["x_anchor"],
             "anchor": r["anchor"]} for r in rows]


# ---- sections --------------------------------------------------------------------------------------------------

def db(x: float) -> str:
    return f"{x:+.2f} dB"


def times(x: float) -> str:
    return "exact" if math.isinf(x) else (f"{x:.2f}x" if x < 10 else f"{x:.3g}x")


def seeds_of(n: int, what: str = "seed") -> str:
    return f"{n} {what}" + ("" if n == 1 else "s")


def psnr_rows(application: str, when: str, rows: list[dict], note: str) -> dict:
    """The best of `rows` (mean PSNR over seeds) against PRNG and against the best other sampler; "tie" when the
    difference is within two standard errors (pt_report.compare)."""
    ranked = sorted(rows, key=lambda r: -r["psnr_mean"])
    best, peer = ranked[0], ranked[1]
    prng = next(r for r in rows if r["sampler"] == "pcg32")
    tie = compare(rows, best["sampler"], peer["sampler"]) == "tie"
    return {"application": application, "when": when, "best": best["sampler"],
            "figure": f"PSNR {best['psnr_mean']:.2f} dB" + (f" at {best['spp']} spp" if when == "equal time" else ""),
            "over_prng": db(best["psnr_mean"] - prng["psnr_mean"]), "peer": peer["sampler"],
            "over_peer": db(best["psnr_mean"] - peer["psnr_mean"]) + (" (a tie within the seeds' spread)" if tie else ""),
            "basis": note}


def verdict_section(doc, out: Path, steps, state, mode: str, machine: dict):
    """The first screen: which sampler to use in each application, and by how much."""
    doc.heading(1, "udm1 report: which sampler, and how much it gains")
    cpu = machine.get("cpu", "?")
    doc.para(f"Measured on **{cpu}**, {machine.get('cores', '?')} cores, {machine.get('date', '')}; configuration "
             f"**{mode}**. Per application, the best sampler at equal samples (spp or N) and at equal time (every "
             "sampler given the same time), its gain over PRNG (pcg32) and over the best other sampler. PSNR in dB "
             "(higher is better); integration: how many times lower the RMSE (equal N) or the time to the same "
             "error (equal time, RMSE^2 x time) is.")
    doc.heading(2, "Verdict", "verdict")
    rows = []
    if done(state, "samplers"):
        err = load(out, "samplers.json")["error"]
        reps = load(out, "samplers.json")["reps"]
        for integ in (SMOOTH_2D, DISCONTINUOUS_2D, SMOOTH_8D):
            n = max((r["n"] for r in err if r["integrand"] == integ), default=None)
            at = [r for r in err if r["integrand"] == integ and r["n"] == n]
            if not at or not any(r["sampler"] == "pcg32" for r in at):
                continue
            for when, cost, what in (("equal N", lambda r: r["relative_rmse"], "lower RMSE"),
                                     ("equal time", lambda r: r["rmse"] ** 2 * r["seconds_per_estimate"],
                                      "less time to its error")):
                ranked = sorted(at, key=cost)
                best, peer = ranked[0], ranked[1]
                prng = next(r for r in at if r["sampler"] == "pcg32")
                rows.append({"application": f"integration, {integ} (d={best['d']})", "when": when,
                             "best": best["sampler"], "figure": f"rel. RMSE {best['relative_rmse']:.3g} at N = {n}",
                             "over_prng": f"{times(ratio(cost(prng), cost(best)))} {what}", "peer": peer["sampler"],
                             "over_peer": f"{times(ratio(cost(peer), cost(best)))} {what}",
                             "basis": seeds_of(reps, "randomization")})
    if done(state, "ao"):
        ao = load(out, "ao.json")
        seeds = ao["figure6"][0]["n_seeds"]
        rows.append(psnr_rows("ambient occlusion (udm1-ao)", f"equal spp ({ao['figure6'][0]['spp']})", ao["figure6"],
                              seeds_of(seeds)))
        rows.append(psnr_rows("ambient occlusion (udm1-ao)", "equal time", ao["equal_time"],
                              f"{seeds_of(seeds)}, EPISWR's {ao['budget_seconds'] * 1e3:.0f} ms"))
    for _, _, sc in pt_scenes(out, state):
        app = f"path tracing (udm1-pt), {sc['title']}"
        rows.append(psnr_rows(app, f"equal spp ({sc['spp']})", sc["figure"], seeds_of(sc["seeds"])))
        rows.append(psnr_rows(app, "equal time", sc["equal_time"],
                              f"{seeds_of(sc['seeds'])}, PRNG's {sc['budget_seconds']:.2f} s"))
    if done(state, "screen"):
        summ = load(out, "screen.json")["summary"]
        for source, name in (("ao", "screen-space, ambient occlusion"), ("pt", "screen-space, path tracing")):
            med = {}
            for r in summ:
                if r["source"] == source:
                    med.setdefault(r["scheme"], []).append(r["median_low"])
            if "shift" not in med:
                continue
            share = {k: sum(v) / len(v) for k, v in med.items()}
            ranked = sorted(share, key=share.get)
            best, peer = ranked[0], ranked[1]
            rows.append({"application": name, "when": "equal spp (same cost)", "best": best,
                         "figure": f"low-frequency share {share[best]:.2f} (white noise 1)",
                         "over_prng": f"{times(ratio(share['shift'], share[best]))} less low-frequency error energy "
                                      "than per-pixel shifts", "peer": peer,
                         "over_peer": f"{times(ratio(share[peer], share[best]))}",
                         "basis": f"each scheme's median over the counts it was measured at (every count 1 .. "
                                  f"{load(out, 'screen.json')['spp_max']} for shift and progressive), "
                                  f"{seeds_of(load(out, 'screen.json')['seeds'])}"})
    if done(state, "noise"):
        simd = load(out, "noise_simd.json")["rows"]
        for group in dict.fromkeys(r["group"] for r in simd):
            rs = [r for r in simd if r["group"] == group]
            best = max(rs, key=lambda r: r["rate"])
            # the best other: the fastest of the other library (the anchor's) if udm1 is fastest, else udm1's fastest
            others = [r for r in rs if r["method"].startswith("udm1") != best["method"].startswith("udm1")]
            if not others:
                continue
            peer = max(others, key=lambda r: r["rate"])
            rows.append({"application": f"noise, {group}", "when": "equal time (evaluations/s, 1 thread)",
                         "best": best["method"], "figure": f"{best['rate']:.3g} per second",
                         "over_prng": "", "peer": peer["method"],
                         "over_peer": times(best["rate"] / peer["rate"]) + " faster", "basis": f"against {best['anchor']}"})
    if not rows:
        doc.para("**No verdict**: none of the samplers, ao, pt, screen and noise steps finished (see the steps table).")
        return
    doc.table("verdict", "verdict", [
        ("application", "application", ""), ("when", "at", ""), ("best", "best", ""), ("figure", "its figure", ""),
        ("over_prng", "over PRNG", ""), ("peer", "best other", ""), ("over_peer", "over the best other", ""),
        ("basis", "over", "")], rows)
    doc.para("Then: the paper's claims with a verdict each, and the details (every step, every sampler). Pages with "
             "every detail: " + ", ".join(f"[{s.name}]({s.page})" for s in steps if s.page and done(state, s.name))
             + ".")


def steps_section(doc, steps, state, mode: str):
    doc.heading(2, "Details", "details")
    doc.para(f"Configuration: **{mode}**. Each step is a program of its own (commands in report.json); a step "
             "whose inputs have not changed since it last finished is reused on the next run.")
    doc.heading(2, "Steps", "steps")
    rows = [{"step": s.name, "what": s.title, "status": state[s.name]["status"], "seconds": state[s.name]["seconds"],
             "cpu_seconds": state[s.name].get("cpu_seconds"), "ran": "alone" if s.exclusive else "beside another",
             "error": state[s.name].get("error") or ""} for s in steps]
    doc.table("steps", "steps", [("step", "step", ""), ("what", "what", ""), ("status", "status", ""),
                                 ("seconds", "time (s)", ".1f"), ("cpu_seconds", "processor time (s)", ".1f"),
                                 ("ran", "ran", ""), ("error", "error", "")], rows)
    doc.para("In the order they ran. The steps whose figures are times ran alone, one at a time, so that no other "
             "step's work is in their times; the others ran two at a time (\"beside another\"; tolerance's times "
             "are compared with each other only, each method in turn within a trial). Processor time: the user and "
             "system time of the step's programs, summed over the cores. Above the step's time, it used more than "
             "one core; far below it on a single-threaded step, it waited for a processor (a machine shared with "
             "other work).")


def claims_section(doc, out: Path, state):
    doc.heading(2, "The paper's claims next to ours", "claims")
    doc.para("Each claim of the paper's Figures 6 (ambient occlusion, 64 spp), 8 (San Miguel) and 10 (the Crown), "
             "checked on our scenes with mean PSNR over seeds: a difference within two standard errors of the "
             "difference of the means (at least 0.05 dB) is a tie. Our scenes are not the paper's, so a verdict "
             "says whether the claim carries over; `./run.sh --full` adds the Crown itself, Figure 10's scene "
             "(docs/crown/ shows it).")
    rows = []
    if done(state, "ao"):
        ao = load(out, "ao.json")
        for table, when in (("figure6", "equal spp"), ("equal_time", "equal time")):
            fig = [r for r in ao[table] if r["sampler"] in AO_PAPER_SET]
            ranked = sorted(fig, key=lambda r: -r["psnr_mean"])
            rank = {r["sampler"]: k + 1 for k, r in enumerate(ranked)}
            best_other = next(r for r in ranked if r["sampler"] != "episwr")
            v = compare(fig, "episwr", best_other["sampler"])
            rows.append({"figure": "6", "scene": f"AO, {when}", "claim": "EPISWR gives the best PSNR of the paper's "
                         "11 AO samplers" + (" (the paper: at equal spp)" if when == "equal time" else ""),
                         "paper": "first", "ours": f"rank {rank['episwr']}; against {best_other['sampler']}",
                         "ours_db": next(r["psnr_mean"] for r in fig if r["sampler"] == "episwr") - best_other["psnr_mean"],
                         "verdict": {"holds": "holds", "tie": "tie", "fails": "fails"}[v]})
            last_two = {r["sampler"] for r in ranked[-2:]}
            hs = {"halton", "sobol"} & last_two
            rows.append({"figure": "6", "scene": f"AO, {when}", "claim": "Halton and Sobol are the poorest of the 11",
                         "paper": "last two", "ours": f"Halton rank {rank['halton']}, Sobol rank {rank['sobol']} of "
                         f"{len(fig)}", "ours_db": None,
                         "verdict": "holds" if len(hs) == 2 else ("partly" if hs else "fails")})
    if pt_scenes(out, state):
        p8, p10 = PT_PAPER["Figure 8 (San Miguel)"], PT_PAPER["Figure 10 (Crown)"]
        for _, _, sc in pt_scenes(out, state):
            fig = sc["figure"]
            p = {r["sampler"]: r["psnr_mean"] for r in fig}
            scene = f"PT, {sc['title']}"
            for w in ("wr", "wmmr", "hwmmr"):
                rows.append({"figure": "8, 10", "scene": scene, "claim": f"{PT_NAMES[w]} beats PRNG",
                             "paper": f"{p8[w] - p8['pcg32']:+.2f} / {p10[w] - p10['pcg32']:+.2f} dB",
                             "ours": "", "ours_db": p[w] - p["pcg32"], "verdict": compare(fig, w, "pcg32")})
            for w in ("wr", "wmmr", "hwmmr"):
                for q in ("halton", "sobol"):
                    v = compare(fig, w, q)
                    rows.append({"figure": "8, 10", "scene": scene, "claim": f"{PT_NAMES[w]} matches or beats "
                                 f"{PT_NAMES[q]}", "paper": f"{p8[w] - p8[q]:+.2f} / {p10[w] - p10[q]:+.2f} dB",
                                 "ours": "", "ours_db": p[w] - p[q], "verdict": "holds (tie)" if v == "tie" else v})
            six = [r for r in fig if r["sampler"] in p8]
            for figname, claimed in (("8", "hwmmr"), ("10", "sobol")):
                best_other = max((r for r in six if r["sampler"] != claimed), key=lambda r: r["psnr_mean"])
                rows.append({"figure": figname, "scene": scene, "claim": f"{PT_NAMES[claimed]} is the best of the "
                             "paper's six samplers", "paper": "best", "ours": f"against {PT_NAMES[best_other['sampler']]}",
                             "ours_db": p[claimed] - best_other["psnr_mean"],
                             "verdict": compare(six, claimed, best_other["sampler"])})
    if not rows:
        doc.para("**No claims checked**: the ao and pt steps did not finish (see the steps table).")
        return
    doc.table("claims", "the paper's claims", [
        ("figure", "figure", ""), ("scene", "our scene", ""), ("claim", "claim", ""), ("paper", "paper (Fig. 8 / 10)", ""),
        ("ours", "ours", ""), ("ours_db", "ours (dB)", "+.2f"), ("verdict", "verdict", "")], rows)
    counts = {}
    for r in rows:
        key = r["verdict"].split(" ")[0]
        counts[key] = counts.get(key, 0) + 1
    doc.para("In all: " + ", ".join(f"{v} {k}" for k, v in sorted(counts.items())) + f" of {len(rows)} checks.")


def pt_gains_section(doc, out: Path, state):
    scenes = pt_scenes(out, state)
    if not scenes:
        return
    samplers = [r["sampler"] for r in scenes[0][2]["figure"]]
    rows = []
    for figname, vals in PT_PAPER.items():
        rows.append({"source": f"paper, {figname}", "spp": 4096,
                     **{s: (vals[s] - vals["pcg32"]) if s in vals else None for s in samplers}})
    for _, _, sc in scenes:
        p = {r["sampler"]: r["psnr_mean"] for r in sc["figure"]}
        rows.append({"source": f"ours, {sc['title']} ({sc['size']})", "spp": sc["spp"],
                     **{s: p[s] - p["pcg32"] for s in samplers}})
    doc.heading(3, "Path tracing: PSNR gain over PRNG at equal spp, the paper's figures and ours")
    doc.table("pt_gains", "PSNR gain over PRNG (dB)", [("source", "source", ""), ("spp", "spp", "d")]
              + [(s, PT_NAMES.get(s, s), "+.2f") for s in samplers], rows)


def slope_guides(ax, curves: dict):
    """Dotted guides error ~ time^-1/2 and time^-1 (time is proportional to N) through the slowest curve's start."""
    pts = [p for c in curves.values() for p in c if p[0] > 0 and p[1] > 0]
    if len(pts) < 2:
        return
    t0, t1 = min(p[0] for p in pts), max(p[0] for p in pts)
    e0 = max(p[1] for p in pts if p[0] <= t0 * 1.5)
    for k, lab in ((0.5, "t^-1/2"), (1.0, "t^-1")):
        ax.loglog([t0, t1], [e0, e0 * (t1 / t0) ** -k], color="0.55", lw=0.8, ls=":", zorder=0)
        ax.text(t1, e0 * (t1 / t0) ** -k, lab, fontsize=6, color="0.4")


def speed_error_plots(out: Path, state) -> list[str]:
    """Error against time, one panel per application and scene; and equal-time gains over PRNG."""
    panels = []
    if done(state, "samplers"):
        err = load(out, "samplers.json")["error"]
        for integ in (SMOOTH_2D, DISCONTINUOUS_2D, SMOOTH_8D):
            rs = [r for r in err if r["integrand"] == integ]
            panels.append((f"integration: {integ} (d={rs[0]['d'] if rs else '?'})", "seconds per estimate (1 thread)",
                           "relative RMSE", {s: sorted((r["seconds_per_estimate"], r["relative_rmse"]) for r in rs
                                                       if r["sampler"] == s) for s in dict.fromkeys(r["sampler"] for r in rs)}))
    if done(state, "ao"):
        sw = load(out, "ao.json")["sweep"]
        panels.append(("ambient occlusion (udm1-ao)", "render time (s, all cores)", "RMSE",
                       {s: sorted((r["seconds"], r["rmse"]) for r in sw if r["sampler"] == s)
                        for s in dict.fromkeys(r["sampler"] for r in sw)}))
    for _, _, sc in pt_scenes(out, state):
        sw = sc["sweep"]
        panels.append((f"path tracing: {sc['title']}", "render time (s, all cores)", "RMSE",
                       {s: sorted((r["seconds"], r["rmse"]) for r in sw if r["sampler"] == s)
                        for s in dict.fromkeys(r["sampler"] for r in sw)}))
    names = []
    if panels:
        cols = min(3, len(panels))
        nrows = math.ceil(len(panels) / cols)
        fig, axes = plt.subplots(nrows, cols, figsize=(5.2 * cols, 4.2 * nrows), squeeze=False)
        for ax in axes.ravel()[len(panels):]:
            ax.axis("off")
        for ax, (title, xl, yl, curves) in zip(axes.ravel(), panels):
            for s, pts in curves.items():
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], **style(s))
            slope_guides(ax, curves)
            ax.set_title(title, fontsize=9)
            ax.set_xlabel(xl, fontsize=8)
            ax.set_ylabel(yl, fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="both", alpha=0.25)
            ax.legend(fontsize=5.5, ncol=2)
        fig.suptitle("Error against time: lower left is better (Weyl sets solid, the others dashed; dotted: "
                     "slope guides, error ~ time^-1/2 and time^-1)", fontsize=11)
        fig.tight_layout()
        fig.savefig(out / "speed_vs_error.png", dpi=90)
        plt.close(fig)
        names.append("speed_vs_error.png")
    bars = []
    if done(state, "ao"):
        eq = load(out, "ao.json")["equal_time"]
        bars.append(("ambient occlusion", eq))
    for _, _, sc in pt_scenes(out, state):
        bars.append((f"path tracing: {sc['title']}", sc["equal_time"]))
    if bars:
        fig, axes = plt.subplots(1, len(bars), figsize=(5.5 * len(bars), 4.2), squeeze=False)
        for ax, (title, eq) in zip(axes.ravel(), bars):
            base = next(r["psnr_mean"] for r in eq if r["sampler"] == "pcg32")
            rs = sorted(eq, key=lambda r: -r["psnr_mean"])
            ax.barh([r["sampler"] for r in rs], [r["psnr_mean"] - base for r in rs],
                    color=[style(r["sampler"])["color"] for r in rs],
                    edgecolor=["#a00" if r["sampler"] in WEYL else "none" for r in rs])
            ax.invert_yaxis()
            ax.axvline(0, color="k", lw=0.8)
            ax.set_title(title, fontsize=9)
            ax.set_xlabel("PSNR gain over PRNG at equal time (dB)", fontsize=8)
            ax.tick_params(labelsize=7)
        fig.suptitle("Equal time: every sampler given the same render time (Weyl sets outlined in red)", fontsize=10)
        fig.tight_layout()
        fig.savefig(out / "equal_time.png", dpi=90)
        plt.close(fig)
        names.append("equal_time.png")
    return names


def sequences_section(doc, out: Path, state):
    doc.heading(2, "Sequences", "sequences")
    if not_shown(doc, state, "sequences"):
        return
    data = load(out, "sequences.json")
    big = max(r["n"] for r in data["discrepancy"])
    doc.image("points_256.png", "points")
    doc.para(f"Discrepancy of the 2D sets at n = {big}, mean over {data['seeds']} randomizations (CD and WD "
             "squared, as scipy.stats.qmc.discrepancy); every N in [sequences](sequences.html).")
    doc.table("discrepancy", "2D discrepancy", [("set", "set", ""), ("n", "n", "d"), ("CD", "CD", ".3g"),
                                                 ("L2-star", "L2-star", ".3g"), ("WD", "WD", ".3g")],
              [r for r in data["discrepancy"] if r["n"] == big])
    doc.para("The constant-set check: the worst 2D projection of the many-dimensional sets against independent "
             "random points (above 1: worse than random).")
    doc.image("discrepancy_CD.png", "CD discrepancy against n")
    doc.table("check", "worst 2D projection", [("preset", "set", ""), ("d", "d", "d"), ("n", "n", "d"),
                                                ("worst_l2_star", "worst L2-star", ".3g"), ("ratio", "x random", ".2f")],
              data["check"])


def integration_section(doc, out: Path, state):
    doc.heading(2, "Integration: error against N and against time", "integration")
    if not_shown(doc, state, "samplers"):
        return
    data = load(out, "samplers.json")
    err, slopes = data["error"], data["slopes"]
    samplers = list(dict.fromkeys(r["sampler"] for r in err))
    n_max = max(r["n"] for r in err if r["integrand"] == SMOOTH_2D)
    at = {(r["sampler"], r["integrand"]): r for r in err if r["n"] == n_max}
    rows = []
    for s in samplers:
        g, d, o = at.get((s, SMOOTH_2D)), at.get((s, DISCONTINUOUS_2D)), at.get((s, SMOOTH_8D))
        rows.append({"sampler": s, "weyl": "yes" if s in WEYL else "",
                     "slope_smooth": slopes.get(f"{s}|{SMOOTH_2D}"), "slope_disc": slopes.get(f"{s}|{DISCONTINUOUS_2D}"),
                     "slope_8d": slopes.get(f"{s}|{SMOOTH_8D}"),
                     "rel_smooth": g["relative_rmse"] if g else None, "rel_disc": d["relative_rmse"] if d else None,
                     "rel_8d": o["relative_rmse"] if o else None,
                     "us_smooth": g["seconds_per_estimate"] * 1e6 if g else None})
    doc.para(f"Relative RMSE over {data['reps']} randomizations at N = {n_max} and the fitted slope of log RMSE "
             f"against log N (N >= 256): {SMOOTH_2D} (smooth, 2D), {DISCONTINUOUS_2D} (discontinuous, 2D), "
             f"{SMOOTH_8D} (smooth, 8D); time per estimate of N points, one thread. Thirteen integrands in "
             "[samplers](samplers.html).")
    doc.table("integration", "integration error", [
        ("sampler", "sampler", ""), ("weyl", "Weyl", ""), ("slope_smooth", f"slope {SMOOTH_2D}", ".2f"),
        ("slope_disc", f"slope {DISCONTINUOUS_2D}", ".2f"), ("slope_8d", f"slope {SMOOTH_8D}", ".2f"),
        ("rel_smooth", f"rel. RMSE {SMOOTH_2D}", ".3g"), ("rel_disc", f"rel. RMSE {DISCONTINUOUS_2D}", ".3g"),
        ("rel_8d", f"rel. RMSE {SMOOTH_8D}", ".3g"), ("us_smooth", "us per estimate", ".3g")], rows)
    doc.image("samplers_rmse_2d.png", "integration RMSE against N, 2D")
    doc.para("Each sampler's 2D points as a power spectrum (white noise = 0 on the log scale; a lattice shows as "
             "isolated peaks):")
    doc.image("samplers_spectra.png", "spectra")
    for key, when in (("verdicts", "equal N"), ("verdicts_equal_time", "equal time")):
        v = data[key]
        wins = sum(1 for r in v if "wins" in r[-1])
        doc.para(f"At {when}, the best of the paper's sets beats the best baseline in {wins} of {len(v)} "
                 "(integrand, N) cases.")


def throughput_section(doc, out: Path, state):
    doc.heading(2, "Sampler throughput", "throughput")
    if not_shown(doc, state, "throughput"):
        return
    rows = parse_throughput((out / "throughput.txt").read_text())
    doc.para("Values per second, one thread, bulk fill of 4096 points and one call per value, against WR and "
             "memset (the write bandwidth) measured in the same run; `udm1_bench_samplers throughput`.")
    doc.table("throughput", "throughput", [
        ("sampler", "sampler", ""), ("d", "d", "d"), ("bulk", "bulk values/s", ".3g"), ("bulk_x_wr", "x WR", ".2f"),
        ("per_sample", "per-sample values/s", ".3g"), ("per_sample_x_wr", "x WR", ".2f")], rows)


def noise_section(doc, out: Path, state):
    doc.heading(2, "Noise", "noise")
    if not_shown(doc, state, "noise"):
        return
    doc.para("The paper's Figure 2 (noise) and Figure 3 (patterns): tables from WR (top) and drand48 (bottom); "
             "[noise/figures.md](noise/figures.md).")
    doc.image("noise/figure2.png", "Figure 2")
    doc.image("noise/figure3.png", "Figure 3")
    rows = parse_libnoise((out / "noise_libnoise.txt").read_text()) + \
        parse_simd_noise(out)
    doc.para("Evaluations per second, each ratio against the anchor named in its row, measured in the same run "
             "(udm1_bench_noise and bench/bench_noise.py).")
    doc.table("noise_speed", "noise speed", [("method", "method", ""), ("per_second", "per second", ".3g"),
                                             ("ratio", "ratio", ".2f"), ("anchor", "anchor", "")], rows)
    spec = load(out, "noise_spectra.json")
    doc.para(f"Power spectra of improved noise ({spec['size']} x {spec['size']}, {spec['cell']} pixels per lattice "
             f"cell) with tables from each source: the udm1 tables give the same band as random (drand48) tables, "
             "without the peaks a lattice-like permutation would add. The table: the largest factor by which a "
             "source's radial spectrum departs from the mean of the others between 0.05 and 2 cycles per cell.")
    doc.image("noise_spectra.png", "noise spectra")
    doc.table("noise_spectra", "noise spectra", [("source", "table source", ""), ("factor", "largest departure (x)", ".2f")],
              [{"source": t, "factor": math.exp(v)} for t, v in spec["max_log_ratio_to_others"].items()])


def ao_section(doc, out: Path, state):
    doc.heading(2, "Ambient occlusion (udm1-ao)", "ao")
    if not_shown(doc, state, "ao"):
        return
    ao = load(out, "ao.json")
    eq = {r["sampler"]: r for r in ao["equal_time"]}
    base = eq["pcg32"]["psnr_mean"]
    fig = ao["figure6"]
    spp = fig[0]["spp"]
    rows = [{"sampler": r["sampler"], "paper": "yes" if r["paper_set"] else "", "psnr": r["psnr_mean"],
             "sd": r["psnr_sd"], "ms": r["seconds"] * 1e3, "eq_spp": eq[r["sampler"]]["spp"],
             "eq_psnr": eq[r["sampler"]]["psnr_mean"], "eq_gain": eq[r["sampler"]]["psnr_mean"] - base}
            for r in sorted(fig, key=lambda r: -r["psnr_mean"])]
    doc.para(f"Every sampler at {spp} spp against the reference (`{ao['reference']}`), mean PSNR over seeds, "
             f"and at equal time (EPISWR's {spp}-spp time, {ao['budget_seconds'] * 1e3:.0f} ms); details in "
             "[ao](ao.html).")
    doc.table("ao", "ambient occlusion", [
        ("sampler", "sampler", ""), ("paper", "paper's set", ""), ("psnr", f"PSNR at {spp} spp (dB)", ".2f"),
        ("sd", "sd", ".2f"), ("ms", "time (ms)", ".1f"), ("eq_spp", "equal-time spp", "d"),
        ("eq_psnr", "equal-time PSNR (dB)", ".2f"), ("eq_gain", "gain over PRNG (dB)", "+.2f")], rows)
    doc.image("ao_figure6.png", "Figure 6")


def pt_section(doc, out: Path, state, step: str = "pt", prefix: str = ""):
    title = "Path tracing (udm1-pt)" if step == "pt" else "Path tracing: the Crown, the paper's Figure 10 scene"
    doc.heading(2, title, step)
    if not_shown(doc, state, step):
        return
    for k, sc in enumerate(load(out, prefix + "pt.json")["scenes"]):
        eq = {r["sampler"]: r for r in sc["equal_time"]}
        prng = next(r for r in sc["figure"] if r["sampler"] == "pcg32")
        rows = [{"sampler": r["sampler"], "psnr": r["psnr_mean"], "sd": r["psnr_sd"],
                 "gain": r["psnr_mean"] - prng["psnr_mean"], "seconds": r["seconds"],
                 "eq_spp": eq[r["sampler"]]["spp"], "eq_psnr": eq[r["sampler"]]["psnr_mean"],
                 "eq_gain": eq[r["sampler"]]["psnr_mean"] - eq["pcg32"]["psnr_mean"],
                 "time_to": sc["time_to_target"].get(r["sampler"])}
                for r in sorted(sc["figure"], key=lambda r: -r["psnr_mean"])]
        doc.heading(3, f"{sc['title']}: {sc['size']}, {sc['spp']} spp, reference {sc['ref_spp']} spp")
        doc.para(f"Mean PSNR over {sc['seeds']} seeds; equal time is PRNG's {sc['spp']}-spp time "
                 f"({sc['budget_seconds']:.2f} s); \"time to PRNG's error\" is the time to reach the RMSE PRNG has at "
                 f"{sc['target_spp']} spp in the sweep at {sc['sweep_size']} (empty: not reached).")
        doc.table(f"{step}_s{k}", sc["title"], [
            ("sampler", "sampler", ""), ("psnr", f"PSNR at {sc['spp']} spp (dB)", ".2f"), ("sd", "sd", ".2f"),
            ("gain", "gain over PRNG (dB)", "+.2f"), ("seconds", "time (s)", ".2f"), ("eq_spp", "equal-time spp", "d"),
            ("eq_psnr", "equal-time PSNR (dB)", ".2f"), ("eq_gain", "equal-time gain (dB)", "+.2f"),
            ("time_to", "time to PRNG's error (s)", ".3g")], rows)
        doc.image(f"{prefix}pt_s{k}_sheet.png", f"{sc['title']} contact sheet")
        doc.image(f"{prefix}pt_s{k}_sweep.png", f"{sc['title']}: error against spp and time")
    doc.para(f"Details, sweeps and verdicts per scene in [{step}]({prefix}pt.html).")


def accuracy_section(doc, out: Path, state):
    doc.heading(2, "Agreement with pbrt-v4", "accuracy")
    if not_shown(doc, state, "accuracy"):
        return
    acc = load(out, "accuracy/accuracy.json")
    if acc.get("skipped"):
        doc.para(f"**Not measured**: {acc['skipped']}.")
        return
    doc.para("Each scene file rendered by udm1-pt and by pbrt-v4 (box filter, same size and spp, several seeds): "
             "the image mean per channel and the relative difference with its standard error. A difference above "
             "1 % has a stated cause, and the variants under it remove the cause one step at a time.")
    rows = [{"scene": r["scene"], "variant": r["variant"] or "as is", "spp": r["spp"],
             **{f"d{c}": 100 * r["difference"][c] for c in range(3)},
             "se": 100 * max(r["difference_stderr"])} for r in acc["rows"]]
    doc.table("accuracy", "udm1-pt against pbrt-v4", [
        ("scene", "scene", ""), ("variant", "variant", ""), ("spp", "spp", "d"), ("d0", "R difference (%)", "+.2f"),
        ("d1", "G difference (%)", "+.2f"), ("d2", "B difference (%)", "+.2f"), ("se", "largest s.e. (%)", ".2f")], rows)
    for r in acc["rows"]:
        if not r["variant"] and r.get("cause") and max(abs(x) for x in r["difference"]) > 0.01:
            doc.para(f"**{r['scene']}**: {r['cause']}.")
    doc.image("accuracy/accuracy.png", "differences")
    for r in acc["rows"]:
        if not r["variant"] and (out / "accuracy" / r["scene"] / "compare.png").exists():
            doc.image(f"accuracy/{r['scene']}/compare.png", f"{r['scene']}: pbrt-v4, udm1-pt, difference")


def renderers_section(doc, out: Path, state):
    doc.heading(2, "udm1-pt against pbrt-v4 and Mitsuba 3 at equal error", "renderers")
    if not_shown(doc, state, "renderers"):
        return
    res = load(out, "renderers/pt_scenes.json")
    if res.get("skipped"):
        doc.para(f"**Not measured**: {res['skipped']}.")
        return
    doc.para("Each renderer against its own converged reference; the seconds each renderer's best sampler needs to "
             "reach the errors pbrt-v4's default sampler (zsobol) reaches, and the fastest other renderer's time over "
             "udm1-pt's (above 1: udm1-pt faster). Every sampler's errors and times: "
             "[renderers/pt_scenes.md](renderers/pt_scenes.md).")
    rows = []
    for sc in res["scenes"]:
        for rec in sc["equal_error"]:
            best = rec["best"]
            rows.append({"scene": f"{sc['scene']} {sc['size'][0]}x{sc['size'][1]}", "rmse": rec["rmse"],
                         **{k: (best[k][0] if best.get(k) else None) for k in best},
                         "fastest": rec.get("fastest_other", ""), "speedup": rec.get("speedup")})
    names = []
    for sc in res["scenes"]:
        for n, _ in sc["renderers"]:
            if n not in names:
                names.append(n)
    doc.table("renderers", "seconds to an error", [("scene", "scene", ""), ("rmse", "target RMSE", ".5f")] +
              [(n, f"{n} (s)", ".3g") for n in names] +
              [("fastest", "fastest other", ""), ("speedup", "fastest other / udm1-pt", ".2f")], rows)
    for sc in res["scenes"]:
        if sc.get("mitsuba"):
            doc.para(f"**{sc['scene']}**: {sc['mitsuba']}.")
        doc.image(f"renderers/{sc['scene']}_error_vs_time.png", f"{sc['scene']}: error against time")


def mitsuba_section(doc, out: Path, state):
    doc.heading(2, "udm1's samplers inside Mitsuba 3", "mitsuba")
    if not_shown(doc, state, "mitsuba"):
        return
    results = load(out, "mitsuba/results.json")
    doc.para("Mitsuba 3's Cornell box (its path integrator) rendered with Mitsuba's own samplers and with udm1's "
             "(the native plugin of integrations/mitsuba3, or `udm1.mitsuba`'s Python sampler where it cannot be built; "
             "bench/bench_mitsuba_sampler.py): RMSE against an independent-sampler reference at "
             "equal spp, render time relative to Mitsuba's independent sampler, and the time each needs to reach "
             "the independent sampler's error.")
    for res in results:
        if res.get("skipped"):
            doc.para(f"**{res.get('variant', 'Mitsuba 3')}: not measured**: {res['skipped']}.")
            continue
        v = res["variant"]
        doc.para(f"**{v}**, {res['size']} x {res['size']}, {res['seeds']} renders per point, reference "
                 f"{res['ref_spp']} spp; udm1's rows: its {res.get('udm1', 'Python sampler')}.")
        doc.table(f"mitsuba_{v}", f"{v}: equal spp",
                  [("sampler", "sampler", ""), ("spp", "spp", "d"), ("spp_taken", "spp taken", "d"),
                   ("rmse", "RMSE", ".5f"), ("seconds", "seconds", ".3f"),
                   ("x_independent_time", "time / independent's", ".2f")], res["rows"])
        for e in res["equal_error"]:
            if e.get("not_compared"):
                doc.para(f"Equal error at {e['target_rmse']:.5f} ({e['target_of']}): not compared: {e['not_compared']}.")
        doc.table(f"mitsuba_{v}_equal", f"{v}: equal error",
                  [("target_of", "target", ""), ("target_rmse", "RMSE", ".5f"), ("best_udm1", "best udm1", ""),
                   ("udm1_seconds", "its seconds", ".3f"), ("best_mitsuba", "best Mitsuba", ""),
                   ("mitsuba_seconds", "its seconds", ".3f"), ("speedup", "Mitsuba / udm1", ".2f")],
                  [e for e in res["equal_error"] if not e.get("not_compared")])


def tolerance_section(doc, out: Path, state):
    doc.heading(2, "Integration to a tolerance", "tolerance")
    if not_shown(doc, state, "tolerance"):
        return
    res = load(out, "tolerance/results.json")
    doc.para(f"`udm1.integrate(..., abs_tol=...)` (the embedded lattice's Fourier criterion, and 16 randomized "
             f"replicates with a Student-t interval at 99 %) against QMCPy's "
             f"criteria and scipy's qmc_quad on Genz's families (bench/bench_integrate.py): {res['trials']} trial(s) "
             f"per case with random coefficients, tolerance {res['rel']:g} x |I|, at most {res['n_max']} "
             "evaluations; the share of trials within the tolerance, the median evaluations and the median time.")
    doc.table("tolerance", "integration to a tolerance",
              [("family", "family", ""), ("d", "d", "d"), ("method", "method", ""), ("success", "within tolerance", ".0%"),
               ("median_n", "median evaluations", ".0f"), ("median_seconds", "median seconds", ".4f")], res["rows"])


def ratio(a: float, b: float) -> float:
    """a / b, with an exact (zero-error) b shown as an infinite gain rather than dropped."""
    if b == 0:
        return float("inf") if a > 0 else 1.0
    return a / b


def tent_rows(out: Path) -> list[dict]:
    with open(out / "tent.csv") as f:
        rows = list(csv.DictReader(f))
    at = {}
    for r in rows:
        at[(r["integrand"], r["sampler"], int(r["n"]))] = r
    table = []
    for integ in dict.fromkeys(r["integrand"] for r in rows):
        n = max(int(r["n"]) for r in rows if r["integrand"] == integ)
        get = {s: at.get((integ, s, n)) for s in {r["sampler"] for r in rows}}
        rel = {s: float(r["relative_rmse"]) for s, r in get.items() if r}
        cost = {s: float(r["rmse"]) ** 2 * float(r["seconds_per_estimate"]) for s, r in get.items() if r}
        tents = [s for s in cost if s.endswith("+tent")]
        anchors = [s for s in cost if s in ("sobol-owen", "pmj02")]
        bt, ba = min(tents, key=cost.get), min(anchors, key=cost.get)
        table.append({"integrand": integ, "d": int(get[bt]["d"]), "n": n,
                      **{f"gain_{w}": ratio(rel[w], rel[w + "+tent"]) for w in ("wr", "rd", "wopt", "lattice")},
                      "best_tent": bt, "best_anchor": ba, "equal_time": ratio(cost[bt], cost[ba])})
    return table


def beyond_section(doc, out: Path, state):
    doc.heading(2, "Beyond the paper", "beyond")
    doc.para("**wopt**, udm1's searched set (tools/alpha_search.py: 64 square roots of primes chosen greedily to keep "
             "every 2D projection near random-shift quality), appears in every table above; its worst 2D projection "
             "is in the constant-set check (sequences) beside WR, WMMR, HWMMR and R_d.")
    doc.para("**The rank-1 lattice** (`lattice`, K points {n z / K + shift}, z by a component-by-component search "
             "on the exact wrap-around L2 discrepancy): the fixed-N counterpart of a Kronecker sequence; it is in "
             "every table above, and with the tent transform below.")
    doc.para("**The tent transform** (`NAME+tent`, any sampler: every value x becomes 1 - |2x - 1|, exact in "
             "integers): relative RMSE at the largest N over randomizations, each Weyl set and the lattice plain and transformed "
             "(gain = plain / tent, above 1: the tent helps), and the best transformed Weyl set against the best "
             "of Owen-scrambled Sobol and PMJ02 at equal time (RMSE^2 x time; below 1: the Weyl set wins).")
    if not not_shown(doc, state, "tent"):
        doc.table("tent", "tent transform", [("integrand", "integrand", ""), ("d", "d", "d"), ("n", "N", "d")]
                  + [(f"gain_{w}", f"gain {w}", ".2f") for w in ("wr", "rd", "wopt", "lattice")]
                  + [("best_tent", "best +tent", ""), ("best_anchor", "best anchor", ""),
                     ("equal_time", "+tent / anchor at equal time", ".3g")], tent_rows(out))
        doc.para("An infinite gain (and an equal-time ratio of 0) means the transformed set integrated that "
                 "integrand exactly for every randomization: the tent-transformed lattice does so for the half "
                 "plane, whose boundary passes through the centre of the square (a symmetry of that integrand, "
                 "not a general property; a line off the centre is not integrated exactly). The plain lattice "
                 "is already spectrally accurate on the nearly periodic Gaussian, which the tent then spoils.")
    doc.para("**Screen-space blue noise** (`--randomize screen`): each pixel of a Weyl sequence keeps the sequence's "
             "points shifted by x G + y H (docs/screen-space.md), blue at every sample count; beside it per-pixel "
             "shifts, the fixed-N scheme (`--randomize screen-fixed`, rendered at each N) and Z-order Owen-Sobol (powers "
             "of two). The low-frequency share of the error image's energy (1 = white noise, lower = blue noise), its "
             "worst and median over the counts 1 .. 256, on ambient occlusion with the direction on one dimension pair, "
             "the path tracer, and two 2D integrands on one dimension pair; the RMSE against per-pixel shifts.")
    if not_shown(doc, state, "screen"):
        return
    data = load(out, "screen.json")
    rows = [dict(r, pair=str(r["pair"]), rmse=f"{r['rmse_min']:.3f} - {r['rmse_max']:.3f}") for r in data["summary"]]
    doc.table("screen", "screen-space blue noise", [
        ("source", "source", ""), ("pair", "pair", ""), ("scheme", "scheme", ""), ("counts", "counts", "d"),
        ("worst_low", "worst share", ".2f"), ("worst_at", "at spp", "d"), ("median_low", "median share", ".2f"),
        ("rmse", "RMSE / shift's", "")], rows)
    t = data["targets"]
    doc.para(f"Targets of the progressive scheme: share at most 0.5 at every count and pair "
             f"({'met' if t['low_met'] else 'not met'}: worst {t['low_share_max']:.2f}); RMSE within 2 % of per-pixel "
             f"shifts ({'met' if t['rmse_met'] else 'not met'}: worst {100 * t['rmse_dev_max']:.1f} %).")
    doc.image("screen_renders.png", "share against spp, renders")
    doc.image("screen_pairs.png", "share against spp, integrands on one pair")
    doc.image("screen_errors.png", "error images")


def plots_section(doc, out: Path, state) -> list[str]:
    return speed_error_plots(out, state)


def guarded(doc, section, *args):
    """Run one section; if it fails (a step's output it cannot read), say so in its place, never drop it."""
    try:
        return section(doc, *args)
    except Exception as exc:  # noqa: BLE001 - any failure is reported in the page, and in the exit status
        doc.para(f"**This section failed** ({section.__name__}): {type(exc).__name__}: {exc}")
        doc.failed_sections.append(section.__name__)
        return None


def build(doc, out: Path, steps, state: dict, mode: str, machine: dict) -> list[str]:
    guarded(doc, verdict_section, out, steps, state, mode, machine)
    guarded(doc, claims_section, out, state)
    steps_section(doc, steps, state, mode)
    guarded(doc, pt_gains_section, out, state)
    figures = guarded(doc, plots_section, out, state) or []
    doc.heading(2, "Speed against error", "speed")
    if figures:
        doc.para("Error against time for each application (integration: one thread per estimate; renderers: all "
                 "cores), and each sampler's PSNR gain over PRNG when every sampler gets the same time.")
        for f in figures:
            doc.image(f, f)
    else:
        doc.para("**No plots**: none of the samplers, ao and pt steps finished.")
    for section in (sequences_section, integration_section, throughput_section, noise_section, ao_section,
                    pt_section, mitsuba_section, tolerance_section, beyond_section):
        guarded(doc, section, out, state)
    if "crown" in state:
        guarded(doc, pt_section, out, state, "crown", "crown/")
    if "accuracy" in state:
        guarded(doc, accuracy_section, out, state)
    if "renderers" in state:
        guarded(doc, renderers_section, out, state)
    return figures
