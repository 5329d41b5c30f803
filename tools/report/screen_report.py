"""Screen-space decorrelation for Kronecker sequences (UDM1_RANDOMIZE_SCREEN) in the renderers.

Each Weyl sampler renders with its usual per-pixel random shift ("shift") and with the screen-space shift
("screen": pixel (x, y) takes the points m N .. m N + N - 1 of one shifted sequence, m its Morton index and
N the spp; libudm1/src/weyl/weyl.h), beside
Owen-scrambled Sobol and PMJ02 with their own randomization. For each: RMSE against a reference (mean over
seeds), render time, and the share of the error image's energy at low screen frequencies (radius below
1/8 of the sampling rate, relative to the mean: 1 for white noise, below 1 for blue noise). The MSE is
what equal time compares; the low-frequency share is what the eye sees at low spp.

Writes OUT/screen.json, OUT/screen.md, OUT/screen.html, OUT/screen_errors.png, OUT/screen_spectra.png;
renders and references go to OUT/screen/.

    PYTHONPATH=python python tools/report/screen_report.py --ao build/bin/udm1-ao --pt build/bin/udm1-pt --out report
"""

from __future__ import annotations

import argparse
import functools
import json
import subprocess
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from report_common import log, md_table, md_to_html, writable_folder  # noqa: E402

WEYL = {"ao": ["wr", "wopt", "rd"], "pt": ["wr", "wmmr", "wopt"]}  # sequences (screen mode excludes point sets)
ANCHORS = ["sobol-owen", "pmj02"]


@functools.cache
def mitsuba():
    """Mitsuba reads OpenEXR (already a dependency: the path tracer's cross-check); its variant is set once."""
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    return mi


def read_exr(path: Path) -> np.ndarray:
    a = np.array(mitsuba().Bitmap(str(path)), dtype=np.float64)
    return a[..., :3].mean(axis=2) if a.ndim == 3 else a


def low_frequency_share(err: np.ndarray) -> float:
    p = np.abs(np.fft.fftshift(np.fft.fft2(err - err.mean()))) ** 2
    h, w = p.shape
    yy, xx = np.indices(p.shape)
    r = np.hypot((yy - h // 2) / h, (xx - w // 2) / w)
    return float(p[(r > 0) & (r < 1 / 8)].mean() / p[r > 0].mean())


def radial(err: np.ndarray, bins: int = 24) -> np.ndarray:
    p = np.abs(np.fft.fftshift(np.fft.fft2(err - err.mean()))) ** 2
    h, w = p.shape
    yy, xx = np.indices(p.shape)
    r = np.hypot((yy - h // 2) / h, (xx - w // 2) / w)
    k = np.minimum((r / 0.5 * bins).astype(int), bins)
    s = np.bincount(k.ravel(), p.ravel(), bins + 1)[:bins] / np.maximum(np.bincount(k.ravel(), None, bins + 1)[:bins], 1)
    return s / p[r > 0].mean()


def run(tool: str, *args: str) -> str:
    r = subprocess.run([tool, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{Path(tool).name} {' '.join(args)}: {r.stderr.strip()}")
    return r.stdout


def measure(app: str, tool: str, common: list[str], spps, seeds: int, ref_spp: int, folder: Path) -> list[dict]:
    ref = folder / f"{app}-reference.exr"
    run(tool, "reference", *common, "--spp", str(ref_spp), "-o", str(ref))
    truth = read_exr(ref)
    rows = []
    configs = [(s, "shift") for s in WEYL[app]] + [(s, "screen") for s in WEYL[app]] + [(s, "default") for s in ANCHORS]
    for spp in spps:
        for sampler, mode in configs:
            errs, secs, lows = [], [], []
            for seed in range(1, seeds + 1):
                img = folder / f"{app}-{sampler}-{mode}-{spp}-{seed}.exr"
                out = run(tool, *common, "--sampler", sampler, "--spp", str(spp), "--seed", str(seed),
                          "--randomize", mode, "-o", str(img))
                secs.append(float(out.split(" seconds ")[1].split()[0]))
                e = read_exr(img) - truth
                errs.append(float(np.mean(e ** 2)))
                lows.append(low_frequency_share(e))
                if seed == 1:
                    np.save(folder / f"{app}-{sampler}-{mode}-{spp}-err.npy", e.astype(np.float32))
            rows.append({"app": app, "sampler": sampler, "randomize": mode, "spp": spp, "rmse": float(np.sqrt(np.mean(errs))),
                         "low_share": float(np.mean(lows)), "low_share_sd": float(np.std(lows)),
                         "seconds": float(np.median(secs))})
            log(f"{app} {sampler:10s} {mode:7s} {spp:4d} spp: RMSE {rows[-1]['rmse']:.4g}, low-frequency share "
                f"{rows[-1]['low_share']:.2f}")
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ao", required=True, help="path of udm1-ao")
    ap.add_argument("--pt", required=True, help="path of udm1-pt")
    ap.add_argument("--out", default="report")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--quick", action="store_true", help="small images, for tests")
    args = ap.parse_args(argv)
    for name in ("ao", "pt"):
        if not Path(getattr(args, name)).exists():
            print(f"screen_report: no udm1-{name} at '{getattr(args, name)}' (build it first)", file=sys.stderr)
            return 2
    out = writable_folder(args.out, "screen_report")
    if out is None:
        return 1
    folder = out / "screen"
    folder.mkdir(exist_ok=True)
    t0 = time.time()
    q = args.quick
    ao = measure("ao", args.ao, ["--scene", "builtin:cornell", "--size", "48x48" if q else "128x128"],
                 [4] if q else [4, 16], 2 if q else args.seeds, 256 if q else 4096, folder)
    pt = measure("pt", args.pt, ["--scene", "builtin:cornell", "--size", "32x32" if q else "96x96"],
                 [4] if q else [16, 64], 2 if q else args.seeds, 128 if q else 2048, folder)
    rows = ao + pt

    # error images (seed 1) at the lowest spp, and the radial spectra of the errors
    panels = [("ao", WEYL["ao"][0], "shift"), ("ao", WEYL["ao"][0], "screen"), ("ao", "sobol-owen", "default"),
              ("pt", WEYL["pt"][1], "shift"), ("pt", WEYL["pt"][1], "screen"), ("pt", "sobol-owen", "default")]
    fig, axes = plt.subplots(2, 3, figsize=(11, 7.6))
    for ax, (app, s, mode) in zip(axes.ravel(), panels):
        spp = min(r["spp"] for r in rows if r["app"] == app)
        e = np.load(folder / f"{app}-{s}-{mode}-{spp}-err.npy")
        lim = np.percentile(np.abs(e), 98) or 1.0
        ax.imshow(e, cmap="RdBu", vmin=-lim, vmax=lim, interpolation="nearest")
        ax.set_title(f"{app.upper()} {s} ({mode}), {spp} spp", fontsize=9)
        ax.axis("off")
    fig.suptitle("Error images (render - reference, seed 1): screen-space shifts move the error to high frequencies")
    fig.tight_layout()
    fig.savefig(out / "screen_errors.png", dpi=90)
    plt.close(fig)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for ax, app in zip(axes, ("ao", "pt")):
        spp = min(r["spp"] for r in rows if r["app"] == app)
        for s, mode in [(x, m) for x in WEYL[app] for m in ("shift", "screen")] + [(a, "default") for a in ANCHORS]:
            r = radial(np.load(folder / f"{app}-{s}-{mode}-{spp}-err.npy"))
            ax.semilogy(np.arange(len(r)) / len(r) * 0.5, r, ls="-" if mode == "screen" else "--", label=f"{s} ({mode})")
        ax.set(xlabel="screen frequency (cycles per pixel)", ylabel="error power / mean (seed 1)",
               title=f"{app.upper()}, {spp} spp: radial spectrum of the error")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out / "screen_spectra.png", dpi=90)
    plt.close(fig)

    (out / "screen.json").write_text(json.dumps({"rows": rows, "seconds": time.time() - t0}, indent=1))
    table = [[r["app"], r["sampler"], r["randomize"], r["spp"], f"{r['rmse']:.4g}", f"{r['low_share']:.2f} +- {r['low_share_sd']:.2f}",
              f"{r['seconds'] * 1e3:.1f}"] for r in rows]
    md = f"""# Screen-space decorrelation for Kronecker sequences

Built-in Cornell box, ambient occlusion (udm1-ao) and path tracing (udm1-pt); every Weyl sampler with its
per-pixel random shift and with `--randomize screen`, beside Owen-scrambled Sobol and PMJ02. RMSE over
seeds against a high-spp reference, render time (median), and the error image's low-frequency share
(energy below 1/8 cycle per pixel relative to the mean: 1 = white noise, lower = blue noise). Made in
{time.time() - t0:.0f} s by `python tools/report/screen_report.py`. Raw numbers: [screen.json](screen.json).

{md_table(["app", "sampler", "randomization", "spp", "RMSE", "low-frequency share", "time (ms)"], table)}

![errors](screen_errors.png)

![spectra](screen_spectra.png)
"""
    (out / "screen.md").write_text(md)
    (out / "screen.html").write_text(md_to_html(md, "udm1 screen-space decorrelation"))
    log(f"wrote {out / 'screen.html'} in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
