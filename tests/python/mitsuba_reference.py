"""What udm1's Mitsuba samplers (the Python one, udm1/mitsuba.py, and the native plugin, integrations/mitsuba3) must
draw: the library's values of the same properties, as float32, for test_mitsuba_differential.py and
test_mitsuba_native.py; and the one line a refusal must end with. Also what the Mitsuba tests share: the draw
pattern of a sample, and the render mean checked against the independent sampler's (test_mitsuba.py too)."""

from __future__ import annotations

import zlib

import numpy as np

import udm1

INFO = {p.name: p for p in udm1.presets()}
PRESETS = [p.name for p in udm1.presets()] + [p.name + "+tent" for p in udm1.presets()]
RANDOMIZE = ("default", "none", "shift", "owen", "permute", "screen")


def rng_of(*key) -> np.random.Generator:
    """A generator of its own per case (reproducible, different in every case)."""
    return np.random.default_rng(zlib.crc32(repr(key).encode()))


def info_of(preset):
    return INFO[preset.removesuffix("+tent")]


def reference(preset, randomize, d, seed, spp):
    """The library's sequence of these properties, as the sampler's docstring maps them; or the
    library's refusal (the exception)."""
    try:
        return udm1.Sequence(preset, d, point_count=spp if info_of(preset).point_set else 0, seed=seed,
                             randomize=True if randomize == "default" else randomize,
                             screen_spp=spp if randomize == "screen" else 0)
    except ValueError as exc:
        return exc


def f32(values):
    """The library's float32 value from its double: the top 24 bits, exactly."""
    return (np.floor(np.asarray(values) * 2.0**24) * 2.0**-24).astype(np.float32)


def library(seq, streams, indices, n):
    return f32(seq.points_at(np.asarray(streams, np.uint64), np.asarray(indices, np.uint64), dims=range(0, n)))


def last_line(exc) -> str:
    return str(exc).strip().splitlines()[-1]


def lane_streams(randomize, render_seed, pixel, width):
    """Each llvm lane's library stream: (y << 32) | x for the screen randomization, else (seed << 32) + pixel."""
    if randomize == "screen":
        return ((pixel // width).astype(np.uint64) << np.uint64(32)) | (pixel % width).astype(np.uint64)
    return (np.uint64(render_seed) << np.uint64(32)) + pixel.astype(np.uint64)


def pass_mismatches(got, seq, streams, first_index, draws):
    """A pass's draws (one array per dimension, evaluated) against the library's at these streams and indices:
    (got, want, the (lane, dimension) pairs that differ)."""
    got = np.stack([np.array(v) for v in got], 1)
    want = library(seq, streams, first_index, draws)
    return got, want, np.argwhere(got != want)


def draw(s, n):
    """n draws of a sample: 1D, 2D, 1D, 2D, ... (a 2D draw takes two dimensions)."""
    out = []
    while len(out) < n:
        if len(out) % 3 == 1 and len(out) + 2 <= n:
            p = s.next_2d()
            out += [p.x, p.y]
        else:
            out.append(s.next_1d())
    return out


def check_mean_against_independent(render_means, name, res, spp, samplers):
    """Each udm1 sampler's Cornell-box mean (render_means(sampler, res, spp, seeds): one render's mean per seed)
    within 5 standard deviations of the independent sampler's mean (the deviation over 16 renders)."""
    indep = render_means({"type": "independent", "sample_count": spp}, res, spp, range(16))
    mean, sd = indep.mean(), indep.std(ddof=1)
    assert sd > 0
    for extra in samplers:
        ours = render_means({"type": "udm1", "sample_count": spp, **extra}, res, spp, [1])[0]
        assert abs(ours - mean) < 5 * sd * (1 + 1 / 16) ** 0.5, f"{name} {extra}: mean {ours} against {mean} +- {sd}"
