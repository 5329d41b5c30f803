"""udm1-pt's grid media (MakeNamedMedium "uniformgrid" and "cloud") through the whole tool: their parameters
change the image, the medium's transform places it, both path loops render the same image, bad grids are
refused with file and line (tests/cpp/test_pt_grid_media.cpp checks the majorants, the DDA and the closed
forms; bench/bench_accuracy.py compares the test scenes grid, grid-fire and cloud with pbrt-v4)."""

import pytest
from cli_checks import fails_cleanly
from pt_tool import TOOL, render_text, run

pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")

SCENE = """LookAt 0 0.5 -4  0 0.3 0  0 1 0
Camera "perspective" "float fov" [ 35 ]
Integrator "volpath" "integer maxdepth" [ 6 ]
WorldBegin
LightSource "point" "point3 from" [ 2 3 -2 ] "rgb I" [ 6 6 6 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -6 -1 -6  6 -1 -6  6 -1 6  -6 -1 6 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeBegin
{transform}
MakeNamedMedium "m" "string type" "{type}" {params}
AttributeEnd
AttributeBegin
Material "interface"
MediumInterface "m" ""
Shape "sphere" "float radius" [ 1.5 ]
AttributeEnd
"""
GRID = ('"integer nx" [ 2 ] "integer ny" [ 2 ] "integer nz" [ 2 ] "float density" [ 0 1 2 3 4 3 2 1 ] '
        '"point3 p0" [ -1 -1 -1 ] "point3 p1" [ 1 1 1 ]')
BASE = {"uniformgrid": dict(transform="", type="uniformgrid", params=GRID + ' "rgb sigma_s" [ 2 2 2 ] "rgb sigma_a" [ 0.5 0.5 0.5 ]'),
        "cloud": dict(transform="Translate -1 -1 -1\nScale 2 2 2", type="cloud", params='"float density" [ 1 ]')}


def render(tmp_path, fields, *args, name="s"):
    return render_text(tmp_path, SCENE.format(**fields), *args, name=name)


@pytest.mark.parametrize("kind,change", [
    ("uniformgrid", dict(params=GRID.replace("0 1 2 3 4 3 2 1", "4 3 2 1 0 1 2 3") + ' "rgb sigma_s" [ 2 2 2 ]')),
    ("uniformgrid", dict(params=BASE["uniformgrid"]["params"] + ' "float scale" [ 3 ]')),
    ("uniformgrid", dict(params=BASE["uniformgrid"]["params"] + ' "float g" [ 0.8 ]')),
    ("uniformgrid", dict(params=BASE["uniformgrid"]["params"] + ' "rgb Le" [ 1 1 1 ]')),
    ("uniformgrid", dict(params=BASE["uniformgrid"]["params"] + ' "float temperature" [ 900 1000 1100 1200 1300 1400 1500 1600 ]')),
    ("uniformgrid", dict(transform="Rotate 90 0 0 1")),
    ("cloud", dict(params='"float density" [ 1 ] "float wispiness" [ 3 ]')),
    ("cloud", dict(params='"float density" [ 1 ] "float frequency" [ 2 ]')),
    ("cloud", dict(params='"float density" [ 3 ]')),
    ("cloud", dict(params='"float density" [ 1 ] "rgb sigma_a" [ 0.2 0.4 0.8 ]')),
    ("cloud", dict(transform="Translate -1 -0.5 -1\nScale 2 2 2")),
])
def test_each_parameter_changes_the_image(kind, change, tmp_path):
    a, _ = render(tmp_path, BASE[kind], name="a")
    b, _ = render(tmp_path, {**BASE[kind], **change}, name="b")
    assert abs(a - b).max() > 0.01 * a.max(), (kind, change)


@pytest.mark.parametrize("kind", ["uniformgrid", "cloud"])
def test_loops_agree(kind, tmp_path):
    # the scalar loop and the wavefront loop's general path trace the same paths: the same image, bit for bit
    a, ra = render(tmp_path, BASE[kind], "--loop", "scalar", name="a")
    b, rb = render(tmp_path, BASE[kind], "--loop", "wavefront", name="b")
    assert (a == b).all() and a.mean() > 0.001, kind


G = 'MakeNamedMedium "m" "string type" "uniformgrid" '
HEAD = 'Integrator "volpath"\nLookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\nLightSource "point" "point3 from" [ 0 0 -5 ]\n'
TRI = 'MediumInterface "m" ""\nShape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0 ] "integer indices" [ 0 1 2 ]\n'


@pytest.mark.parametrize("params,words", [
    ('"integer nx" [ 2 ] "float density" [ 1 ]', "'density' has 1 values; nx ny nz need 2 x 1 x 1 = 2"),
    ('"integer ny" [ 0 ] "float density" [ 1 ]', "'ny' must be at least 1"),
    ('"integer nz" [ -3 ] "float density" [ 1 ]', "'nz' must be at least 1"),
    ('"float density" [ -1 ]', "'density' value 0 (-1.000000) must be finite and not negative"),
    ('', 'no "float density" values'),
    ('"integer nx" [ 2 ] "float density" [ 1 1 ] "float Lescale" [ 2 ]', "'Lescale' has 1 values; nx ny nz need 2 x 1 x 1 = 2"),
    ('"float density" [ 1 ] "float Lescale" [ -2 ]', "'Lescale' value 0 (-2.000000) must be finite and not negative"),
    ('"integer nx" [ 2 ] "float density" [ 1 1 ] "float temperature" [ 1000 ]', "'temperature' has 1 values"),
    ('"float density" [ 1 ] "float temperature" [ 1000 ] "rgb Le" [ 1 1 1 ]', 'both "Le" and "temperature"'),
    ('"float density" [ 1 ] "string preset" [ "Ketchup" ]', "unsupported parameter 'preset'"),
    ('"float density" [ 1 ] "point3 p0" [ 0 0 0 ] "point3 p1" [ 1 0 1 ]', "the box p0 p1 is empty along an axis"),
])
def test_bad_grids_refused_with_file_and_line(params, words, tmp_path):
    scene = tmp_path / "bad.pbrt"
    scene.write_text(HEAD + G + params + "\n" + TRI)
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr"], f"{scene}:6: ",
                      tmp_path, code=1)
    assert words in r.stderr, (words, r.stderr)


def test_bad_cloud_and_transform_refused(tmp_path):
    scene = tmp_path / "bad.pbrt"
    for text, words in [(HEAD + 'MakeNamedMedium "m" "string type" "cloud" "float scale" [ 2 ]\n' + TRI,
                         "unsupported parameter 'scale'"),
                        (HEAD + 'Scale 1 0 1\n' + G + '"float density" [ 1 ]\n' + TRI, "singular"),
                        ]:
        scene.write_text(text)
        r = run("--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr", cwd=tmp_path)
        assert r.returncode == 1 and f"{scene}:" in r.stderr and words in r.stderr, r.stderr
