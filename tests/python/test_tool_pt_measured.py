"""udm1-pt's Material "measured" (pbrt-v4's tabulated BSDF files) through the whole tool, on files of known content
written by tabulated_bsdf_files.py: the file found by pbrt-v4's path rule (beside the main scene file, from another
working directory), a sphere of the tabulated Trowbridge-Reitz conductor under a uniform sky matching its albedo
in closed form, a named material the same image as the plain one; and every kind of damaged file (truncated,
another magic or version, a field missing or of another type or shape, data outside the file, values that are
not finite, densities below 0 or 0 everywhere, axes that do not increase, anisotropic tables not over the whole
circle) refused with one line naming the scene's file:line and the tabulated file, and no image; anisotropic tables
oriented by the surface's dp/du, as pbrt-v4 orients them. (tests/cpp/test_pt.cpp, test_measured,
checks the BSDF itself: the closed form on the tables' nodes, sampling against evaluation and density.)"""

import os
import struct

import numpy as np
import pytest
from cli_checks import fails_cleanly
from tabulated_bsdf_files import ggx_aniso_fields, ggx_fields, tensor_bytes
from test_tool_pt_scenes import read_exr, run

TOOL = os.environ.get("UDM1_PT_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")

# a unit sphere seen head-on through a narrow field of view (every pixel within 10 degrees of its normal), under
# a uniform white sky
SPHERE = ('LookAt 0 0 10  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 2 ]\n'
          'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]\nWorldBegin\n'
          'LightSource "infinite" "rgb L" [ 1 1 1 ]\n')


def small_fields():
    return ggx_fields(n_theta_i=3, grid=5, square=3)


def test_sphere_under_a_uniform_sky_has_the_closed_form_albedo(tmp_path):
    # seen along its normal, the tabulated conductor (F 0.8, alpha 0.5) under a sky of 1 reflects its albedo:
    # F times the normals' projected area within 45 degrees (the half vectors of the upper hemisphere), which
    # for Trowbridge-Reitz is 1 / (1 + alpha^2): 0.64. The scene names the file relative to its own folder and
    # is rendered from another working directory (pbrt-v4's path rule).
    folder = tmp_path / "scene"
    (folder / "bsdfs").mkdir(parents=True)
    (folder / "bsdfs" / "ggx.bsdf").write_bytes(tensor_bytes(ggx_fields()))
    scene = folder / "main.pbrt"
    scene.write_text(SPHERE + 'Material "measured" "string filename" "bsdfs/ggx.bsdf"\nShape "sphere"\n')
    out = tmp_path / "sphere.exr"
    r = run("--scene", str(scene), "--spp", "256", "-o", str(out), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    img = read_exr(out)
    expect = 0.8 / (1 + 0.5 ** 2)
    assert np.all(np.isfinite(img))
    for c in range(3):
        assert abs(img[..., c].mean() / expect - 1) < 0.015, (c, img[..., c].mean(), expect)
    # the same material made with MakeNamedMaterial: the same image, bit for bit
    named = folder / "named.pbrt"
    named.write_text(SPHERE + 'MakeNamedMaterial "m" "string type" "measured" "string filename" "bsdfs/ggx.bsdf"\n'
                     'NamedMaterial "m"\nShape "sphere"\n')
    out2 = tmp_path / "named.exr"
    r = run("--scene", str(named), "--spp", "256", "-o", str(out2), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert np.array_equal(read_exr(out2), img)


def test_anisotropic_tables_are_oriented_by_the_surfaces_dp_du(tmp_path):
    # pbrt-v4 orients a tabulated BSDF's azimuths by dp/du: a quad whose texture coordinates turn a quarter (u
    # along y, not x) with the table's roughnesses swapped (0.6 along u, 0.2 across) is the same surface and
    # renders the same image, up to the sampling's noise (its warps start at another azimuth); turned alone, or
    # swapped alone, it is another surface, lit otherwise
    (tmp_path / "a.bsdf").write_bytes(tensor_bytes(ggx_aniso_fields(ax=0.2, ay=0.6)))
    (tmp_path / "b.bsdf").write_bytes(tensor_bytes(ggx_aniso_fields(ax=0.6, ay=0.2)))
    head = ('LookAt 0 0 5  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 30 ]\n'
            'Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]\nWorldBegin\n'
            'LightSource "distant" "point3 from" [ 1 2 5 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3 3 3 ]\n'
            'LightSource "infinite" "rgb L" [ 0.2 0.2 0.2 ]\n')
    quad = 'Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ] "point3 P" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ] "point2 uv" '
    along_x, along_y = "[ 0 0  1 0  1 1  0 1 ]", "[ 0 0  0 1  -1 1  -1 0 ]"
    means = {}
    for name, table, uv in [("a", "a.bsdf", along_x), ("b", "b.bsdf", along_y), ("c", "a.bsdf", along_y),
                            ("d", "b.bsdf", along_x)]:
        (tmp_path / f"{name}.pbrt").write_text(head + f'Material "measured" "string filename" "{table}"\n' + quad + uv + "\n")
        r = run("--scene", str(tmp_path / f"{name}.pbrt"), "--spp", "256", "-o", str(tmp_path / f"{name}.exr"), cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        means[name] = read_exr(tmp_path / f"{name}.exr").mean()
    assert abs(means["b"] / means["a"] - 1) < 0.002 and abs(means["d"] / means["c"] - 1) < 0.002, means
    assert abs(means["c"] / means["a"] - 1) > 0.1, means


def field_record_offset(data, name):
    """Where the record of field `name` begins in a tensor file's bytes (after its name: rank, type, offset, shape)."""
    at = 18
    while True:
        n = struct.unpack_from("<H", data, at)[0]
        this = data[at + 2:at + 2 + n].decode()
        rank = struct.unpack_from("<H", data, at + 2 + n)[0]
        if this == name:
            return at + 2 + n
        at += 2 + n + 2 + 1 + 8 + 8 * rank


def with_field(**changes):
    f = small_fields()
    for k, v in changes.items():
        if v is None:
            del f[k]
        else:
            f[k] = v
    return tensor_bytes(f)


def changed_value(name, index, value):
    f = small_fields()
    a = f[name].copy()
    a.reshape(-1)[index] = value
    f[name] = a
    return tensor_bytes(f)


def patched(offset_of, fmt, value):
    def make():
        data = bytearray(tensor_bytes(small_fields()))
        struct.pack_into(fmt, data, offset_of(data), value)
        return bytes(data)
    return make


GOOD = tensor_bytes(small_fields())
F32 = np.float32
FLOAT_FIELDS = ["theta_i", "phi_i", "wavelengths", "ndf", "sigma", "vndf", "luminance", "spectra"]

DAMAGED = [
    ("empty", lambda: b"", "truncated"),
    ("header cut", lambda: GOOD[:15], "truncated"),
    ("records cut", lambda: GOOD[:60], "truncated"),
    ("data cut", lambda: GOOD[:-7], "lies outside the file"),
    ("magic", lambda: b"tensor_fild\0" + GOOD[12:], 'does not begin with "tensor_file"'),
    ("version", lambda: GOOD[:12] + bytes([2, 0]) + GOOD[14:], "tensor file version 2.0"),
    ("minor version", lambda: GOOD[:12] + bytes([1, 1]) + GOOD[14:], "tensor file version 1.1"),
    ("unknown type", patched(lambda d: field_record_offset(d, "ndf") + 2, "<B", 12), "unknown type (12)"),
    ("offset past the end", patched(lambda d: field_record_offset(d, "sigma") + 3, "<Q", 1 << 40), "lies outside the file"),
    ("shape overflows", patched(lambda d: field_record_offset(d, "vndf") + 11, "<Q", 1 << 62), "lies outside the file"),
    ("a field twice", lambda: tensor_bytes(list(small_fields().items()) + [("ndf", small_fields()["ndf"])]),
     'field "ndf" appears twice'),
    ("half circle", lambda: with_field(phi_i=np.linspace(0, np.pi, 4).astype(F32), vndf=np.ones((4, 3, 5, 5), F32),
                                       luminance=np.ones((4, 3, 3, 3), F32), spectra=np.ones((4, 3, 2, 3, 3), F32)),
     "over the whole circle"),
    ("vndf axes", lambda: with_field(vndf=np.ones((1, 2, 5, 5), F32)), "vndf's first axes must be phi_i's and theta_i's"),
    ("luminance not square", lambda: with_field(luminance=np.ones((1, 3, 3, 4), F32)), "its last two equal"),
    ("spectra's wavelengths", lambda: with_field(spectra=np.ones((1, 3, 3, 3, 3), F32)), "spectra's first axes"),
    ("spectra's grid", lambda: with_field(spectra=np.ones((1, 3, 2, 4, 4), F32)), "the same grid"),
    ("a grid of one", lambda: with_field(ndf=np.ones((1, 5), F32)), "2 to 2^20 values along each axis"),
    ("jacobian", lambda: with_field(jacobian=np.array([1, 1], np.uint8)), '"jacobian" must hold one value'),
    ("description type", lambda: with_field(description=np.zeros(3, F32)), 'field "description" is float32 [3], not uint8'),
    ("rank", lambda: with_field(ndf=np.ones((1, 3, 5), F32)), "not float32 of rank 2"),
    ("no wavelengths", lambda: with_field(wavelengths=np.zeros(0, F32), spectra=np.ones((1, 3, 0, 3, 3), F32)),
     "need a value each"),
    ("theta_i not increasing", lambda: changed_value("theta_i", 1, 0.0), '"theta_i" does not increase'),
    ("wavelengths not increasing", lambda: changed_value("wavelengths", 1, 360.0), '"wavelengths" does not increase'),
    ("negative wavelength", lambda: changed_value("wavelengths", 0, -1.0), "it must be above 0"),
    ("negative ndf", lambda: changed_value("ndf", 3, -0.5), 'field "ndf" value 3 is -0.5 (it must be at least 0)'),
    ("negative vndf", lambda: changed_value("vndf", 7, -1.0), 'field "vndf" value 7 is -1'),
    ("negative luminance", lambda: changed_value("luminance", 4, -2.0), 'field "luminance" value 4 is -2'),
    ("sigma 0", lambda: changed_value("sigma", 2, 0.0), "it must be above 0"),
    ("luminance 0 everywhere", lambda: with_field(luminance=np.zeros((1, 3, 3, 3), F32)), '"luminance" slice 0 is 0 everywhere'),
    ("a vndf slice 0", lambda: with_field(vndf=np.concatenate([np.ones((1, 2, 5, 5)), np.zeros((1, 1, 5, 5))], 1).astype(F32)),
     '"vndf" slice 2 is 0 everywhere'),
] + [(f"{name} {bad}", (lambda name=name, bad=bad: changed_value(name, 0, bad)), f'field "{name}" value 0 is not finite')
     for name in FLOAT_FIELDS for bad in (np.nan, np.inf)
     ] + [(f"no {name}", (lambda name=name: with_field(**{name: None})), f'no field "{name}"')
          for name in FLOAT_FIELDS + ["description", "jacobian"]
          ] + [(f"{name} float64", (lambda name=name: with_field(**{name: small_fields()[name].astype(np.float64)})),
                f'field "{name}" is float64') for name in FLOAT_FIELDS]


@pytest.mark.parametrize("damage,make,words", DAMAGED, ids=[d[0] for d in DAMAGED])
def test_damaged_files_are_refused_with_file_and_line(damage, make, words, tmp_path):
    (tmp_path / "bad.bsdf").write_bytes(make())
    scene = tmp_path / "s.pbrt"
    scene.write_text(SPHERE + 'AttributeBegin\nMaterial "measured"\n  "string filename" "bad.bsdf"\nShape "sphere"\nAttributeEnd\n')
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "-o", str(tmp_path / "x.exr")], words, tmp_path)
    assert f"{scene}:8: Material \"measured\": {tmp_path / 'bad.bsdf'}: " in r.stderr, r.stderr


@pytest.mark.parametrize("body,line,words", [
    ('Material "measured"\nShape "sphere"\n', 6, 'Material "measured": no "string filename"'),
    ('Material "measured" "string filename" ""\nShape "sphere"\n', 6, 'no "string filename"'),
    ('Material "measured" "string filename" "missing.bsdf"\nShape "sphere"\n', 6,
     "missing.bsdf: cannot open the tabulated BSDF file"),
    ('Material "measured" "string filename" "."\nShape "sphere"\n', 6, "is not a regular file"),
    ('Material "measured" "string filename" "good.bsdf" "rgb reflectance" [ 1 1 1 ]\nShape "sphere"\n', 6,
     "measured: unsupported parameter 'reflectance'"),
    ('MakeNamedMaterial "m" "string type" "measured" "string filename" "bad.bsdf"\n', 6, "bad.bsdf: field \"description\" (uint8 [47] at byte 394) lies outside"),
])
def test_measured_material_refusals(body, line, words, tmp_path):
    (tmp_path / "good.bsdf").write_bytes(GOOD)
    (tmp_path / "bad.bsdf").write_bytes(GOOD[:100])
    scene = tmp_path / "s.pbrt"
    scene.write_text(SPHERE + body)
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "-o", str(tmp_path / "x.exr")], words, tmp_path)
    assert f"{scene}:{line}:" in r.stderr, r.stderr
