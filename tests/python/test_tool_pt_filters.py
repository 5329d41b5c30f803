"""udm1-pt's pixel filters are pbrt-v4's (box, gaussian - its default -, mitchell, sinc, triangle, with their
radii and parameters), by filter importance sampling as pbrt-v4 does: an emitter's sharp edge against black
renders, pixel by pixel, as the edge convolved with the filter pbrt-v4 tabulates (its closed form here), and
as pbrt-v4 renders it (where the pbrt-v4 anchor is built: $UDM1_PBRT or build/anchors/pbrt-v4-build/pbrt);
negative lobes carry their sign (a weight channel W in the exact sums, merged exactly); both path loops and
any thread count draw the same bits; an unknown filter or a bad parameter is refused with file:line."""

import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
from cli_checks import fails_cleanly
from pt_tool import TOOL, ok, read_exr, run

pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
ROOT = Path(__file__).resolve().parents[2]
PBRT = os.environ.get("UDM1_PBRT") or str(ROOT / "build" / "anchors" / "pbrt-v4-build" / "pbrt")

W, H, FOV, Z = 32, 8, 30, 10.0
EDGE = 16.3  # the emitter covers the film left of x = EDGE (raster x, pixels)


def edge_x(e):
    """The camera-space X at depth Z of the film's column e (pbrt-v4's perspective camera, looking down +z)."""
    aspect = W / H
    return (e - W / 2) / (W / 2) * aspect * Z * math.tan(math.radians(FOV / 2))


def edge_scene(filt, slant=0.0, material='Material "diffuse" "rgb reflectance" [ 0 0 0 ]', spp=1024, xe=None):
    xe = edge_x(EDGE) if xe is None else xe
    y0, y1 = -20, 20
    p = [-50, y0, Z, xe + slant * y0, y0, Z, xe + slant * y1, y1, Z, -50, y1, Z]
    return (f'{filt}\nFilm "rgb" "integer xresolution" [ {W} ] "integer yresolution" [ {H} ] "string filename" "out.exr"\n'
            f'Sampler "zsobol" "integer pixelsamples" [ {spp} ]\nIntegrator "path" "integer maxdepth" [ 1 ]\n'
            f'Camera "perspective" "float fov" [ {FOV} ]\nWorldBegin\n'
            f'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true\n{material}\n'
            f'Shape "trianglemesh" "point3 P" [ {" ".join(map(str, p))} ] "integer indices" [ 0 1 2 0 2 3 ]\n')


def pt(tmp_path, name, text, *args):
    scene = tmp_path / f"{name}.pbrt"
    scene.write_text(text)
    out = tmp_path / f"{name}.exr"
    ok("--scene", str(scene), "-o", str(out), "--spp", "1024", *args)
    return read_exr(out)


# pbrt-v4's filters along one axis (filters.h), and their defaults (filters.cpp), written out here
def gaussian(x, s):
    return np.exp(-x * x / (2 * s * s)) / math.sqrt(2 * math.pi * s * s)


def mitchell(x, b, c):
    x = np.abs(x)
    near = ((12 - 9 * b - 6 * c) * x ** 3 + (-18 + 12 * b + 6 * c) * x ** 2 + (6 - 2 * b)) / 6
    far = ((-b - 6 * c) * x ** 3 + (6 * b + 30 * c) * x ** 2 + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6
    return np.where(x <= 1, near, np.where(x <= 2, far, 0.0))


def f1(kind, x, r, p):
    if kind == "box":
        return (np.abs(x) <= r).astype(float)
    if kind == "triangle":
        return np.maximum(0, r - np.abs(x))
    if kind == "gaussian":
        return np.maximum(0, gaussian(x, p.get("sigma", 0.5)) - gaussian(r, p.get("sigma", 0.5)))
    if kind == "mitchell":
        return mitchell(2 * x / r, p.get("B", 1 / 3), p.get("C", 1 / 3))
    return np.where(np.abs(x) > r, 0.0, np.sinc(x) * np.sinc(x / p.get("tau", 3)))  # sinc (np.sinc is sin(pi x)/(pi x))


RADIUS = {"box": 0.5, "gaussian": 1.5, "mitchell": 2, "sinc": 4, "triangle": 2}


def expected_columns(kind, params):
    """Each column's value for the vertical edge: the integral of the filter (as pbrt-v4 samples it: tabulated at
    32 cells per unit of radius, piecewise constant, for gaussian, mitchell and sinc) over the part of the pixel's
    footprint left of the edge, over its whole integral."""
    r = params.get("xradius", RADIUS[kind])
    if kind in ("gaussian", "mitchell", "sinc"):
        n = int(32 * r)
        centres = -r + (np.arange(n) + 0.5) / n * 2 * r
        fine = np.linspace(-r, r, 64 * n + 1)[:-1] + r / (64 * n)  # 64 points per cell: the cell's constant
        values = f1(kind, centres, r, params)[np.minimum(((fine + r) / (2 * r) * n).astype(int), n - 1)]
    else:
        fine = np.linspace(-r, r, 200001)[:-1] + r / 200000
        values = f1(kind, fine, r, params)
    cols = np.arange(W)
    inside = (cols[:, None] + 0.5 + fine[None, :]) < EDGE
    return (values[None, :] * inside).sum(axis=1) / values.sum()


FILTERS = [
    ("box", {}), ("box", {"xradius": 1.2}), ("gaussian", {}), ("gaussian", {"xradius": 2.2, "sigma": 0.8}),
    ("triangle", {"xradius": 1.3}), ("mitchell", {}), ("mitchell", {"xradius": 3, "B": 0, "C": 0.8}),
    ("sinc", {"xradius": 2.5, "tau": 2}),
]


def filter_line(kind, params):
    if kind == "gaussian" and not params:
        return ""  # (pbrt-v4's default: no PixelFilter line)
    return f'PixelFilter "{kind}" ' + " ".join(f'"float {k}" [ {v} ]' for k, v in params.items())


@pytest.mark.parametrize("kind,params", FILTERS, ids=[f"{k}-{'-'.join(map(str, p.values())) or 'default'}" for k, p in FILTERS])
def test_an_edge_is_convolved_with_the_filter(kind, params, tmp_path):
    img = pt(tmp_path, "edge", edge_scene(filter_line(kind, params)))
    columns = img.mean(axis=(0, 2))  # (the edge is vertical: every row alike)
    want = expected_columns(kind, params)
    err = np.abs(columns - want)
    assert err.max() < 0.006, (kind, params, np.round(columns[12:20], 4), np.round(want[12:20], 4))
    if kind in ("mitchell", "sinc"):  # negative lobes: a dark ring outside the edge
        assert columns.min() < -0.015 and want.min() < -0.015


@pytest.mark.skipif(not os.path.isfile(PBRT), reason="pbrt-v4 (the anchor) is not built")
@pytest.mark.parametrize("kind,params", FILTERS, ids=[f"{k}-{'-'.join(map(str, p.values())) or 'default'}" for k, p in FILTERS])
def test_pixels_as_pbrt_v4_renders_them(kind, params, tmp_path):
    # a slanted edge (each row at another sub-pixel offset, both axes of the filter at work) rendered by both;
    # the emitter is white, so that pbrt-v4's spectral samples and udm1-pt's RGB agree, up to their noise
    text = edge_scene(filter_line(kind, params), slant=0.3)
    mine = pt(tmp_path, "mine", text).mean(axis=2)
    (tmp_path / "pbrt.pbrt").write_text(text)
    r = subprocess.run([PBRT, "--nthreads", "1", "--quiet", "--outfile", str(tmp_path / "pbrt.exr"), str(tmp_path / "pbrt.pbrt")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    theirs = read_exr(tmp_path / "pbrt.exr").mean(axis=2)
    err = np.abs(mine - theirs)
    assert err.max() < 0.03 and err.mean() < 0.004, (kind, params, err.max(), err.mean())
    assert np.abs(theirs - (theirs > 0.5)).max() > 0.2  # (the edge is there, blurred)


@pytest.mark.parametrize("kind", ["gaussian", "mitchell"])
def test_same_bits_in_every_loop_thread_count_and_split(kind, tmp_path):
    # 1 and 2 threads, two sample ranges merged: the same sums, the weight channel W included; the general
    # wavefront (a conductor) and the scalar loop: the same bits; the diffuse wavefront (float SIMD shading) and
    # the scalar loop: the same within float rounding
    line = filter_line(kind, {}) if kind != "gaussian" else 'PixelFilter "gaussian" "float sigma" [ 0.6 ]'
    floor = 'Shape "trianglemesh" "point3 P" [ -9 -3 5  9 -3 5  9 -3 30  -9 -3 30 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
    for material, loop in (('Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]', "wavefront"),
                           ('Material "conductor" "float roughness" [ 0.2 ]', "wavefront-general")):
        text = edge_scene(line, slant=0.3, material=material).replace('"integer maxdepth" [ 1 ]', '"integer maxdepth" [ 3 ]')
        text += floor
        (tmp_path / "s.pbrt").write_text(text)
        common = ["--scene", str(tmp_path / "s.pbrt"), "--spp", "32"]
        r = ok(*common, "--threads", "2", "-o", str(tmp_path / "a.exr"))
        assert f" loop {loop} " in r.stdout, r.stdout
        ok(*common, "--threads", "1", "-o", str(tmp_path / "b.exr"))
        ok(*common, "--loop", "scalar", "-o", str(tmp_path / "s.exr"))
        for first, count in ((0, 12), (12, 20)):
            ok(*common, "--spp-first", str(first), "--spp-count", str(count), "-o", str(tmp_path / f"part{first}.exr"))
        ok("merge", str(tmp_path / "part0.exr"), str(tmp_path / "part12.exr"), "-o", str(tmp_path / "m.exr"))
        exact = ["b", "m"] + (["s"] if loop == "wavefront-general" else [])
        for k in exact:
            r = ok("compare", str(tmp_path / f"{k}.exr"), str(tmp_path / "a.exr"), "--exact")
            assert "identical" in r.stdout, (material, k, r.stdout)
        a, s_ = read_exr(tmp_path / "a.exr"), read_exr(tmp_path / "s.exr")
        assert np.abs(a - s_).max() < 1e-5 and np.abs(a).max() > 0.1, (material, np.abs(a - s_).max())


def channels(path):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return [f.name for f in mi.Bitmap(str(path)).struct_()]


def test_negative_weights_sum_in_a_weight_channel(tmp_path):
    # mitchell's negative lobes: the EXR's exact sums hold W (the samples' signs), and the pixel is the weighted
    # mean: an emitter filling the view is 1 in every pixel although some samples weigh -1 (their mean sign is
    # below 1: without W the pixels would be that mean)
    flat = edge_scene('PixelFilter "mitchell"', xe=50)
    img = pt(tmp_path, "flat", flat)
    assert np.abs(img - 1).max() < 1e-6, np.abs(img - 1).max()
    assert "sum.W.hi" in channels(tmp_path / "flat.exr")
    pt(tmp_path, "gauss", edge_scene(""))
    assert "sum.W.hi" not in channels(tmp_path / "gauss.exr")  # (filters without negative lobes: R, G, B only)


def test_no_filter_line_is_pbrt_v4s_gaussian(tmp_path):
    # without a PixelFilter line the film is pbrt-v4's gaussian (radius 1.5, sigma 0.5): the same bits as the line
    a = pt(tmp_path, "none", edge_scene(""))
    b = pt(tmp_path, "line", edge_scene('PixelFilter "gaussian" "float xradius" [ 1.5 ] "float yradius" [ 1.5 ] "float sigma" [ 0.5 ]'))
    c = pt(tmp_path, "box", edge_scene('PixelFilter "box"'))
    assert np.array_equal(a, b) and not np.array_equal(a, c)


@pytest.mark.parametrize("line,lineno,words", [
    ('PixelFilter "lanczos"', 1, ['PixelFilter "lanczos"', "box, gaussian, mitchell, sinc, triangle"]),
    ('PixelFilter "gaussian"\n "float xradius" [ 0 ]', 2, ["xradius must be positive"]),
    ('PixelFilter "box" "float yradius" [ -1 ]', 1, ["yradius must be positive"]),
    ('PixelFilter "gaussian" "float sigma" [ -0.5 ]', 1, ["sigma must be positive"]),
    ('PixelFilter "sinc" "float tau" [ 0 ]', 1, ["tau must be positive"]),
    ('PixelFilter "mitchell" "float xradius" [ 0.02 ]', 1, ["below 1/32"]),
    ('PixelFilter "gaussian" "float sigma" [ 0.0001 ]', 1, ["zero at every cell"]),
    ('PixelFilter "gaussian" "float alpha" [ 2 ]', 1, ["unsupported parameter 'alpha'"]),  # (pbrt-v3's)
    ('PixelFilter "box" "float sigma" [ 2 ]', 1, ["unsupported parameter 'sigma'"]),
    ('PixelFilter "triangle" "float xradius" [ 5000 ]', 1, ["above 1024"]),
])
def test_bad_filters_refused_with_file_and_line(line, lineno, words, tmp_path):
    (tmp_path / "bad.pbrt").write_text(line + "\n" + edge_scene("").split("\n", 1)[1])
    r = fails_cleanly(run, ["--scene", "bad.pbrt", "--spp", "1", "-o", "x.exr"], f"bad.pbrt:{lineno}:", tmp_path, 1)
    assert all(w in r.stderr for w in words), r.stderr
