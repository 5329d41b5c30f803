"""udm1.mitsuba: the udm1 sampler inside Mitsuba 3 (PyPI mitsuba), in scalar_rgb and llvm_ad_rgb, through
mi.render (test_mitsuba_differential.py compares the sampler with the library combination by combination).

- Values in a render: an integrator that returns its sample's draws as the pixel's colour renders, in
  llvm_ad_rgb, the library's values bit for bit (as float32; with two samples their float32 mean), in one
  pass and in two (the integrator's samples_per_pass), at the render's spp (not the sampler's), for Weyl
  presets (and a tent) with every randomization of their Dr.Jit path, a table preset and a point set.
- Renders: the Cornell box rendered with the plugin has the mean radiance of Mitsuba's independent
  sampler within 5 standard deviations of the mean, the deviation measured over 16 independent renders
  (so the test fails by chance with probability below 1e-4 for an unbiased sampler).

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
from mitsuba_reference import check_mean_against_independent  # noqa: E402


def variant(name):
    mi.set_variant(name)
    udm1.mitsuba.register(native=False)  # the Python sampler (test_mitsuba_native.py tests the plugin)


def f32(values):
    """The library's float32 value from its double: the top 24 bits, exactly."""
    return (np.floor(np.asarray(values) * 2.0**24) * 2.0**-24).astype(np.float32)


def register_draws_integrator():
    """Integrator "udm1_test_draws" of the current variant: a pixel's colour is its sample's draws after
    the film position (dimensions 2, 3, 4)."""

    class DrawsIntegrator(mi.SamplingIntegrator):
        def sample(self, scene, sampler, ray, medium=None, active=True):
            a, b = sampler.next_1d(), sampler.next_2d()
            return mi.Spectrum(mi.Color3f(a, b.x, b.y)), mi.Bool(True), []

    mi.register_integrator("udm1_test_draws", lambda props: DrawsIntegrator(props))


@pytest.mark.parametrize("preset,randomize", [("wr", "owen"), ("wopt+tent", "permute"), ("rd", "shift"),
                                              ("wr", "none"), ("wr", "screen"), ("sobol-owen", "default"),
                                              ("pmj02", "owen")])
def test_llvm_render_draws_the_library_s_values(preset, randomize):
    variant("llvm_ad_rgb")
    register_draws_integrator()
    W, H, seed, render_seed = 5, 3, 12345, 7
    pixel = np.arange(W * H)
    for spp, per_pass in ((1, None), (2, 1)):  # (two values: their float32 sum does not depend on the order)
        integrator = {"type": "udm1_test_draws"} | ({"samples_per_pass": per_pass} if per_pass else {})
        scene = mi.load_dict({"type": "scene", "integrator": integrator, "sensor": {
            "type": "perspective",
            "film": {"type": "hdrfilm", "width": W, "height": H, "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": "udm1", "preset": preset, "randomize": randomize, "sample_count": 1,
                        "dimensions": 4, "seed": seed, "film_width": W, "film_height": H}}})
        # (render's spp: the sampler's count set again, a point set's K and screen's N with it)
        image = np.array(mi.render(scene, seed=render_seed, spp=spp)).reshape(-1, 3)
        point_set = {p.name: p for p in udm1.presets()}[preset.removesuffix("+tent")].point_set
        seq = udm1.Sequence(preset, 4, point_count=spp if point_set else 0,
                            seed=seed + (render_seed if randomize == "screen" else 0),
                            randomize=True if randomize == "default" else randomize,
                            screen_spp=spp if randomize == "screen" else 0)
        if randomize == "screen":
            streams = ((pixel // W).astype(np.uint64) << np.uint64(32)) | (pixel % W).astype(np.uint64)
        else:
            streams = (np.uint64(render_seed) << np.uint64(32)) + pixel.astype(np.uint64)
        total = np.zeros((W * H, 3), np.float32)
        for n in range(spp):  # the film's sum, then its division by the weight
            total += f32(seq.points_at(streams, np.full(W * H, n, np.uint64), dims=range(2, 5)))
        want = total / np.float32(spp)
        bad = np.argwhere(image != want)
        assert bad.size == 0, f"{preset}/{randomize} at {spp} spp: (pixel, channel) {bad[:4].tolist()} differ"


def render_means(sampler: dict, res: int, spp: int, seeds) -> np.ndarray:
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    d["sensor"]["sampler"] = sampler | ({"film_width": res, "film_height": res} if sampler["type"] == "udm1" else {})
    scene = mi.load_dict(d)
    return np.array([np.mean(np.array(mi.render(scene, spp=spp, seed=s))) for s in seeds])


@pytest.mark.parametrize("name,res,spp,samplers", [
    ("llvm_ad_rgb", 32, 64, [{"preset": "wr"}, {"preset": "sobol-owen", "dimensions": 24},
                             {"preset": "wr", "randomize": "screen"}]),
    ("scalar_rgb", 16, 16, [{"preset": "wr"}]),
])
def test_cornell_box_mean_equals_independent(name, res, spp, samplers):
    variant(name)
    check_mean_against_independent(render_means, name, res, spp, samplers)
