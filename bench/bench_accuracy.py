"""udm1-pt against pbrt-v4 on the same scene files: does udm1-pt render what pbrt-v4 renders?

Every shared scene (../shared/scenes: cornell-box, veach-mis, crown; skipped with a message where absent)
and every test scene of the project (tests/scenes) is rendered by udm1-pt and by pbrt-v4 (built from the
snapshot in ../shared/anchors by scripts/anchors.sh; skipped with a message where absent) with a box pixel
filter, at the same size and spp, --seeds times each with different seeds. For each channel the table
gives both renderers' image means, the relative difference udm1-pt / pbrt-v4 - 1 and its standard error
(from the spread of the means over the seeds). A difference above 1 % has a stated cause, and the
variants below its scene demonstrate it: the same file changed one step at a time (pbrt-v4 with textures
point-sampled as udm1-pt samples them, the CIE 1931 sensor in place of a camera's, white lights in place
of coloured or spectral ones, all materials grey), each rendered by both, the difference shrinking as the
cause is removed.

Writes DIR/accuracy.json, DIR/accuracy.md (the table), DIR/accuracy.png (the differences with their
errors) and DIR/<scene>/compare.png (pbrt-v4, udm1-pt and their difference, side by side). pbrt-v4's images
are kept in DIR/pbrt-cache, named by a hash of the scene file's text, the arguments and the pbrt-v4 binary,
and reused (--no-cache renders them again); scenes with media render with one pbrt-v4 thread (the snapshot
crashes at start-up on them with more).

    python bench/bench_accuracy.py [--tool build/bin/udm1-pt] [--pbrt PATH] [--seeds 4] [--scale 1]
                                   [--only crown,lights] [--out build/accuracy] [--shared ../shared/scenes]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "scenes"
TEST_SCENES = ROOT / "tests" / "scenes"


def log(msg: str) -> None:
    print(f"[bench_accuracy {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


@dataclass
class Variant:
    """The scene changed: text substitutions (regex, replacement) and pbrt-v4 options, cumulative."""
    name: str
    subs: list = field(default_factory=list)
    pbrt_args: list = field(default_factory=list)
    grey: bool = False  # every material a grey diffuse one
    grey_media: bool = False  # every medium's rgb coefficients their mean (no colour: RGB and spectral agree)


@dataclass
class Case:
    name: str
    file: Path
    size: tuple  # film size rendered
    spp: int
    cause: str = ""  # the stated cause of a difference above 1 %
    variants: list = field(default_factory=list)  # cumulative steps that remove the cause
    setup: object = None  # writes files the scene needs into its folder; returns a digest of them (pbrt-v4's cache)
    setup_digest: str = ""


SENSOR = (r'"string sensor" "[^"]*"', '"string sensor" "cie1931"')
NO_FILTER = ["--disable-texture-filtering"]


def cases() -> list[Case]:
    out = []
    if SHARED.is_dir():
        crown_ladder = [Variant("pbrt-v4 textures point-sampled", pbrt_args=NO_FILTER),
                        Variant("+ CIE 1931 sensor", [SENSOR], NO_FILTER),
                        Variant("+ white lights", [SENSOR, (r'"blackbody L" \[ 5500 \]', '"rgb L" [ 1 1 1 ]')], NO_FILTER),
                        Variant("+ grey media", [SENSOR, (r'"blackbody L" \[ 5500 \]', '"rgb L" [ 1 1 1 ]')], NO_FILTER,
                                grey_media=True),
                        Variant("+ every material grey", [SENSOR, (r'"blackbody L" \[ 5500 \]', '"rgb L" [ 1 1 1 ]')],
                                NO_FILTER, grey=True, grey_media=True)]
        out += [
            Case("cornell-box", SHARED / "cornell-box" / "cornell-box.pbrt", (144, 144), 1024),
            Case("veach-mis", SHARED / "veach-mis" / "veach-mis.pbrt", (144, 108), 1024),
            Case("crown", SHARED / "crown" / "crown.pbrt", (100, 140), 256,
                 cause="pbrt-v4 filters textures at each pixel's footprint (MIP-mapped image lookups: the Crown's bump "
                       "maps are smoothed, its normals less perturbed), udm1-pt point-samples them; pbrt-v4 renders "
                       "through the film's camera sensor (canon_eos_5d_mkiv) and spectrally (the 5500 K lights on gold "
                       "and coloured coats: spectral products are not RGB products); each step below removes one",
                 variants=[Variant("pbrt-v4 textures point-sampled", pbrt_args=NO_FILTER),
                           Variant("+ CIE 1931 sensor", [SENSOR], NO_FILTER),
                           Variant("+ white lights", [SENSOR, (r'"blackbody L" \[ 5500 \]', '"rgb L" [ 1 1 1 ]')], NO_FILTER),
                           Variant("+ every material grey", [SENSOR, (r'"blackbody L" \[ 5500 \]', '"rgb L" [ 1 1 1 ]')],
                                   NO_FILTER, grey=True)]),
            Case("crown-volpath", SHARED / "crown" / "crown-volpath.pbrt", (100, 140), 256,
                 cause="the causes of the shared copy's difference (crown, above: pbrt-v4's filtered textures, its "
                       "camera sensor, spectral products with gold's reflectance, here over maxdepth 100, not the "
                       "copy's 5: gold multiplies with itself over many more bounces, spectrally in pbrt-v4 and as RGB "
                       "in udm1-pt) and spectral absorption: pbrt-v4 attenuates each "
                       "wavelength by exp(-sigma(lambda) d) of the gems' media upsampled from RGB, udm1-pt each "
                       "channel by exp(-sigma_rgb d), and as distributed the media are outside the gems "
                       "(MediumInterface \"\" \"ruby-medium\", the gems' normals facing out), so light that "
                       "leaves a gem crosses the scene in them; each step below removes one cause",
                 variants=crown_ladder),
        ]
    else:
        log(f"skipped the shared scenes: {SHARED} is absent")
    white_lights = [(r'"blackbody I" \[ 3200 \]', '"rgb I" [ 1 1 1 ]'), (r'"rgb I" \[ 12 10 8 \]', '"rgb I" [ 10 10 10 ]'),
                    (r'"rgb L" \[ 0.6 0.7 0.9 \]', '"rgb L" [ 0.7 0.7 0.7 ]')]
    out += [
        Case("lights", TEST_SCENES / "lights.pbrt", (160, 120), 1024,
             cause="spectral rendering: coloured and blackbody lights on coloured surfaces (pbrt-v4 multiplies "
                   "their spectra, udm1-pt their RGB); with white lights the two agree",
             variants=[Variant("white lights", white_lights)]),
        Case("sky", TEST_SCENES / "sky.pbrt", (160, 120), 1024),
        Case("sky-map", TEST_SCENES / "sky-map.pbrt", (160, 120), 1024),
        Case("spectral", TEST_SCENES / "spectral.pbrt", (160, 120), 1024,
             cause="spectral rendering: a narrow-band light (spds/sodium-ish.spd) and a blackbody on spectral "
                   "reflectances; with white lights the spectra's RGB agree",
             variants=[Variant("white lights", [(r'"spectrum L" "spds/sodium-ish.spd"', '"rgb L" [ 1 1 1 ]'),
                                                (r'"blackbody L" \[ 9000 \]', '"rgb L" [ 1 1 1 ]')])]),
        Case("transforms", TEST_SCENES / "transforms.pbrt", (160, 120), 1024),
        Case("media", TEST_SCENES / "media.pbrt", (128, 128), 256),
        Case("ruby", TEST_SCENES / "ruby.pbrt", (160, 120), 256,
             cause="spectral absorption: pbrt-v4 attenuates each wavelength by exp(-sigma(lambda) d) of the media "
                   "upsampled from RGB, udm1-pt each channel by exp(-sigma_rgb d) (not the same RGB where "
                   "sigma varies across a channel's wavelengths); with grey media the two agree",
             variants=[Variant("grey media", grey_media=True)]),
        Case("fog", TEST_SCENES / "fog.pbrt", (80, 60), 256),
        Case("grid", TEST_SCENES / "grid.pbrt", (96, 72), 256),
        Case("grid-fire", TEST_SCENES / "grid-fire.pbrt", (96, 72), 256),
        Case("cloud", TEST_SCENES / "cloud.pbrt", (96, 72), 256),
        Case("noise", TEST_SCENES / "noise.pbrt", (96, 72), 256),
        Case("anisotropic", TEST_SCENES / "anisotropic.pbrt", (96, 72), 256),
        Case("thin", TEST_SCENES / "thin.pbrt", (96, 72), 256),
        Case("format", TEST_SCENES / "format.pbrt", (160, 120), 1024),
        Case("displacement", TEST_SCENES / "displacement.pbrt", (96, 64), 1024),
        Case("measured", TEST_SCENES / "measured.pbrt", (160, 120), 1024, setup=tabulated_bsdfs),
        Case("clamp", TEST_SCENES / "clamp.pbrt", (160, 120), 1024,
             cause="the film's maxcomponentvalue acts on each sample's sensor values: pbrt-v4's are a spectral "
                   "sample's (four wavelengths, whose XYZ vary from sample to sample), udm1-pt's an RGB sample's, so the "
                   "clamp takes more from pbrt-v4's bright samples; without the clamp the two agree",
             variants=[Variant("without maxcomponentvalue", [(r' "float maxcomponentvalue" \[ 1 \]', "")])]),
    ]
    return out


def tabulated_bsdfs(folder: Path) -> str:
    """measured.pbrt's tabulated BSDF files (tests/python/tabulated_bsdf_files.py) in folder/bsdfs; their digest."""
    sys.path.insert(0, str(ROOT / "tests" / "python"))
    from tabulated_bsdf_files import write_test_files

    write_test_files(folder / "bsdfs")
    h = hashlib.sha256()
    for f in sorted((folder / "bsdfs").iterdir()):
        h.update(f.name.encode() + f.read_bytes())
    return h.hexdigest()


def grey_materials(text: str) -> str:
    """Every MakeNamedMaterial and Material a grey diffuse one (its parameter lines dropped)."""
    out, lines, i = [], text.split("\n"), 0
    while i < len(lines):
        m = re.match(r'\s*(MakeNamedMaterial "[^"]+"|Material "[^"]+")', lines[i])
        if not m:
            out.append(lines[i])
            i += 1
            continue
        head = m.group(1)
        i += 1
        while i < len(lines) and (re.match(r'\s+"', lines[i]) or lines[i].lstrip().startswith("#")):
            i += 1
        if head.startswith("Material"):
            out.append('Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]')
        else:
            out.append(head + ' "string type" [ "diffuse" ] "rgb reflectance" [ 0.5 0.5 0.5 ]')
    return "\n".join(out)


def grey_media(text: str) -> str:
    """Every medium's "rgb sigma_a" and "rgb sigma_s" the mean of its three values."""
    def grey(m: re.Match) -> str:
        v = [float(x) for x in m.group(2).split()]
        g = sum(v) / len(v)
        return f'{m.group(1)}[ {g:.6g} {g:.6g} {g:.6g} ]'
    out, n = re.subn(r'("rgb sigma_[as]"\s*)\[\s*([-+0-9.eE\s]+?)\s*\]', grey, text)
    if n == 0:
        raise RuntimeError("grey media: no rgb sigma_a or sigma_s in the scene")
    return out


def prepare(case: Case, variant: Variant | None, work: Path) -> Path:
    """The scene's file as both renderers read it: a box pixel filter, the case's film size, the variant's
    changes; in a folder of its own whose other entries link to the scene's folder (meshes, textures)."""
    folder = work / case.name
    folder.mkdir(parents=True, exist_ok=True)
    if case.setup:
        case.setup_digest = case.setup(folder)
    for entry in case.file.parent.iterdir():
        link = folder / entry.name
        if entry.suffix != ".pbrt" and not link.exists():
            link.symlink_to(entry)
    text = case.file.read_text()
    text = re.sub(r'("integer xresolution"\s*)\[\s*\d+\s*\]', rf"\g<1>[ {case.size[0]} ]", text)
    text = re.sub(r'("integer yresolution"\s*)\[\s*\d+\s*\]', rf"\g<1>[ {case.size[1]} ]", text)
    text = re.sub(r"^\s*PixelFilter[^\n]*\n", "", text, flags=re.M)
    text = 'PixelFilter "box"\n' + text
    if variant:
        for pattern, repl in variant.subs:
            text, n = re.subn(pattern, repl, text)
            if n == 0:
                raise RuntimeError(f"{case.name}, variant '{variant.name}': '{pattern}' matches nothing")
        if variant.grey:
            text = grey_materials(text)
        if variant.grey_media:
            text = grey_media(text)
    name = case.name if variant is None else f"{case.name}-{re.sub(r'[^a-z0-9]+', '-', variant.name.lower()).strip('-')}"
    path = folder / f"{name}.pbrt"
    path.write_text(text)
    return path


def read_exr(path: Path) -> np.ndarray:
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(str(path)), dtype=np.float64)[..., :3]


def render_both(scene: Path, case: Case, variant: Variant | None, args, seeds: int) -> dict:
    """Both renderers, alternating, seeds 1..seeds: the image means, their seconds, the last images."""
    means = {"pbrt": [], "udm1": []}
    seconds = {"pbrt": 0.0, "udm1": 0.0}
    images = {}
    extra = variant.pbrt_args if variant else []
    spp = max(1, int(round(case.spp * args.scale)))
    # (the pbrt-v4 snapshot crashes at start-up on scenes with media with more than one thread)
    pbrt_threads = 1 if "MakeNamedMedium" in scene.read_text() else args.threads
    for seed in range(1, seeds + 1):
        for who in ("pbrt", "udm1"):
            out = scene.with_name(f"{scene.stem}-{who}-{seed}.exr")
            cached = None
            if who == "pbrt":
                cmd = [args.pbrt, "--spp", str(spp), "--seed", str(seed), "--nthreads", str(pbrt_threads), "--quiet",
                       "--outfile", str(out), *extra, str(scene)]
                cached = pbrt_cache(args, scene, [str(spp), str(seed), *extra] + ([case.setup_digest] if case.setup_digest else []))
            else:
                cmd = [args.tool, "--scene", str(scene), "--spp", str(spp), "--seed", str(seed), "--threads",
                       str(args.threads), "-o", str(out)]
            t0 = time.perf_counter()
            if cached and cached.exists():
                shutil.copyfile(cached, out)
                seconds[who] += json.loads(cached.with_suffix(".json").read_text())["seconds"]
            else:
                r = subprocess.run(cmd, capture_output=True, text=True, cwd=scene.parent)
                if r.returncode != 0:
                    raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip()[-400:]}")
                seconds[who] += time.perf_counter() - t0
                if cached:
                    shutil.copyfile(out, cached)
                    cached.with_suffix(".json").write_text(json.dumps({"seconds": time.perf_counter() - t0,
                                                                        "command": cmd}))
            img = read_exr(out)
            means[who].append(img.reshape(-1, 3).mean(axis=0))
            images[who] = img
            out.unlink()
    row = {"scene": case.name, "variant": variant.name if variant else "", "spp": spp, "seeds": seeds,
           "size": list(case.size)}
    for who in ("pbrt", "udm1"):
        m = np.array(means[who])
        row[who] = {"mean": m.mean(axis=0).tolist(),
                    "stderr": (m.std(axis=0, ddof=1) / np.sqrt(len(m))).tolist() if len(m) > 1 else [0.0] * 3,
                    "seconds": seconds[who] / seeds}
    p, u = np.array(row["pbrt"]["mean"]), np.array(row["udm1"]["mean"])
    sp, su = np.array(row["pbrt"]["stderr"]), np.array(row["udm1"]["stderr"])
    row["difference"] = (u / p - 1).tolist()
    row["difference_stderr"] = ((u / p) * np.sqrt((sp / p) ** 2 + (su / u) ** 2)).tolist()
    return row, images


def pbrt_cache(args, scene: Path, key: list) -> Path | None:
    """Where pbrt-v4's render of this scene text with these arguments (spp, seed, options) by this binary is
    kept, or None with --no-cache."""
    if args.no_cache:
        return None
    st = Path(args.pbrt).stat()
    h = hashlib.sha256("\n".join([scene.read_text(), *key, str(Path(args.pbrt).resolve()), str(st.st_size),
                                   str(st.st_mtime_ns)]).encode()).hexdigest()[:24]
    folder = Path(args.out) / "pbrt-cache"
    folder.mkdir(parents=True, exist_ok=True)
    return folder / f"{h}.exr"


def compare_png(images: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    a, b = images["pbrt"], images["udm1"]
    tone = lambda x: np.clip(x / (1 + x), 0, 1) ** (1 / 2.2)
    d = (b - a).mean(axis=2)
    lim = max(float(np.percentile(np.abs(d), 99)), 1e-6)
    fig, ax = plt.subplots(1, 3, figsize=(10, 3.6 * a.shape[0] / a.shape[1] + 0.6))
    for k, (img, title) in enumerate([(tone(a), "pbrt-v4"), (tone(b), "udm1-pt")]):
        ax[k].imshow(img)
        ax[k].set_title(title)
    im = ax[2].imshow(d, cmap="RdBu_r", vmin=-lim, vmax=lim)
    ax[2].set_title("udm1-pt - pbrt-v4 (one seed)")
    fig.colorbar(im, ax=ax[2], fraction=0.046)
    for x in ax:
        x.set_axis_off()
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def table(rows: list[dict]) -> str:
    """One row per render pair: both means and the noise of each (the largest channel's standard error,
    relative), the difference per channel and its standard error, both renderers' seconds per render."""
    lines = ["| scene | variant | spp x seeds | pbrt-v4 mean (R G B) | s.e. % | udm1-pt mean (R G B) | s.e. % |"
             " difference % (R / G / B) | +- 1 s.e. % | pbrt-v4 s | udm1-pt s |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        f = lambda v: " ".join(f"{x:.5f}" for x in v)
        noise = lambda w: f"{100 * max(e / m for e, m in zip(r[w]['stderr'], r[w]['mean'])):.2f}"
        d = " / ".join(f"{100 * x:+.2f}" for x in r["difference"])
        e = " / ".join(f"{100 * x:.2f}" for x in r["difference_stderr"])
        flag = " **>1 %**" if max(abs(x) for x in r["difference"]) > 0.01 else ""
        lines.append(f"| {r['scene']} | {r['variant'] or 'as is'} | {r['spp']} x {r['seeds']} | {f(r['pbrt']['mean'])} | "
                     f"{noise('pbrt')} | {f(r['udm1']['mean'])} | {noise('udm1')} | {d}{flag} | {e} | "
                     f"{r['pbrt']['seconds']:.1f} | {r['udm1']['seconds']:.1f} |")
    return "\n".join(lines)


def figure(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = [f"{r['scene']}" + (f": {r['variant']}" if r["variant"] else "") for r in rows]
    y = np.arange(len(rows))
    fig, ax = plt.subplots(figsize=(8, 0.35 * len(rows) + 1.2))
    for c, (colour, off) in enumerate([("tab:red", -0.25), ("tab:green", 0), ("tab:blue", 0.25)]):
        ax.errorbar([100 * r["difference"][c] for r in rows], y + off,
                    xerr=[200 * r["difference_stderr"][c] for r in rows], fmt="o", color=colour, ms=4,
                    label="RGB"[c])
    ax.axvspan(-1, 1, color="0.9")
    ax.axvline(0, color="0.5", lw=0.8)
    ax.set_yticks(y)
    ax.set_yticklabels(labels, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("udm1-pt / pbrt-v4 - 1, image mean (%), +- 2 standard errors; grey: within 1 %")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def find_pbrt(given: str) -> str | None:
    if given:
        return given
    r = subprocess.run([str(ROOT / "scripts" / "anchors.sh"), "pbrt-v4"], capture_output=True, text=True)
    if r.returncode == 3:
        log(r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "pbrt-v4 snapshot absent")
        return None
    if r.returncode != 0:
        raise RuntimeError(f"building pbrt-v4 failed: {r.stderr.strip()[-400:]}")
    return r.stdout.strip()


def main() -> int:
    global SHARED
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tool", default=str(ROOT / "build" / "bin" / "udm1-pt"))
    ap.add_argument("--pbrt", default="", help="a pbrt-v4 binary (default: built by scripts/anchors.sh pbrt-v4)")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--scale", type=float, default=1.0, help="multiplies every case's spp")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--only", default="", help="comma-separated scene names")
    ap.add_argument("--out", default=str(ROOT / "build" / "accuracy"))
    ap.add_argument("--shared", default=str(SHARED), help="the shared scenes (cornell-box, veach-mis, crown)")
    ap.add_argument("--no-cache", action="store_true", help="render pbrt-v4's images again (see the cache above)")
    args = ap.parse_args()
    SHARED = Path(args.shared).resolve()
    args.tool = str(Path(args.tool).resolve())
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    args.pbrt = find_pbrt(args.pbrt)
    if not args.pbrt:
        why = "no pbrt-v4 to compare with (its snapshot, ../shared/anchors, is absent)"
        log(f"skipped: {why}")
        (out / "accuracy.json").write_text(json.dumps({"skipped": why, "rows": []}))
        return 0
    todo = [c for c in cases() if not args.only or c.name in args.only.split(",")]
    rows = []
    for case in todo:
        for variant in [None, *case.variants]:
            scene = prepare(case, variant, out)
            log(f"{case.name}{': ' + variant.name if variant else ''}: {args.seeds} seeds x {case.spp} spp, both renderers")
            row, images = render_both(scene, case, variant, args, args.seeds)
            if variant is None:
                row["cause"] = case.cause
                compare_png(images, out / case.name / "compare.png")
            rows.append(row)
            log("  difference % " + " / ".join(f"{100 * x:+.2f}" for x in row["difference"]) + "  +- " +
                " / ".join(f"{100 * x:.2f}" for x in row["difference_stderr"]))
    md = ["# udm1-pt against pbrt-v4: image means per channel", "",
          f"`python bench/bench_accuracy.py --seeds {args.seeds} --scale {args.scale}` on {platform.node()} "
          f"({os.cpu_count()} cores), {time.strftime('%Y-%m-%d')}. Box pixel filter, the same film size and spp for "
          "both; the standard error comes from the spread of the means over the seeds.", "", table(rows), ""]
    causes = [r for r in rows if not r["variant"] and max(abs(x) for x in r["difference"]) > 0.01]
    for r in causes:
        md += [f"- **{r['scene']}**: {r['cause'] or 'no cause stated'}.", ""]
    (out / "accuracy.md").write_text("\n".join(md))
    (out / "accuracy.json").write_text(json.dumps({"rows": rows, "pbrt": args.pbrt, "machine": platform.node(),
                                                   "cores": os.cpu_count(), "date": time.strftime("%Y-%m-%d")}, indent=1))
    figure(rows, out / "accuracy.png")
    print("\n".join(md))
    unexplained = [r["scene"] for r in causes if not r["cause"]]
    if unexplained:
        log(f"differences above 1 % without a stated cause: {', '.join(unexplained)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
