"""The native Mitsuba 3 sampler plugin "udm1" (integrations/mitsuba3), built here from this checkout
(udm1.mitsuba_build, scalar_rgb and llvm_ad_rgb only: the same code, a third of the compile time) into a
temporary folder, against the installed Mitsuba and the build's libudm1.a:

- values: bit for bit (as float32) the library's, lane by lane, at the streams and indices the Python
  sampler's docstring maps (udm1.Sequence.points_at), past D (the padding) included, over several passes
  (llvm_ad_rgb) or samples (scalar_rgb); every preset (and its "+tent") with two randomizations and the
  presets of each kind of draw (Weyl, tent, Sobol, pmj02, a table preset, a point set) with all six; what
  the library refuses is refused at load with one line naming it;
- renders: a draws integrator renders the same image with the plugin as with the Python sampler, in both
  variants, with Mitsuba's own samples per pass (no film_width/film_height given to the plugin); so does
  Mitsuba's path tracer, whose bounces run in a symbolic loop holding the sampler (llvm_ad_rgb); the
  Cornell box's mean radiance is the independent sampler's within noise;
- bad properties refused at load (one line naming the property), a draw past a point set refused, another
  Mitsuba version refused by the build, register()'s choice between plugin and Python sampler, and the
  XML-only route (the mitsuba command line with -a <folder>).

Skipped, saying why, where Mitsuba, nanobind (the headers Mitsuba's need), CMake or a C++ compiler is absent."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zlib
from pathlib import Path

LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
if "DRJIT_LIBLLVM_PATH" not in os.environ and os.path.exists(LLVM):
    os.environ["DRJIT_LIBLLVM_PATH"] = LLVM

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import udm1  # noqa: E402

mi = pytest.importorskip("mitsuba", reason="Mitsuba 3 is not installed (python/requirements.txt installs it)")
pytest.importorskip("nanobind", reason="nanobind is not installed (its headers build the plugin: python/requirements.txt)")
if shutil.which("cmake") is None or not (shutil.which("c++") or shutil.which("g++") or shutil.which("clang++")):
    pytest.skip("no CMake or no C++ compiler: the plugin cannot be built", allow_module_level=True)
import drjit as dr  # noqa: E402

import udm1.mitsuba  # noqa: E402
from mitsuba_reference import (INFO, PRESETS, RANDOMIZE, f32, info_of, lane_streams, last_line, library,  # noqa: E402,F401
                               check_mean_against_independent, draw, pass_mismatches, reference, rng_of)
from udm1 import mitsuba_build  # noqa: E402

EVERY_RANDOMIZATION = ("wr", "wopt+tent", "sobol", "sobol-owen", "pmj02", "halton", "epis")
W, H, SPP, SPP_PASS = 3, 2, 4, 2  # the llvm wavefront: 3 x 2 pixels, 4 samples in two passes of 2
DRAWS = 9  # per sample, past every D below
SCALAR_DRAWS = 20


@pytest.fixture(scope="module")
def plugin(tmp_path_factory):
    """The plugin's folder (plugins/udm1.so), built from this checkout, prepended to Mitsuba's resolver."""
    lib = os.environ.get("UDM1_LIBRARY")
    static = Path(lib).parent / "libudm1.a" if lib else None
    if static is not None and static.is_file() and "UDM1_STATIC_LIBRARY" not in os.environ:
        os.environ["UDM1_STATIC_LIBRARY"] = str(static)  # the library these tests load, linked in
    folder = mitsuba_build.build(tmp_path_factory.mktemp("mitsuba_plugin"), jobs=2, test_variants=True)
    mi.file_resolver().prepend(str(folder))
    return folder


def variant(name):
    mi.set_variant(name)
    udm1.mitsuba.register("udm1py", native=False)  # the Python sampler, beside the plugin


def randomizations(preset):
    """Every randomization for the presets of EVERY_RANDOMIZATION, two for the others (one of them turning
    over the six with the preset's place in the list)."""
    if preset in EVERY_RANDOMIZATION:
        return RANDOMIZE
    k = PRESETS.index(preset)
    return ("default", RANDOMIZE[1 + k % 5])














def assert_refused(props, *words):
    with pytest.raises(Exception) as e:
        mi.load_dict({"type": "udm1", **props})
    line = last_line(e.value)
    assert "udm1 sampler: " in line and len(str(e.value).strip().splitlines()) == 1, str(e.value)
    for w in words:
        assert w in line, f"{w!r} not in {line!r}"


def llvm_pass_mismatches(s, seq, streams, lane, per_pass, passes, label):
    """Each pass in `passes` of the seeded vector sampler s (advanced through the others) drawn and compared with
    the library's values: one line per pass that differs."""
    bad = []
    for p in range(max(passes) + 1):
        if p in passes:
            got = draw(s, DRAWS)
            dr.eval(got)
            got, want, where = pass_mismatches(got, seq, streams, p * per_pass + lane % per_pass, DRAWS)
            if where.size:
                bad.append(f"{label} pass {p}: (lane, dim) {where[:3].tolist()}")
        s.advance()
    return bad


def test_llvm_values_are_the_library_s(plugin):
    variant("llvm_ad_rgb")
    lane = np.arange(W * H * SPP_PASS)
    pixel = lane // SPP_PASS
    bad = []
    for preset in PRESETS:
        for randomize in randomizations(preset):
            rng = rng_of("llvm", preset, randomize)
            d, seed = min(5, info_of(preset).max_dimensions), int(rng.integers(0, 2**63))
            props = {"preset": preset, "randomize": randomize, "sample_count": SPP, "dimensions": d, "seed": seed,
                     "film_width": W, "film_height": H}
            render_seed = int(rng.integers(0, 2**32))
            seq = reference(preset, randomize, d, (seed + render_seed) if randomize == "screen" else seed, SPP)
            if isinstance(seq, Exception):
                assert_refused(props, preset, randomize)
                continue
            s = mi.load_dict({"type": "udm1", **props})
            s.seed(render_seed, W * H * SPP_PASS)
            streams = lane_streams(randomize, render_seed, pixel, W)
            bad += llvm_pass_mismatches(s, seq, streams, lane, SPP_PASS, range(SPP // SPP_PASS), f"{preset}/{randomize}")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("spp", [1024, 65536 + 512])
def test_llvm_values_at_high_sample_indices(plugin, spp):
    """The vector variant's Sobol draws read as many bytes of the Gray code as the sample count needs: passes
    whose indices reach past 2^8 (and 2^16) are the library's too, for each Sobol randomization (and pmj02)."""
    variant("llvm_ad_rgb")
    per_pass = 512
    lane = np.arange(W * H * per_pass)
    pixel = lane // per_pass
    bad = []
    for preset in ("sobol", "sobol-owen", "pmj02"):
        for randomize in randomizations(preset):
            if randomize == "screen":
                continue
            rng = rng_of("llvm-high", preset, randomize)
            d, seed = min(5, info_of(preset).max_dimensions), int(rng.integers(0, 2**63))
            props = {"preset": preset, "randomize": randomize, "sample_count": spp, "dimensions": d, "seed": seed,
                     "film_width": W, "film_height": H}
            seq = reference(preset, randomize, d, seed, spp)
            if isinstance(seq, Exception):
                assert_refused(props, preset, randomize)
                continue
            s = mi.load_dict({"type": "udm1", **props})
            render_seed = int(rng.integers(0, 2**32))
            s.seed(render_seed, W * H * per_pass)
            streams = lane_streams(randomize, render_seed, pixel, W)
            last = spp // per_pass - 1  # the first pass and the last (the largest indices)
            bad += llvm_pass_mismatches(s, seq, streams, lane, per_pass, (0, last), f"{preset}/{randomize}")
    assert not bad, "\n".join(bad)


def test_scalar_values_are_the_library_s(plugin):
    variant("scalar_rgb")
    bad = []
    for preset in PRESETS:
        for randomize in randomizations(preset):
            rng = rng_of("scalar", preset, randomize)
            d, seed = min(5, info_of(preset).max_dimensions), int(rng.integers(0, 2**63))
            props = {"preset": preset, "randomize": randomize, "sample_count": SPP, "dimensions": d, "seed": seed}
            seq = reference(preset, randomize, d, seed, SPP)
            if randomize == "screen":
                assert_refused(props, "screen", "vector variant")
                continue
            if isinstance(seq, Exception):
                assert_refused(props, preset, randomize)
                continue
            s = mi.load_dict({"type": "udm1", **props})
            for stream in rng.integers(0, 2**32, 2):
                s.seed(int(stream))
                for n in range(SPP):
                    got = np.float32(draw(s, SCALAR_DRAWS))
                    want = library(seq, [stream], [n], SCALAR_DRAWS)[0]
                    if not np.array_equal(got, want):
                        bad.append(f"{preset}/{randomize} stream {stream} sample {n}: {got.tolist()} for {want.tolist()}")
                    s.advance()
    assert not bad, "\n".join(bad)


def test_scalar_values_across_the_dimension_blocks(plugin):
    """The scalar sampler fills a pixel's dimensions 16 at a time: long samples (2D draws across a block's
    end, dimensions past 64 and past D) are the library's too."""
    variant("scalar_rgb")
    bad = []
    for preset, d in (("wr", 40), ("wr", 64), ("sobol-owen", 40), ("pmj02", 36), ("halton", 20), ("rd", 70)):
        seq = reference(preset, "default", d, 5, SPP)
        s = mi.load_dict({"type": "udm1", "preset": preset, "sample_count": SPP, "dimensions": d, "seed": 5})
        for stream in (0, 2**32 - 1):
            s.seed(stream)
            for n in range(SPP):
                got = np.float32(draw(s, 80))
                want = library(seq, [stream], [n], 80)[0]
                if not np.array_equal(got, want):
                    bad.append(f"{preset} D={d} stream {stream} sample {n}: dims {np.flatnonzero(got != want)[:5]}")
                s.advance()
    assert not bad, "\n".join(bad)


def test_scalar_copies_draw_on(plugin):
    """clone() continues where its original is (the same future draws); fork() is seeded afresh."""
    variant("scalar_rgb")
    s = mi.load_dict({"type": "udm1", "preset": "sobol-owen", "dimensions": 8})
    s.seed(17)
    s.advance()
    s.next_1d()
    c = s.clone()
    assert draw(c, 6) == draw(s, 6)
    f = s.fork()
    f.seed(17)
    s.seed(17)
    assert draw(f, 6) == draw(s, 6)


def register_draws_integrator():
    class DrawsIntegrator(mi.SamplingIntegrator):
        def sample(self, scene, sampler, ray, medium=None, active=True):
            a, b = sampler.next_1d(), sampler.next_2d()
            return mi.Spectrum(mi.Color3f(a, b.x, b.y)), mi.Bool(True), []

    mi.register_integrator("udm1_test_draws", lambda props: DrawsIntegrator(props))


@pytest.mark.parametrize("name", ["scalar_rgb", "llvm_ad_rgb"])
def test_render_equals_the_python_sampler_s(plugin, name):
    """The draws integrator's image, the plugin's and the Python sampler's (which is given the film's size),
    in one pass and in several (the integrator's samples_per_pass)."""
    variant(name)
    register_draws_integrator()
    Wr, Hr = 5, 3
    cases = [("wr", "owen"), ("sobol-owen", "default"), ("pmj02", "default"), ("wgr+tent", "permute")]
    if name.startswith("llvm"):
        cases.append(("wr", "screen"))
    for preset, randomize in cases:
        # (scalar_rgb adds a pixel's passes in the order its threads finish them: two values, whose float32 sum
        # does not depend on the order)
        for spp, per_pass in ((2, None), (2, 1)) + (((4, 2),) if name.startswith("llvm") else ()):
            images = []
            for kind in ("udm1", "udm1py"):
                film = {"film_width": Wr, "film_height": Hr} if kind == "udm1py" or randomize == "screen" else {}
                integrator = {"type": "udm1_test_draws"} | ({"samples_per_pass": per_pass} if per_pass else {})
                scene = mi.load_dict({"type": "scene", "integrator": integrator, "sensor": {
                    "type": "perspective",
                    "film": {"type": "hdrfilm", "width": Wr, "height": Hr, "rfilter": {"type": "box"}},
                    "sampler": {"type": kind, "preset": preset, "randomize": randomize, "sample_count": spp,
                                "dimensions": min(4, info_of(preset).max_dimensions), "seed": 99, **film}}})
                images.append(np.array(mi.render(scene, seed=5, spp=spp)))
            # equal up to the order of the film's float32 sums (llvm_ad_rgb adds the lanes' samples into a pixel with
            # atomic adds on several threads: a few ulp, run to run); a different draw moves a pixel by far more
            np.testing.assert_allclose(images[0], images[1], rtol=0, atol=2e-7, err_msg=f"{name} {preset}/{randomize} {spp} spp")


@pytest.mark.parametrize("name", ["scalar_rgb", "llvm_ad_rgb"])
def test_path_tracer_equals_the_python_sampler_s(plugin, name):
    """Mitsuba's own path tracer on its Cornell box (max_depth 8) renders the same image with the plugin as with
    the Python sampler. In llvm_ad_rgb its bounces run in a symbolic loop that holds the sampler in its state:
    each bounce draws its own dimensions only if the sampler's dimension index is part of that state (without
    it every bounce redrew the first bounce's dimensions and the image came out 1.8 % too dark)."""
    variant(name)
    res, spp = 8, 4
    for preset in ("wr", "sobol-owen"):
        images = []
        for kind in ("udm1", "udm1py"):
            d = mi.cornell_box()
            d["sensor"]["film"].update(width=res, height=res, rfilter={"type": "box"})
            d["integrator"]["max_depth"] = 8
            d["sensor"]["sampler"] = {"type": kind, "preset": preset, "sample_count": spp, "seed": 3,
                                      **({"dimensions": 32} if preset != "wr" else {}),
                                      **({"film_width": res, "film_height": res} if kind == "udm1py" else {})}
            images.append(np.array(mi.render(mi.load_dict(d), seed=1, spp=spp)))
        # (the film's float32 sums in another order: a few ulp; another draw moves a pixel by far more)
        np.testing.assert_allclose(images[0], images[1], rtol=1e-5, atol=1e-6, err_msg=f"{name} {preset}")


def render_means(sampler: dict, res: int, spp: int, seeds) -> np.ndarray:
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = res
    d["sensor"]["sampler"] = sampler
    scene = mi.load_dict(d)
    return np.array([np.mean(np.array(mi.render(scene, spp=spp, seed=s))) for s in seeds])


@pytest.mark.parametrize("name,res,spp,samplers", [
    ("llvm_ad_rgb", 32, 64, [{"preset": "wr"}, {"preset": "sobol-owen", "dimensions": 24}, {"preset": "pmj02"},
                             {"preset": "wr", "randomize": "screen", "film_width": 32, "film_height": 32}]),
    ("scalar_rgb", 16, 16, [{"preset": "wr"}, {"preset": "sobol-owen"}]),
])
def test_cornell_box_mean_equals_independent(plugin, name, res, spp, samplers):
    """Within 5 standard deviations of the independent sampler's mean (the deviation over 16 renders)."""
    variant(name)
    check_mean_against_independent(render_means, name, res, spp, samplers)


BAD = [({"sample_count": 0}, "sample_count 0"), ({"sample_count": -1}, "sample_count -1"),
       ({"sample_count": 2**32}, "sample_count 4294967296"), ({"sample_count": 2.5}, "sample_count 2.5"),
       ({"sample_count": "8"}, "sample_count '8'"), ({"sample_count": True}, "sample_count True"),
       ({"seed": -1}, "seed -1"), ({"seed": 2**63}, "seed 9.22"), ({"seed": 2**64 + 5}, "seed 1.8"),
       ({"seed": 3.5}, "seed 3.5"), ({"seed": "7"}, "seed '7'"),
       ({"dimensions": 0}, "dimensions 0"), ({"dimensions": 65537}, "dimensions 65537"),
       ({"dimensions": 2.0}, "dimensions 2.0"), ({"dimensions": "4"}, "dimensions '4'"),
       ({"preset": "wr-ao", "dimensions": 3}, "dimensions 3"), ({"preset": "pmj02", "dimensions": 65}, "dimensions 65"),
       ({"preset": "nope"}, "preset 'nope'"), ({"preset": "wr+tentx"}, "preset 'wr+tentx'"),
       ({"preset": 5}, "preset 5"), ({"randomize": "blue"}, "randomize 'blue'"), ({"randomize": 1}, "randomize 1"),
       ({"film_width": 0, "film_height": 4}, "film_width 0"), ({"film_width": -3, "film_height": 4}, "film_width -3"),
       ({"film_width": 2.5, "film_height": 4}, "film_width 2.5"),
       ({"film_width": 4, "film_height": 2**32}, "film_height 4294967296"),
       ({"film_width": 4}, "film_width and film_height"), ({"film_height": 4}, "film_width and film_height"),
       ({"preset": "pmj02", "sample_count": 2**20 + 1}, "sample_count 1048577"),
       ({"preset": "lattice", "sample_count": 2**24 + 1}, "sample_count 16777217"),
       ({"unknown": 1}, "unknown")]


@pytest.mark.parametrize("name", ["scalar_rgb", "llvm_ad_rgb"])
def test_bad_properties_refused_at_load(plugin, name):
    variant(name)
    for props, words in BAD:
        with pytest.raises(Exception) as e:
            mi.load_dict({"type": "udm1", **props})
        message = str(e.value).strip()
        assert words in message, f"{props}: {message!r}"
        if "unknown" not in props:  # (an unknown property: Mitsuba's own refusal, which lists them on lines of their own)
            assert len(message.splitlines()) == 1 and "udm1 sampler: " in message, message
    if name.startswith("llvm"):
        assert_refused({"preset": "halton", "randomize": "screen", "film_width": 4, "film_height": 4}, "'halton'")
        assert_refused({"randomize": "screen"}, "screen", "film_width and film_height")
    else:
        assert_refused({"randomize": "screen"}, "screen", "vector variant")
    s = mi.load_dict({"type": "udm1", "preset": "pmj02", "sample_count": 16})
    with pytest.raises(Exception, match="sample_count 2097152"):
        s.set_sample_count(2**21)
    with pytest.raises(Exception, match="sample_count 0"):
        s.set_sample_count(0)
    assert s.sample_count() == 16  # (a refused count leaves the sampler as it was)


def test_draws_the_library_refuses_are_refused(plugin):
    """scalar: a point set's sample past K; llvm: a wavefront that is not the film's size times a divisor of
    sample_count, at its first draw (a seed alone is not refused: Mitsuba seeds with 1 lane to release)."""
    variant("scalar_rgb")
    s = mi.load_dict({"type": "udm1", "preset": "pmj02", "sample_count": 2})
    s.seed(3)
    s.advance()
    s.next_1d()
    s.advance()
    with pytest.raises(Exception, match="sample 2 of stream 3 cannot be drawn"):
        s.next_1d()
    variant("llvm_ad_rgb")
    s = mi.load_dict({"type": "udm1", "sample_count": 6, "film_width": 4, "film_height": 2})
    for lanes in (4 * 2 * 4, 7, 1):
        s.seed(0, lanes)
        with pytest.raises(Exception, match="film_width x film_height"):
            s.next_1d()
    s.seed(0, 4 * 2 * 3)
    dr.eval(s.next_1d())


def test_build_refuses_another_mitsuba(monkeypatch, tmp_path):
    monkeypatch.setattr(mi, "__version__", "3.8.0")
    with pytest.raises(mitsuba_build.BuildError) as e:
        mitsuba_build.build(tmp_path)
    assert "Mitsuba 3.8.0 is installed" in str(e.value) and "3.9.1" in str(e.value)
    assert len(str(e.value).splitlines()) == 1
    assert not (tmp_path / "build").exists()  # refused before anything is made
    # the pin the build checks is python/requirements.txt's
    pins = (Path(__file__).resolve().parents[2] / "python" / "requirements.txt").read_text()
    assert f"mitsuba=={mitsuba_build.PINNED_MITSUBA} " in pins


def test_register_prefers_the_plugin(plugin, monkeypatch, capsys):
    """register(): the plugin's folder when built (the Python sampler not registered: it would shadow the
    plugin), the Python sampler with a one-line note otherwise."""
    variant("scalar_rgb")
    monkeypatch.setattr(mitsuba_build, "built", lambda folder=None: plugin)
    assert udm1.mitsuba.register() == plugin
    s = mi.load_dict({"type": "udm1"})
    assert type(s).__module__ != "udm1.mitsuba", type(s)  # the plugin's, not a Python sampler
    monkeypatch.setattr(mitsuba_build, "built", lambda folder=None: None)
    monkeypatch.setattr(udm1.mitsuba, "_NOTED", [])
    cls = udm1.mitsuba.register("udm1_fallback")
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "using the Python sampler" in err[0]
    assert isinstance(mi.load_dict({"type": "udm1_fallback"}), cls) and cls.__module__ == "udm1.mitsuba"
    with pytest.raises(mitsuba_build.BuildError, match="not built"):
        udm1.mitsuba.register(native=True)


def test_mitsuba_command_line_with_the_plugin_s_folder(plugin, tmp_path):
    """The XML-only route: mitsuba -a <folder> renders a scene whose sampler is udm1."""
    exe = Path(sys.executable).parent / "mitsuba"
    if not exe.exists():
        pytest.skip(f"no mitsuba command line beside {sys.executable}")
    scene = tmp_path / "scene.xml"
    scene.write_text("""<scene version="3.0.0">
  <integrator type="path"/>
  <sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    <sampler type="udm1"><string name="preset" value="sobol-owen"/><integer name="sample_count" value="4"/></sampler>
  </sensor>
  <shape type="sphere"><bsdf type="diffuse"/></shape>
  <emitter type="constant"/>
</scene>
""")
    out = tmp_path / "out.exr"
    r = subprocess.run([str(exe), "-m", "scalar_rgb", "-a", str(plugin), "-o", str(out), str(scene)],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0 and out.exists(), r.stdout + r.stderr
    bad = scene.read_text().replace('value="sobol-owen"', 'value="sobol-owenx"')
    scene.write_text(bad)
    r = subprocess.run([str(exe), "-m", "scalar_rgb", "-a", str(plugin), "-o", str(tmp_path / "bad.exr"), str(scene)],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode != 0 and "preset 'sobol-owenx'" in r.stdout + r.stderr
