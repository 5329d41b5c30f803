"""Writes sky-map.png beside this file: a 64 x 64 equal-area octahedral environment map (pbrt-v4's
layout: the square's centre is the light's +z pole, its corners -z) with a blue gradient sky, a darker
ground, and a small bright sun, as an 8-bit sRGB PNG (both renderers decode it to linear).

Usage: python tests/scenes/make_sky_map.py
"""
import pathlib

import numpy as np


def main():
    n = 64
    u, v = np.meshgrid((np.arange(n) + 0.5) / n, (np.arange(n) + 0.5) / n)
    a, b = 2 * u - 1, 2 * v - 1
    z = np.sign(1 - (abs(a) + abs(b))) * (1 - (1 - abs(1 - (abs(a) + abs(b)))) ** 2)  # the direction's z
    sky = np.stack([0.25 + 0.2 * z, 0.45 + 0.2 * z, 0.85 + 0.1 * z], axis=-1)
    ground = np.stack([0.30 + 0 * z, 0.25 + 0 * z, 0.20 + 0 * z], axis=-1)
    img = np.where((z > 0)[..., None], sky, ground)
    img[20:22, 40:42] = 1.0  # the sun: saturated, the brightest an 8-bit file holds
    import matplotlib.image as mpimg

    mpimg.imsave(pathlib.Path(__file__).with_name("sky-map.png"), np.clip(img, 0, 1))


if __name__ == "__main__":
    main()
