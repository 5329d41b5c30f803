"""Screen-space constructions for a Kronecker sequence, compared (docs/screen-space.md).

With R2's generator alpha (udm1's "rd" in 2D) on a W x W image, each pixel estimates a 2D integrand with
an edge whose position drifts over the image, at counts 1 .. 256. Constructions:
  shift          per-pixel random shifts (white noise)
  interleave-P   pixels in Morton order, tiles of P pixels each with a random shift; pixel m of a tile
                 takes the points k P + m of the tile's sequence: every layer of a tile is a run of P
                 points, but each pixel integrates with the generator P alpha
  root-P         the same tiles, pixel m shifted by m gamma with P gamma = alpha (mod 1), gamma =
                 (alpha + t) / P, t = floor(P beta) for a second generator beta: each pixel keeps alpha
  fixed-N        udm1's fixed scheme (screen_spp = N, rendered at each N)
  progressive    udm1's progressive scheme (screen_spp = 0)
Printed: per count, each construction's low-frequency share (error power below 1/8 cycle per pixel over
the mean: 1 = white) and RMSE over that of per-pixel shifts, averaged over seeds.

    PYTHONPATH=python python bench/screen_constructions.py [--size 128] [--seeds 3]
"""

from __future__ import annotations

import argparse

import numpy as np

import udm1

COUNTS = [1, 2, 3, 4, 6, 8, 16, 32, 64, 128, 256]


def spread(v):
    v = v.astype(np.uint64)
    for s, m in ((16, 0x0000FFFF0000FFFF), (8, 0x00FF00FF00FF00FF), (4, 0x0F0F0F0F0F0F0F0F),
                 (2, 0x3333333333333333), (1, 0x5555555555555555)):
        v = (v | (v << np.uint64(s))) & np.uint64(m)
    return v


def low_share(err):
    p = np.abs(np.fft.fftshift(np.fft.fft2(err - err.mean()))) ** 2
    h, w = p.shape
    yy, xx = np.indices(p.shape)
    r = np.hypot((yy - h // 2) / h, (xx - w // 2) / w)
    return float(p[(r > 0) & (r < 1 / 8)].mean() / p[r > 0].mean())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--seeds", type=int, default=3)
    args = ap.parse_args(argv)
    W = args.size
    yy, xx = np.indices((W, W))
    drift = 0.15 * np.sin(xx / 9.0) * np.cos(yy / 11.0) + 0.1 * np.sin((xx + yy) / 23.0)
    morton = (spread(xx) | (spread(yy) << np.uint64(1))).astype(np.float64)
    alpha = np.array([udm1.Sequence("rd", 2, randomize=False).alpha(j) / 2.0**128 for j in range(2)])
    beta = np.array([np.sqrt(2) % 1, np.sqrt(3) % 1])

    def f(u, v):
        return (u < 0.5 + 0.3 * np.sin(2 * np.pi * v) + drift).astype(np.float64)

    g = (np.arange(256) + 0.5) / 256
    levels = np.linspace(drift.min(), drift.max(), 65)
    vals = [np.mean(g[:, None] < 0.5 + 0.3 * np.sin(2 * np.pi * g[None, :]) + b) for b in levels]
    truth = np.interp(drift, levels, vals)
    streams = ((yy.astype(np.uint64) << np.uint64(32)) | xx.astype(np.uint64)).ravel()

    def estimate(name, n, rng, seed):
        k = np.arange(n)[:, None, None]
        if name in ("fixed-N", "progressive"):
            seq = udm1.Sequence("rd", 2, seed=seed, randomize="screen", screen_spp=n if name == "fixed-N" else 0)
            p = seq.points_at(np.repeat(streams, n), np.tile(np.arange(n, dtype=np.uint64), len(streams)))
            p = p.reshape(W, W, n, 2)
            return f(np.moveaxis(p[..., 0], 2, 0), np.moveaxis(p[..., 1], 2, 0)).mean(axis=0)
        if name == "shift":
            s = rng.random((2, W, W))
            x = [(s[j] + k * alpha[j]) % 1 for j in range(2)]
        else:
            P = int(name.split("-")[1])
            tile, m = np.floor(morton / P), morton % P
            _, inv = np.unique(tile, return_inverse=True)
            s = rng.random((2, inv.max() + 1))[:, inv.reshape(W, W)]
            if name.startswith("interleave"):
                x = [(s[j] + (k * P + m) * alpha[j]) % 1 for j in range(2)]
            else:
                gamma = (alpha + np.floor(P * beta)) / P
                x = [(s[j] + m * gamma[j] + k * alpha[j]) % 1 for j in range(2)]
        return f(x[0], x[1]).mean(axis=0)

    names = ["shift", "interleave-256", "interleave-4096", "root-256", "root-4096", "fixed-N", "progressive"]
    print("count  " + "  ".join(f"{n:>17s}" for n in names[1:]) + "   (low-frequency share / RMSE over shift's)")
    for n in COUNTS:
        lows, mses = {}, {}
        for name in names:
            rng = np.random.default_rng(n)
            errs = [estimate(name, n, rng, seed) - truth for seed in range(1, args.seeds + 1)]
            lows[name] = np.mean([low_share(e) for e in errs])
            mses[name] = np.mean([np.mean(e ** 2) for e in errs])
        print(f"{n:5d}  " + "  ".join(f"{lows[x]:8.2f} / {np.sqrt(mses[x] / mses['shift']):5.2f}" for x in names[1:]),
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
