"""udm1-pt reads the scene format as pbrt-v4 reads it, through the whole tool: file names relative to the main
scene file (in included files too), gzip-compressed includes and meshes, parameter lists that go on after an
Include, names (materials, textures, objects) resolved when the scene is complete, named coordinate systems,
ActiveTransform and the camera's shutter, Attribute defaults, Import, object instancing (an instance renders
as the same shapes written out under the composed transform, in both path loops), the film's
maxcomponentvalue (each sample clamped as computed here) and cropwindow/pixelbounds (the window of the whole
render, bit for bit); what pbrt-v4 renders to the same image accepted with a note, and what udm1-pt does not
model refused with file:line."""

import gzip
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest
from cli_checks import fails_cleanly

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = os.environ.get("UDM1_PT_TOOL", "")
AO_TOOL = os.environ.get("UDM1_AO_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
MEAN = re.compile(r" mean (\S+) (\S+) (\S+)\n")

HEAD = ('LookAt 0 4 -8  0 0.5 0  0 1 0\nCamera "perspective" "float fov" [ 40 ]\n'
        'Film "rgb" "integer xresolution" [ 20 ] "integer yresolution" [ 16 ]\n')
LIGHTS = ('LightSource "infinite" "rgb L" [ 0.3 0.3 0.3 ]\n'
          'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\n'
          'Shape "trianglemesh" "point3 P" [ -1 5 -1  1 5 -1  1 5 1  -1 5 1 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
          'AttributeEnd\n')
FLOOR = ('Shape "trianglemesh" "point3 P" [ -4 0 -4  4 0 -4  4 0 4  -4 0 4 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]\n'
         '  "integer indices" [ 0 1 2 0 2 3 ]\n')
SPP = ["--spp", "4", "--seed", "2"]


def run(*args, cwd=None, tool=None):
    return subprocess.run([tool or TOOL, *args], capture_output=True, text=True, cwd=cwd, timeout=600)


def read_exr(path):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(str(path)), dtype=np.float64)[..., :3]


def write(folder, name, text):
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(text) if isinstance(text, bytes) else path.write_text(text)
    return path


def render(scene, *args, cwd=None, tool=None):
    """The scene file rendered to an EXR next to it: (image, stderr)."""
    out = scene.with_name(scene.name.split(".")[0] + "-out.exr")
    r = run("--scene", str(scene), "-o", str(out), *SPP, *args, cwd=cwd or scene.parent, tool=tool)
    assert r.returncode == 0, r.stderr
    return read_exr(out), r.stderr


def scene(folder, name, world, head=HEAD):
    return write(folder, name, head + "WorldBegin\n" + LIGHTS + world)


def refused(folder, text, line, words, name="s.pbrt"):
    """The scene is refused with one line naming its file and line (0: the folder) and the words, and no file."""
    path = write(folder, name, text)
    where = f"{path}:{line}:" if line else str(folder)
    r = fails_cleanly(run, ["--scene", str(path), "--spp", "1", "-o", "out.exr"], words, folder, code=1)
    assert where in r.stderr, (where, r.stderr)


# --- file names, gzip, includes ----------------------------------------------------------------------------

def ply_text(offset):
    return ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            f"{offset} 0.2 0\n{offset + 1.5} 0.2 0\n{offset} 1.7 0.5\n3 0 1 2\n")


def texture_png(path):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    rgb = np.zeros((4, 4, 3), np.uint8)
    rgb[..., 0] = np.arange(4)[:, None] * 60 + 20
    rgb[..., 1] = np.arange(4)[None, :] * 50 + 30
    rgb[..., 2] = 90
    path.parent.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(rgb).write(str(path))


MATERIALS = ('Texture "map" "spectrum" "imagemap" "string filename" "textures/map.png" "string filter" "point"\n'
             'MakeNamedMaterial "floor" "string type" "diffuse" "texture reflectance" "map"\n'
             'MakeNamedMaterial "lit" "string type" "diffuse" "spectrum reflectance" "spds/flat.spd"\n')
SHAPES = ('NamedMaterial "floor"\n' + FLOOR + 'NamedMaterial "lit"\n'
          'Shape "plymesh" "string filename" "meshes/tri.ply"\n')


def test_file_names_are_relative_to_the_main_scene_file(tmp_path):
    # an include in a subfolder names a texture, a mesh, a spectrum and a further include by their paths from
    # the main file's folder, as pbrt-v4 resolves them; from any working directory
    texture_png(tmp_path / "textures" / "map.png")
    write(tmp_path, "meshes/tri.ply", ply_text(-1))
    write(tmp_path, "spds/flat.spd", "400 0.6\n700 0.6\n")
    write(tmp_path, "parts/materials.pbrt", MATERIALS + 'Include "parts/deeper/shapes.pbrt"\n')
    write(tmp_path, "parts/deeper/shapes.pbrt", SHAPES)
    nested = scene(tmp_path, "nested.pbrt", 'Include "parts/materials.pbrt"\n')
    flat = scene(tmp_path, "flat.pbrt", MATERIALS + SHAPES)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    a, _ = render(nested, cwd=elsewhere)
    b, _ = render(flat)
    assert a.mean() > 0.01 and np.array_equal(a, b)
    # a name relative to the including file is not pbrt-v4's: refused, saying where pbrt-v4 looks
    write(tmp_path, "parts/local.pbrt", 'Shape "plymesh" "string filename" "tri.ply"\n')
    write(tmp_path, "parts/tri.ply", ply_text(0))
    path = scene(tmp_path, "local.pbrt", 'Include "parts/local.pbrt"\n')
    r = run("--scene", str(path), "--spp", "1", "-o", "x.exr", cwd=elsewhere)
    assert r.returncode == 1 and "parts/local.pbrt:1:" in r.stderr and "the main scene file's folder" in r.stderr, r.stderr


def gzip_members(text, parts):
    """text gzip-compressed as `parts` gzip members one after the other (as `cat a.gz b.gz` makes)."""
    data, cut = text.encode(), len(text) // parts
    return b"".join(gzip.compress(data[i * cut:(i + 1) * cut if i + 1 < parts else len(data)]) for i in range(parts))


@pytest.mark.parametrize("members", [1, 3])
def test_gzip_includes_and_meshes_equal_the_plain_files(members, tmp_path):
    texture_png(tmp_path / "textures" / "map.png")
    write(tmp_path, "spds/flat.spd", "400 0.6\n700 0.6\n")
    write(tmp_path, "meshes/tri.ply", ply_text(-1))
    write(tmp_path, "meshes/tri.ply.gz", gzip_members(ply_text(-1), members))
    write(tmp_path, "parts/all.pbrt", MATERIALS + SHAPES)
    write(tmp_path, "parts/all.pbrt.gz", gzip_members(MATERIALS + SHAPES.replace("tri.ply", "tri.ply.gz"), members))
    plain = scene(tmp_path, "plain.pbrt", 'Include "parts/all.pbrt"\n')
    zipped = scene(tmp_path, "zipped.pbrt", 'Include "parts/all.pbrt.gz"\n')
    write(tmp_path, "main.pbrt.gz", gzip.compress(zipped.read_bytes()))  # the main file itself compressed
    a, b, c = render(plain)[0], render(zipped)[0], render(tmp_path / "main.pbrt.gz")[0]
    assert a.mean() > 0.01 and np.array_equal(a, b) and np.array_equal(a, c)


@pytest.mark.parametrize("file,data", [
    ("parts/x.pbrt.gz", b"Shape \"sphere\"\n"),                                # not compressed at all
    ("parts/x.pbrt.gz", gzip.compress(b"Shape \"sphere\"\n" * 20, mtime=0)[:-9]),  # truncated
    ("parts/x.pbrt.gz", gzip.compress(b"Shape \"sphere\"\n", mtime=0) + b"junk"),  # junk after the stream
    ("meshes/m.ply.gz", b"ply\nformat ascii 1.0\n"),
])
def test_bad_gzip_is_one_line_naming_the_file(file, data, tmp_path):
    write(tmp_path, file, data)
    include = f'Include "{file}"\n' if file.endswith(".pbrt.gz") else f'Shape "plymesh" "string filename" "{file}"\n'
    path = write(tmp_path, "s.pbrt", HEAD + "WorldBegin\n" + include)
    r = fails_cleanly(run, ["--scene", str(path), "--spp", "1", "-o", "out.exr"], "is not valid gzip data", tmp_path, 1)
    assert f"{path}:5:" in r.stderr and file in r.stderr, r.stderr


def test_parameter_lists_go_on_after_an_include(tmp_path):
    # pbrt-v4 reads an included file's tokens in the same stream: a directive at its end takes the parameters
    # that follow the Include (smoke-plume/plume.pbrt of the collection does this)
    write(tmp_path, "parts/floor.pbrt",
          'Material "diffuse" "rgb reflectance" [ 0.7 0.2 0.2 ]\n'
          'Shape "trianglemesh" "point3 P" [ -4 0 -4  4 0 -4  4 0 4  -4 0 4 ]\n')
    split = scene(tmp_path, "split.pbrt", 'Include "parts/floor.pbrt"\n  "integer indices" [ 0 1 2 0 2 3 ]\n')
    whole = scene(tmp_path, "whole.pbrt", 'Material "diffuse" "rgb reflectance" [ 0.7 0.2 0.2 ]\n'
                                          'Shape "trianglemesh" "point3 P" [ -4 0 -4  4 0 -4  4 0 4  -4 0 4 ]\n'
                                          '  "integer indices" [ 0 1 2 0 2 3 ]\n')
    a, b = render(split)[0], render(whole)[0]
    assert a.mean() > 0.01 and np.array_equal(a, b)
    # but an Include ends the directive before it: parameters in the included file are not its
    write(tmp_path, "parts/indices.pbrt", '"integer indices" [ 0 1 2 ]\n')
    refused(tmp_path, HEAD + 'WorldBegin\nShape "trianglemesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 ]\n'
                            'Include "parts/indices.pbrt"\n', 0, "expected a directive")


# --- names resolved when the scene is complete -------------------------------------------------------------

def test_named_materials_and_textures_resolve_after_parsing(tmp_path):
    texture_png(tmp_path / "textures" / "map.png")
    texture_png(tmp_path / "textures" / "bumps.png")
    early = ('Texture "map" "spectrum" "imagemap" "string filename" "textures/map.png"\n'
             'Texture "dim" "spectrum" "scale" "texture tex" "map" "float scale" 0.5\n'
             'Texture "dim" "float" "imagemap" "string filename" "textures/bumps.png"\n'  # a float of the same name
             'MakeNamedMaterial "floor" "string type" "diffuse" "texture reflectance" "dim"\n'
             'MakeNamedMaterial "shiny" "string type" "conductor" "texture roughness" "dim"\n')
    use = 'NamedMaterial "floor"\n' + FLOOR + 'NamedMaterial "shiny"\nShape "sphere" "float radius" 0.8\n'
    ordered = scene(tmp_path, "ordered.pbrt", early + use)
    # the materials used before they are made (in a later Include), the scale texture before the image it scales
    write(tmp_path, "parts/late.pbrt", early.split("\n", 1)[1].replace(
        'MakeNamedMaterial "floor"',
        'Texture "map" "spectrum" "imagemap" "string filename" "textures/map.png"\nMakeNamedMaterial "floor"'))
    late = scene(tmp_path, "late.pbrt", use + 'Include "parts/late.pbrt"\n')
    a, b = render(ordered)[0], render(late)[0]
    assert a.mean() > 0.01 and np.array_equal(a, b)


@pytest.mark.parametrize("world,line,words", [
    ('NamedMaterial "nope"\n' + FLOOR, 10, 'NamedMaterial "nope" was not made'),
    ('MakeNamedMaterial "m" "string type" "diffuse"\nMakeNamedMaterial "m" "string type" "conductor"\n', 11,
     'MakeNamedMaterial "m" was already made at'),
    # pbrt-v4 makes named materials in order: a named mix takes only those made before it; an unnamed mix any
    ('MakeNamedMaterial "x" "string type" "mix" "string materials" [ "a" "b" ]\n'
     'MakeNamedMaterial "a" "string type" "diffuse"\nMakeNamedMaterial "b" "string type" "conductor"\n'
     'NamedMaterial "x"\n' + FLOOR, 10, 'is made after this named mix'),
    # a texture that is not an image may use only textures made before it
    ('Texture "a" "float" "scale" "texture tex" "b"\nTexture "b" "float" "scale" "texture tex" "a"\n', 10,
     'is made after the texture that uses it'),
    ('Texture "a" "float" "scale" "texture tex" "zz"\n', 10, 'texture "zz" was not made'),
    # (an image texture is read first only as its file's first: a second one of the file is made in order)
    ('Texture "s" "spectrum" "scale" "texture tex" "b"\nTexture "a" "float" "imagemap" "string filename" "x.png"\n'
     'Texture "b" "spectrum" "imagemap" "string filename" "x.png"\n', 10, 'is made after the texture that uses it'),
    ('Texture "a" "float" "scale" "texture tex" "zz"\nTexture "a" "float" "scale" "texture tex" "zz"\n', 11,
     'a float texture of that name was already made'),
])
def test_names_refused_as_pbrt_v4_refuses_them(world, line, words, tmp_path):
    refused(tmp_path, HEAD + "WorldBegin\n" + LIGHTS + world, line, words)


def test_unnamed_mix_takes_materials_made_later(tmp_path):
    mix = ('Material "mix" "string materials" [ "a" "b" ] "float amount" 0.3\n' + FLOOR +
           'MakeNamedMaterial "a" "string type" "diffuse"\nMakeNamedMaterial "b" "string type" "conductor"\n')
    img, _ = render(scene(tmp_path, "mix.pbrt", mix))
    assert img.mean() > 0.01


# --- transforms: named coordinate systems, ActiveTransform, shutter, Attribute, Import ---------------------

BALL = 'Material "diffuse" "rgb reflectance" [ 0.2 0.6 0.3 ]\nShape "sphere" "float radius" 0.8\n'


def test_named_coordinate_systems(tmp_path):
    # "camera" is the camera's frame (a point light at its origin is at the eye); a named system comes back;
    # "world" is the identity
    explicit = scene(tmp_path, "explicit.pbrt", 'LightSource "point" "point3 from" [ 0 4 -8 ] "rgb I" [ 20 20 20 ]\n'
                                                'Translate 1 0.8 0\n' + BALL + 'Translate -1 -0.8 0\n' + FLOOR)
    named = scene(tmp_path, "named.pbrt", 'AttributeBegin\nCoordSysTransform "camera"\n'
                                          'LightSource "point" "rgb I" [ 20 20 20 ]\nAttributeEnd\n'
                                          'Translate 1 0.8 0\nCoordinateSystem "ball"\nIdentity\nRotate 30 0 1 0\n'
                                          'CoordSysTransform "ball"\n' + BALL + 'CoordSysTransform "world"\n' + FLOOR)
    a, b = render(explicit)[0], render(named)[0]
    assert a.mean() > 0.01 and np.abs(a - b).max() < 1e-5 * a.max()
    # an unknown name leaves the transform as it is, as pbrt-v4 does (with a note)
    plain = 'LightSource "point" "point3 from" [ 0 4 -8 ] "rgb I" [ 20 20 20 ]\nTranslate 1 0.8 0\n'
    c, _ = render(scene(tmp_path, "plain.pbrt", plain + BALL + FLOOR))
    d, err = render(scene(tmp_path, "unknown.pbrt", plain + 'CoordSysTransform "nope"\n' + BALL + FLOOR))
    assert np.array_equal(c, d) and 'CoordSysTransform: no coordinate system "nope"' in err


def test_active_transform_without_motion(tmp_path):
    a, _ = render(scene(tmp_path, "still.pbrt", 'Translate 1 0.8 0\n' + BALL + FLOOR))
    # both transforms changed alike, or one changed and changed back: nothing moves
    same = ('ActiveTransform StartTime\nTranslate 1 0.8 0\nActiveTransform EndTime\nTranslate 1 0.8 0\n'
            'ActiveTransform All\n')
    b, _ = render(scene(tmp_path, "same.pbrt", same + BALL + FLOOR))
    assert np.array_equal(a, b)
    # the shutter closes before the motion starts (TransformTimes): the start transform is the one seen
    head = HEAD.replace('[ 40 ]', '[ 40 ] "float shutteropen" 0 "float shutterclose" 0.5') + "TransformTimes 0.5 1\n"
    moving = 'ActiveTransform EndTime\nTranslate 0 2 0\nActiveTransform All\nTranslate 1 0.8 0\n'
    c, err = render(scene(tmp_path, "before.pbrt", moving + BALL + FLOOR, head))
    d, _ = render(scene(tmp_path, "before-still.pbrt", 'Translate 1 0.8 0\n' + BALL + FLOOR, head))
    assert np.array_equal(c, d) and np.allclose(c, a * 0.5, rtol=1e-6, atol=1e-9)
    assert "nothing in the scene moves" in err
    # a light that moves is placed by its start transform, as pbrt-v4 places it (with a note)
    e, err = render(scene(tmp_path, "light.pbrt", 'AttributeBegin\nActiveTransform EndTime\nTranslate 0 3 0\n'
                                                  'LightSource "point" "point3 from" [ 0 2 -2 ] "rgb I" [ 9 9 9 ]\n'
                                                  'AttributeEnd\nTranslate 1 0.8 0\n' + BALL + FLOOR))
    f, _ = render(scene(tmp_path, "light-still.pbrt", 'LightSource "point" "point3 from" [ 0 2 -2 ] "rgb I" [ 9 9 9 ]\n'
                                                      'Translate 1 0.8 0\n' + BALL + FLOOR))
    assert np.array_equal(e, f) and "moves (ActiveTransform): placed by its start transform" in err


@pytest.mark.parametrize("text,line,words", [
    (HEAD + 'WorldBegin\nActiveTransform StartTime\nTranslate 1 0 0\nActiveTransform All\nShape "sphere"\n', 8,
     "the shape moves while the shutter is open"),
    (HEAD.replace("Camera", "ActiveTransform EndTime\nTranslate 0 0 1\nActiveTransform All\nCamera") + 'WorldBegin\n'
     'Shape "sphere"\n', 5, "the camera moves"),
    (HEAD + 'WorldBegin\nObjectBegin "o"\nShape "sphere"\nObjectEnd\nActiveTransform EndTime\nScale 2 2 2\n'
            'ObjectInstance "o"\n', 10, "the instance moves"),
    (HEAD + 'WorldBegin\nActiveTransform Later\n', 5, "ActiveTransform takes All, StartTime or EndTime"),
    (HEAD + 'WorldBegin\nTransformTimes 0 1\n', 5, "TransformTimes after WorldBegin"),
    (HEAD.replace('[ 40 ]', '[ 40 ] "float shutteropen" 1 "float shutterclose" 1') + 'WorldBegin\nShape "sphere"\n', 2,
     "shutterclose must be after shutteropen"),
    ('Film "rgb" "float exposuretime" 0.5\n' + HEAD + 'WorldBegin\nShape "sphere"\n', 1,
     "'exposuretime' is not a parameter of pbrt-v4's film"),
    ('Film "rgb" "float scale" 2\n' + HEAD + 'WorldBegin\nShape "sphere"\n', 1, "'scale' is not a parameter of pbrt-v4's film"),
])
def test_motion_and_shutter_refused(text, line, words, tmp_path):
    refused(tmp_path, text, line, words)


def test_attribute_defaults(tmp_path):
    a, _ = render(scene(tmp_path, "own.pbrt", 'Translate 1 0.8 0\nMaterial "diffuse" "rgb reflectance" [ 0.2 0.6 0.3 ]\n'
                                              'Shape "sphere" "float radius" 0.5\n' + FLOOR))
    # shape and material defaults (AttributeEnd ends them); a directive's own parameter wins; a shape that does
    # not take one ignores it (the floor, a trianglemesh)
    b, _ = render(scene(tmp_path, "attr.pbrt", 'Translate 1 0.8 0\nAttributeBegin\nAttribute "shape" "float radius" 3\n'
                                               'AttributeEnd\nAttribute "shape" "float radius" 0.5\n'
                                               'Attribute "material" "rgb reflectance" [ 0.2 0.6 0.3 ]\n'
                                               'Material "diffuse"\nShape "sphere"\n' + FLOOR))
    c, _ = render(scene(tmp_path, "over.pbrt", 'Translate 1 0.8 0\nAttribute "shape" "float radius" 3\n'
                                               'Material "diffuse" "rgb reflectance" [ 0.2 0.6 0.3 ]\n'
                                               'Shape "sphere" "float radius" 0.5\n' + FLOOR))
    assert a.mean() > 0.01 and np.array_equal(a, b) and np.array_equal(a, c)


def test_import_keeps_its_state(tmp_path):
    # an imported file's shapes join the scene; its transform and material changes stay in it
    write(tmp_path, "parts/ball.pbrt", 'Translate 1 0.8 0\n' + BALL)
    a, _ = render(scene(tmp_path, "import.pbrt", 'Import "parts/ball.pbrt"\n' + FLOOR))
    b, _ = render(scene(tmp_path, "inline.pbrt", 'AttributeBegin\nTranslate 1 0.8 0\n' + BALL + 'AttributeEnd\n' + FLOOR))
    assert a.mean() > 0.01 and np.array_equal(a, b)


@pytest.mark.parametrize("text,line,words", [
    ('Import "x.pbrt"\n' + HEAD + 'WorldBegin\n', 1, "Import before WorldBegin"),
    (HEAD + 'WorldBegin\nAttribute "surface" "float radius" 1\n', 5, 'Attribute "surface"'),
    (HEAD + 'WorldBegin\nAttribute "shape" "float width" 0.5\nShape "sphere"\n', 5, "parameter 'width' is not modelled"),
    (HEAD + 'WorldBegin\nAttribute "material" "float sigma" 0.5\nMaterial "diffuse"\nShape "sphere"\n', 5,
     "parameter 'sigma' is not modelled"),
    (HEAD + 'WorldBegin\nColorSpace "aces2065-1"\n', 5, 'ColorSpace "aces2065-1" is not modelled'),
    ('Integrator "path" "string rrthreshold" "high"\n' + HEAD + 'WorldBegin\nShape "sphere"\n', 1,
     "rrthreshold takes one float"),
    ('Integrator "bdpt" "bool visualizestrategies" true\n' + HEAD + 'WorldBegin\nShape "sphere"\n', 1,
     "visualizestrategies"),
    (HEAD + 'WorldBegin\nAttributeBegin\nShape "sphere"\n', 5, "AttributeBegin is never ended"),
])
def test_directives_refused(text, line, words, tmp_path):
    refused(tmp_path, text, line, words)


def test_import_refusals(tmp_path):
    write(tmp_path, "parts/open.pbrt", 'AttributeBegin\nShape "sphere"\n')
    refused(tmp_path, HEAD + 'WorldBegin\nImport "parts/open.pbrt"\n', 0, "never ended in its imported file")
    write(tmp_path, "parts/end.pbrt", 'ObjectEnd\n')
    refused(tmp_path, HEAD + 'WorldBegin\nObjectBegin "o"\nShape "sphere"\nImport "parts/end.pbrt"\nObjectEnd\n', 0,
            "ObjectEnd in an imported file")


def test_environment_under_a_projective_transform(tmp_path):
    # an environment uses directions only: pbrt-v4 turns them by the upper 3x3 of the transform (sampling) and
    # of its inverse (lookup), which agree - the bottom row doing nothing - where the transform moves nothing
    # (the sssdragon scenes of the collection); with a translation they disagree, and it is refused
    (tmp_path / "sky.png").write_bytes((ROOT / "tests" / "scenes" / "sky-map.png").read_bytes())
    light = 'AttributeBegin\nConcatTransform [ -0.224951 0 -0.97437 0  -0.97437 0 0.224951 0  0 1 0 {w}  {t} 1 ]\n' \
            'LightSource "infinite" "string filename" "sky.png"\nAttributeEnd\n'
    text = HEAD + "WorldBegin\n" + light + FLOOR + BALL
    a, _ = render(write(tmp_path, "affine.pbrt", text.format(w=0, t="0 0 0")))
    b, _ = render(write(tmp_path, "projective.pbrt", text.format(w=8.87, t="0 0 0")))
    assert a.mean() > 0.01 and np.array_equal(a, b)
    refused(tmp_path, text.format(w=8.87, t="0 0 2"), 7, "projective")


# --- object instancing --------------------------------------------------------------------------------------

OBJECT = ('Translate 0.5 0 0\nMaterial "conductor" "float roughness" 0.2\nShape "sphere" "float radius" 0.6\n'
          'Material "diffuse" "rgb reflectance" [ 0.8 0.2 0.2 ]\n'
          'Shape "trianglemesh" "point3 P" [ -1 0 0  1 0 0  0 2 0.3 ] "normal N" [ 0 0.2 -1  0.3 0 -1  -0.3 0 -1 ]\n'
          '  "point2 uv" [ 0 0 1 0 0.5 1 ] "integer indices" [ 0 1 2 ]\n')
PLACES = ['Translate -1.5 0.7 0\nRotate 30 0 1 0\nScale 1 1.3 0.8\n',      # an ellipsoid: non-uniform scale
          'Translate 1.6 0.6 0.5\nRotate -50 1 1 0\nScale 0.7 0.7 0.7\n']  # a uniformly scaled sphere


def instanced(places, object_text=OBJECT, before=False):
    use = "".join(f"AttributeBegin\n{p}ObjectInstance \"thing\"\nAttributeEnd\n" for p in places)
    define = 'ObjectBegin "thing"\n' + object_text + 'ObjectEnd\n'
    return FLOOR + (use + define if before else define + use)


def flattened(places, object_text=OBJECT):
    return FLOOR + "".join(f"AttributeBegin\n{p}{object_text}AttributeEnd\n" for p in places)


@pytest.mark.parametrize("loop", ["scalar", "wavefront"])
def test_instances_render_as_the_flattened_shapes(loop, tmp_path):
    # the instance's transform times the shapes' own (pbrt-v4's composition), normals by the inverse transpose,
    # texture coordinates and shading normals from the object's data: the image of the same shapes written out
    # under the composed transform, within float rounding (Embree instances transform rays in float)
    a, _ = render(scene(tmp_path, "inst.pbrt", instanced(PLACES)), "--loop", loop, "--spp", "16")
    b, _ = render(scene(tmp_path, "flat.pbrt", flattened(PLACES)), "--loop", loop, "--spp", "16")
    assert a.mean() > 0.01
    assert abs(a.mean() / b.mean() - 1) < 2e-4, (a.mean(), b.mean())
    far = np.abs(a - b).max(axis=2) > 1e-3 * max(1.0, b.max())  # a path that turned on a rounding: at most a few
    assert far.mean() < 0.01, far.sum()
    # an instance before its ObjectBegin (pbrt-v4 resolves the name when the scene is complete) is the same
    c, _ = render(scene(tmp_path, "early.pbrt", instanced(PLACES, before=True)), "--loop", loop, "--spp", "16")
    assert np.array_equal(a, c)


def test_instances_in_both_loops(tmp_path):
    # the scalar loop and the wavefront loop find the same instance hits: the same image
    triangles = ('Material "diffuse" "rgb reflectance" [ 0.8 0.2 0.2 ]\n'
                 'Shape "trianglemesh" "point3 P" [ -1 0 0  1 0 0  0 2 0.3 ] "integer indices" [ 0 1 2 ]\n')
    path = scene(tmp_path, "inst.pbrt", instanced(PLACES, triangles))
    a, _ = render(path, "--loop", "scalar")
    b, _ = render(path, "--loop", "wavefront")
    assert a.mean() > 0.01 and np.allclose(a, b, rtol=1e-6, atol=1e-7)


def test_a_mirroring_instance_does_not_reverse_its_shapes(tmp_path):
    # pbrt-v4 flips a sphere's normals where its own transform swaps handedness, not where an instance's does:
    # a glass sphere under a mirroring instance is the sphere mirrored with ReverseOrientation undoing the flip
    glass = 'Material "dielectric" "float eta" 1.5\nShape "sphere" "float radius" 0.8\n'
    place = 'Translate 0.3 0.9 0\nScale -1 1 1\n'
    a, _ = render(scene(tmp_path, "inst.pbrt", instanced([place], glass)), "--spp", "16")
    b, _ = render(scene(tmp_path, "rev.pbrt", flattened([place], "ReverseOrientation\n" + glass)), "--spp", "16")
    c, _ = render(scene(tmp_path, "plain.pbrt", flattened([place], glass)), "--spp", "16")
    assert abs(a.mean() / b.mean() - 1) < 2e-4 and np.abs(a - b).max() < 0.05 * a.max()
    assert np.abs(a - c).max() > 0.2 * a.max()  # (a reversed glass sphere is another image)


@pytest.mark.parametrize("world,line,words", [
    ('ObjectInstance "nope"\n', 10, 'ObjectInstance "nope": no such object'),
    ('ObjectBegin "o"\nAreaLightSource "diffuse"\nShape "sphere"\nObjectEnd\nObjectInstance "o"\n', 12,
     "an area light inside ObjectBegin"),
    ('ObjectBegin "o"\nObjectBegin "p"\n', 11, "ObjectBegin inside the ObjectBegin"),
    ('ObjectBegin "o"\nObjectInstance "o"\n', 11, "ObjectInstance inside the ObjectBegin"),
    ('ObjectBegin "o"\nShape "sphere"\nObjectEnd\nObjectBegin "o"\n', 13, "the object was already made"),
    ('ObjectEnd\n', 10, "ObjectEnd without an ObjectBegin"),
    ('ObjectBegin "o"\nAttributeEnd\n', 11, "ends the ObjectBegin"),
    ('ObjectBegin "o"\nShape "sphere"\n', 10, "ObjectBegin is never ended"),
])
def test_instancing_refused_as_pbrt_v4_refuses_it(world, line, words, tmp_path):
    refused(tmp_path, HEAD + "WorldBegin\n" + LIGHTS + world, line, words)


@pytest.mark.skipif(not AO_TOOL, reason="UDM1_AO_TOOL (the udm1-ao binary) is not set")
def test_ambient_occlusion_of_instances(tmp_path):
    a = render(scene(tmp_path, "inst.pbrt", instanced(PLACES)), tool=AO_TOOL)[0]
    b = render(scene(tmp_path, "flat.pbrt", flattened(PLACES)), tool=AO_TOOL)[0]
    assert a.mean() > 0.1 and abs(a.mean() / b.mean() - 1) < 1e-3


# --- the film: maxcomponentvalue, cropwindow, pixelbounds ---------------------------------------------------

def xyz_from_rgb():
    """CIE XYZ from linear sRGB: the Rec. 709 primaries and the D65 white point (standard values)."""
    xy = np.array([[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]])
    p = np.array([[x / y, 1.0, (1 - x - y) / y] for x, y in xy]).T
    white = np.array([0.3127 / 0.3290, 1.0, (1 - 0.3127 - 0.3290) / 0.3290])
    return p * np.linalg.solve(p, white)


@pytest.mark.parametrize("loop", ["scalar", "wavefront"])
@pytest.mark.parametrize("film,scale", [("", 1.0), ('"float iso" 300', 3.0)])
def test_maxcomponentvalue_clamps_each_sample(loop, film, scale, tmp_path):
    # an emitter filling the view: every sample is scale * L; pbrt-v4 scales a sample whose largest CIE XYZ
    # value exceeds maxcomponentvalue down to it, after the imaging ratio
    L = np.array([10.0, 5.0, 1.0])
    text = ('LookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 20 ]\n'
            f'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 6 ] {film} {{mcv}}\nWorldBegin\n'
            f'AreaLightSource "diffuse" "rgb L" [ {L[0]} {L[1]} {L[2]} ] "bool twosided" true\n'
            'Shape "trianglemesh" "point3 P" [ -5 -5 0  5 -5 0  5 5 0  -5 5 0 ] "integer indices" [ 0 1 2 0 2 3 ]\n')
    clamped, _ = render(write(tmp_path, "c.pbrt", text.format(mcv='"float maxcomponentvalue" 2')), "--loop", loop)
    free, _ = render(write(tmp_path, "f.pbrt", text.format(mcv='"float maxcomponentvalue" 1e6')), "--loop", loop)
    expected = scale * L * 2 / (xyz_from_rgb() @ (scale * L)).max()
    assert np.allclose(clamped, expected, rtol=3e-4), (clamped[0, 0], expected)
    assert np.allclose(free, scale * L, rtol=1e-6)


@pytest.mark.parametrize("film,window,randomize", [
    ('"float cropwindow" [ 0.25 0.7 0.1 0.55 ]', (16, 45, 5, 27), "owen"),  # ceil(64 * 0.25) .. ceil(48 * 0.55), in float
    ('"float cropwindow" [ 0.7 0.25 0.55 0.1 ]', (16, 45, 5, 27), "screen"),  # (pbrt-v4 orders each pair)
    ('"integer pixelbounds" [ 3 40 10 30 ]', (3, 40, 10, 30), "screen"),
    ('"integer pixelbounds" [ -5 80 10 30 ]', (0, 64, 10, 30), "owen"),     # (clipped to the film)
])
def test_crop_is_the_window_of_the_whole_render(film, window, randomize, tmp_path):
    head = HEAD.replace("[ 20 ] ", "[ 64 ] ").replace("[ 16 ]", "[ 48 ]")
    whole, _ = render(scene(tmp_path, "whole.pbrt", instanced(PLACES), head), "--randomize", randomize)
    crop, err = render(scene(tmp_path, "crop.pbrt", instanced(PLACES), head.replace("[ 48 ]", "[ 48 ] " + film)),
                       "--randomize", randomize)
    x0, x1, y0, y1 = window
    assert crop.shape == (y1 - y0, x1 - x0, 3) and np.array_equal(crop, whole[y0:y1, x0:x1])
    assert f"pixels [{x0}, {x1}) x [{y0}, {y1}) of the 64x48 film" in err


def test_crop_tiles_merge_into_the_crop(tmp_path):
    path = scene(tmp_path, "crop.pbrt", instanced(PLACES),
                 HEAD.replace("[ 16 ]", '[ 16 ] "float cropwindow" [ 0.1 0.9 0.2 0.8 ]'))
    whole, _ = render(path)
    h, w = whole.shape[:2]
    for k, bounds in enumerate([f"0,0,{w // 2},{h}", f"{w // 2},0,{w},{h}"]):
        r = run("--scene", str(path), *SPP, "--pixel-bounds", bounds, "-o", f"t{k}.exr", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
    r = run("merge", "t0.exr", "t1.exr", "-o", "m.exr", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert np.array_equal(read_exr(tmp_path / "m.exr"), whole)


@pytest.mark.parametrize("film,line,words", [
    ('"float cropwindow" [ 0.5 0.5 0 1 ]', 3, "leaves no pixel of the film"),
    ('"integer pixelbounds" [ 30 40 0 16 ]', 3, "leaves no pixel of the film"),
    ('"float cropwindow" [ 0 1 0 ]', 3, "cropwindow needs 4 numbers"),
    ('"float maxcomponentvalue" 0', 3, "maxcomponentvalue must be positive"),
])
def test_film_windows_refused(film, line, words, tmp_path):
    refused(tmp_path, HEAD.replace("[ 16 ]", "[ 16 ] " + film) + 'WorldBegin\nShape "sphere"\n', line, words)


# --- what pbrt-v4 renders to the same image: accepted with a note -------------------------------------------

_PLAIN = {}


@pytest.mark.parametrize("change,note", [
    (("Camera", 'Integrator "bdpt" "integer maxdepth" 5\nCamera'), 'Integrator "bdpt" renders as "volpath"'),
    (("Camera", 'Integrator "sppm" "float radius" 0.1\nCamera'), 'Integrator "sppm" renders as "path"'),
    (("Camera", 'Integrator "path" "bool regularize" true\nCamera'), "regularize ignored: udm1-pt renders the unbiased"),
    (("Camera", 'Integrator "volpath" "float rrthreshold" 0.5\nCamera'), "rrthreshold ignored: pbrt-v3's roulette"),
    (('Film "rgb"', 'Film "gbuffer"'), 'Film "gbuffer" renders as "rgb"'),
    (('Film "rgb"', 'Film "rgb" "bool savefp16" false'), "savefp16 ignored"),
    (("WorldBegin\n", 'WorldBegin\nColorSpace "srgb"\n'), 'ColorSpace "srgb": pbrt-v4\'s default'),
    (('"rgb L" [ 0.3 0.3 0.3 ]', '"rgb L" [ 0.3 0.3 0.3 ] "point3 portal" [ -1 5 -1  1 5 -1  1 5 1  -1 5 1 ]'),
     "portal ignored"),
])
def test_accepted_with_a_note(change, note, tmp_path):
    text = HEAD + "WorldBegin\n" + LIGHTS + FLOOR + BALL
    if "plain" not in _PLAIN:  # (rendered once for every case)
        _PLAIN["plain"] = render(write(tmp_path, "plain.pbrt", text))[0]
    a = _PLAIN["plain"]
    b, err = render(write(tmp_path, "noted.pbrt", text.replace(*change)))
    notes = [line for line in err.splitlines() if note in line]
    assert len(notes) == 1 and notes[0].startswith("udm1-pt: note: ") and np.array_equal(a, b), err
