"""Writes the test scenes' small textures beside this file, as 8-bit PNGs:
  leaf-alpha.png   64 x 64 RGBA: a green leaf whose alpha is 1 inside an ellipse, 0 outside, and 0.5 (128) in a
                   band across it (pbrt-v4 reads a float texture of an RGBA image as its alpha, sRGB-decoded)
  normal-map.png   64 x 64 RGB: a tangent-space normal map of a grid of round bumps, (n + 1) / 2 (read linear)
  ramp.png         32 x 8 RGB: a left-to-right colour ramp with a marker column (for texture mappings)

Usage: python tests/scenes/make_textures.py
"""
import pathlib

import numpy as np


def main():
    import matplotlib.image as mpimg

    here = pathlib.Path(__file__).parent
    n = 64
    y, x = np.meshgrid((np.arange(n) + 0.5) / n, (np.arange(n) + 0.5) / n, indexing="ij")
    inside = ((x - 0.5) / 0.42) ** 2 + ((y - 0.5) / 0.3) ** 2 <= 1
    alpha = np.where(inside, 1.0, 0.0)
    alpha[(inside) & (np.abs(y - 0.5) < 0.06)] = 128 / 255
    leaf = np.stack([0.2 + 0.3 * x, 0.55 + 0.2 * y, 0.15 + 0 * x, alpha], axis=-1)
    mpimg.imsave(here / "leaf-alpha.png", leaf)

    cx, cy = (x * 4) % 1 - 0.5, (y * 4) % 1 - 0.5  # 4 x 4 bumps
    r2 = (cx ** 2 + cy ** 2) / 0.16
    h = np.where(r2 < 1, np.sqrt(np.clip(1 - r2, 0, 1)), 0)
    gx, gy = np.where(r2 < 1, -cx / np.maximum(h, 0.2), 0), np.where(r2 < 1, cy / np.maximum(h, 0.2), 0)
    nrm = np.stack([gx * 0.5, gy * 0.5, np.ones_like(gx)], axis=-1)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    mpimg.imsave(here / "normal-map.png", np.clip((nrm + 1) / 2, 0, 1))

    u = (np.arange(32) + 0.5) / 32
    ramp = np.stack([u, 0.2 + 0.6 * (1 - u), 0.5 + 0 * u], axis=-1)[None].repeat(8, axis=0)
    ramp[:, 3] = [1.0, 1.0, 0.0]
    mpimg.imsave(here / "ramp.png", ramp)


if __name__ == "__main__":
    main()
