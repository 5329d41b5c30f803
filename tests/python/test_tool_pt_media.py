"""udm1-pt's participating media through the whole tool (Integrator "volpath"): every medium parameter
changes the image as pbrt-v4 defines it (linear ones by their ratio exactly), MediumInterface and the camera's
medium put media where pbrt-v4 puts them, what pbrt-v4 refuses or udm1-pt does not model refused with file and
line (grid media named), what pbrt-v4 renders with a warning rendered with a note, media through the format's
rules (names resolved when the scene is complete, object instances in both loops, graphics state restored by
blocks and Imports, Attribute defaults, the default integrator and bdpt), the film's clamp and crop under
volpath, the test scenes and the Crown as distributed rendering (tests/cpp/test_pt_media.cpp checks the closed
forms)."""

import re
from pathlib import Path

import numpy as np
import pytest
from cli_checks import fails_cleanly
from pt_tool import TOOL, ok, read_exr, run

pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
ROOT = Path(__file__).resolve().parents[2]
CROWN = ROOT.parent / "shared" / "scenes" / "crown" / "crown-volpath.pbrt"


def render(tmp_path, text, *args, name="s"):
    """The scene text rendered to an EXR: (image, stderr)."""
    scene = tmp_path / f"{name}.pbrt"
    scene.write_text(text)
    out = tmp_path / f"{name}.exr"
    r = ok("--scene", str(scene), "-o", str(out), "--size", "8x8", *args, cwd=tmp_path)
    return read_exr(out), r.stderr


# A narrow view along +z through a box of medium (or around the camera) at an emitter of radiance 1.
VIEW = """{before}LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 1 ]
Integrator "{integrator}" "integer maxdepth" [ 5 ]
WorldBegin
AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
Shape "trianglemesh" "point3 P" [ -9 -9 5  9 -9 5  9 9 5  -9 9 5 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeEnd
{medium}
AttributeBegin
Material "{material}"
MediumInterface {interface}
Shape "trianglemesh" "point3 P" [ -1 -1 -0.5  1 -1 -0.5  1 1 -0.5  -1 1 -0.5  -1 -1 0.5  1 -1 0.5  1 1 0.5  -1 1 0.5 ]
    "integer indices" [ 0 2 1 0 3 2  4 5 6 4 6 7  0 5 4 0 1 5  3 6 2 3 7 6  0 7 3 0 4 7  1 6 5 1 2 6 ]
AttributeEnd
"""
MEDIUM = 'MakeNamedMedium "m" "string type" "homogeneous" {params}'
BASE = dict(before="", integrator="volpath", material="interface", interface='"m" ""',
            medium=MEDIUM.format(params='"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]'))


def mean_rgb(tmp_path, fields, *args):
    img, err = render(tmp_path, VIEW.format(**{**BASE, **fields}), "--spp", "8", *args)
    return img.reshape(-1, 3).mean(axis=0), err


def test_transmittance_and_interfaces(tmp_path):
    # the unit slab of ink: exp(-sigma_a); with the medium outside the box (its normals face out): 4.5 of it on
    # the way to the emitter; with the camera in it (MediumInterface before Camera) and no box: 10
    sig = np.array([0.5, 1, 2])
    inside, err = mean_rgb(tmp_path, {})
    assert err == "" and np.allclose(inside, np.exp(-sig), rtol=2e-4), (inside, err)
    outside, _ = mean_rgb(tmp_path, {"interface": '"" "m"'})
    assert np.allclose(outside, np.exp(-4.5 * sig), rtol=1e-3), outside
    thin = MEDIUM.format(params='"rgb sigma_a" [ 0.05 0.1 0.2 ] "rgb sigma_s" [ 0 0 0 ]')
    camera, _ = mean_rgb(tmp_path, {"before": thin + '\nMediumInterface "" "m"\n', "medium": "", "interface": '""'})
    assert np.allclose(camera, np.exp(-sig), rtol=1e-3), camera  # (10 x sigma / 10)
    # a medium on both sides is no transition: pbrt-v4 ignores it (the ray keeps the medium it is in)
    same, _ = mean_rgb(tmp_path, {"interface": '"m" "m"'})
    assert np.allclose(same, 1, rtol=1e-6), same
    # Integrator "path" leaves media out (a note says so), as pbrt-v4's PathIntegrator; the box is still invisible
    path, err = mean_rgb(tmp_path, {"integrator": "path"})
    assert np.allclose(path, 1, rtol=1e-6), path
    assert re.fullmatch(r'udm1-pt: note: \S+:9: media are left out, as Integrator "path" leaves them out\n', err), err


GLOW = '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ] "rgb Le" [ 1 2 3 ]'
# (parameter, the medium's parameters for the base image, changed, expected ratio of the means or None: differs)
PARAMETERS = [
    ("sigma_a", '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]', '"rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 0 0 0 ]', None),
    ("sigma_s", '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]', '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 1 1 1 ]', None),
    ("scale", '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]',
     '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ] "float scale" [ 2 ]', None),
    ("g", '"rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 3 3 3 ]', '"rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 3 3 3 ] '
     '"float g" [ 0.9 ]', None),
    ("preset", '"rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0 0 0 ]', '"string preset" "Wholemilk"', None),
    ("sigma_a default 1", '"rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 0 0 0 ]', '"rgb sigma_s" [ 0 0 0 ]', 1.0),
    ("Le", GLOW, GLOW.replace("[ 1 2 3 ]", "[ 2 4 6 ]"), 2.0),
    ("Lescale", GLOW, GLOW + ' "float Lescale" [ 3 ]', 3.0),
]


@pytest.mark.parametrize("name,base,changed,ratio", PARAMETERS, ids=[p[0] for p in PARAMETERS])
def test_each_medium_parameter_changes_the_image(name, base, changed, ratio, tmp_path):
    glow = "Le" in name
    a, _ = mean_rgb(tmp_path, {"medium": MEDIUM.format(params=base)})
    b, _ = mean_rgb(tmp_path, {"medium": MEDIUM.format(params=changed)})
    if ratio is None:
        assert np.abs(a - b).max() > 0.01 * a.max(), (name, a, b)
    elif glow:  # (the emitter behind adds exp(-sigma_a) to both)
        t = np.exp(-np.array([0.5, 1, 2]))
        assert np.allclose((b - t) / (a - t), ratio, rtol=1e-4), (name, a, b)
    else:
        assert np.allclose(b / a, ratio, rtol=1e-6), (name, a, b)


HEAD = ('Integrator "volpath"\nLookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\n'
        'LightSource "point" "point3 from" [ 0 0 -5 ]\n')
TRI = 'Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0 ] "integer indices" [ 0 1 2 ]\n'
HOMOGENEOUS = 'MakeNamedMedium "m" "string type" "homogeneous"'


@pytest.mark.parametrize("text,line,words", [
    (HEAD + HOMOGENEOUS + '\n' + HOMOGENEOUS + '\n' + TRI, 7, 'MakeNamedMedium "m" is made twice'),
    (HEAD + 'MakeNamedMedium "m" "rgb sigma_a" [ 1 1 1 ]\n' + TRI, 6, 'has no "string type"'),
    (HEAD + 'MakeNamedMedium "m" "string type" "fog"\n' + TRI, 6, '"fog" is not supported'),
    (HEAD + HOMOGENEOUS + ' "rgb sigma_a" [ 1 -1 1 ]\n' + TRI, 6, "'sigma_a' must not be negative"),
    (HEAD + HOMOGENEOUS + ' "float sigma_s" [ 1 ]\n' + TRI, 6, "'sigma_s' must be \"rgb\", \"spectrum\" or \"blackbody\""),
    (HEAD + HOMOGENEOUS + ' "spectrum sigma_a" [ 400 1 500 -1 ]\n' + TRI, 6, "'sigma_a' is negative at"),
    (HEAD + HOMOGENEOUS + ' "string preset" "Ketchup" "rgb sigma_a" [ 1 1 1 ]\n' + TRI, 6, "'sigma_a' with a preset"),
    (HEAD + HOMOGENEOUS + ' "float scale" [ -1 ]\n' + TRI, 6, "scale must not be negative"),
    (HEAD + HOMOGENEOUS + ' "rgb Le" [ 1 1 1 ] "float Lescale" [ -1 ]\n' + TRI, 6, "Lescale must not be negative"),
    (HEAD + HOMOGENEOUS + ' "float density" [ 1 ]\n' + TRI, 6, "unsupported parameter 'density'"),
    (HEAD + 'MediumInterface "" "nope"\n' + TRI, 6, 'medium "nope" was not made (used by the Shape at'),
    ('MediumInterface "nope"\n' + HEAD + TRI, 1, 'medium "nope" was not made (used by the Camera at'),
    (HEAD + 'Material "interface" "rgb reflectance" [ 1 1 1 ]\n' + TRI, 6, "unsupported parameter 'reflectance'"),
    (HEAD + 'MakeNamedMaterial "i" "string type" "interface"\nMakeNamedMaterial "d" "string type" "diffuse"\n'
     'Material "mix" "string materials" [ "d" "i" ]\n' + TRI, 8, 'a mix of the "interface" material ("i")'),
])
def test_refused_with_file_and_line(text, line, words, tmp_path):
    scene = tmp_path / "bad.pbrt"
    scene.write_text(text)
    fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr"], f"{scene}:{line}: ",
                  tmp_path, code=1)
    r = run("--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr", cwd=tmp_path)
    assert words in r.stderr, (words, r.stderr)


def test_rgbgrid_refused_where_rendered(tmp_path):
    # pbrt-v4's rgbgrid medium is not modelled: refused, named, where Integrator "volpath" renders something in
    # one ("nanovdb": test_tool_pt_nanovdb.py)
    grid_medium = 'MakeNamedMedium "smoke" "string type" "rgbgrid" "float density" [ 1 ]\n'
    text = HEAD + grid_medium + 'MediumInterface "smoke" ""\n' + TRI
    scene = tmp_path / "grid.pbrt"
    scene.write_text(text)
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "g.exr"], f"{scene}:6: ",
                      tmp_path, code=1)
    assert 'type "rgbgrid" is not modelled' in r.stderr, r.stderr
    # unused, or under Integrator "path" (media left out, with a note): rendered
    render(tmp_path, HEAD + grid_medium + TRI, "--spp", "1", name="unused")
    _, err = render(tmp_path, text.replace('"volpath"', '"path"'), "--spp", "1", name="path")
    assert "media are left out" in err, err


def test_notes_for_what_pbrt_renders_with_a_warning(tmp_path):
    # an unknown preset: pbrt-v4 warns and takes sigma_a and sigma_s from the parameters (default 1)
    a, err = mean_rgb(tmp_path, {"medium": MEDIUM.format(params='"string preset" "Tomato soup"')})
    assert re.fullmatch(r'udm1-pt: note: \S+:9: MakeNamedMedium "m": preset "Tomato soup" is not one of pbrt-v4\'s '
                        r'\(Apple, .*\): sigma_a and sigma_s are the parameters\' \(default 1\), as pbrt-v4 takes them\n',
                        err), err
    b, _ = mean_rgb(tmp_path, {"medium": MEDIUM.format(params='"rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 1 1 1 ]')})
    assert np.allclose(a, b), (a, b)
    # an area light on a shape with the interface material: pbrt-v4 leaves it out (the image black), so does udm1-pt
    text = ('Integrator "volpath"\nLookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\n'
            'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]\nMaterial "interface"\n'
            'Shape "trianglemesh" "point3 P" [ -9 -9 5  9 -9 5  9 9 5  -9 9 5 ] "integer indices" [ 0 2 1 0 3 2 ]\n')
    img, err = render(tmp_path, text, "--spp", "1")
    assert img.max() == 0, img.max()
    assert re.search(r'note: \S+:7: the AreaLightSource of a shape with the "interface" material is left out, as '
                     r'pbrt-v4 leaves it out \(1 shape\)\n', err), err


# --- media through the format's rules: names resolved when the scene is complete, instances, Import, Attribute

SCATTER = MEDIUM.format(params='"rgb sigma_a" [ 0.2 0.3 0.4 ] "rgb sigma_s" [ 1 1.5 2 ] "float g" [ 0.3 ]')
SIDE_LIGHT = 'LightSource "point" "point3 from" [ 0 3 0 ] "rgb I" [ 2 2 2 ]\n'


@pytest.mark.parametrize("loop", ["scalar", "wavefront"])
def test_media_through_object_instances(loop, tmp_path):
    # a shape's MediumInterface inside ObjectBegin goes with every instance of it (pbrt-v4 keeps it per shape):
    # the box scaled to 2 units of ink by its instance absorbs exp(-2 sigma_a), in both loops
    sig = np.array([0.5, 1, 2])
    view = VIEW.format(**{**BASE, "medium": BASE["medium"] + '\nObjectBegin "box"'})
    place = 'AttributeBegin\nTranslate 0 0 1\nScale 1 1 2\nObjectInstance "box"\nAttributeEnd\n'
    img, err = render(tmp_path, view + 'ObjectEnd\n' + place, "--spp", "8", "--loop", loop, name="ink")
    assert np.allclose(img.reshape(-1, 3).mean(axis=0), np.exp(-2 * sig), rtol=1e-3), img.reshape(-1, 3).mean(axis=0)
    # a scattering medium lit from the side: paths scatter in the instance and its shadow rays cross its faces;
    # the image of the same box written out under the instance's transform, within float rounding
    view = VIEW.format(**{**BASE, "medium": SIDE_LIGHT + SCATTER + '\nObjectBegin "box"'})
    a, _ = render(tmp_path, view + 'ObjectEnd\n' + place, "--spp", "16", "--loop", loop, name="inst")
    flat = VIEW.format(**{**BASE, "medium": SIDE_LIGHT + SCATTER + '\nTranslate 0 0 1\nScale 1 1 2'})
    b, _ = render(tmp_path, flat, "--spp", "16", "--loop", loop, name="flat")
    assert a.mean() > 0.05 and abs(a.mean() / b.mean() - 1) < 2e-4, (a.mean(), b.mean())


def test_media_and_interfaces_named_anywhere(tmp_path):
    # names are resolved when the scene is complete, as pbrt-v4 resolves them: a medium made in an Import after the
    # shape that names it, an "interface" material named before its MakeNamedMaterial; pbrt-v4 leaves out the area
    # light of a shape whose named material is "interface", wherever it is made
    sig = np.array([0.5, 1, 2])
    (tmp_path / "media.pbrt").write_text(BASE["medium"] + "\n")
    late = VIEW.format(**{**BASE, "medium": "", "material": "interface"}).replace('Material "interface"',
                                                                                   'NamedMaterial "i"')
    img, err = render(tmp_path, late + 'Import "media.pbrt"\nMakeNamedMaterial "i" "string type" "interface"\n')
    assert err == "" and np.allclose(img.reshape(-1, 3).mean(axis=0), np.exp(-sig), rtol=2e-4), err
    # (a two-sided light in front of a diffuse wall, which it would light)
    light = ('AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true\nNamedMaterial "i"\n'
             'Shape "trianglemesh" "point3 P" [ -9 -9 5  9 -9 5  9 9 5  -9 9 5 ] "integer indices" [ 0 2 1 0 3 2 ]\n'
             'AttributeEnd\n')
    make = 'MakeNamedMaterial "i" "string type" "interface"\n'
    head = ('Integrator "volpath"\nLookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\n'
            'Shape "trianglemesh" "point3 P" [ -20 -20 9  20 -20 9  20 20 9  -20 20 9 ]\n'
            '  "integer indices" [ 0 2 1 0 3 2 ]\n')
    for name, text in [("before", head + make + light), ("after", head + light + make)]:
        img, err = render(tmp_path, text, "--spp", "1", name=name)
        assert img.max() == 0 and "is left out, as pbrt-v4 leaves it out (1 shape)" in err, (name, img.max(), err)


def test_medium_state_in_blocks_and_imports(tmp_path):
    # MediumInterface is graphics state: an Import's shapes take the interface current in it, and AttributeEnd,
    # ObjectEnd and the end of an Import restore it: an interface quad after each, in front of the box, is no
    # transition (were "m" "" still current, the camera ray would cross 4 more units of ink behind it)
    sig = np.array([0.5, 1, 2])
    box = VIEW.format(**BASE).split("AttributeEnd\n", 1)[1]  # (the medium and the box, outside any block)
    box = box.replace("AttributeBegin\n", "").replace("AttributeEnd\n", "")
    (tmp_path / "box.pbrt").write_text(box)
    head = VIEW.format(**{**BASE, "medium": ""}).split("AttributeBegin\nMaterial", 1)[0]
    front = ('Material "interface"\n'
             'Shape "trianglemesh" "point3 P" [ -9 -9 -4  9 -9 -4  9 9 -4  -9 9 -4 ]\n'
             '  "integer indices" [ 0 2 1 0 3 2 ]\n')
    for name, text in [("import", head + 'Import "box.pbrt"\n'),
                       ("attribute", head + "AttributeBegin\n" + box + "AttributeEnd\n"),
                       ("object", head + 'ObjectBegin "b"\n' + box + 'ObjectEnd\nObjectInstance "b"\n')]:
        img, err = render(tmp_path, text + front, "--spp", "8", name=name)
        got = img.reshape(-1, 3).mean(axis=0)
        assert err == "" and np.allclose(got, np.exp(-sig), rtol=2e-4), (name, got, err)


def test_integrators_and_defaults_with_media(tmp_path):
    # pbrt-v4's default integrator is "volpath", and its bdpt samples media as volpath does: both render the ink;
    # its sppm leaves media out as path does (a note says so)
    sig = np.array([0.5, 1, 2])
    text = VIEW.format(**BASE)
    img, err = render(tmp_path, text.replace('Integrator "volpath" "integer maxdepth" [ 5 ]\n', ""), "--spp", "8",
                      name="default")
    assert err == "" and np.allclose(img.reshape(-1, 3).mean(axis=0), np.exp(-sig), rtol=2e-4), err
    bdpt, err = mean_rgb(tmp_path, {"integrator": "bdpt"})
    assert np.allclose(bdpt, np.exp(-sig), rtol=2e-4) and 'Integrator "bdpt" renders as "volpath"' in err, (bdpt, err)
    sppm, err = mean_rgb(tmp_path, {"integrator": "sppm"})
    assert np.allclose(sppm, 1, rtol=1e-6) and "media are left out" in err, (sppm, err)


def test_attribute_defaults_of_media(tmp_path):
    # Attribute "medium" gives defaults to later MakeNamedMedium: the medium's own parameters win, and a preset
    # takes its coefficients over a default sigma_a (pbrt-v4 never calls an Attribute default unused)
    default, err = mean_rgb(tmp_path, {"medium": 'Attribute "medium" "float scale" [ 2 ] "rgb sigma_a" [ 9 9 9 ]\n' +
                                                 BASE["medium"]})
    assert err == "" and np.allclose(default, np.exp(-2 * np.array([0.5, 1, 2])), rtol=2e-4), (default, err)
    milk = MEDIUM.format(params='"string preset" "Wholemilk"')
    preset, _ = mean_rgb(tmp_path, {"medium": milk})
    with_default, err = mean_rgb(tmp_path, {"medium": 'Attribute "medium" "rgb sigma_a" [ 9 9 9 ]\n' + milk})
    assert err == "" and np.allclose(with_default, preset, rtol=1e-6), (with_default, preset, err)


def test_volpath_film_clamp_and_crop(tmp_path):
    # the film's maxcomponentvalue and cropwindow act on volpath's samples as on path's: every sample of a glowing
    # medium scaled so that its largest CIE XYZ value is at most 1 (so is their mean), and a crop that is the
    # window of the whole render, bit for bit
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    glow = MEDIUM.format(params='"rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 0.5 0.5 0.5 ] "rgb Le" [ 40 20 10 ]')
    free, _ = mean_rgb(tmp_path, {"medium": SIDE_LIGHT + glow})
    film = 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "float maxcomponentvalue" [ 1 ]\n'
    clamped, _ = mean_rgb(tmp_path, {"medium": SIDE_LIGHT + glow, "before": film})
    assert (xyz @ free).max() > 4 and (xyz @ clamped).max() < 1 + 1e-3, (free, clamped)
    text = VIEW.format(**{**BASE, "medium": SIDE_LIGHT + SCATTER})
    crop = 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "float cropwindow" [ 0.25 0.75 0 0.5 ]\n'
    whole, _ = render(tmp_path, text, "--spp", "4", name="whole")
    part, err = render(tmp_path, crop + text, "--spp", "4", name="crop")
    assert whole.mean() > 0.05 and part.shape == (4, 4, 3) and np.array_equal(part, whole[0:4, 2:6]), err


def test_export_refuses_media(tmp_path):
    # scene.json has surfaces only: a scene whose media volpath renders is refused, not written without them
    scene = tmp_path / "m.pbrt"
    scene.write_text(VIEW.format(**BASE))
    r = fails_cleanly(run, ["export", str(tmp_path / "out"), "--scene", str(scene)], f"{scene}:9: ", tmp_path, code=1)
    assert "export writes no participating media" in r.stderr, r.stderr


@pytest.mark.parametrize("name", ["media", "ruby", "fog", "grid", "grid-fire", "cloud"])
def test_test_scenes_render(name, tmp_path):
    scene = ROOT / "tests" / "scenes" / f"{name}.pbrt"
    r = ok("--scene", str(scene), "--spp", "2", "--size", "16x12", "-o", str(tmp_path / "x.exr"))
    assert r.stderr == "" and " loop wavefront-general " in r.stdout, (r.stderr, r.stdout)
    assert read_exr(tmp_path / "x.exr").mean() > 0.01


@pytest.mark.skipif(not CROWN.exists(), reason=f"{CROWN} is absent: the shared scenes are not here")
def test_crown_as_distributed_renders(tmp_path):
    # Integrator "volpath" with maximum depth 100 and its gems' media, as distributed: red and blue gems, and
    # the one note is the camera's sensor, which renders as cie1931
    out = tmp_path / "crown.exr"
    r = ok("--scene", str(CROWN), "--spp", "2", "--size", "40x56", "-o", str(out))
    assert re.fullmatch(r'udm1-pt: note: \S+crown-volpath.pbrt:8: Film: sensor "canon_eos_5d_mkiv" [^\n]+\n',
                        r.stderr), r.stderr
    img = read_exr(out)
    assert img.shape == (56, 40, 3) and 0.1 < img.mean() < 0.9, img.mean()
