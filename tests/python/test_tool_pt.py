"""udm1-pt from the command line: runs with no arguments, the furnace through the whole
pipeline, the Cornell box against Mitsuba 3, the three strategies agree, bit-identical
images across runs, thread counts and merged sample ranges, merge refusing what does
not belong together, the shared pbrt-v4 scenes, and every bad input failing with one
line (file and line for scene files), a non-zero exit and no file."""

import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
from cli_checks import exr_compression, fails_cleanly
from pt_tool import read_exr
from tabulated_bsdf_files import write_test_files

TOOL = os.environ.get("UDM1_PT_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT.parent / "shared" / "scenes"
RENDER_LINE = re.compile(
    r"sampler (\S+) spp (\d+) samples \[(\d+), (\d+)\) size (\d+)x(\d+) image \d+x\d+ at \d+,\d+ dimensions (\d+) of (\d+) loop \S+ seconds \S+ "
    r"paths (\d+) rays (\d+) paths_per_second \S+ rays_per_second \S+ mean (\S+) (\S+) (\S+)\n")


def run(*args, cwd=None):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, cwd=cwd, timeout=900)


def ok(*args, cwd=None):
    r = run(*args, cwd=cwd)
    assert r.returncode == 0, r.stderr
    return r


def mean_of(result):
    m = RENDER_LINE.match(result.stdout)
    assert m, result.stdout
    return np.array([float(m.group(i)) for i in (11, 12, 13)])


def read_png(path):
    import matplotlib.image as mpimg

    return mpimg.imread(path)


def test_runs_with_no_arguments(tmp_path):
    r = ok(cwd=tmp_path)
    m = RENDER_LINE.match(r.stdout)
    assert m and r.stdout.endswith("wrote pt.png\n"), r.stdout
    assert (m.group(1), m.group(2), m.group(5), m.group(6)) == ("sobol-owen", "16", "256", "256")
    img = read_png(tmp_path / "pt.png")
    assert img.shape[:2] == (256, 256)
    # the Cornell box: a light that saturates, dark corners, and the coloured walls where pbrt puts
    # them: its LookAt is left-handed (camera x = up x dir), so the red wall at world x = 550 is on
    # the right and the green one on the left, as in pbrt-v4's render of the same data
    assert img[..., :3].max() == 1.0 and img[..., :3].min() < 0.05
    left, right = img[128, 10, :3], img[128, 245, :3]
    assert left[1] > 1.5 * left[0] and right[0] > 2 * right[1], (left, right)


@pytest.mark.parametrize("scene", ["builtin:furnace", "builtin:furnace-box"])
def test_furnace_through_the_tool(scene, tmp_path):
    # an enclosure of albedo 1/2 that emits 1 everywhere: every pixel sees 1 / (1 - 1/2) = 2
    # (roulette and the depth limit: maxdepth 60 leaves 2^-60 out). Light sampling alone is left out
    # in the box: in its corners the geometry term of two faces meeting at an edge has an infinite
    # second moment, so its finite-sample mean runs low (1.977 here); MIS bounds it by BSDF sampling
    for strategy in ("mis", "nee", "bsdf") if scene == "builtin:furnace" else ("mis", "bsdf"):
        r = ok("--scene", scene, "--spp", "64", "--size", "24x16", "--maxdepth", "60", "--strategy", strategy,
               "--sampler", "sobol-owen", "-o", str(tmp_path / f"{strategy}.exr"))
        assert np.all(np.abs(mean_of(r) - 2.0) < 0.02), (strategy, r.stdout)


REPEAT = pytest.mark.release_only("the same code at other parameters, which the first case runs under the sanitizers")


@pytest.mark.parametrize("sampler,randomize,spp", [("wmmr", "screen", 12),
                                                  pytest.param("wmmr", "default", 12, marks=REPEAT),
                                                  pytest.param("wmmr", "screen-fixed", 12, marks=REPEAT),
                                                  pytest.param("sobol-owen", "screen", 16, marks=REPEAT)])
def test_identical_across_runs_threads_and_ranges(tmp_path, sampler, randomize, spp):
    common = ["--sampler", sampler, "--spp", str(spp), "--size", "40x30", "--randomize", randomize]
    outs = []
    for threads in ("1", "2", "8"):
        out = tmp_path / f"t{threads}.exr"
        ok(*common, "--threads", threads, "-o", str(out))
        outs.append(out.read_bytes())
    ok(*common, "-o", str(tmp_path / "again.exr"))
    outs.append((tmp_path / "again.exr").read_bytes())
    assert all(o == outs[0] for o in outs)
    # three uneven ranges, each with its own thread count, merged in any order: the whole render, bit for bit
    for first, count, threads in ((0, 5, "1"), (5, 1, "2"), (6, spp - 6, "8")):
        ok(*common, "--spp-first", str(first), "--spp-count", str(count), "--threads", threads,
           "-o", str(tmp_path / f"r{first}.exr"))
    ok("merge", str(tmp_path / "r6.exr"), str(tmp_path / "r0.exr"), str(tmp_path / "r5.exr"),
       "-o", str(tmp_path / "merged.exr"), "--png", str(tmp_path / "merged.png"))
    assert (tmp_path / "merged.exr").read_bytes() == outs[0]
    ok(*common, "--png", str(tmp_path / "whole.png"))
    assert (tmp_path / "merged.png").read_bytes() == (tmp_path / "whole.png").read_bytes()
    # merging parts of a merge works as well: ((0..5) + (5..6)) + (6..12)
    ok("merge", str(tmp_path / "r0.exr"), str(tmp_path / "r5.exr"), "-o", str(tmp_path / "half.exr"))
    ok("merge", str(tmp_path / "half.exr"), str(tmp_path / "r6.exr"), "-o", str(tmp_path / "merged2.exr"))
    assert (tmp_path / "merged2.exr").read_bytes() == outs[0]
    r = ok("compare", str(tmp_path / "merged.exr"), str(tmp_path / "t1.exr"))
    assert r.stdout == "mse 0 rmse 0 psnr inf\n"
    # --exact: every value unclamped, bit for bit (the clamped MSE above cannot see values above 1)
    r = ok("compare", str(tmp_path / "merged.exr"), str(tmp_path / "t1.exr"), "--exact")
    assert re.fullmatch(r"identical: (\d+) values bit for bit", r.stdout.splitlines()[1]), r.stdout
    assert int(r.stdout.split()[-5]) % (40 * 30 * 3) == 0, r.stdout  # every channel: RGB and the film's sums
    ok(*common, "--seed", "2", "-o", str(tmp_path / "seed2.exr"))
    r = ok("compare", str(tmp_path / "seed2.exr"), str(tmp_path / "t1.exr"), "--exact")
    assert re.fullmatch(r"different: \d+ of \d+ values, largest difference \S+", r.stdout.splitlines()[1]), r.stdout
    r = ok("compare", str(tmp_path / "merged.exr"), str(tmp_path / "merged.png"), "--exact")
    assert re.fullmatch(r"different: \d+ channels and 3", r.stdout.splitlines()[1]), r.stdout


def test_tiles_and_ranges_merge_to_the_whole_render(tmp_path):
    # four tiles, each cut into its own ranges, merged in any order: the whole render bit for bit
    common = ["--sampler", "hwmmr", "--spp", "6", "--size", "30x22"]
    ok(*common, "-o", str(tmp_path / "whole.exr"), "--png", str(tmp_path / "whole.png"))
    tiles = {"0,0,13,10": [(0, 6)], "13,0,30,10": [(0, 2), (2, 4)], "0,10,13,22": [(0, 5), (5, 1)],
             "13,10,30,22": [(0, 1), (1, 1), (2, 4)]}
    parts = []
    for k, (bounds, ranges) in enumerate(tiles.items()):
        for first, count in ranges:
            out = tmp_path / f"t{k}_{first}.exr"
            ok(*common, "--pixel-bounds", bounds, "--spp-first", str(first), "--spp-count", str(count), "-o", str(out))
            parts.append(str(out))
    ok("merge", *parts[::-1], "-o", str(tmp_path / "merged.exr"), "--png", str(tmp_path / "merged.png"))
    assert (tmp_path / "merged.exr").read_bytes() == (tmp_path / "whole.exr").read_bytes()
    assert (tmp_path / "merged.png").read_bytes() == (tmp_path / "whole.png").read_bytes()
    # a tile alone is a valid image of its window
    r = ok("merge", parts[0], "-o", str(tmp_path / "tile.exr"))
    assert "samples [0, 6) of 6" in r.stdout
    # a missing tile or a tile given twice is refused, naming a pixel or the file
    r = run("merge", *parts[:-1], "-o", str(tmp_path / "no.exr"))
    assert r.returncode == 2 and "pixel (13, 10) has samples [0, 2)" in r.stderr, r.stderr
    r = run("merge", *parts, parts[0], "-o", str(tmp_path / "no.exr"))
    assert r.returncode == 2 and parts[0] in r.stderr, r.stderr
    assert not (tmp_path / "no.exr").exists()
    r = run(*common, "--pixel-bounds", "0,0,31,22", "-o", str(tmp_path / "no.exr"))
    assert r.returncode == 2 and "not inside the 30x22 image" in r.stderr and not (tmp_path / "no.exr").exists()


def test_merge_refuses_what_does_not_belong_together(tmp_path):
    base = ["--sampler", "halton", "--spp", "8", "--size", "16x16"]
    ok(*base, "--spp-first", "0", "--spp-count", "4", "-o", str(tmp_path / "a.exr"))
    ok(*base, "--spp-first", "4", "--spp-count", "4", "-o", str(tmp_path / "b.exr"))
    ok(*base, "--spp-first", "2", "--spp-count", "4", "-o", str(tmp_path / "overlap.exr"))
    ok(*base, "--spp-first", "6", "--spp-count", "2", "-o", str(tmp_path / "late.exr"))
    ok(*base, "--spp-first", "4", "--spp-count", "4", "--seed", "2", "-o", str(tmp_path / "seed2.exr"))
    ok("--sampler", "halton", "--spp", "8", "--size", "16x8", "--spp-first", "4", "--spp-count", "4",
       "-o", str(tmp_path / "size.exr"))
    (tmp_path / "junk.exr").write_bytes(b"not an image")
    cases = [
        (["a.exr", "a.exr"], "a.exr"),            # the same range twice
        (["a.exr", "overlap.exr"], "overlap.exr"),  # overlapping ranges
        (["a.exr", "late.exr"], "late.exr"),       # a gap
        (["a.exr", "seed2.exr"], "seed2.exr"),     # another render (seed)
        (["a.exr", "size.exr"], "size.exr"),       # another render (size)
        (["a.exr", "junk.exr"], "junk.exr"),       # not an image
        (["a.exr", "nothere.exr"], "nothere.exr"),
    ]
    for inputs, words in cases:
        fails_cleanly(run, ["merge", *inputs, "-o", "out.exr", "--png", "out.png"], words, tmp_path)


@pytest.mark.release_only("a statistical check of the estimator over seeds; small renders run its code under the sanitizers")
def test_strategies_agree_on_the_cornell_box(tmp_path):
    # next-event estimation, BSDF sampling and their MIS combination estimate the same integral;
    # BSDF sampling alone is the noisiest (it finds the light only by chance): 4 seeds, 2 %
    means = {}
    for strategy in ("mis", "nee", "bsdf"):
        m = [mean_of(ok("--strategy", strategy, "--sampler", "pcg32", "--seed", str(s), "--spp", "64",
                        "--size", "64x64", "-o", str(tmp_path / "x.exr"))) for s in range(1, 5)]
        means[strategy] = np.mean(m, axis=0)
    for strategy in ("nee", "bsdf"):
        rel = np.abs(means[strategy] / means["mis"] - 1)
        assert np.all(rel < 0.02), (strategy, means)


@pytest.mark.release_only("a statistical check of the estimator over seeds; small renders run its code under the sanitizers")
def test_cornell_box_mean_matches_mitsuba(tmp_path):
    """The built-in Cornell box, exported by `udm1-pt export` (world-space PLY and scene.json) and
    rendered by Mitsuba 3 scalar_rgb's path integrator (bench/mitsuba_scene.py states how the scenes
    are matched): the mean radiance agrees within 1 % per channel."""
    pytest.importorskip("mitsuba")
    sys.path.insert(0, str(ROOT / "bench"))
    import mitsuba_scene

    ok("export", str(tmp_path / "scene"), "--size", "96x96")
    img, _ = mitsuba_scene.render(tmp_path / "scene", spp=256, sampler="independent", seed=3)
    theirs = np.asarray(img, dtype=np.float64).reshape(-1, img.shape[-1])[:, :3].mean(axis=0)
    ours = mean_of(ok("--spp", "256", "--size", "96x96", "-o", str(tmp_path / "ours.exr")))
    rel = np.abs(ours / theirs - 1)
    assert np.all(rel < 0.01), (ours, theirs)
    # a LightSource has no place in scene.json: refused, naming it, nothing written
    fails_cleanly(run, ["export", "out", "--scene", str(ROOT / "tests" / "scenes" / "lights.pbrt")],
                  "lights.pbrt:8: export writes area lights only", tmp_path, code=1)


def test_export_maps_materials_to_mitsuba(tmp_path):
    """scene.json keeps each material's parameters with their kind (a texture by name, a sampled spectrum as
    its numbers, vertex normals flagged); bench/mitsuba_scene.py gives Mitsuba the nearest BSDF of each
    material it can, and refuses what it cannot, naming the shape and the parameter."""
    sys.path.insert(0, str(ROOT / "bench"))
    import mitsuba_scene

    scene = tmp_path / "m.pbrt"
    scene.write_text('''LookAt 0 1 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
  Shape "trianglemesh" "integer indices" [ 0 1 2 ] "point3 P" [ -1 3 0  1 3 0  0 3 1 ]
AttributeEnd
Material "coateddiffuse" "rgb reflectance" [ 0.2 0.3 0.4 ] "float roughness" [ 0.04 ]
Shape "trianglemesh" "integer indices" [ 0 1 2 ] "point3 P" [ -2 0 -2  2 0 -2  0 0 2 ]
  "normal N" [ 0 1 0  0 1 0  0 1 0 ]
Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" [ 0 ]
Shape "sphere" "float radius" [ 0.3 ]
Texture "checks" "spectrum" "imagemap" "string filename" "tex.png"
Material "diffuse" "texture reflectance" "checks"
Shape "trianglemesh" "integer indices" [ 0 1 2 ] "point3 P" [ -2 0 -3  2 0 -3  0 1 -3 ]
''')
    (tmp_path / "tex.png").write_bytes((ROOT / "tests" / "scenes" / "sky-map.png").read_bytes())  # any image
    ok("export", str(tmp_path / "out"), "--scene", str(scene))
    js = json.loads((tmp_path / "out" / "scene.json").read_text())
    shapes = js["shapes"]
    assert shapes[1]["normals"] is True and shapes[0]["normals"] is False
    assert shapes[3]["material"]["reflectance"] == {"texture": "checks"}
    coated = mitsuba_scene.bsdf_of(1, shapes[1]["material"])
    assert coated["type"] == "twosided" and coated["bsdf"]["type"] == "roughplastic"
    assert abs(coated["bsdf"]["alpha"] - 0.2) < 1e-12 and coated["bsdf"]["int_ior"] == 1.5  # sqrt(0.04), pbrt's eta
    gold = mitsuba_scene.bsdf_of(2, shapes[2]["material"])
    assert gold["bsdf"] == {"type": "conductor", "material": "Au"}
    with pytest.raises(ValueError, match=r"shape 3: .*'reflectance'"):
        mitsuba_scene.bsdf_of(3, shapes[3]["material"])
    for m, words in (({"type": "mix", "amount": 0.5}, "'mix'"),
                     ({"type": "dielectric", "eta": {"spectrum": [400, 1.5, 700, 1.4]}}, "'eta'"),
                     ({"type": "conductor", "eta": "metal-Xx-eta", "k": "metal-Xx-k"}, "not a metal")):
        with pytest.raises(ValueError, match=words):
            mitsuba_scene.bsdf_of(0, m)


@pytest.mark.skipif(not SCENES.is_dir(), reason=f"{SCENES} is absent: the shared test scenes are not here")
@pytest.mark.release_only("a statistical check of the estimator over seeds; small renders run its code under the sanitizers")
@pytest.mark.parametrize("name", ["cornell-box", "veach-mis"])
def test_shared_scenes(name, tmp_path):
    scene = str(SCENES / name / f"{name}.pbrt")
    png = tmp_path / f"{name}.png"
    r = ok("--scene", scene, "--spp", "16", "--size", "96x72", "--png", str(png))
    assert r.stderr == "", r.stderr  # nothing in these scenes is left out
    img = read_png(png)[..., :3]
    assert img.shape == (72, 96, 3) and 0.05 < img.mean() < 0.9 and img.std() > 0.05, (img.mean(), img.std())
    # the three strategies agree in the mean (veach-mis: glossy plates lit by lights of four sizes), within 5
    # standard errors measured from 4 seeds or 1 %: light sampling of the small lights on the glossy plates
    # makes fireflies, a 4-seed mean's standard error there is about 3 %
    runs = {st: np.array([mean_of(ok("--scene", scene, "--strategy", st, "--sampler", "pcg32", "--seed", str(s),
                                     "--spp", "64", "--size", "64x48", "-o", str(tmp_path / "x.exr")))
                          for s in (1, 2, 3, 4)])
            for st in ("mis", "nee", "bsdf")}
    means = {st: r.mean(axis=0) for st, r in runs.items()}
    se = {st: r.std(axis=0, ddof=1) / np.sqrt(len(r)) for st, r in runs.items()}
    for st in ("nee", "bsdf"):
        tol = np.maximum(5 * np.sqrt(se[st] ** 2 + se["mis"] ** 2), 0.01 * means["mis"])
        assert np.all(np.abs(means[st] - means["mis"]) <= tol), (name, means, se)


@pytest.mark.skipif(not SCENES.is_dir(), reason=f"{SCENES} is absent: the shared test scenes are not here")
def test_crown_renders(tmp_path):
    # the paper's scene: 3.5 M triangles, gold, gems, pearls, velvet, image and bump textures, six lights
    png = tmp_path / "crown.png"
    r = ok("--scene", str(SCENES / "crown" / "crown.pbrt"), "--spp", "4", "--size", "50x70", "--png", str(png))
    # two notes: the camera's sensor renders as cie1931, and the gems' media are left out under "path"
    assert re.fullmatch(r'udm1-pt: note: \S+crown.pbrt:8: Film: sensor "canon_eos_5d_mkiv" [^\n]+ cie1931 [^\n]+\n'
                        r'udm1-pt: note: \S+crown.pbrt:114: media are left out, as Integrator "path" leaves them out\n',
                        r.stderr), r.stderr
    img = read_png(png)[..., :3]
    mean = img.reshape(-1, 3).mean(axis=0)
    assert img.shape == (70, 50, 3) and mean[0] > mean[2] and 0.1 < img.mean() < 0.9, mean  # gold and velvet: warm


HEAD = 'LookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 45 ]\nWorldBegin\n'
TRI = 'Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0 ] "integer indices" [ 0 1 2 ]\n'
LIGHT = ('AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 1 1 1 ]\n'
         'Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  2 0 0 ] "integer indices" [ 0 1 2 ]\nAttributeEnd\n')


@pytest.mark.parametrize("integrator", ["path", "volpath"])
def test_a_scene_without_shapes_renders_its_lights(integrator, tmp_path):
    # as pbrt-v4 renders it: every camera ray escapes to the infinite light; the point light lights nothing
    scene = tmp_path / "lights.pbrt"
    scene.write_text(f'Integrator "{integrator}"\n' + HEAD + 'LightSource "infinite" "rgb L" [ 0.5 0.3 0.2 ]\n'
                     'LightSource "point" "rgb I" [ 10 10 10 ]\n')
    r = ok("--scene", str(scene), "--spp", "4", "--size", "8x6", "-o", str(tmp_path / "x.exr"))
    assert r.stderr == "", r.stderr
    img = read_exr(tmp_path / "x.exr")
    assert img.shape == (6, 8, 3) and np.allclose(img, [0.5, 0.3, 0.2], rtol=1e-6), img.reshape(-1, 3)[:2]


PLY_HEAD = (b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            b"property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n")


@pytest.mark.parametrize(
    "text,line,words",
    [
        (HEAD + "Frobnicate 3\n" + TRI, 4, "unsupported directive 'Frobnicate'"),
        (HEAD + 'LightSource "goniometric"\n' + TRI, 4, 'LightSource "goniometric" is not supported'),
        (HEAD + 'LightSource "infinite" "string filename" "nomap.exr"\n' + TRI, 4, "nomap.exr"),
        (HEAD + 'LightSource "infinite" "string filename" "wide.exr"\n' + TRI, 4, "not square"),
        (HEAD + 'LightSource "infinite" "rgb L" [ 1 1 1 ] "string filename" "wide.exr"\n' + TRI, 4, 'both "L" and "filename"'),
        (HEAD + 'LightSource "infinite" "point3 portal" [ 0 0 0 1 0 0 1 1 0 ]\n' + TRI, 4, "portal needs 4 points"),
        (HEAD + 'LightSource "spot" "float coneangle" [ 30 ] "float conedeltaangle" [ 40 ]\n' + TRI, 4, "conedeltaangle"),
        (HEAD + 'LightSource "point" "point3 to" [ 0 0 1 ]\n' + TRI, 4, "to, coneangle, conedeltaangle are a spot's"),
        (HEAD + 'LightSource "distant" "point3 from" [ 1 1 1 ] "point3 to" [ 1 1 1 ]\n' + TRI, 4, "from and to coincide"),
        (HEAD + 'LightSource "point" "rgb I" [ 1 -1 1 ]\n' + TRI, 4, "negative emission"),
        (HEAD + 'Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 x ]\n', 4, "x"),
        (HEAD + 'Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 1e999 ]\n', 4, "1e999"),
        (HEAD + 'Shape "trianglemesh" "point3 P" [ 0 0 0 1 ]\n', 4, "3 numbers per vertex"),
        (HEAD + TRI.replace("0 1 2 ]", "0 1 7 ]"), 4, "index 7 out of range"),
        (HEAD + TRI.replace("0 1 2 ]", "0 1 -1 ]"), 4, "out of range"),
        (HEAD + 'Shape "plymesh" "string filename" "missing.ply"\n', 4, "missing.ply: cannot open"),
        (HEAD + 'Shape "plymesh" "string filename" "trunc.ply"\n', 0, "trunc.ply"),
        (HEAD + 'Shape "plymesh" "string filename" "badindex.ply"\n', 0, "badindex.ply"),
        (HEAD + LIGHT + TRI, 6, "an area light of zero area"),
        (HEAD + 'Material "measured"\n' + TRI, 4, 'Material "measured": no "string filename"'),
        (HEAD + 'Material "conductor" "spectrum eta" "metal-Xx-eta"\n' + TRI, 4, '"metal-Xx-eta" is not a named spectrum that udm1 knows'),
        (HEAD + 'Material "conductor" "spectrum k" [ 300 1 200 2 ]\n' + TRI, 4, "wavelengths must be positive and increasing"),
        (HEAD + 'Material "dielectric" "float eta" [ -1.5 ]\n' + TRI, 4, "eta must be positive"),
        (HEAD + 'Material "dielectric" "float roughness" [ -0.1 ]\n' + TRI, 4, "roughness must not be negative"),
        (HEAD + 'Material "diffuse" "texture reflectance" "checks"\n' + TRI, 4, "reflectance"),
        (HEAD + 'Material "coateddiffuse" "rgb albedo" [ 1.3 0.3 0.3 ]\n' + TRI, 4, "albedo and has a component above 1"),
        (HEAD + 'NamedMaterial "nope"\n' + TRI, 4, 'NamedMaterial "nope"'),
        (HEAD + 'AreaLightSource "diffuse" "spectrum L" "spds/none.spd"\n' + TRI, 4, 'nor a spectrum file'),
        (HEAD + 'AreaLightSource "diffuse" "spectrum L" [ 400 1 500 ]\n' + TRI, 4, "(wavelength, value) pairs"),
        (HEAD + 'Material "diffuse" "rgb reflectance" [ 2 2 2 ]\n' + TRI, 4, "albedo and has a component above 1"),
        (HEAD + 'Material "coateddiffuse" "rgb reflectance" [ 0.5 1.01 0.5 ]\n' + TRI, 4, "component above 1"),
        ('Integrator "mlt"\n' + HEAD + TRI, 1, 'Integrator "mlt" is not supported'),
        (HEAD + 'MakeNamedMedium "fog" "string type" "heterogeneous"\n' + TRI, 4, '"heterogeneous" is not supported'),
        (HEAD + 'MediumInterface "" "glass"\n' + TRI, 4, 'medium "glass" was not made'),
        (HEAD + 'AreaLightSource "diffuse" "blackbody L" [ 20 ]\n' + TRI, 4, "one temperature in 1000..40000 K"),
        ('Film "rgb" "float iso" [ -100 ]\n' + HEAD + TRI, 1, "iso"),
        ('Film "spectral"\n' + HEAD + TRI, 1, 'Film "spectral"'),
        ('Camera "orthographic"\n' + HEAD + TRI, 1, "orthographic"),
        (HEAD + 'Include "nothere.pbrt"\n', 4, "nothere.pbrt: cannot open"),
        (HEAD + TRI.replace(" ]\n", "\n"), 0, "missing ']'"),
    ],
)
def test_bad_scenes_name_file_and_line(text, line, words, tmp_path):
    scene = tmp_path / "s.pbrt"
    scene.write_text(text)
    (tmp_path / "trunc.ply").write_bytes(PLY_HEAD + b"\0" * 20)
    (tmp_path / "badindex.ply").write_bytes(PLY_HEAD + np.zeros(9, "<f4").tobytes() + b"\3"
                                            + np.array([0, 1, 3], "<i4").tobytes())
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    mi.Bitmap(np.ones((2, 4, 3), np.float32)).write(str(tmp_path / "wide.exr"))  # not an equal-area map
    before = set(tmp_path.iterdir())
    r = run("--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "out.exr", "--png", "out.png", cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    lines = r.stderr.strip().splitlines()
    where = f"{scene}:{line}:" if line else str(tmp_path)
    assert len(lines) == 1 and lines[0].startswith("udm1-pt: ") and where in lines[0] and words in lines[0], \
        (where, words, r.stderr)
    assert set(tmp_path.iterdir()) == before  # no image, not even a temporary file


@pytest.mark.parametrize(
    "args,code,words",
    [
        (["--scene", "nope.pbrt"], 1, "nope.pbrt"),
        (["--scene", "builtin:teapot"], 1, "builtin:teapot"),
        (["--sampler", "nope"], 2, "'nope'"),
        (["--sampler", "golden"], 2, "golden"),
        (["--spp", "0"], 2, "--spp '0'"),
        (["--spp", "many"], 2, "--spp 'many'"),
        (["--spp", "8", "--spp-first", "6", "--spp-count", "4"], 2, "exceeds --spp 8"),
        (["--spp-count", "0"], 2, "--spp-count '0'"),
        (["--size", "0x10"], 2, "--size '0"),
        (["--strategy", "bdpt"], 2, "'bdpt'"),
        (["--maxdepth", "-1"], 2, "--maxdepth '-1'"),
        (["--randomize", "sideways"], 2, "'sideways'"),
        (["--rr-depth", "-2"], 2, "--rr-depth '-2'"),
        (["--solid-angle", "sometimes"], 2, "'sometimes'"),
        (["--threads", "0"], 2, "--threads '0'"),
        (["--frobnicate"], 2, "'--frobnicate'"),
        (["-o", "out.png"], 2, "'out.png'"),
        (["-o", "missing/out.exr"], 1, "missing"),
        (["--png", "missing/out.png"], 1, "missing"),
        (["-o", "good.exr", "--png", "missing/out.png"], 1, "missing"),
        (["reference"], 2, "reference needs -o"),
        (["merge", "-o", "out.exr"], 2, "merge needs"),
        (["compare", "a.exr"], 2, "compare needs"),
        (["compare", "a.exr", "b.exr"], 1, "'a.exr'"),
        (["--exact"], 2, "--exact is an option of udm1-pt compare"),
    ],
)
def test_bad_arguments(args, code, words, tmp_path):
    before = set(tmp_path.iterdir())
    r = run(*args, "--size", "8x8", cwd=tmp_path) if args[0] not in ("merge", "compare", "reference") \
        else run(*args, cwd=tmp_path)
    assert r.returncode == code, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("udm1-pt: ") and words in lines[0], r.stderr
    assert set(tmp_path.iterdir()) == before


def test_metal_and_glass_scene(tmp_path):
    # a gold sphere, a glass sphere (eta as pbrt's spectrum pairs) and a rough copper floor under a light
    scene = tmp_path / "metals.pbrt"
    scene.write_text(HEAD + """
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
Shape "trianglemesh" "point3 P" [ -1 3 -1  1 3 -1  1 3 1  -1 3 1 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
AttributeBegin
Translate -0.8 0 0
Shape "sphere" "float radius" [ 0.7 ]
AttributeEnd
Material "dielectric" "spectrum eta" [ 300 1.52 800 1.50 ]
AttributeBegin
Translate 0.8 0 0
Shape "sphere" "float radius" [ 0.7 ]
AttributeEnd
Material "conductor" "float roughness" [ 0.1 ]
Shape "trianglemesh" "point3 P" [ -5 -0.7 -5  5 -0.7 -5  5 -0.7 5  -5 -0.7 5 ] "integer indices" [ 0 1 2 0 2 3 ]
""")
    png = tmp_path / "metals.png"
    r = ok("--scene", str(scene), "--spp", "64", "--size", "64x48", "--png", str(png))
    assert r.stderr == "", r.stderr
    img = read_png(png)[..., :3]
    gold = img[26:32, 16:28].reshape(-1, 3).mean(axis=0)  # the gold sphere's lower half, reflecting the floor
    assert img.mean() > 0.05 and gold[0] > 1.5 * gold[2] and gold.mean() > 0.1, (img.mean(), gold)
    outs = [tmp_path / f"t{t}.exr" for t in ("1", "2")]
    for t, out in zip(("1", "2"), outs):
        ok("--scene", str(scene), "--spp", "16", "--size", "32x24", "--threads", t, "-o", str(out))
    assert outs[0].read_bytes() == outs[1].read_bytes()


def test_film_light_and_media_settings(tmp_path):
    light = ('AttributeBegin\nAreaLightSource "diffuse" "blackbody L" [ 3000 ] "float scale" [ 4 ] "bool twosided" true\n'
             'Shape "trianglemesh" "point3 P" [ -9 -9 3  9 -9 3  9 9 3  -9 9 3 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
             'AttributeEnd\n')
    means = {}
    for iso in (100, 250):
        scene = tmp_path / f"iso{iso}.pbrt"
        scene.write_text('Integrator "path"\n'
                         f'Film "rgb" "float iso" [ {iso} ]\n' + HEAD + light
                         + 'MakeNamedMedium "ink" "string type" "homogeneous" "rgb sigma_a" [ 1 2 3 ]\n'
                         + 'MediumInterface "ink" ""\n')
        r = ok("--scene", str(scene), "--spp", "4", "--size", "16x16", "-o", str(tmp_path / "x.exr"))
        # media are left out as pbrt-v4's path integrator leaves them out, and said so in one line
        assert re.fullmatch(r'udm1-pt: note: \S+:10: media are left out, as Integrator "path" leaves them out\n',
                            r.stderr), r.stderr
        means[iso] = mean_of(r)
    # a view straight into a 3000 K light of scale 4: luminance 4, warm; ISO 250 is 2.5 times brighter
    y = 0.2126 * means[100][0] + 0.7152 * means[100][1] + 0.0722 * means[100][2]
    assert abs(y - 4) < 0.02 and means[100][0] > means[100][1] > means[100][2], means[100]
    assert np.allclose(means[250], 2.5 * means[100], rtol=1e-5), means


TEX_SCENE = HEAD.replace("WorldBegin", 'Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]\nWorldBegin') + """
AttributeBegin
Material "diffuse" "rgb reflectance" [ 0 0 0 ]
AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true
Shape "trianglemesh" "point3 P" [ -50 -50 -9  50 -50 -9  50 50 -9  -50 50 -9 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
{textures}
{material}
Shape "trianglemesh" "point3 P" [ -3 -3 0  3 -3 0  3 3 0  -3 3 0 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]
      "integer indices" [ 0 1 2 0 2 3 ]
"""


def render_textured(tmp_path, name, textures, material, spp="16"):
    scene = tmp_path / f"{name}.pbrt"
    scene.write_text(TEX_SCENE.format(textures=textures, material=material))
    png = tmp_path / f"{name}.png"
    r = ok("--scene", str(scene), "--spp", spp, "--png", str(png), "-o", str(tmp_path / f"{name}.exr"))
    return read_png(png)[..., :3], mean_of(r)


def test_textures_and_mix(tmp_path):
    import matplotlib.image as mpimg

    # a 16 x 16 image, white on top and black below: pbrt looks images up at (u, 1 - v), so the top of
    # the quad (v = 1) is white
    half = np.zeros((16, 16, 3))
    half[:8] = 1
    mpimg.imsave(tmp_path / "half.png", half)
    tex = 'Texture "half" "spectrum" "imagemap" "string filename" "half.png" "string encoding" "linear"'
    img, _ = render_textured(tmp_path, "half", tex, 'Material "diffuse" "texture reflectance" "half"')
    top, bottom = img[3:10, 10:22].mean(), img[22:29, 10:22].mean()
    assert top > 0.3 and bottom < 0.05, (top, bottom)
    # 8-bit files decode from sRGB unless the texture says "linear": 50 % grey is 0.214 linear
    mpimg.imsave(tmp_path / "grey.png", np.full((2, 2, 3), 128 / 255))
    means = {}
    for enc in ("sRGB", "linear"):
        t = f'Texture "g" "spectrum" "imagemap" "string filename" "grey.png" "string encoding" "{enc}"'
        _, means[enc] = render_textured(tmp_path, f"grey-{enc}", t, 'Material "diffuse" "texture reflectance" "g"')
    ratio = means["sRGB"] / means["linear"]
    assert np.allclose(ratio, ((128 / 255 + 0.055) / 1.055) ** 2.4 / (128 / 255), rtol=1e-3), ratio
    # a scale texture, and a mix: a quarter white, three quarters black, chosen per point by a hash
    white = 'MakeNamedMaterial "white" "string type" "diffuse" "rgb reflectance" [ 1 1 1 ]\n'
    black = 'MakeNamedMaterial "black" "string type" "diffuse" "rgb reflectance" [ 0 0 0 ]\n'
    _, full = render_textured(tmp_path, "white", white, 'NamedMaterial "white"', spp="64")
    mix = 'MakeNamedMaterial "m" "string type" "mix" "string materials" [ "black" "white" ] "float amount" 0.25\n'
    _, quarter = render_textured(tmp_path, "mix", white + black + mix, 'NamedMaterial "m"', spp="64")
    assert np.allclose(quarter / full, 0.25, atol=0.02), quarter / full
    scaled = tex.replace('"half"', '"h0"') + '\nTexture "half" "spectrum" "scale" "texture tex" "h0" "float scale" 0.5'
    img2, _ = render_textured(tmp_path, "scaled", scaled, 'Material "diffuse" "texture reflectance" "half"')
    assert abs(img2[3:10, 10:22].mean() - top) > 0.05  # half as bright before the sRGB encoding of the PNG
    # bad textures: a missing file, an unknown texture, a float texture where a spectrum is needed
    for textures, material, words in (
        ('Texture "t" "spectrum" "imagemap" "string filename" "nothere.png"', 'Material "diffuse"', "nothere.png"),
        ("", 'Material "diffuse" "texture reflectance" "t"', 'texture "t" was not made'),
        ('Texture "t" "float" "imagemap" "string filename" "half.png"', 'Material "diffuse" "texture reflectance" "t"',
         "needs a spectrum texture"),
        ('Texture "t" "spectrum" "marble"', 'Material "diffuse"', '"marble" is not supported'),
    ):
        scene = tmp_path / "bad.pbrt"
        scene.write_text(TEX_SCENE.format(textures=textures, material=material))
        r = run("--scene", str(scene), "--spp", "1", "-o", str(tmp_path / "bad.exr"))
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 1 and len(lines) == 1 and str(scene) + ":" in lines[0] and words in lines[0], r.stderr
        assert not (tmp_path / "bad.exr").exists()


def test_thin_lens(tmp_path):
    import matplotlib.image as mpimg

    half = np.zeros((16, 16, 3))
    half[:8] = 1
    mpimg.imsave(tmp_path / "half.png", half)
    tex = 'Texture "half" "spectrum" "imagemap" "string filename" "half.png" "string encoding" "linear"'
    mat = 'Material "diffuse" "texture reflectance" "half"'
    grey = {}
    for name, lens in (("pinhole", ""), ("focused", '"float lensradius" 0.4 "float focaldistance" 5'),
                       ("blurred", '"float lensradius" 0.4 "float focaldistance" 2')):
        text = TEX_SCENE.replace('"float fov" [ 45 ]', '"float fov" [ 45 ] ' + lens).format(textures=tex, material=mat)
        scene = tmp_path / f"{name}.pbrt"
        scene.write_text(text)
        png = tmp_path / f"{name}.png"
        ok("--scene", str(scene), "--spp", "64", "--png", str(png))
        col = read_png(png)[:, 8:24, 1].mean(axis=1)  # the middle columns, top to bottom
        grey[name] = int(((col > 0.1) & (col < 0.8 * col.max())).sum())  # rows in the transition
    # the plane is 5 away: focused there, the edge is as sharp as the pinhole's; focused at 2, blurred
    assert grey["focused"] <= grey["pinhole"] + 1 and grey["blurred"] >= grey["pinhole"] + 4, grey


def test_reference_written_once_and_reused(tmp_path):
    ref = tmp_path / "ref.exr"
    r = ok("reference", "-o", str(ref), "--spp", "8", "--size", "16x16")
    assert RENDER_LINE.match(r.stdout), r.stdout
    stamp = ref.stat().st_mtime_ns
    r = ok("reference", "-o", str(ref), "--spp", "8", "--size", "16x16")
    assert r.stdout.startswith(f"reference {ref} reused") and ref.stat().st_mtime_ns == stamp
    r = ok("reference", "-o", str(ref), "--spp", "16", "--size", "16x16")  # other settings: rendered again
    assert RENDER_LINE.match(r.stdout) and ref.stat().st_mtime_ns != stamp


def test_sweep_against_a_reference(tmp_path):
    ref = tmp_path / "ref.exr"
    ok("reference", "-o", str(ref), "--spp", "256", "--size", "24x24")
    r = ok("sweep", "--against", str(ref), "--samplers", "pcg32,sobol-owen,wmmr", "--spps", "4,16",
           "--size", "24x24", "--images", str(tmp_path))
    rows = [line.split(",") for line in r.stdout.strip().splitlines()]
    assert rows[0] == ["sampler", "spp", "seed", "seconds", "paths", "rays", "rmse", "psnr", "mean_r", "mean_g", "mean_b"]
    assert [(x[0], x[1]) for x in rows[1:]] == [(s, n) for s in ("pcg32", "sobol-owen", "wmmr") for n in ("4", "16")]
    for s in ("pcg32", "sobol-owen", "wmmr"):
        e4, e16 = (float(x[6]) for x in rows[1:] if x[0] == s)
        assert e16 < e4, (s, e4, e16)  # more samples, less error
    assert (tmp_path / "wmmr-16spp.png").exists()


def test_screen_randomization_needs_a_weyl_sequence_or_zorder_sobol(tmp_path):
    for sampler, spp, words in (("pmj02", "4", "Weyl"), ("halton", "4", "Weyl"), ("sobol-owen", "12", "power-of-two")):
        r = run("--sampler", sampler, "--randomize", "screen", "--spp", spp, "--size", "8x8", "-o", str(tmp_path / "x.exr"))
        assert r.returncode != 0 and words in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
        assert not (tmp_path / "x.exr").exists()
    r = run("--randomize", "blue", "-o", str(tmp_path / "x.exr"))
    assert r.returncode != 0 and "screen" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr


BUILD = os.environ.get("UDM1_BUILD_DIR", "")


def test_wavefront_loop_traces_the_scalar_loops_estimator(tmp_path):
    """On the Cornell box udm1-pt's default loop is the wavefront loop of the diffuse subset (pt/wavefront_diffuse.h). --loop scalar traces
    the same estimator on the same sampler points in double: the two images differ by float rounding only
    (far below the noise, which their RMSE against a reference shows), with the same mean and about the
    same rays, for several samplers and without randomization too."""
    ref = tmp_path / "ref.exr"
    ok("reference", "-o", str(ref), "--spp", "256", "--size", "16x16")
    for sampler, randomize in (("wr", "default"), ("pmj02", "default"), ("pcg32", "default"), ("sobol", "none")):
        common = ["--size", "16x16", "--spp", "8", "--sampler", sampler, "--randomize", randomize]
        w = ok(*common, "-o", str(tmp_path / "w.exr"))
        s = ok(*common, "--loop", "scalar", "-o", str(tmp_path / "s.exr"))
        assert " loop wavefront " in w.stdout and " loop scalar " in s.stdout, (w.stdout, s.stdout)
        mw, ms = RENDER_LINE.match(w.stdout), RENDER_LINE.match(s.stdout)
        rays_w, rays_s = int(mw.group(10)), int(ms.group(10))
        assert abs(rays_w - rays_s) <= 0.01 * rays_s
        mean_w, mean_s = np.array(mw.group(11, 12, 13), float), np.array(ms.group(11, 12, 13), float)
        assert np.all(np.abs(mean_w - mean_s) <= 1e-4 * mean_s), (mean_w, mean_s)
        err = {k: float(re.match(r"mse \S+ rmse (\S+)", ok("compare", str(tmp_path / f"{k}.exr"), str(ref)).stdout).group(1))
               for k in ("w", "s")}
        diff = float(re.match(r"mse \S+ rmse (\S+)", ok("compare", str(tmp_path / "w.exr"), str(tmp_path / "s.exr")).stdout)
                     .group(1))
        assert err["s"] > 0.005 and diff < 1e-3 * err["s"] and abs(err["w"] - err["s"]) < 1e-3 * err["s"], (err, diff)


def rmse_between(a, b) -> float:
    return float(re.match(r"mse \S+ rmse (\S+)", ok("compare", str(a), str(b)).stdout).group(1))


def test_wavefront_loop_renders_every_scene(tmp_path):
    """Outside the diffuse subset the wavefront loop (the default) traces the scalar loop's own estimator path
    by path (pt/wavefront_general.h): the scalar loop's image bit for bit where Embree's streams find the hits
    of its single queries (triangles: the Cornell box with light sampling alone, veach-mis), and within float
    rounding where a sphere's hit moves by a rounding in Embree's stream code (the furnace, the test scene of
    every LightSource, the Crown): there the two images differ by less than a tenth of what two seeds differ
    by (the noise; the furnace, which has none, by less than 1e-5), with the same means. Every shared scene is checked where ../shared is present. An unknown
    --loop is a one-line error."""
    veach, crown, cornell = (SCENES / "veach-mis" / "veach-mis.pbrt", SCENES / "crown" / "crown.pbrt",
                             SCENES / "cornell-box" / "cornell-box.pbrt")
    cases = [(["--strategy", "nee", "--size", "16x16", "--spp", "4"], "wavefront-general", True),
             (["--scene", "builtin:furnace", "--size", "16x16", "--spp", "4"], "wavefront-general", False),
             (["--scene", str(ROOT / "tests" / "scenes" / "lights.pbrt"), "--size", "40x30", "--spp", "8"],
              "wavefront-general", False)]
    # (the shared scenes load large meshes again: the release suite renders them, the sanitized run the small cases)
    if veach.exists() and not os.environ.get("UDM1_SANITIZED"):
        cases += [(["--scene", str(veach), "--size", "48x32", "--spp", "4"], "wavefront-general", True),
                  (["--scene", str(crown), "--size", "24x32", "--spp", "2"], "wavefront-general", False),
                  (["--scene", str(cornell), "--size", "24x24", "--spp", "4"], "wavefront", False)]
    for args, loop, exact in cases:
        w = ok(*args, "-o", str(tmp_path / "w.exr"))
        s = ok(*args, "--loop", "scalar", "-o", str(tmp_path / "s.exr"))
        assert f" loop {loop} " in w.stdout and " loop scalar " in s.stdout, (args, w.stdout, s.stdout)
        same = run("compare", str(tmp_path / "w.exr"), str(tmp_path / "s.exr"), "--exact")
        if exact:
            assert "identical:" in same.stdout, (args, same.stdout)
            continue
        ok(*args, "--loop", "scalar", "--seed", "2", "-o", str(tmp_path / "s2.exr"))
        noise = rmse_between(tmp_path / "s2.exr", tmp_path / "s.exr")
        diff = rmse_between(tmp_path / "w.exr", tmp_path / "s.exr")
        mean_w = np.array(RENDER_LINE.match(w.stdout).group(11, 12, 13), float)
        mean_s = np.array(RENDER_LINE.match(s.stdout).group(11, 12, 13), float)
        assert diff < max(0.1 * noise, 1e-5), (args, diff, noise)  # (the furnace has no noise: 1e-5, a few float ulps)
        assert np.all(np.abs(mean_w - mean_s) <= 0.01 * mean_s + 1e-6), (args, mean_w, mean_s)
    if not veach.exists():
        print(f"shared scenes not checked: {SCENES} is absent")
    r = run("--size", "8x8", "--spp", "2", "--loop", "bogus", "-o", str(tmp_path / "x.exr"))
    assert r.returncode != 0 and "--loop 'bogus'" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "x.exr").exists()


@pytest.mark.skipif(not BUILD, reason="UDM1_BUILD_DIR (for udm1_bench_pt_embree) is not set: run through CTest")
def test_embree_share_benchmark_replays_the_render(tmp_path):
    """udm1_bench_pt_embree records every query of a render (it refuses to report if the count differs from
    the render's own ray count, or if the single and stream replays disagree on the hits) and prints
    Embree's share of the render time."""
    bench = pathlib.Path(BUILD) / "bin" / "udm1_bench_pt_embree"
    r = subprocess.run([str(bench), "--size", "16x16", "--spp", "2", "--reps", "1"], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    m = re.search(r"queries recorded: (\d+) \((\d+) intersect, (\d+) occluded\)", r.stdout)
    assert m and int(m.group(1)) == int(m.group(2)) + int(m.group(3)) > 16 * 16 * 2, r.stdout
    # the same render through the tool counts the same rays
    rays = int(RENDER_LINE.match(ok("--size", "16x16", "--spp", "2", "--sampler", "wr", "--loop", "scalar", "-o",
                                    str(tmp_path / "a.exr")).stdout).group(10))
    assert rays == int(m.group(1))
    share = re.search(r"Embree's share of udm1-pt's render time: ([0-9.]+) % \(single queries\), ([0-9.]+) % \(as "
                      r"streams\); without robust traversal ([0-9.]+) % \(single\), ([0-9.]+) %", r.stdout)
    # the shares are timings of a tiny render: that they are printed, not how large (a loaded machine can
    # stretch one replay past the render's own time)
    assert share and all(float(share.group(k)) > 0 for k in range(1, 5)), r.stdout
    hits = re.search(r"hits: (\d+) of (\d+) queries \(robust\), (\d+) \(not robust\)", r.stdout)
    assert hits and 0 < int(hits.group(1)) <= int(hits.group(2)) and 0 < int(hits.group(3)) <= int(hits.group(2)), r.stdout
    for args, words in ((["--sampler", "nope", "--size", "16x16"], "unknown sampler 'nope'"),
                        (["--size", "2x2"], "usage: udm1_bench_pt_embree"), (["--spp"], "usage")):
        bad = subprocess.run([str(bench), *args], capture_output=True, text=True, timeout=60)
        assert bad.returncode != 0 and words in bad.stderr and len(bad.stderr.strip().splitlines()) == 1, bad.stderr


def test_ab_tool_alternates_two_builds(tmp_path):
    """bench/ab_pt.py (the step A/Bs of BENCHMARKS.md): both binaries render every round, the summary
    gives each one's minimum and whether the images are identical (the same build twice: identical; a
    different sampler seed through a wrapper: different). Bad input is one line, exit 2, no file left."""
    ab = [sys.executable, str(ROOT / "bench" / "ab_pt.py")]
    r = subprocess.run([*ab, TOOL, TOOL, "--rounds", "2", "--", "--size", "8x8", "--spp", "2"], capture_output=True,
                       text=True, timeout=300, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stderr.count("[ab_pt] round") == 2, r.stderr
    assert re.search(r"old: .* min [0-9.]+ s, median [0-9.]+ s\nnew: .* min [0-9.]+ s", r.stdout), r.stdout
    assert "images: identical: " in r.stdout, r.stdout
    other = tmp_path / "other_seed.sh"
    other.write_text(f'#!/bin/sh\nexec "{TOOL}" "$@" --seed 9\n')
    other.chmod(0o755)
    r = subprocess.run([*ab, TOOL, str(other), "--rounds", "1", "--", "--size", "8x8", "--spp", "2"],
                       capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert r.returncode == 0 and re.search(r"images: different: \d+ of \d+ values", r.stdout), (r.stdout, r.stderr)
    # --instructions: the same build twice executes about the same instructions in its own code and Embree's
    # (callgrind, where valgrind is installed; its set-up and progress lines vary by a fraction of a per cent);
    # without valgrind on PATH, one line naming it (valgrind cannot run a sanitized build)
    if shutil.which("valgrind") and shutil.which("callgrind_annotate") and os.environ.get("UDM1_SANITIZED") != "1":
        r = subprocess.run([*ab, TOOL, TOOL, "--instructions", "--", "--size", "4x4", "--spp", "1", "--threads", "1"],
                           capture_output=True, text=True, timeout=600, cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        for binary in ("udm1-pt", "embree"):
            row = re.search(rf"^\| {binary} \| ([0-9.]+) \| ([0-9.]+) \| ([0-9.]+) \|$", r.stdout, re.M)
            assert row and float(row.group(1)) > 0 and abs(float(row.group(3)) - 1) < 0.05, r.stdout
    r = subprocess.run([*ab, TOOL, TOOL, "--instructions", "--", "--size", "4x4"], capture_output=True, text=True,
                       timeout=60, cwd=tmp_path, env=dict(os.environ, PATH="/nonexistent"))
    assert r.returncode == 2 and "needs valgrind" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    for args, words in (([str(tmp_path / "missing"), TOOL, "--"], "not an executable file"),
                        ([TOOL, TOOL, "--", "-o", "x.exr"], "must not name an output"),
                        ([TOOL, TOOL, "--rounds", "0"], "--rounds 0"),
                        ([TOOL, TOOL, "--rounds", "1", "--", "--sampler", "nope"], "unknown sampler 'nope'")):
        fails_cleanly(lambda *a, cwd=None: subprocess.run([*ab, *a], capture_output=True, text=True, cwd=cwd,
                                                          timeout=300), args, words, tmp_path, code=2)


def _cie():
    """The CIE 1931 tables and D65 at 1 nm over 360..830 nm (Mitsuba's copies), and linear sRGB from XYZ built
    as pbrt-v4 builds it (Rec. 709 primaries, the white point of the D65 table): an independent reference
    for the renderer's spectral conversions."""
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    lam = np.arange(360, 831, dtype=float)
    cmf = np.array([mi.cie1931_xyz(float(l)) for l in lam])
    d65 = np.array([mi.cie_d65(float(l)) for l in lam])
    w = d65 @ cmf
    w /= w[1]
    prim = np.array([[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]])
    p = np.array([[x / y, 1, (1 - x - y) / y] for x, y in prim]).T
    m = p * np.linalg.solve(p, w)
    return lam, cmf, d65, np.linalg.inv(m)


def _light_rgb(lam, cmf, rgb_from_xyz, values):
    xyz = values @ cmf
    return np.maximum(rgb_from_xyz @ (xyz / xyz[1]), 0)


def _albedo_rgb(lam, cmf, d65, rgb_from_xyz, values):
    return rgb_from_xyz @ ((values * d65) @ cmf) / (d65 @ cmf)[1]


def _fresnel_conductor(cos, eta, k):
    n = eta + 1j * k
    cost = np.sqrt(1 - (1 - cos * cos) / n ** 2)
    rs, rp = (cos - n * cost) / (cos + n * cost), (n * cos - cost) / (n * cos + cost)
    return (abs(rs) ** 2 + abs(rp) ** 2) / 2


SPECTRAL_HEAD = """LookAt 0 0 0  0 0 -1  0 1 0
Camera "perspective" "float fov" [ 2 ]
Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
Integrator "path" "integer maxdepth" [ {depth} ]
WorldBegin
"""


def test_spectra_become_rgb_as_pbrt_records_them(tmp_path):
    lam, cmf, d65, rgb_from_xyz = _cie()
    (tmp_path / "spds").mkdir()
    pairs = [(400, 0.2), (520, 1.0), (610, 1.7), (700, 0.4)]
    (tmp_path / "spds" / "warm.spd").write_text("# a warm light\n" + "".join(f"{a} {b}\n" for a, b in pairs))
    values = np.interp(lam, [a for a, _ in pairs], [b for _, b in pairs], left=0, right=0)
    want = 3 * _light_rgb(lam, cmf, rgb_from_xyz, values)
    inline = " ".join(f"{a} {b}" for a, b in pairs)
    # a light seen directly: its spectrum at luminance 1 times its scale, from a file or inline pairs
    for i, L in enumerate(['"spectrum L" "spds/warm.spd"', f'"spectrum L" [ {inline} ]']):
        scene = tmp_path / f"light{i}.pbrt"
        scene.write_text(SPECTRAL_HEAD.format(depth=0) + f'AreaLightSource "diffuse" {L} "float scale" [ 3 ]\n'
                         'Shape "trianglemesh" "point3 P" [ -5 -5 -4  5 -5 -4  5 5 -4  -5 5 -4 ] "integer indices" [ 0 1 2 0 2 3 ]\n')
        got = mean_of(ok("--scene", str(scene), "--spp", "4", "-o", str(tmp_path / f"light{i}.exr")))
        assert np.allclose(got, want, rtol=2e-4), (L, got, want)
    # a blackbody: Planck's law, luminance 1
    scene = tmp_path / "bb.pbrt"
    scene.write_text(SPECTRAL_HEAD.format(depth=0) + 'AreaLightSource "diffuse" "blackbody L" [ 3000 ]\n'
                     'Shape "trianglemesh" "point3 P" [ -5 -5 -4  5 -5 -4  5 5 -4  -5 5 -4 ] "integer indices" [ 0 1 2 0 2 3 ]\n')
    h, c, kb = 6.62606957e-34, 299792458.0, 1.3806488e-23
    planck = 1 / ((lam * 1e-9) ** 5 * (np.exp(h * c / (lam * 1e-9 * kb * 3000)) - 1))
    got = mean_of(ok("--scene", str(scene), "--spp", "4", "-o", str(tmp_path / "bb.exr")))
    assert np.allclose(got, _light_rgb(lam, cmf, rgb_from_xyz, planck), rtol=2e-4), got
    # a reflectance spectrum inside a sphere that emits 1 everywhere: one bounce of BSDF sampling sees
    # 1 + the reflectance's RGB under D65, exactly
    refl = [(380, 0.05), (480, 0.3), (600, 0.9), (760, 0.7)]
    values = np.interp(lam, [a for a, _ in refl], [b for _, b in refl], left=0, right=0)
    scene = tmp_path / "refl.pbrt"
    scene.write_text(SPECTRAL_HEAD.format(depth=1) + 'Material "diffuse" "spectrum reflectance" [ '
                     + " ".join(f"{a} {b}" for a, b in refl) + ' ]\n'
                     'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true\nShape "sphere" "float radius" [ 10 ]\n')
    got = mean_of(ok("--scene", str(scene), "--spp", "4", "--strategy", "bsdf", "-o", str(tmp_path / "refl.exr")))
    assert np.allclose(got, 1 + _albedo_rgb(lam, cmf, d65, rgb_from_xyz, values), rtol=2e-4), got


def test_reflectance_spectra_are_clamped_as_pbrt_clamps_them(tmp_path):
    # a reflectance spectrum above 1 or below 0 is clamped to [0, 1] at each wavelength (pbrt-v4's materials
    # clamp it; an rgb albedo above 1 is refused): inside a sphere that emits 1 everywhere, one bounce of BSDF
    # sampling sees 1 + the clamped spectrum's RGB under D65
    lam, cmf, d65, rgb_from_xyz = _cie()
    for refl in ([(400, 0), (500, 8), (600, 0.5), (700, 2)], [(380, -1), (500, 0.6), (780, 3)]):
        values = np.interp(lam, [a for a, _ in refl], [b for _, b in refl], left=0, right=0)
        scene = tmp_path / "refl.pbrt"
        scene.write_text(SPECTRAL_HEAD.format(depth=1) + 'Material "diffuse" "spectrum reflectance" [ '
                         + " ".join(f"{a} {b}" for a, b in refl) + ' ]\n'
                         'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true\nShape "sphere" "float radius" [ 10 ]\n')
        got = mean_of(ok("--scene", str(scene), "--spp", "4", "--strategy", "bsdf", "-o", str(tmp_path / "refl.exr")))
        want = 1 + _albedo_rgb(lam, cmf, d65, rgb_from_xyz, np.clip(values, 0, 1))
        assert np.allclose(got, want, rtol=2e-4), (refl, got, want)


def test_spectral_gold_reflects_as_pbrt_records_it(tmp_path):
    # a smooth gold mirror seen head-on, reflecting a white light behind the camera: each channel is the
    # spectral Fresnel reflectance projected as pbrt-v4's film records it (red above 1: out of gamut)
    import mitsuba as mi

    lam, cmf, d65, rgb_from_xyz = _cie()
    ior = pathlib.Path(mi.__file__).parent / "data" / "ior"
    eta, k = (np.loadtxt(ior / f"Au.{p}.spd", comments="#") for p in ("eta", "k"))
    r = _fresnel_conductor(1.0, np.interp(lam, eta[:, 0], eta[:, 1]), np.interp(lam, k[:, 0], k[:, 1]))
    want = _albedo_rgb(lam, cmf, d65, rgb_from_xyz, r)
    scene = tmp_path / "gold.pbrt"
    scene.write_text(SPECTRAL_HEAD.format(depth=1) +
                     'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true\n'
                     'Shape "trianglemesh" "point3 P" [ -50 -50 5  50 -50 5  50 50 5  -50 50 5 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
                     'AttributeEnd\nMaterial "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"\n'
                     'Shape "trianglemesh" "point3 P" [ -5 -5 -4  5 -5 -4  5 5 -4  -5 5 -4 ] "integer indices" [ 0 1 2 0 2 3 ]\n')
    got = mean_of(ok("--scene", str(scene), "--spp", "4", "-o", str(tmp_path / "gold.exr")))
    assert want[0] > 1 and np.allclose(got, want, rtol=1e-3), (got, want)


def test_directives_that_change_nothing_are_rendered_with_a_note(tmp_path):
    # Integrator "simplepath" and "randomwalk" converge to "path"'s image, an Accelerator does not change
    # it: rendered, the same image bit for bit, with one note line each naming file and line
    body = ('Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]\n' + HEAD
            + 'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\n'
              'Shape "trianglemesh" "point3 P" [ -1 2 -1  1 2 -1  1 2 1  -1 2 1 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
              'AttributeEnd\nShape "trianglemesh" "point3 P" [ -3 -1 -3  3 -1 -3  3 -1 3  -3 -1 3 ] '
              '"integer indices" [ 0 1 2 0 2 3 ]\n')
    images = {}
    for name, head in [("path", 'Integrator "path"\n'), ("simplepath", 'Integrator "simplepath" "integer maxdepth" [ 5 ]\n'),
                       ("randomwalk", 'Integrator "randomwalk"\n'), ("accel", 'Accelerator "kdtree" "integer maxprims" [ 4 ]\n')]:
        scene = tmp_path / f"{name}.pbrt"
        scene.write_text(head + body)
        out = tmp_path / f"{name}.exr"
        r = ok("--scene", str(scene), "--spp", "8", "-o", str(out))
        notes = [l for l in r.stderr.splitlines() if l.startswith("udm1-pt: note: ")]
        if name == "path":
            assert notes == [], r.stderr
        else:
            assert len(notes) == 1 and f"{scene}:1:" in notes[0], r.stderr
            assert ('renders as "path"' if name != "accel" else 'Accelerator "kdtree" ignored') in notes[0], r.stderr
        images[name] = out.read_bytes()
    assert images["simplepath"] == images["path"] == images["randomwalk"] == images["accel"]
    # a biased variant renders as the unbiased image, with a note saying so
    reg = tmp_path / "reg.pbrt"
    reg.write_text('Integrator "path" "bool regularize" true\n' + body)
    r = ok("--scene", str(reg), "--spp", "8", "-o", str(tmp_path / "reg.exr"))
    assert "regularize ignored: udm1-pt renders the unbiased image" in r.stderr, r.stderr
    assert (tmp_path / "reg.exr").read_bytes() == images["path"]


def test_the_scenes_pixelsamples_without_spp(tmp_path):
    scene = tmp_path / "s.pbrt"
    scene.write_text('Sampler "halton" "integer pixelsamples" [ 8 ]\n'
                     'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]\n' + HEAD + TRI)
    r = ok("--scene", str(scene), "-o", str(tmp_path / "a.exr"))
    assert RENDER_LINE.match(r.stdout).group(2) == "8", r.stdout
    notes = [l for l in r.stderr.splitlines() if l.startswith("udm1-pt: note: ")]
    assert any(f"{scene}:1: 8 samples per pixel" in n and '"halton"' in n for n in notes), r.stderr
    r = ok("--scene", str(scene), "--spp", "4", "-o", str(tmp_path / "b.exr"))  # --spp wins, nothing to say
    assert RENDER_LINE.match(r.stdout).group(2) == "4" and "samples per pixel" not in r.stderr, (r.stdout, r.stderr)
    # a sample range checked against the scene's count
    fails_cleanly(run, ["--scene", str(scene), "--spp-first", "8", "-o", "c.exr"], "--spp-first 8 is not below --spp 8",
                  tmp_path, code=2)


@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "tests" / "scenes").glob("*.pbrt")))
def test_the_project_scenes_render(name, tmp_path):
    # the scenes the accuracy benchmark compares with pbrt-v4 (bench/bench_accuracy.py): they render, every
    # channel finite and lit
    scene = ROOT / "tests" / "scenes" / f"{name}.pbrt"
    if "bsdfs/" in scene.read_text():  # (measured.pbrt: its tabulated BSDF files are written by their generator)
        write_test_files(tmp_path / "bsdfs")
        scene = pathlib.Path(shutil.copy(scene, tmp_path / scene.name))
    r = ok("--scene", str(scene), "--spp", "4", "--size", "40x30", "-o", str(tmp_path / "out.exr"))
    mean = mean_of(r)
    assert np.all(np.isfinite(mean)) and np.all(mean > 0.01), mean
    assert "warning" not in r.stdout, r.stdout


def test_screen_is_progressive_checkpoints_are_prefixes(tmp_path):
    # the path tracer's domains under progressive screen shifts: the first k samples of a longer render
    # are a k-sample render, bit for bit (scalar and wavefront loops)
    common = ["--sampler", "wmmr", "--size", "20x16", "--randomize", "screen"]
    ok(*common, "--spp", "8", "--checkpoints", "2,5", "-o", str(tmp_path / "ck.exr"))
    ok(*common, "--spp", "8", "--checkpoints", "2,5", "--exr-compression", "none", "-o", str(tmp_path / "raw.exr"))
    for k in (2, 5):
        ok(*common, "--spp", str(k), "--exr-compression", "none", "-o", str(tmp_path / f"s{k}.exr"))
        for name in (f"ck.{k}.exr", f"raw.{k}.exr"):
            r = ok("compare", str(tmp_path / name), str(tmp_path / f"s{k}.exr"), "--exact")
            assert "identical" in r.stdout and "mse 0 " in r.stdout, (name, r.stdout)
        assert [exr_compression(tmp_path / f) for f in (f"ck.{k}.exr", f"raw.{k}.exr", f"s{k}.exr")] == ["zip", "none", "none"]
