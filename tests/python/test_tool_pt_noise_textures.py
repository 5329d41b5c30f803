"""udm1-pt's solid noise textures ("fbm", "wrinkled", "windy") hold pbrt-v4's values: a floor whose every pixel
is its reflectance, a mix of two greys by the noise, against pbrt-v4's noise written out here from its
definition (Perlin's improved noise over Ken Perlin's permutation with pbrt-v4's gradient choice, octaves at
lacunarity 1.99, Turbulence's 0.2 for the octaves past the last, Windy's two sums), averaged over each pixel.
Perlin's reference gradients (which differ in 2 of the 16 hash cases) are far from the image. The noise textures
are float textures under the transform at their Texture directive; what pbrt-v4 refuses is refused with
file:line; every render that uses one says in a note that all octaves are summed (no ray differentials)."""

import os

import numpy as np
import pytest
from test_tool_pt_models import floor_corners, floor_scene, refused_at
from test_tool_pt_scenes import render

import udm1

TOOL = os.environ.get("UDM1_PT_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")

PERM = np.tile(udm1.Noise().tables()[0].astype(np.int64), 2)  # Ken Perlin's permutation, twice over


def noise(p, pbrt_gradients=True):
    """pbrt-v4's Noise at points p (..., 3), or with Perlin's reference gradients."""
    p = np.fmod(p, float(1 << 30))
    f = np.floor(p)
    d = p - f
    i = f.astype(np.int64) & 255
    fade = d * d * d * (d * (d * 6 - 15) + 10)
    out = 0.0
    for c in range(8):
        o = np.array([c & 1, (c >> 1) & 1, (c >> 2) & 1])
        x, y, z = (i + o).T if i.ndim == 1 else np.moveaxis(i + o, -1, 0)
        dx, dy, dz = np.moveaxis(d - o, -1, 0)
        h = PERM[PERM[PERM[x] + y] + z] & 15
        if pbrt_gradients:
            u = np.where((h < 8) | (h == 12) | (h == 13), dx, dy)
            v = np.where((h < 4) | (h == 12) | (h == 13), dy, dz)
        else:  # Perlin's reference (Improved Noise, 2002)
            u = np.where(h < 8, dx, dy)
            v = np.where(h < 4, dy, np.where((h == 12) | (h == 14), dx, dz))
        g = np.where(h & 1, -u, u) + np.where(h & 2, -v, v)
        w = np.prod(np.where(o == 1, fade, 1 - fade), axis=-1)
        out = out + w * g
    return out


def fbm(p, omega, octaves, **kw):
    return sum(omega ** k * noise(p * 1.99 ** k, **kw) for k in range(octaves))


def turbulence(p, omega, octaves, **kw):
    return sum(omega ** k * np.abs(noise(p * 1.99 ** k, **kw)) for k in range(octaves)) + omega ** octaves * 0.2


def windy(p, **kw):
    return np.abs(fbm(p * 0.1, 0.5, 3, **kw)) * fbm(p, 0.5, 6, **kw)


# Texture "n" under Scale 0.7 1.3 0.9 and a translation (texture space = their inverse of the world point)
CASES = {
    "fbm": ('"integer octaves" [ 5 ] "float roughness" [ 0.7 ]', lambda p, **kw: fbm(p, 0.7, 5, **kw)),
    "wrinkled": ('', lambda p, **kw: turbulence(p, 0.5, 8, **kw)),
    "windy": ('', lambda p, **kw: windy(p, **kw)),
}


def pixel_means(f, n=6, **kw):
    """The mix's reflectance 0.5 + 0.5 a (a the noise, clamped to [0, 1]) averaged over n x n points of each
    pixel of floor_scene's floor, in the texture's space."""
    x, y = floor_corners()
    s = (np.arange(n) + 0.5) / n
    a, b = np.meshgrid(s, s)
    w = np.stack([(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b], -1).reshape(-1, 4)  # corners (00, 10, 01, 11)
    cx, cy = np.einsum("hwk,sk->hws", x, w), np.einsum("hwk,sk->hws", y, w)
    world = np.stack([cx, cy, np.zeros_like(cx)], -1)
    tex = (world - np.array([0.3, -0.2, 0.5])) / np.array([0.7, 1.3, 0.9])
    return np.clip(0.5 + 0.5 * f(tex, **kw), 0, 1).mean(-1)


@pytest.mark.parametrize("kind", sorted(CASES))
def test_noise_textures_hold_pbrt_values(kind, tmp_path):
    params, f = CASES[kind]
    tex = ('AttributeBegin\nTranslate 0.3 -0.2 0.5\nScale 0.7 1.3 0.9\n'
           f'Texture "n" "float" "{kind}" {params}\nAttributeEnd\n'
           'Texture "t" "spectrum" "mix" "rgb tex1" [ 0.5 0.5 0.5 ] "rgb tex2" [ 1 1 1 ] "texture amount" "n"')
    img, err = render(tmp_path, kind, floor_scene(tex), "--spp", "64", "--maxdepth", "1", "--strategy", "bsdf")
    assert f'Texture "{kind}": udm1-pt traces no ray differentials' in err, err
    got = img.mean(-1)
    want = pixel_means(f)
    perlin = pixel_means(f, pbrt_gradients=False)
    err_pbrt, err_perlin = np.abs(got - want), np.abs(got - perlin)
    assert want.std() > 0.01, want.std()  # (the noise varies over the floor)
    assert err_pbrt.mean() < 2e-3 and err_pbrt.max() < 2e-2, (err_pbrt.mean(), err_pbrt.max())
    assert err_perlin.mean() > 5 * err_pbrt.mean(), (err_perlin.mean(), err_pbrt.mean())


@pytest.mark.parametrize("body, line, words", [
    ('Texture "n" "spectrum" "fbm"', 2, '"fbm" is a float texture in pbrt-v4'),
    ('Texture "n" "float" "wrinkled" "integer octaves" [ -1 ]', 2, "octaves must be in [0, 64]"),
    ('Texture "n" "float" "fbm" "integer octaves" [ 65 ]', 2, "octaves must be in [0, 64]"),
    ('Texture "n" "float" "windy" "integer octaves" [ 4 ]', 2, "Texture windy: unsupported parameter 'octaves'"),
    ('Scale 1 0 1\nTexture "n" "float" "wrinkled"', 3, "singular or projective"),
])
def test_noise_texture_refusals(body, line, words, tmp_path):
    refused_at(tmp_path, "WorldBegin\n" + body + '\nShape "sphere"\n', line, words)
