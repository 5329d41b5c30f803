"""udm1-pt renders pbrt-v4's disks, cylinders, bilinear patches, Loop-subdivided meshes, alpha cut-outs,
coated conductors, diffuse transmission and its textures (checkerboards, image mappings, mixes, normal
maps) as pbrt-v4 defines them, through the whole tool: silhouettes of sheared quadrics against a ray-cast
here, a disk light's irradiance on its axis against its closed form, an alpha-0 shape leaving the image bit
for bit, alpha 1/2 covering half, texture values where the mapping puts them, energy conserved by a
transmitting slab in a furnace, a coat of index 1 adding nothing to a conductor, both path loops drawing
the same image; and what pbrt-v4 renders inconsistently or refuses, refused with file:line
(tests/cpp/test_pt_models.cpp checks the same at the level of rays, samples and texture lookups)."""

import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from cli_checks import fails_cleanly
from test_tool_pt_scenes import BOX, camera_rays, look_at, read_exr, render, rotate, run, scale, translate

TOOL = os.environ.get("UDM1_PT_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
ENV = 'LightSource "infinite" "rgb L" [ 1 1 1 ]\n'
SHEAR = np.array([[1, 0.4, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def quadric_coverage(kind, world_from_object, params, world_from_camera, fov, w, h, n=16):
    """The fraction of each pixel's area whose camera ray meets pbrt-v4's disk or cylinder (object space:
    a disk of radii [ri, r] at z = height, a cylinder of radius r over [zmin, zmax], both over phi <= phimax)."""
    o, d = camera_rays(world_from_camera, fov, w, h, n)
    B = np.linalg.inv(world_from_object)
    p = B[:3, :3] @ o + B[:3, 3]
    q = d @ B[:3, :3].T
    phimax = np.radians(params["phimax"])

    def inside_phi(x, y):
        return np.mod(np.arctan2(y, x), 2 * np.pi) <= phimax

    if kind == "disk":
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (params["height"] - p[2]) / q[..., 2]
        x, y = p[0] + t * q[..., 0], p[1] + t * q[..., 1]
        r2 = x * x + y * y
        hit = (t > 0) & (r2 <= params["r"] ** 2) & (r2 >= params["ri"] ** 2) & inside_phi(x, y)
        return hit.mean(axis=-1)
    a = q[..., 0] ** 2 + q[..., 1] ** 2
    b = 2 * (q[..., 0] * p[0] + q[..., 1] * p[1])
    c = p[0] ** 2 + p[1] ** 2 - params["r"] ** 2
    disc = b * b - 4 * a * c
    hit = np.zeros(disc.shape, bool)
    for sign in (-1, 1):  # either root: the nearer if it lies on the clipped cylinder, else the farther
        t = (-b + sign * np.sqrt(np.maximum(disc, 0))) / (2 * a)
        x, y, z = p[0] + t * q[..., 0], p[1] + t * q[..., 1], p[2] + t * q[..., 2]
        hit |= (disc > 0) & (t > 0) & (z >= params["zmin"]) & (z <= params["zmax"]) & inside_phi(x, y)
    return hit.mean(axis=-1)


@pytest.mark.parametrize("kind", ["disk", "cylinder"])
def test_silhouettes_of_sheared_quadrics(kind, tmp_path):
    # a black disk or cylinder (clipped in phi, a disk with a hole) under a rotation, a non-uniform scale and a
    # shear, before a white sky: each pixel is 1 - the part the quadric covers, ray-cast here in its object
    # space as pbrt-v4 defines the shape
    w, h, fov = 48, 32, 18
    xf_text = "Rotate 40 1 0.3 0\nScale 1.5 0.7 1.2\nConcatTransform [ 1 0 0 0  0.4 1 0 0  0 0 1 0  0 0 0 1 ]\n"
    xf = rotate(40, [1, 0.3, 0]) @ scale([1.5, 0.7, 1.2]) @ SHEAR
    if kind == "disk":
        params = dict(r=1.0, ri=0.35, height=0.2, phimax=300)
        shape = 'Shape "disk" "float radius" [ 1 ] "float innerradius" [ 0.35 ] "float height" [ 0.2 ] "float phimax" [ 300 ]'
    else:
        params = dict(r=0.6, zmin=-0.8, zmax=0.9, phimax=250)
        shape = 'Shape "cylinder" "float radius" [ 0.6 ] "float zmin" [ -0.8 ] "float zmax" [ 0.9 ] "float phimax" [ 250 ]'
    cam = look_at([0, 0, -10], [0, 0, 0], [0, 1, 0])
    text = (f'Film "rgb" "integer xresolution" [ {w} ] "integer yresolution" [ {h} ]\n{BOX}LookAt 0 0 -10  0 0 0  0 1 0\n'
            f'Camera "perspective" "float fov" [ {fov} ]\nWorldBegin\n{ENV}Material "diffuse" "rgb reflectance" [ 0 0 0 ]\n'
            f'AttributeBegin\n{xf_text}{shape}\nAttributeEnd\n')
    img, _ = render(tmp_path, "s", text, "--spp", "64", "--maxdepth", "1")
    want = 1 - quadric_coverage(kind, xf, params, np.linalg.inv(cam), fov, w, h)
    err = np.abs(img.mean(axis=-1) - want)
    assert 0.2 < want.mean() < 0.95 and err.mean() < 0.005 and err.max() < 0.15, (kind, err.mean(), err.max())


@pytest.mark.parametrize("strategy", ["mis", "nee", "bsdf"])
def test_disk_light_on_its_axis(strategy, tmp_path):
    # a floor of reflectance 1/2 under a one-sided disk light (L 2, radius 0.6, height 1.5) seen in a narrow
    # field at the disk's axis: L_out = rho / pi E, E = L pi r^2 / (r^2 + h^2), by every strategy
    text = ('Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]\nLookAt 0 1 -1  0 0 0  0 1 0\n'
            'Camera "perspective" "float fov" [ 0.05 ]\nWorldBegin\n'
            'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 2 2 2 ]\nTranslate 0 1.5 0\nRotate 90 1 0 0\n'
            'Shape "disk" "float radius" [ 0.6 ]\nAttributeEnd\n'
            'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n'
            'Shape "bilinearmesh" "point3 P" [ -5 0 -5  -5 0 5  5 0 -5  5 0 5 ]\n')
    img, _ = render(tmp_path, "axis", text, "--spp", "4096", "--maxdepth", "1", "--strategy", strategy)
    want = 0.5 * 2 * 0.36 / (0.36 + 1.5 ** 2)
    tol = 0.04 if strategy == "bsdf" else 0.005  # (BSDF sampling finds the light in 1 of 7 directions: noisier)
    assert abs(img.mean() / want - 1) < tol, (strategy, img.mean(), want)


SCENE = ('Film "rgb" "integer xresolution" [ 40 ] "integer yresolution" [ 30 ]\nLookAt 0 3 -6  0 0.5 0  0 1 0\n'
         'Camera "perspective" "float fov" [ 45 ]\nWorldBegin\n'
         'LightSource "infinite" "rgb L" [ 0.3 0.3 0.3 ]\n'
         'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\nTranslate 0 3 0\nRotate 90 1 0 0\n'
         'Shape "disk" "float radius" [ 0.8 ]\nAttributeEnd\n'
         'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n'
         'Shape "trianglemesh" "point3 P" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
         'AttributeBegin\nMaterial "coatedconductor" "float interface.roughness" [ 0.1 ] "float conductor.roughness" [ 0.2 ]\n'
         'Translate -1 0.6 0\nShape "disk" "float radius" [ 0.6 ]\nAttributeEnd\n'
         'AttributeBegin\nMaterial "diffusetransmission"\nTranslate 1 0 0\nRotate -90 1 0 0\n'
         'Shape "cylinder" "float radius" [ 0.5 ] "float zmin" [ 0 ] "float zmax" [ 1.2 ]\nAttributeEnd\n')
OCCLUDERS = ('AttributeBegin\nMaterial "diffuse"\n'  # in front of the camera and between the light and the floor
             'Shape "bilinearmesh" "point3 P" [ -3 -1 -3  3 -1 -3  -3 4 -3  3 4 -3 ] "float alpha" [ 0 ]\n'
             'Translate 0 2 0\nShape "sphere" "float radius" [ 1 ] "float alpha" [ 0 ]\n'
             'Translate 0 0.3 0\nRotate 90 1 0 0\nShape "disk" "float radius" [ 2 ] "float alpha" [ 0 ]\nAttributeEnd\n')


def test_alpha_zero_leaves_the_image_bit_for_bit(tmp_path):
    # shapes of alpha 0 before the camera and between the light and the floor: every ray, camera, bounce or
    # shadow, passes them (pbrt-v4): the same image, bit for bit, in both path loops
    for loop in ("auto", "scalar"):
        a, _ = render(tmp_path, f"plain-{loop}", SCENE, "--spp", "8", "--loop", loop)
        b, _ = render(tmp_path, f"occluded-{loop}", SCENE + OCCLUDERS, "--spp", "8", "--loop", loop)
        assert np.array_equal(a, b), (loop, np.abs(a - b).max())
        assert a.mean() > 0.05


def test_both_loops_draw_the_same_image(tmp_path):
    # the wavefront loop (general: the scalar loop's estimator path by path, Embree streams) and the scalar
    # loop meet the user geometry and the alpha tests the same way: the same image bit for bit
    alpha = ('Texture "c" "float" "checkerboard" "float uscale" [ 6 ] "float vscale" [ 6 ]\n'
             'Shape "bilinearmesh" "point3 P" [ -2 0.01 -2  2 0.01 -2  -2 1.5 2  2 0.2 2 ] "texture alpha" "c"\n'
             'Shape "loopsubdiv" "integer levels" [ 2 ] "point3 P" [ 1 1 1  -1 -1 1  -1 1 -1  1 -1 -1 ] '
             '"integer indices" [ 0 1 2  0 3 1  0 2 3  1 3 2 ] "float alpha" [ 0.6 ]\n')
    a, err_a = render(tmp_path, "auto", SCENE + alpha, "--spp", "8")
    b, _ = render(tmp_path, "scalar", SCENE + alpha, "--spp", "8", "--loop", "scalar")
    assert np.array_equal(a, b), np.abs(a - b).max()


def test_alpha_half_covers_half(tmp_path):
    # a black quad of alpha 1/2 over the whole view of a white sky: half the camera rays pass it
    text = ('Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]\nCamera "perspective" "float fov" [ 30 ]\n'
            f'WorldBegin\n{ENV}Material "diffuse" "rgb reflectance" [ 0 0 0 ]\n'
            'Shape "trianglemesh" "point3 P" [ -5 -5 3  5 -5 3  5 5 3  -5 5 3 ] "integer indices" [ 0 1 2 0 2 3 ] '
            '"float alpha" [ 0.5 ]\n')
    img, _ = render(tmp_path, "half", text, "--spp", "16", "--maxdepth", "1")
    n = 32 * 32 * 16
    assert abs(img.mean() - 0.5) < 4 * np.sqrt(0.25 / n), img.mean()


def floor_scene(texture):
    """A floor z = 0 of (u, v) = (x, y) / 4 over [0, 4]^2 seen from above, lit by a white sky: with BSDF
    sampling only and one bounce, every pixel is the reflectance at its point exactly."""
    return ('Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]\n' + BOX + 'LookAt 2 2 -40  2 2 0  0 1 0\n'
            f'Camera "perspective" "float fov" [ 5.7 ]\nWorldBegin\n{ENV}{texture}\n'
            'Material "diffuse" "texture reflectance" "t"\n'
            'Shape "trianglemesh" "point3 P" [ 0 0 0  4 0 0  4 4 0  0 4 0 ] "point2 uv" [ 0 0 1 0 1 1 0 1 ] '
            '"integer indices" [ 0 1 2 0 2 3 ]\n')


def floor_corners(w=32, h=32):
    """Each pixel's 4 corners on the floor (x, y), (h, w, 4), for the camera of floor_scene: it looks straight
    at the floor, so pixels map to it affinely and the corners follow from two points inside (1/4, 3/4)."""
    cam = look_at([2, 2, -40], [2, 2, 0], [0, 1, 0])
    o, d = camera_rays(np.linalg.inv(cam), 5.7, w, h, 2)  # points at (1/4, 1/4), (3/4, 1/4), (1/4, 3/4), (3/4, 3/4)
    t = -o[2] / d[..., 2]
    x, y = o[0] + t * d[..., 0], o[1] + t * d[..., 1]
    ext = np.array([[1.5, -0.5], [-0.5, 1.5]])  # (1/4, 3/4) -> (0, 1) along each axis
    def corners(a):
        a = a.reshape(h, w, 2, 2)  # (row: y sample, column: x sample)
        return np.einsum("ij,hwjk,lk->hwil", ext, a, ext).reshape(h, w, 4)
    return corners(x), corners(y)


def test_checkerboard_and_image_mappings(tmp_path):
    x, y = floor_corners()
    u, v = x / 4, y / 4
    # a checkerboard through a uv mapping scaled and offset: tex1 where floor(s) + floor(t) is even
    tex = ('Texture "t" "spectrum" "checkerboard" "float uscale" [ 3 ] "float vscale" [ 2 ] "float udelta" [ 0.25 ] '
           '"float vdelta" [ 0.5 ] "rgb tex1" [ 0.8 0.6 0.4 ] "rgb tex2" [ 0.1 0.2 0.3 ]')
    img, _ = render(tmp_path, "checks", floor_scene(tex), "--spp", "16", "--maxdepth", "1", "--strategy", "bsdf")
    cs, ct = np.floor(3 * u + 0.25), np.floor(2 * v + 0.5)
    pure = (cs == cs[..., :1]).all(-1) & (ct == ct[..., :1]).all(-1)  # the whole pixel in one square
    odd = ((cs[..., 0] + ct[..., 0]) % 2 == 1)[..., None]
    want = np.where(odd, [0.1, 0.2, 0.3], [0.8, 0.6, 0.4])
    assert pure.sum() > 600 and np.abs(img - want)[pure].max() < 1e-5, np.abs(img - want)[pure].max()
    # an image (point-sampled) through uscale, vscale, udelta, vdelta: the texel at (s, 1 - t)
    import matplotlib.image as mpimg
    here = os.path.dirname(os.path.abspath(__file__))
    ramp = os.path.join(here, "..", "scenes", "ramp.png")
    texels = mpimg.imread(ramp)[..., :3].astype(np.float64)
    texels = np.where(texels <= 0.04045, texels / 12.92, ((texels + 0.055) / 1.055) ** 2.4)  # (sRGB-decoded)
    tex = (f'Texture "t" "spectrum" "imagemap" "string filename" "{ramp}" "string filter" "point" '
           '"float uscale" [ 0.25 ] "float vscale" [ 0.5 ] "float udelta" [ 0.3 ] "float vdelta" [ -0.2 ] '
           '"float maxanisotropy" [ 4 ]')
    img, _ = render(tmp_path, "ramp", floor_scene(tex), "--spp", "16", "--maxdepth", "1", "--strategy", "bsdf")
    s, t = 0.25 * u + 0.3, 0.5 * v - 0.2
    hh, ww = texels.shape[:2]
    xi = np.mod(np.round(s * ww - 0.5), ww).astype(int)
    yi = np.mod(np.round((1 - t) * hh - 0.5), hh).astype(int)
    want = texels[yi[..., 0], xi[..., 0]]
    pure = (xi == xi[..., :1]).all(-1) & (yi == yi[..., :1]).all(-1)
    assert pure.sum() > 300 and np.abs(img - want)[pure].max() < 2e-3, np.abs(img - want)[pure].max()


def test_transmitting_slab_in_a_furnace(tmp_path):
    # diffusetransmission with R + T = 1 (0.3 and 0.7) under a white sky: no energy lost or made, every
    # pixel 1 (BSDF sampling carries exactly R + T per bounce; MIS converges to it); a closed cylinder too
    text = ('Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]\nLookAt 0 0.5 -4  0 0.5 0  0 1 0\n'
            f'Camera "perspective" "float fov" [ 40 ]\nWorldBegin\n{ENV}'
            'Material "diffusetransmission" "rgb reflectance" [ 0.3 0.3 0.3 ] "rgb transmittance" [ 0.7 0.7 0.7 ]\n'
            'Shape "bilinearmesh" "point3 P" [ -1 -0.5 0  1 -0.5 0  -1 1.5 0.3  1 1.5 -0.2 ]\n'
            'Translate 0 0.5 -1\nShape "sphere" "float radius" [ 0.4 ]\n')
    img, _ = render(tmp_path, "slab", text, "--spp", "8", "--maxdepth", "200", "--strategy", "bsdf", "--no-roulette")
    assert np.abs(img - 1).max() < 1e-5, np.abs(img - 1).max()
    img, _ = render(tmp_path, "slab-mis", text, "--spp", "64", "--maxdepth", "200")
    assert abs(img.mean() - 1) < 0.01, img.mean()


def test_coat_of_index_one_is_no_coat(tmp_path):
    # a coated conductor whose coat is smooth, of index 1 and (nearly) no thickness reflects as the bare
    # conductor: the same image within the noise (the layered walk draws its own random numbers)
    body = ('Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]\nLookAt 0 1 -4  0 0.5 0  0 1 0\n'
            'Camera "perspective" "float fov" [ 35 ]\nWorldBegin\nLightSource "infinite" "rgb L" [ 0.5 0.5 0.5 ]\n'
            'LightSource "distant" "point3 from" [ 1 3 -2 ] "rgb L" [ 2 2 2 ]\n{m}\nShape "sphere" "float radius" [ 0.8 ]\n')
    bare = body.format(m='Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" [ 0.2 ]')
    coat = body.format(m='Material "coatedconductor" "spectrum conductor.eta" "metal-Au-eta" "spectrum conductor.k" "metal-Au-k" '
                         '"float conductor.roughness" [ 0.2 ] "float interface.eta" [ 1 ] "float thickness" [ 1e-30 ]')
    a, _ = render(tmp_path, "bare", bare, "--spp", "256", "--maxdepth", "1")
    b, _ = render(tmp_path, "coat", coat, "--spp", "256", "--maxdepth", "1")
    blocks = lambda x: x.reshape(6, 4, 6, 4, 3).mean(axis=(1, 3))
    sphere = blocks(a) != 0.5  # (blocks that see the sphere)
    assert sphere.sum() > 30 and abs(b.mean() / a.mean() - 1) < 0.003, (a.mean(), b.mean())
    assert np.abs(blocks(b) - blocks(a))[sphere].max() < 0.02, np.abs(blocks(b) - blocks(a)).max()


def test_image_encodings_as_pbrt_reads_them(tmp_path):
    # pbrt-v4 decodes a texture from sRGB by default only for .png files (others: linear), and decodes integer
    # files of 16 bits as it does 8-bit ones
    from PIL import Image
    Image.new("RGB", (4, 4), (128, 128, 128)).save(tmp_path / "grey.jpg", quality=100)
    Image.fromarray(np.full((4, 4), 32768, np.uint16)).save(tmp_path / "grey16.png")
    srgb = ((32768 / 65535 + 0.055) / 1.055) ** 2.4
    for name, want in (("grey.jpg", 128 / 255), ("grey16.png", srgb)):
        tex = f'Texture "t" "spectrum" "imagemap" "string filename" "{tmp_path / name}"'
        img, _ = render(tmp_path, name.replace(".", "-"), floor_scene(tex), "--spp", "4", "--maxdepth", "1",
                        "--strategy", "bsdf")
        assert abs(img.mean() - want) < 3e-3, (name, img.mean(), want)


HEAD = 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]\nCamera "perspective"\nWorldBegin\n'


def refused_at(tmp_path, text, line, words):
    """The scene `text` is refused with one line holding `words`, naming the scene file and `line`, and no image."""
    scene = tmp_path / "s.pbrt"
    scene.write_text(text)
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "-o", str(tmp_path / "x.exr")], words, tmp_path)
    assert f"{scene}:{line}:" in r.stderr, r.stderr


@pytest.mark.parametrize(
    "body,line,words",
    [
        ('AreaLightSource "diffuse"\nShape "disk" "float innerradius" [ 0.2 ]\n', 5, "innerradius or a phimax below 360"),
        ('AreaLightSource "diffuse"\nScale 2 1 1\nShape "cylinder"\n', 6, "scales or shears it"),
        ('AreaLightSource "diffuse"\nScale -1 1 1\nShape "disk"\n', 6, "swaps handedness"),
        ('Texture "a" "float" "constant"\nAreaLightSource "diffuse"\nShape "sphere" "texture alpha" "a"\n', 6,
         "alpha texture or an alpha between 0 and 1"),
        ('Shape "bilinearmesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 1 1 0 ] "integer indices" [ 0 1 2 4 ]\n', 4, "index 4 out of range"),
        ('Shape "bilinearmesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 ] "integer indices" [ 0 1 2 ]\n', 4,
         "not a multiple of 4"),
        ('Shape "loopsubdiv" "point3 P" [ 0 0 0 1 0 0 0 1 0 1 1 0 ] "integer indices" [ 0 1 2 1 2 3 ]\n', 4,
         "inconsistent orientation"),
        ('Shape "cylinder" "float zmin" [ 1 ] "float zmax" [ 1 ]\n', 4, "zmin and zmax must differ"),
        ('Shape "sphere" "string alpha" "x"\n', 4, "\"float alpha\" or \"texture alpha\""),
        ('Texture "t" "spectrum" "imagemap" "string filename" "x.png" "string mapping" "spherical" '
         '"float uscale" [ 2 ]\nShape "sphere"\n', 4, "unsupported parameter 'uscale'"),
        ('Texture "t" "spectrum" "checkerboard" "integer dimension" [ 4 ]\nShape "sphere"\n', 4, "dimension must be 2 or 3"),
        ('Material "coatedconductor" "rgb reflectance" [ 0.5 0.5 0.5 ] "spectrum conductor.eta" "metal-Au-eta"\n'
         'Shape "sphere"\n', 4, 'both "reflectance" and "eta" and "k"'),
        ('Material "conductor" "spectrum eta" [ 400 -0.2 700 0.2 ] "spectrum k" [ 300 3 900 3 ]\nShape "sphere"\n', 4,
         "eta and k must not be negative"),
        ('Material "diffuse" "string normalmap" "nothere.png"\nShape "sphere"\n', 4, "nothere.png"),
        ('Material "measured" "string filename" "x.bsdf"\nShape "sphere"\n', 4, "x.bsdf: cannot open the tabulated BSDF file"),
        ('Material "thindielectric" "float roughness" [ 0.1 ]\nShape "sphere"\n', 4,
         "thindielectric: unsupported parameter 'roughness'"),
        ('Material "thindielectric" "float eta" [ 0 ]\nShape "sphere"\n', 4, "thindielectric: eta must be positive"),
    ],
)
def test_refusals_name_file_and_line(body, line, words, tmp_path):
    refused_at(tmp_path, HEAD + body, line, words)


SCENES = Path(__file__).resolve().parents[1] / "scenes"
GRID = SCENES / "displacement" / "grid.ply"  # a 4 x 4-vertex grid with normals and uv


@pytest.mark.parametrize(
    "params,line,words",
    [
        ('"texture displacement" "lift" "float edgelength" [ 0 ]', 6, "edgelength must be a positive number"),
        ('"texture displacement" "lift" "float edgelength" [ -1 ]', 6, "edgelength must be a positive number"),
        ('"texture displacement" "nothere"', 6, 'float texture "nothere" was not made'),
        ('"float displacement" [ 0.1 ]', 6, 'displacement must be "texture displacement"'),
        ('"texture displacement" "colour"', 6, 'float texture "colour" was not made'),
    ],
)
def test_displacement_refusals(params, line, words, tmp_path):
    refused_at(tmp_path, HEAD + 'Texture "lift" "float" "constant" "float value" [ 0.1 ]\n'
               'Texture "colour" "spectrum" "constant" "rgb value" [ 0.1 0.2 0.3 ]\n'
               f'Shape "plymesh" "string filename" "{GRID}" {params}\n', line, words)


def test_displacement_needs_uv(tmp_path):
    ply = tmp_path / "nouv.ply"
    ply.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    scene = tmp_path / "s.pbrt"
    scene.write_text(HEAD + 'Texture "lift" "float" "constant" "float value" [ 0.1 ]\n'
                     f'Shape "plymesh" "string filename" "{ply}" "texture displacement" "lift"\n')
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "-o", str(tmp_path / "x.exr")], "needs the mesh's vertex uv",
                      tmp_path)
    assert f"{scene}:5:" in r.stderr, r.stderr


def test_displacement_changes_the_surface_and_zero_changes_nothing(tmp_path):
    # tests/scenes/displacement.pbrt (its relief within 0.1 % of pbrt-v4: bench/bench_accuracy.py): the relief
    # changes the image; a displacement of 0 refines the grids but leaves the surface, so the image stays
    text = (SCENES / "displacement.pbrt").read_text()
    (tmp_path / "displacement").mkdir()
    shutil.copy(GRID, tmp_path / "displacement" / "grid.ply")
    shutil.copy(SCENES / "sky-map.png", tmp_path / "sky-map.png")
    plain = re.sub(r' "texture displacement" "\w+" "float edgelength" \[ [\d.]+ \]', "", text)
    zero = text.replace('"float value" [ 0.2 ]', '"float value" [ 0 ]').replace('"float scale" [ 0.35 ]', '"float scale" [ 0 ]')
    assert plain != text and zero != text
    means = {}
    for name, t in (("relief", text), ("plain", plain), ("zero", zero)):
        scene = tmp_path / f"{name}.pbrt"
        scene.write_text(t)
        r = run("--scene", str(scene), "--spp", "16", "--size", "48x32", "-o", str(tmp_path / f"{name}.exr"))
        assert r.returncode == 0 and r.stderr == "", r.stderr
        means[name] = read_exr(tmp_path / f"{name}.exr").reshape(-1, 3).mean(axis=0)
    assert np.all(np.abs(means["zero"] / means["plain"] - 1) < 2e-3), means
    assert np.all(np.abs(means["relief"] / means["plain"] - 1) > 5e-3), means


@pytest.mark.parametrize("material", [
    'Material "conductor" "float uroughness" [ {u} ] "float vroughness" [ {v} ]',
    'Material "coatedconductor" "float conductor.uroughness" [ {u} ] "float conductor.vroughness" [ {v} ] '
    '"float interface.roughness" [ 0 ]',
    'Material "coateddiffuse" "float uroughness" [ {u} ] "float vroughness" [ {v} ] "rgb reflectance" [ 0.2 0.2 0.2 ]',
    'Material "dielectric" "float uroughness" [ {u} ] "float vroughness" [ {v} ] "float eta" [ 1.5 ]',
])
def test_anisotropic_roughness_is_oriented_by_dp_du(material, tmp_path):
    # pbrt-v4 lays uroughness along dp/du: a quad whose texture coordinates turn a quarter (u along y) with the
    # two roughnesses swapped is the same surface and renders the same image up to the noise; turned alone it is
    # another surface, lit otherwise (a grazing distant light across x)
    head = ('LookAt 0 -3 4  0 0 0  0 0 1\nCamera "perspective" "float fov" [ 40 ]\n' + BOX +
            'Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]\nWorldBegin\n'
            'LightSource "distant" "point3 from" [ 3 0 1 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3 3 3 ]\n'
            'LightSource "infinite" "rgb L" [ 0.1 0.1 0.1 ]\n')
    quad = 'Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ] "point3 P" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ] "point2 uv" '
    along_x, along_y = "[ 0 0  1 0  1 1  0 1 ]", "[ 0 0  0 1  -1 1  -1 0 ]"
    means = {}
    for name, (u, v), uv in [("a", (0.05, 0.5), along_x), ("b", (0.5, 0.05), along_y), ("c", (0.05, 0.5), along_y)]:
        img, _ = render(tmp_path, name, head + material.format(u=u, v=v) + "\n" + quad + uv + "\n", "--spp", "256")
        means[name] = img.mean()
    assert abs(means["b"] / means["a"] - 1) < 0.01, means
    assert abs(means["c"] / means["a"] - 1) > 0.03, means


@pytest.mark.parametrize("eta", [1.5, 2.2])
def test_thin_dielectric_transmits_its_summed_fresnel_share(eta, tmp_path):
    # a thin sheet between the camera and a light of radiance 1 that fills the view, nothing on the camera's side:
    # each path crosses the sheet straight with the probability T' of pbrt-v4's ThinDielectricBxDF (one interface's
    # R summed over the inner reflections: T' = (1 - R) / (1 + R) at normal incidence) and meets the light, or
    # is reflected into the dark; the image mean is T' within the binomial noise (the view's 2 degrees change R
    # by less than 1e-4)
    R = ((eta - 1) / (eta + 1)) ** 2
    want = (1 - R) / (1 + R)
    text = ('LookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 4 ]\n' + BOX +
            'Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]\nWorldBegin\n'
            'AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 1 1 1 ]\nMaterial "diffuse" "rgb reflectance" [ 0 0 0 ]\n'
            'Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ] "point3 P" [ -9 -9 3  -9 9 3  9 9 3  9 -9 3 ]\n'
            'AttributeEnd\n'
            f'Material "thindielectric" "float eta" [ {eta} ]\n'
            'Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ] "point3 P" [ -3 -3 0  3 -3 0  3 3 0  -3 3 0 ]\n')
    img, _ = render(tmp_path, "thin", text, "--spp", "64", "--maxdepth", "3")
    n = 16 * 16 * 64
    se = np.sqrt(want * (1 - want) / n)
    assert abs(img.mean() - want) < 4 * se, (img.mean(), want, se)
    # the same light through the sheet with R alone (no inner reflections) would be 1 - R: far outside the noise
    assert abs((1 - R) - want) > 10 * se
