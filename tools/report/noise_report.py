"""Noise spectra: the power spectrum of Perlin noise whose tables come from different sources.

A lattice noise's spectrum is a band around its lattice frequency; a poor permutation (for example the
ranks of {n*alpha} taken directly) adds peaks. For each table source (Perlin's own permutation, drand48 as
the paper's baseline, and udm1 sequences) this renders improved noise on a 512 x 512 grid (8 pixels per
lattice cell), and plots the 2D power spectrum and its radial average. Writes OUT/noise_spectra.png and
OUT/noise_spectra.json (radial averages and the largest ratio of a spectrum to the mean of the others).

    PYTHONPATH=python python tools/report/noise_report.py --out report [--quick]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import udm1  # noqa: E402
from report_common import log, writable_folder  # noqa: E402

SOURCES = [(None, "Perlin's permutation"), ("drand48", "drand48 (the paper)"), ("wr", "WR"), ("wmmr", "WMMR"),
           ("rd", "R_d"), ("sobol", "Sobol")]


def spectrum(table: str | None, size: int, cell: int, seeds: int) -> np.ndarray:
    """Mean power spectrum (fftshifted) of noise images, over seeds (tables from seed 1..seeds)."""
    ys, xs = np.mgrid[0:size, 0:size] / cell
    pts = np.stack([xs.ravel(), ys.ravel(), np.full(xs.size, 0.5)], axis=1)
    acc = np.zeros((size, size))
    for s in range(seeds):
        img = udm1.Noise(table, seed=s + 1).noise(pts).reshape(size, size)
        acc += np.abs(np.fft.fft2(img - img.mean())) ** 2
    return np.fft.fftshift(acc / seeds)


def radial(power: np.ndarray) -> np.ndarray:
    n = power.shape[0]
    y, x = np.indices(power.shape) - n // 2
    r = np.hypot(x, y).astype(int)
    return np.bincount(r.ravel(), power.ravel())[: n // 2] / np.maximum(np.bincount(r.ravel())[: n // 2], 1)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="report")
    ap.add_argument("--quick", action="store_true", help="a 128 x 128 grid and one seed, for tests")
    args = ap.parse_args(argv)
    out = writable_folder(args.out, "noise_report")
    if out is None:
        return 1
    size, cell, seeds = (128, 8, 1) if args.quick else (512, 8, 4)
    spectra = {}
    for table, title in SOURCES:
        log(f"spectrum of improved noise with tables from {title}")
        spectra[title] = spectrum(table, size, cell, 1 if table is None else seeds)
    radials = {t: radial(p) for t, p in spectra.items()}
    freqs = np.arange(size // 2) / size * cell  # cycles per lattice cell
    fig = plt.figure(figsize=(15, 6.2))
    grid = fig.add_gridspec(2, len(SOURCES) // 2 + 2)
    for k, (title, p) in enumerate(spectra.items()):
        ax = fig.add_subplot(grid[k // (len(SOURCES) // 2), k % (len(SOURCES) // 2)])
        ax.imshow(np.log10(p + 1e-12 * p.max()), cmap="magma", vmin=np.log10(p.max()) - 5, vmax=np.log10(p.max()))
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    ax = fig.add_subplot(grid[:, len(SOURCES) // 2:])
    for title, r in radials.items():
        ax.semilogy(freqs[1:], r[1:], lw=1.8 if "drand48" in title or "Perlin" in title else 1.2,
                    ls="--" if "drand48" in title or "Perlin" in title else "-", label=title)
    ax.set(xlabel="frequency (cycles per lattice cell)", ylabel="radially averaged power",
           title="radial average: the tables' sources side by side")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(f"Power spectra of improved noise, {size} x {size}, {cell} pixels per cell "
                 f"(log scale, 5 decades; mean of {seeds} tables per source)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "noise_spectra.png", dpi=90)
    plt.close(fig)
    # how far each source's radial spectrum strays from the others' mean (1 = the same)
    dev = {}
    for title, r in radials.items():
        others = np.mean([v for t, v in radials.items() if t != title], axis=0)
        band = (freqs > 0.05) & (freqs < 2)
        dev[title] = float(np.max(np.abs(np.log(r[band] / others[band]))))
    (out / "noise_spectra.json").write_text(json.dumps({
        "size": size, "cell": cell, "seeds": seeds, "frequencies": freqs.tolist(),
        "radial": {t: r.tolist() for t, r in radials.items()},
        "max_log_ratio_to_others": dev}, indent=1))
    log(f"wrote {out / 'noise_spectra.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
