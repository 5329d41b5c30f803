"""udm1.mitsuba against the library, every combination: each preset of udm1.presets() and its "+tent",
each randomization ("default", "none", "shift", "owen", "permute", "screen"), in scalar_rgb and in
llvm_ad_rgb. A combination the library accepts is drawn as the library draws it, bit for bit as
float32 (udm1.Sequence.points_at at the same stream, index and dimension, made here from the
documented mapping, not from the sampler's code), dimensions past D (the padding) included, at random
seeds, render seeds and streams, over two passes (llvm: advance() with film_width and film_height) or
several samples (scalar: advance()). A combination the library refuses (or the sampler: "screen" in a
scalar variant) is refused when the scene loads, with one line naming it. And the Dr.Jit values
themselves (what the llvm sampler draws) at random 64-bit streams and indices, which a wavefront of a
test's size cannot reach.

Kept small: 3 x 2 pixels, 4 samples per pixel in two passes, 9 draws per sample (20 in scalar_rgb, past
the 16 its sampler draws in one cursor fill); one Dr.Jit kernel per
randomization mode and path (their values enter as opaque parameters), reused by every preset."""

from __future__ import annotations

import os
import zlib

LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
if "DRJIT_LIBLLVM_PATH" not in os.environ and os.path.exists(LLVM):
    os.environ["DRJIT_LIBLLVM_PATH"] = LLVM

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import udm1  # noqa: E402

mi = pytest.importorskip("mitsuba", reason="Mitsuba 3 is not installed (python/requirements.txt installs it)")
import drjit as dr  # noqa: E402

import udm1.mitsuba  # noqa: E402
from mitsuba_reference import (INFO, PRESETS, RANDOMIZE, f32, info_of, lane_streams, last_line, library,  # noqa: E402,F401
                               check_mean_against_independent, draw, pass_mismatches, reference, rng_of)

W, H, SPP, SPP_PASS = 3, 2, 4, 2  # the llvm wavefront: 3 x 2 pixels, 4 samples in two passes of 2
DRAWS = 9  # per sample: 1D and 2D draws, past every D below
SCALAR_DRAWS = 20  # the scalar sampler's too, and past the 16 it draws in one cursor fill


def variant(name):
    mi.set_variant(name)
    udm1.mitsuba.register(native=False)  # the Python sampler (test_mitsuba_native.py tests the plugin)






def dims_of(preset) -> int:
    return min(5, info_of(preset).max_dimensions)










def assert_refused(props, *words):
    """The load refuses: Mitsuba's message ends with the sampler's one line, naming every word."""
    with pytest.raises(Exception) as e:
        mi.load_dict({"type": "udm1", **props})
    line = last_line(e.value)
    assert "udm1 sampler: " in line, str(e.value)
    for w in words:
        assert w in line, f"{w!r} not in {line!r}"


def load(props, bad):
    """The sampler of a combination the library accepts; None, said in `bad`, where the load fails."""
    try:
        return mi.load_dict({"type": "udm1", **props})
    except Exception as exc:
        bad.append(f"{props['preset']}/{props['randomize']}: refused: {last_line(exc)}")
        return None


@pytest.mark.parametrize("randomize", RANDOMIZE)
def test_llvm_sampler_equals_the_library(randomize):
    """Every preset with this randomization, through mi.load_dict, seed() and advance()."""
    variant("llvm_ad_rgb")
    lane = np.arange(W * H * SPP_PASS)
    pixel = lane // SPP_PASS
    bad = []
    for preset in PRESETS:
        rng = rng_of("llvm", preset, randomize)
        d, seed = dims_of(preset), int(rng.integers(0, 2**63))
        props = {"preset": preset, "randomize": randomize, "sample_count": SPP, "dimensions": d, "seed": seed,
                 "film_width": W, "film_height": H}
        render_seed = int(rng.integers(0, 2**32))
        seq = reference(preset, randomize, d, (seed + render_seed) if randomize == "screen" else seed, SPP)
        if isinstance(seq, Exception):
            assert_refused(props, preset, randomize)
            continue
        s = load(props, bad)
        if s is None:
            continue
        s.seed(render_seed, W * H * SPP_PASS)
        streams = lane_streams(randomize, render_seed, pixel, W)
        for p in range(SPP // SPP_PASS):
            got = draw(s, DRAWS)
            dr.eval(got)
            got, want, where = pass_mismatches(got, seq, streams, p * SPP_PASS + lane % SPP_PASS, DRAWS)
            if where.size:
                bad.append(f"{preset}/{randomize} pass {p}: (lane, dim) {where[:3].tolist()}: {got[tuple(where[0])]} "
                           f"for {want[tuple(where[0])]}")
            s.advance()
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("randomize", RANDOMIZE)
def test_scalar_sampler_equals_the_library(randomize):
    """Every preset with this randomization: Mitsuba's seed is the stream, advance() the index."""
    variant("scalar_rgb")
    bad = []
    for preset in PRESETS:
        rng = rng_of("scalar", preset, randomize)
        d, seed = dims_of(preset), int(rng.integers(0, 2**63))
        props = {"preset": preset, "randomize": randomize, "sample_count": SPP, "dimensions": d, "seed": seed}
        seq = reference(preset, randomize, d, seed, SPP)
        if randomize == "screen":  # refused in the scalar variants (and by the library for most kinds)
            assert_refused(props, randomize)
            continue
        if isinstance(seq, Exception):
            assert_refused(props, preset, randomize)
            continue
        s = load(props, bad)
        if s is None:
            continue
        for stream in rng.integers(0, 2**32, 2):
            s.seed(int(stream))
            for n in range(SPP):
                got = np.float32(draw(s, SCALAR_DRAWS))
                want = library(seq, [stream], [n], SCALAR_DRAWS)[0]
                if not np.array_equal(got, want):
                    bad.append(f"{preset}/{randomize} stream {stream} sample {n}: {got.tolist()} for {want.tolist()}")
                s.advance()
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("randomize", RANDOMIZE)
def test_llvm_draws_at_random_64_bit_streams_and_indices(randomize):
    """What the llvm sampler computes (udm1.mitsuba.draws_class(), the Weyl arithmetic in Dr.Jit and the
    library's table) at any stream and index: 16 random 64-bit pairs per preset (indices below K for a
    point set)."""
    variant("llvm_ad_rgb")
    Draws = udm1.mitsuba.draws_class()
    bad = []
    for preset in PRESETS:
        rng = rng_of("draws", preset, randomize)
        d, seed = dims_of(preset), int(rng.integers(0, 2**63))
        seq = reference(preset, randomize, d, seed, SPP)
        if isinstance(seq, Exception):
            continue
        streams = rng.integers(0, 2**64, 16, dtype=np.uint64)
        indices = rng.integers(0, SPP if info_of(preset).point_set else 2**64, 16, dtype=np.uint64)
        o = udm1.mitsuba._options(mi.Properties()) | {"preset": preset, "tent": preset.endswith("+tent"),
                                                     "weyl": info_of(preset).name in udm1.mitsuba.WEYL_PRESETS}
        # (arrays in Dr.Jit's memory: one made from numpy keeps numpy's alignment, a new kernel each time)
        zero = dr.opaque(mi.UInt64, 0)
        draws = Draws(seq, o, mi.UInt64(streams) + zero, mi.UInt64(indices) + zero, SPP)
        got = [draws.value(dr.full(mi.UInt32, j, 16) + mi.UInt32(zero)) for j in range(DRAWS)]
        dr.eval(got)
        got = np.stack([np.array(v) for v in got], 1)
        want = library(seq, streams, indices, DRAWS)
        where = np.argwhere(got != want)
        if where.size:
            k, j = where[0]
            bad.append(f"{preset}/{randomize}: stream {streams[k]} index {indices[k]} dim {j}: {got[k, j]} for "
                       f"{want[k, j]} ({len(where)} values differ)")
    assert not bad, "\n".join(bad)


def test_every_property_checked_at_load():
    """Each bad property is refused when the scene loads, with one line naming it (Mitsuba's Properties
    hand a float, a bool or a string through as they are, and an integer past 2^63 - 1 as a float)."""
    cases = [({"sample_count": 0}, "sample_count 0"), ({"sample_count": -1}, "sample_count -1"),
             ({"sample_count": 2**32}, "sample_count 4294967296"), ({"sample_count": 2.5}, "sample_count 2.5"),
             ({"sample_count": "8"}, "sample_count '8'"), ({"sample_count": True}, "sample_count True"),
             ({"seed": -1}, "seed -1"), ({"seed": 2**63}, "seed 9.22"), ({"seed": 2**64 + 5}, "seed 1.8"),
             ({"seed": 3.5}, "seed 3.5"), ({"seed": "7"}, "seed '7'"),
             ({"dimensions": 0}, "dimensions 0"), ({"dimensions": 65537}, "dimensions 65537"),
             ({"dimensions": 2.0}, "dimensions 2.0"), ({"dimensions": "4"}, "dimensions '4'"),
             ({"preset": "wr-ao", "dimensions": 3}, "dimensions 3"),
             ({"preset": "pmj02", "dimensions": 65}, "dimensions 65"),
             ({"preset": "nope"}, "preset 'nope'"), ({"preset": "wr+tentx"}, "preset 'wr+tentx'"),
             ({"preset": 5}, "preset 5"), ({"randomize": "blue"}, "randomize 'blue'"),
             ({"randomize": 1}, "randomize 1"),
             ({"film_width": 0}, "film_width 0"), ({"film_width": -3}, "film_width -3"),
             ({"film_width": 2.5}, "film_width 2.5"), ({"film_height": 2**32}, "film_height 4294967296"),
             ({"preset": "pmj02", "sample_count": 2**20 + 1}, "sample_count 1048577"),
             ({"preset": "lattice", "sample_count": 2**24 + 1}, "sample_count 16777217"),
             ({"preset": "halton", "randomize": "screen"}, "'halton'")]
    variant("llvm_ad_rgb")
    for props, words in cases:
        assert_refused({"film_width": 4, "film_height": 4, **props}, words)
    for props in ({}, {"film_width": 8}, {"film_height": 8}):  # the vector variants need the film's size
        assert_refused(props, "film_width and film_height")
    variant("scalar_rgb")
    for props, words in cases[:-1] + [({"randomize": "screen"}, "vector variant")]:
        assert_refused(props, words)


def test_seeds_past_32_bits_are_the_library_s():
    """The udm1 seed is 64-bit (Mitsuba's base class would take 32 bits of it): 2^40 + 3 and 2^63 - 1."""
    variant("scalar_rgb")
    for seed in (2**40 + 3, 2**63 - 1):
        s = mi.load_dict({"type": "udm1", "seed": seed, "dimensions": 4})
        s.seed(11)
        want = library(reference("wr", "default", 4, seed, 4), [11], [0], 4)[0]
        assert np.array_equal(np.float32(draw(s, 4)), want), seed


def test_llvm_wavefront_checked_against_the_film():
    """A wavefront that is not the film's pixels times a divisor of sample_count is refused at its first
    draw (Mitsuba seeds a sampler with a wavefront of 1 after a render, to release its state: a seed
    alone is not refused); a sample count is checked wherever it is set."""
    variant("llvm_ad_rgb")
    s = mi.load_dict({"type": "udm1", "sample_count": 6, "film_width": 4, "film_height": 2})
    for lanes in (4 * 2 * 4, 4 * 2 * 6 + 1, 7, 1):  # 4 does not divide 6; not a multiple of the film
        s.seed(0, lanes)
        with pytest.raises(Exception, match="film_width x film_height"):
            s.next_1d()
    s.seed(0, 4 * 2 * 3)  # two passes of 3
    for p in range(2):
        dr.eval(s.next_1d())
        s.advance()
    for spp in (0, -2, 2**32, 3.0):
        with pytest.raises(Exception, match="sample_count"):
            s.set_sample_count(spp)
    s3 = mi.load_dict({"type": "udm1", "preset": "pmj02", "sample_count": 16, "film_width": 4, "film_height": 2})
    with pytest.raises(Exception, match="sample_count 2097152"):
        s3.set_sample_count(2**21)
    assert s3.sample_count() == 16  # (a refused count leaves the sampler as it was)
    with pytest.raises(Exception, match="render's seed"):
        s3.seed(2**32, 8)
