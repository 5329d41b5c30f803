"""udm1.mitsuba: the udm1 sampler inside Mitsuba 3 (PyPI mitsuba), in scalar_rgb and llvm_ad_rgb.

- Values: what the plugin draws for (pixel, sample, dimension) equals the library's value of
  (stream, index, dimension) bit for bit as float32 (the top 24 bits), for Weyl presets computed in
  Dr.Jit (shift, none and screen randomization, a render seed, two passes) and for the table presets
  (sobol-owen, pmj02), dimensions past D included (the padding rule); in scalar_rgb through the cursor.
- Renders: the Cornell box rendered with the plugin has the mean radiance of Mitsuba's independent
  sampler within 5 standard deviations of the mean, the deviation measured over 16 independent renders
  (so the test fails by chance with probability below 1e-4 for an unbiased sampler).
- Bad properties: one error naming the property.

llvm_ad_rgb needs a libLLVM that Dr.Jit can drive: Debian's libllvm19 (installed by ./run.sh), found
through DRJIT_LIBLLVM_PATH, which this test sets when it is unset and the library is there."""

from __future__ import annotations

import os

LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
if "DRJIT_LIBLLVM_PATH" not in os.environ and os.path.exists(LLVM):
    os.environ["DRJIT_LIBLLVM_PATH"] = LLVM

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import udm1  # noqa: E402

mi = pytest.importorskip("mitsuba", reason="Mitsuba 3 is not installed (python/requirements.txt installs it)")
import drjit as dr  # noqa: E402

import udm1.mitsuba  # noqa: E402


def variant(name):
    mi.set_variant(name)
    udm1.mitsuba.register()


def f32(values):
    """The library's float32 value from its double: the top 24 bits, exactly."""
    return (np.floor(np.asarray(values) * 2.0**24) * 2.0**-24).astype(np.float32)


def library(preset, randomize, d, seed, spp, streams, indices, dims):
    o = udm1.mitsuba._options(mi.Properties()) | {"preset": preset, "randomize": randomize, "dimensions": d,
                                                 "seed": seed}
    seq = udm1.mitsuba._sequence(o, spp)
    return f32(seq.points_at(np.asarray(streams, np.uint64), np.asarray(indices, np.uint64), dims=dims))


CASES = [("wr", "shift"), ("wr", "none"), ("wr", "screen"), ("rd", "default"), ("wopt", "default"),
         ("sobol-owen", "default"), ("pmj02", "default")]


@pytest.mark.parametrize("preset,randomize", CASES)
def test_llvm_values_equal_the_library(preset, randomize):
    variant("llvm_ad_rgb")
    W, H, spp, D, seed = 5, 3, 4, 6, 3
    s = mi.load_dict({"type": "udm1", "preset": preset, "sample_count": spp, "randomize": randomize, "dimensions": D,
                      "film_width": W, "seed": seed})
    for render_seed in (0, 9):
        s.seed(render_seed, W * H * spp)
        got = []
        for k in range(D + 4):  # 1D and 2D draws, past D
            if k % 3 == 1:
                p = s.next_2d()
                dr.eval(p)
                got += [np.array(p.x), np.array(p.y)]
            else:
                v = s.next_1d()
                dr.eval(v)
                got.append(np.array(v))
        got = np.stack(got, 1)
        lane = np.arange(W * H * spp)
        pixel = lane // spp
        if randomize == "screen":
            streams = ((pixel // W).astype(np.uint64) << np.uint64(32)) | (pixel % W).astype(np.uint64)
        else:
            streams = (np.uint64(render_seed) << np.uint64(32)) + pixel.astype(np.uint64)
        want = library(preset, randomize, D, seed + (render_seed if randomize == "screen" else 0), spp, streams,
                       lane % spp, range(0, got.shape[1]))
        bad = np.argwhere(got != want)
        assert bad.size == 0, f"{preset} {randomize} seed {render_seed}: lane, dim {bad[:5].tolist()} differ"


def test_llvm_two_passes():
    variant("llvm_ad_rgb")
    W, H, spp = 4, 2, 6  # three passes of two samples
    s = mi.load_dict({"type": "udm1", "preset": "wr", "sample_count": spp, "film_width": W, "film_height": H})
    s.seed(0, W * H * 2)
    lane = np.arange(W * H * 2)
    for p in range(3):
        v = s.next_1d()
        dr.eval(v)
        want = library("wr", "default", 64, 0, spp, lane // 2, p * 2 + lane % 2, range(0, 1))[:, 0]
        assert np.array_equal(np.array(v), want), f"pass {p}"
        s.advance()
    s2 = mi.load_dict({"type": "udm1", "preset": "wr", "sample_count": spp})  # no film size: refused
    s2.seed(0, W * H * 2)
    s2.next_1d()
    s2.advance()
    with pytest.raises(Exception, match="film_width and film_height"):
        s2.next_1d()


@pytest.mark.parametrize("preset", ["wr", "sobol-owen", "pmj02"])
def test_scalar_values_equal_the_library(preset):
    variant("scalar_rgb")
    spp, D = 4, 4
    s = mi.load_dict({"type": "udm1", "preset": preset, "sample_count": spp, "dimensions": D, "seed": 3})
    for stream in (7, 123456789):
        s.seed(stream)
        for n in range(spp):
            got = [s.next_1d(), *s.next_2d(), s.next_1d(), *s.next_2d()]  # 6 draws: past D = 4
            want = library(preset, "default", D, 3, spp, [stream], [n], range(0, 6))[0]
            assert np.array_equal(np.float32(got), want), f"{preset} stream {stream} sample {n}"
            s.advance()


def render_means(sampler: dict, res: int, spp: int, seeds) -> np.ndarray:
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    d["sensor"]["sampler"] = sampler
    scene = mi.load_dict(d)
    return np.array([np.mean(np.array(mi.render(scene, spp=spp, seed=s))) for s in seeds])


@pytest.mark.parametrize("name,res,spp,samplers", [
    ("llvm_ad_rgb", 32, 64, [{"preset": "wr"}, {"preset": "sobol-owen", "dimensions": 24},
                             {"preset": "wr", "randomize": "screen", "film_width": 32}]),
    ("scalar_rgb", 16, 16, [{"preset": "wr"}]),
])
def test_cornell_box_mean_equals_independent(name, res, spp, samplers):
    variant(name)
    indep = render_means({"type": "independent", "sample_count": spp}, res, spp, range(16))
    mean, sd = indep.mean(), indep.std(ddof=1)
    assert sd > 0
    for extra in samplers:
        ours = render_means({"type": "udm1", "sample_count": spp, **extra}, res, spp, [1])[0]
        assert abs(ours - mean) < 5 * sd * (1 + 1 / 16) ** 0.5, f"{name} {extra}: mean {ours} against {mean} +- {sd}"


def test_bad_properties():
    variant("llvm_ad_rgb")
    for props, words in [({"preset": "nope"}, "preset 'nope'"), ({"randomize": "blue"}, "randomize 'blue'"),
                         ({"randomize": "screen"}, "film_width"), ({"dimensions": 0}, "dimensions 0")]:
        with pytest.raises(Exception, match=words):
            mi.load_dict({"type": "udm1", **props})
    variant("scalar_rgb")
    with pytest.raises(Exception, match="vector variant"):
        mi.load_dict({"type": "udm1", "randomize": "screen", "film_width": 8})
