"""udm1-pt renders what a pbrt-v4 scene file describes, as pbrt-v4 renders it, or refuses it with file:line:
closed forms through the whole tool (the silhouette of a sphere under any affine transform and of a camera
with a scaled transform against the quadric ray-cast here, a thin lens's circle of confusion, emitters
flipped by ReverseOrientation and by transforms that swap handedness, a furnace lit from a reversed sphere,
texture filters and clamped albedos), the integrators that find fewer lights or lobes than "path", what
pbrt-v4 refuses or renders inconsistently refused, and every scene parameter udm1-pt reads changing the
image (tests/cpp/test_pt_scene.cpp checks the same at the level of rays)."""

import re

import numpy as np
import pytest
from cli_checks import fails_cleanly
from pt_tool import TOOL, ok, read_exr, run

pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
MEAN = re.compile(r" mean (\S+) (\S+) (\S+)\n")


def render(tmp_path, name, text, *args):
    """The scene text rendered to an EXR: (image, stderr)."""
    scene = tmp_path / f"{name}.pbrt"
    scene.write_text(text)
    out = tmp_path / f"{name}.exr"
    r = ok("--scene", str(scene), "-o", str(out), *args, cwd=tmp_path)
    return read_exr(out), r.stderr


# --- pbrt-v4's camera and transforms, written out here (independent of the renderer's code) ---------------

def rotate(deg, axis):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    t = np.radians(deg)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    m = np.eye(4)
    m[:3, :3] = np.cos(t) * np.eye(3) + np.sin(t) * k + (1 - np.cos(t)) * np.outer(a, a)
    return m


def translate(v):
    m = np.eye(4)
    m[:3, 3] = v
    return m


def scale(v):
    return np.diag([*v, 1.0])


def look_at(eye, target, up):
    """pbrt's LookAt: camera-from-world (its inverse has columns right, up, direction, eye)."""
    eye, target, up = (np.asarray(x, float) for x in (eye, target, up))
    d = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(up / np.linalg.norm(up), d)
    right /= np.linalg.norm(right)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, np.cross(d, right), d, eye
    return np.linalg.inv(m)


def camera_rays(world_from_camera, fov, w, h, n):
    """pbrt-v4's perspective camera rays at n x n points of each pixel: origins and directions, (h, w, n*n, 3)."""
    aspect = w / h
    sx0, sx1 = (-aspect, aspect) if aspect > 1 else (-1, 1)
    sy0, sy1 = (-1, 1) if aspect > 1 else (-1 / aspect, 1 / aspect)
    f = (np.arange(n) + 0.5) / n
    px = (np.arange(w)[:, None] + f[None, :]).reshape(-1)
    py = (np.arange(h)[:, None] + f[None, :]).reshape(-1)
    sx = sx0 + px / w * (sx1 - sx0)
    sy = sy1 - py / h * (sy1 - sy0)
    t = np.tan(np.radians(fov) / 2)
    X, Y = np.meshgrid(sx * t, sy * t)  # (h n, w n)
    d = np.stack([X, Y, np.ones_like(X)], axis=-1)
    d = d @ world_from_camera[:3, :3].T
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    d = d.reshape(h, n, w, n, 3).transpose(0, 2, 1, 3, 4).reshape(h, w, n * n, 3)
    o = world_from_camera[:3, 3] / world_from_camera[3, 3]
    return o, d


def ellipsoid_coverage(world_from_object, radius, world_from_camera, fov, w, h, n=24):
    """The fraction of each pixel's area whose camera ray meets the quadric |B (x - c)| = radius."""
    o, d = camera_rays(world_from_camera, fov, w, h, n)
    B = np.linalg.inv(world_from_object)[:3, :3]
    p = B @ (o - world_from_object[:3, 3])
    q = d @ B.T
    a, b, c = (q * q).sum(-1), 2 * (q @ p), p @ p - radius * radius
    disc = b * b - 4 * a * c
    t = (-b - np.sqrt(np.maximum(disc, 0))) / (2 * a)
    return ((disc > 0) & (t > 0)).mean(axis=-1)


ENV = 'LightSource "infinite" "rgb L" [ 1 1 1 ]\n'
# the box pixel filter of radius 1/2, for the tests whose closed forms are each pixel's own area (a scene file
# without a PixelFilter line has pbrt-v4's gaussian, which reaches into the neighbouring pixels)
BOX = 'PixelFilter "box"\n'


@pytest.mark.parametrize("case", ["sheared ellipsoid", "mirrored ellipsoid", "rotated world sphere", "scaled camera"])
def test_silhouettes_are_the_quadrics_pbrt_intersects(case, tmp_path):
    # a black sphere under a transform before a white sky: each pixel is 1 - the part of it the quadric
    # covers, ray-cast here for pbrt-v4's camera (a sphere under a non-uniform scale is the ellipsoid, not a
    # sphere of the mean radius; a camera transform that scales maps its rays as pbrt-v4 maps them)
    w, h, fov, r = (32, 48, 14, 1.0) if case == "rotated world sphere" else (48, 32, 14, 1.0)  # (fov: the shorter axis)
    xf_text, xf = {
        "sheared ellipsoid": ("Translate 0.3 -0.2 0\nRotate 30 0 0 1\nScale 1.6 0.5 1\n"
                              "ConcatTransform [ 1 0 0 0  0.4 1 0 0  0 0 1 0  0 0 0 1 ]\n",
                              translate([0.3, -0.2, 0]) @ rotate(30, [0, 0, 1]) @ scale([1.6, 0.5, 1])
                              @ np.array([[1, 0.4, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])),
        "mirrored ellipsoid": ("Rotate 50 1 1 0\nScale -1.7 0.6 0.9\n", rotate(50, [1, 1, 0]) @ scale([-1.7, 0.6, 0.9])),
        "rotated world sphere": ("Translate -0.5 0.4 1\nRotate 70 0 1 1\nScale 1.2 1.2 1.2\n",
                                 translate([-0.5, 0.4, 1]) @ rotate(70, [0, 1, 1]) @ scale([1.2, 1.2, 1.2])),
        "scaled camera": ("Translate 0.2 0 0\n", translate([0.2, 0, 0])),
    }[case]
    camera_xf = scale([1.5, 0.8, 1]) if case == "scaled camera" else np.eye(4)
    camera_text = "Scale 1.5 0.8 1\n" if case == "scaled camera" else ""
    cam = camera_xf @ look_at([0, 0, -20], [0, 0, 0], [0, 1, 0])
    text = (f'Film "rgb" "integer xresolution" [ {w} ] "integer yresolution" [ {h} ]\n{BOX}{camera_text}'
            f'LookAt 0 0 -20  0 0 0  0 1 0\nCamera "perspective" "float fov" [ {fov} ]\nWorldBegin\n{ENV}'
            f'Material "diffuse" "rgb reflectance" [ 0 0 0 ]\nAttributeBegin\n{xf_text}'
            f'Shape "sphere" "float radius" [ {r} ]\nAttributeEnd\n')
    img, _ = render(tmp_path, "s", text, "--spp", "64", "--maxdepth", "1")
    want = 1 - ellipsoid_coverage(xf, r, np.linalg.inv(cam), fov, w, h)
    err = np.abs(img.mean(axis=-1) - want)
    assert 0.15 < want.mean() < 0.95 and err.mean() < 0.004 and err.max() < 0.12, (case, err.mean(), err.max())


def coverage_profile(k_r, tan_half, w, h):
    """A half-plane x < 0 seen through a thin lens: the fraction of (pixel x lens disc) that sees it, per
    column (the blur disc's radius is |1/focal - 1/depth| * lens radius in tan units: k_r)."""
    sub = 64
    px = (np.arange(w)[:, None] + (np.arange(sub) + 0.5)[None, :] / sub)
    sx = (-w / h + px / w * (2 * w / h)) * tan_half  # tan units
    if k_r == 0:
        return (sx < 0).mean(axis=1)
    u = np.clip(-sx / k_r, -1, 1)
    frac = 1 - (np.arccos(u) - u * np.sqrt(1 - u * u)) / np.pi  # of the unit disc left of x = u
    return frac.mean(axis=1)


def test_thin_lens_circle_of_confusion(tmp_path):
    # an emitting half-plane at depth 4 seen through a lens of radius 0.5: focused at 4 its edge is sharp;
    # focused at 2 or 8 it spreads over the circle of confusion, of radius |1/f - 1/4| 0.5 (pbrt-v4's thin
    # lens: the ray from the lens point through the focal plane's point)
    w, h, fov = 64, 16, 30
    tan_half = np.tan(np.radians(fov) / 2)
    head = (f'Film "rgb" "integer xresolution" [ {w} ] "integer yresolution" [ {h} ]\n{BOX}LookAt 0 0 0  0 0 1  0 1 0\n'
            'Camera "perspective" "float fov" [ 30 ] "float lensradius" [ 0.5 ] "float focaldistance" [ {f} ]\nWorldBegin\n'
            'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true\n'
            'Shape "trianglemesh" "point3 P" [ -100 -100 4  0 -100 4  0 100 4  -100 100 4 ] "integer indices" [ 0 1 2 0 2 3 ]\n')
    for f in (4, 2, 8):
        img, _ = render(tmp_path, f"f{f}", head.replace("{f}", str(f)), "--spp", "256", "--maxdepth", "0")
        profile = img.mean(axis=(0, 2))
        want = coverage_profile(abs(1 / f - 1 / 4) * 0.5, tan_half, w, h)
        assert np.abs(profile - want).max() < 0.015, (f, np.round(profile - want, 3))
        if f == 4:  # sharp: the edge between two columns (but for a few rays rounded across it)
            assert np.all(profile[:w // 2] > 0.999) and np.all(profile[w // 2:] < 1e-3), profile


FLOOR = ('Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n'
         'Shape "trianglemesh" "point3 P" [ -20 -2 -20  20 -2 -20  20 -2 20  -20 -2 20 ] "integer indices" [ 0 1 2 0 2 3 ]\n')
ABOVE = 'LookAt 0 6 -8  0 -2 0  0 1 0\nCamera "perspective" "float fov" [ 40 ]\nWorldBegin\n'


@pytest.mark.parametrize("strategy", ["mis", "nee", "bsdf"])
def test_reversed_one_sided_sphere_light(strategy, tmp_path):
    # ReverseOrientation turns a one-sided sphere light inwards, for the rays that hit it and for light
    # sampling alike (pbrt-v4): the floor outside is black, and inside, a furnace of albedo 1/2 whose walls
    # emit 1 inwards, every pixel is 1 / (1 - 1/2) = 2
    light = 'AttributeBegin\nReverseOrientation\nAreaLightSource "diffuse" "rgb L" [ 5 5 5 ]\nShape "sphere"\nAttributeEnd\n'
    img, _ = render(tmp_path, "out", ABOVE + light + FLOOR, "--spp", "16", "--size", "24x16", "--strategy", strategy)
    assert img.max() == 0, img.max()
    furnace = ('Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]\nCamera "perspective"\nWorldBegin\n'
               'ReverseOrientation\nMaterial "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]\n'
               'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]\nShape "sphere" "float radius" [ 10 ]\n')
    img, _ = render(tmp_path, "in", furnace, "--spp", "64", "--strategy", strategy, "--maxdepth", "60")
    assert abs(img.mean() - 2) < 0.02, img.mean()


@pytest.mark.parametrize("flip,lit", [("", True), ("ReverseOrientation\n", False), ("Scale 1 -1 1\n", False),
                                      ("ReverseOrientation\nScale 1 -1 1\n", True)])
@pytest.mark.parametrize("normals", [False, True])
def test_emitting_side_of_a_one_sided_quad(flip, lit, normals, tmp_path):
    # a one-sided emitting quad at y = 0 facing down onto the floor (by its winding, or by its vertex
    # normals): ReverseOrientation flips the side it emits from, and so does a transform that swaps
    # handedness, both together do not (pbrt-v4: vertex normals by the inverse transpose and flipped by
    # ReverseOrientation, the geometric normal facing them, or flipped by orientation XOR handedness).
    # Turned up, its light leaves the scene: the image is black
    n = '"normal N" [ 0 -1 0  0 -1 0  0 -1 0  0 -1 0 ] ' if normals else ""
    winding = "0 2 1 0 3 2" if normals else "0 1 2 0 2 3"  # (with normals, the winding does not matter)
    light = ('AttributeBegin\n' + flip + 'AreaLightSource "diffuse" "rgb L" [ 5 5 5 ]\n'
             'Shape "trianglemesh" "point3 P" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] ' + n
             + f'"integer indices" [ {winding} ]\nAttributeEnd\n')
    side = 'LookAt 0 -0.5 -8  0 -2 0  0 1 0\nCamera "perspective" "float fov" [ 40 ]\nWorldBegin\n'
    img, _ = render(tmp_path, "q", side + light + FLOOR, "--spp", "16", "--size", "24x16")
    assert (img.mean() > 0.05) if lit else (img.max() == 0), (flip, normals, img.mean())


TEX_HEAD = ('Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]\n' + BOX + 'LookAt 0 0 -5  0 0 0  0 1 0\n'
            'Camera "perspective" "float fov" [ 30 ]\nWorldBegin\n' + ENV)
TEX_QUAD = ('Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ] '
            '"integer indices" [ 0 1 2 0 2 3 ]\n')


def albedo_image(tmp_path, name, textures, material):
    """A textured quad under a white sky of radiance 1, one bounce, BSDF-sampled: each pixel is the albedo
    it sees, exactly."""
    img, _ = render(tmp_path, name, TEX_HEAD + textures + material + TEX_QUAD, "--spp", "16", "--maxdepth", "1",
                    "--strategy", "bsdf")
    return img[8:24, 8:24].mean(axis=-1)  # the quad


def test_texture_point_filter(tmp_path):
    import matplotlib.image as mpimg

    # a 2 x 2 checker magnified: "filter" "point" takes the nearest texel (0 or 1 but on the pixels across
    # texel borders), bilinear blends them (a ramp)
    mpimg.imsave(tmp_path / "check.png", np.array([[[1, 1, 1], [0, 0, 0]], [[0, 0, 0], [1, 1, 1]]], float))
    tex = 'Texture "c" "spectrum" "imagemap" "string filename" "check.png" "string filter" "{f}"\n'
    mat = 'Material "diffuse" "texture reflectance" "c"\n'
    point = albedo_image(tmp_path, "point", tex.replace("{f}", "point"), mat)
    bilinear = albedo_image(tmp_path, "bilinear", tex.replace("{f}", "bilinear"), mat)
    mid = lambda a: ((a > 0.05) & (a < 0.95)).mean()
    assert mid(point) < 0.2 and mid(bilinear) > 0.6, (mid(point), mid(bilinear))
    # "invert" true: 1 - the texel (clamped at 0, as pbrt-v4)
    inverted = albedo_image(tmp_path, "inverted", tex.replace("{f}", "point").replace("\n", ' "bool invert" true\n'), mat)
    assert np.allclose(inverted, 1 - point, atol=1e-6), np.abs(inverted - (1 - point)).max()


def test_scaled_texture_albedo_is_clamped(tmp_path):
    import matplotlib.image as mpimg

    # a scale texture taking an albedo above 1 is clamped to 1 (pbrt-v4 clamps a reflectance to [0, 1]):
    # the same image as an rgb reflectance of 1
    mpimg.imsave(tmp_path / "grey.png", np.full((2, 2, 3), 0.8))
    g = ('Texture "g0" "spectrum" "imagemap" "string filename" "grey.png" "string encoding" "linear"\n'
         'Texture "g" "spectrum" "scale" "texture tex" "g0" "float scale" 2\n')
    scaled = albedo_image(tmp_path, "scaled", g, 'Material "diffuse" "texture reflectance" "g"\n')
    white = albedo_image(tmp_path, "white", "", 'Material "diffuse" "rgb reflectance" [ 1 1 1 ]\n')
    assert np.array_equal(scaled, white), (scaled.mean(), white.mean())


def test_transform_blocks_restore_attributes(tmp_path):
    # pbrt-v4 reads TransformBegin/End as AttributeBegin/End: a material set inside is gone after the end
    inner = ('Material "diffuse" "rgb reflectance" [ 1 1 1 ]\nTransformBegin\nTranslate 0 0 1\n'
             'Material "diffuse" "rgb reflectance" [ 0 0 0 ]\nTransformEnd\n')
    assert np.all(albedo_image(tmp_path, "tb", "", inner) == 1)


def test_mix_amounts_outside_0_1(tmp_path):
    # a mix's amount outside [0, 1] takes one of the two materials, as pbrt-v4's MixMaterial
    named = ('MakeNamedMaterial "black" "string type" "diffuse" "rgb reflectance" [ 0 0 0 ]\n'
             'MakeNamedMaterial "white" "string type" "diffuse" "rgb reflectance" [ 1 1 1 ]\n')
    for amount, want in ((-1, 0.0), (2, 1.0)):
        mix = f'MakeNamedMaterial "m" "string type" "mix" "string materials" [ "black" "white" ] "float amount" {amount}\n'
        assert np.all(albedo_image(tmp_path, f"mix{amount}", named + mix, 'NamedMaterial "m"\n') == want), amount


POINT = 'LightSource "point" "point3 from" [ 0 1 0 ] "rgb I" [ 3 3 3 ]\n'
AREA = ('AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\n'
        'Shape "trianglemesh" "point3 P" [ -1 1.5 -1  1 1.5 -1  1 1.5 1  -1 1.5 1 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
        'AttributeEnd\n')


def test_integrators_without_light_sampling_leave_delta_lights_out(tmp_path):
    # pbrt-v4's randomwalk, and simplepath with "samplelights" false, find lights only where paths hit them:
    # a point light is left out (with a note), and the image is that of the scene without it
    film = 'Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 12 ]\n'
    ref, _ = render(tmp_path, "ref", film + ABOVE + AREA + FLOOR, "--spp", "8")
    for name, integrator in (("rw", 'Integrator "randomwalk"\n'),
                             ("sp", 'Integrator "simplepath" "bool samplelights" false\n')):
        img, err = render(tmp_path, name, integrator + film + ABOVE + POINT + AREA + FLOOR, "--spp", "8")
        assert np.array_equal(img, ref), name
        assert re.search(r":1: point, spot and distant lights are left out", err), err
    img, _ = render(tmp_path, "lit", 'Integrator "simplepath"\n' + film + ABOVE + POINT + AREA + FLOOR, "--spp", "8")
    assert img.mean() > 1.05 * ref.mean() > 0  # with light sampling the point light is there


@pytest.mark.parametrize("integrator", ['Integrator "randomwalk"\n', 'Integrator "simplepath" "bool samplebsdf" false\n'])
def test_integrators_sampling_directions_uniformly_refuse_specular_lobes(integrator, tmp_path):
    # randomwalk, and simplepath with "samplebsdf" false, sample directions uniformly, which never finds a
    # specular lobe (pbrt-v4 renders smooth metal, glass and coats without it): refused; a rough lobe is
    # found by uniform directions too, and the scene renders as "path"
    for material, refused in (('Material "conductor"\n', True), ('Material "dielectric" "float eta" 1.5\n', True),
                              ('Material "coateddiffuse"\n', True),
                              ('Material "conductor" "float roughness" 0.3\n', False)):
        scene = tmp_path / "u.pbrt"
        scene.write_text(integrator + ABOVE + AREA + material + FLOOR.replace("Material", "# Material"))
        if refused:
            fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "-o", "u.exr"],
                          f"{scene}:1: Integrator samples directions uniformly", tmp_path, code=1)
        else:
            ok("--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", str(tmp_path / "u.exr"))


@pytest.mark.parametrize("text,line,words", [
    # parameters pbrt-v4 refuses as unused for the integrator named, or values it does not know
    ('Integrator "path" "bool samplelights" false\n', 1, "unsupported parameter 'samplelights'"),
    ('Integrator "randomwalk" "string lightsampler" "power"\n', 1, "unsupported parameter 'lightsampler'"),
    ('Integrator "path" "string lightsampler" "nearest"\n', 1, 'lightsampler "nearest"'),
    # degenerate lenses (a pinhole, lensradius 0, takes any focal distance)
    ('Camera "perspective" "float lensradius" 0.2 "float focaldistance" 0\n', 1, "focaldistance 0"),
    ('Camera "perspective" "float lensradius" 0.2 "float focaldistance" -3\n', 1, "focaldistance -3"),
    ('Camera "perspective" "float lensradius" -1\n', 1, "is negative"),
    ('Camera "perspective" "float fov" 180\n', 1, "fov outside (0, 180)"),
    # what pbrt-v4 renders inconsistently: a sphere light it samples as a sphere of the object radius,
    # a one-sided one it flips only where rays hit it, a spot cone or an environment map it samples unshaped
    ('WorldBegin\nAreaLightSource "diffuse"\nScale 2 2 2\nShape "sphere"\n', 4, "scales or shears"),
    ('WorldBegin\nAreaLightSource "diffuse"\nScale 1 0.5 1\nShape "sphere"\n', 4, "scales or shears"),
    ('WorldBegin\nAreaLightSource "diffuse"\nScale 1 1 -1\nShape "sphere"\n', 4, "swaps handedness"),
    ('WorldBegin\nScale 3 1 1\nLightSource "spot"\n', 3, 'LightSource "spot" under a transform'),
    ('WorldBegin\nScale 1 1 2\nLightSource "infinite" "string filename" "sky.png"\n', 3, "untransformed image"),
    # projective transforms (pbrt-v4 applies them to points only)
    ('WorldBegin\nConcatTransform [ 1 0 0 0  0 1 0 0  0 0 1 0.1  0 0 0 1 ]\nShape "sphere"\n', 3, "projective"),
    ('WorldBegin\nConcatTransform [ 1 0 0 0  0 1 0 0  0 0 1 0.1  0 0 0 1 ]\nLightSource "distant"\n', 3, "projective"),
    ('ConcatTransform [ 1 0 0 0.2  0 1 0 0  0 0 1 0  0 0 0 1 ]\nCamera "perspective"\n', 2, "projective"),
    # directives in the other block than pbrt-v4 takes them in
    ('WorldBegin\nCamera "perspective"\n', 2, "Camera after WorldBegin"),
    ('WorldBegin\nFilm "rgb"\n', 2, "Film after WorldBegin"),
    ('Material "diffuse"\nWorldBegin\n', 1, "Material before WorldBegin"),
    ('AttributeBegin\nAttributeEnd\nWorldBegin\n', 1, "AttributeBegin before WorldBegin"),
    ('LightSource "point"\nWorldBegin\n', 1, "LightSource before WorldBegin"),
    # parameters of another type than pbrt-v4 reads them as
    ('Camera "perspective" "integer fov" 40\n', 1, '\'fov\' must be "float fov"'),
    ('WorldBegin\nShape "sphere" "integer radius" 2\n', 2, '\'radius\' must be "float radius"'),
    ('WorldBegin\nShape "trianglemesh" "point P" [ 0 0 0 1 0 0 0 1 0 ]\n', 2, '\'P\' must be "point3 P"'),
    ('Film "rgb" "float xresolution" 64\n', 1, '\'xresolution\' must be "integer xresolution"'),
    # "st" is read by pbrt-v4 only when it upgrades an old file
    ('WorldBegin\nShape "trianglemesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 ] "point2 st" [ 0 0 1 0 0 1 ]\n', 2, "'st'"),
])
def test_refused_with_file_and_line(text, line, words, tmp_path):
    if "WorldBegin" not in text:
        text += "WorldBegin\n"
    text += 'Shape "trianglemesh" "point3 P" [ 0 0 1  1 0 1  0 1 1 ]\n'
    scene = tmp_path / "bad.pbrt"
    scene.write_text(text)
    fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr"], f"{scene}:{line}: ",
                  tmp_path, code=1)
    r = run("--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr", cwd=tmp_path)
    assert words in r.stderr, (words, r.stderr)


# --- every scene parameter udm1-pt reads changes the image -------------------------------------------------

BASE = """Film "rgb" "integer xresolution" [ 12 ] "integer yresolution" [ 10 ] {film}
LookAt 0 5 -6  0 0 0  0 1 0
Camera "perspective" {camera}
Integrator "path" {integrator}
WorldBegin
{lights}
AttributeBegin
{material}
Shape "trianglemesh" "point3 P" [ -3 -1 -3  3 -1 -3  3 -1 3  -3 -1 3 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]
      "integer indices" [ 0 1 2 0 2 3 ] {mesh}
AttributeEnd
AttributeBegin
Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
Translate 0 0 0.5
Shape "sphere" "float radius" [ {radius} ]
AttributeEnd
"""
AREA_LIGHT = ('AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 6 6 6 ] {area}\n'
              'Shape "trianglemesh" "point3 P" [ -1 3 -1  1 3 -1  1 3 1  -1 3 1 ] "integer indices" [ 0 1 2 0 2 3 ]\n'
              'AttributeEnd')
DEFAULTS = dict(film="", camera='"float fov" [ 50 ]', integrator="", lights=AREA_LIGHT.replace("{area}", ""),
                material='Material "diffuse"', mesh="", radius="0.8")

# (parameter, the scene's fields for the base image, the fields changed, expected mean ratio or None for
# "differs"): every parameter of the `only(...)` lists of apps/scene/pbrt_parser.cpp and apps/pt/material.cpp
# that changes pbrt-v4's image
SILVER = "Material \"conductor\" \"spectrum eta\" \"metal-Ag-eta\" \"spectrum k\" \"metal-Ag-k\""
PARAMETERS = [
    ("Camera fov", {}, {"camera": '"float fov" [ 30 ]'}, None),
    ("Camera lensradius, focaldistance", {}, {"camera": '"float fov" [ 50 ] "float lensradius" 0.3 "float focaldistance" 2'},
     None),
    ("Film iso", {}, {"film": '"float iso" [ 400 ]'}, 4.0),
    ("Film maxcomponentvalue", {}, {"film": '"float maxcomponentvalue" [ 0.1 ]'}, None),
    ("Camera shutteropen, shutterclose", {}, {"camera": '"float fov" [ 50 ] "float shutteropen" 0.25 "float shutterclose" 0.75'},
     0.5),
    ("Integrator maxdepth", {}, {"integrator": '"integer maxdepth" [ 1 ]'}, None),
    ("AreaLightSource L", {}, {"lights": AREA_LIGHT.replace('[ 6 6 6 ] {area}', '[ 3 3 3 ]')}, 0.5),
    ("AreaLightSource scale", {}, {"lights": AREA_LIGHT.replace("{area}", '"float scale" 3')}, 3.0),
    ("AreaLightSource twosided", {}, {"lights": AREA_LIGHT.replace("{area}", '"bool twosided" true')}, None),
    ("LightSource point I", {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ] "rgb I" [ 2 2 2 ]'},
     {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ] "rgb I" [ 6 6 6 ]'}, 3.0),
    ("LightSource point scale", {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ]'},
     {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ] "float scale" 2'}, 2.0),
    ("LightSource point power", {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ] "float power" 10'},
     {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ] "float power" 30'}, 3.0),
    ("LightSource point from", {"lights": 'LightSource "point" "point3 from" [ 0 2 0 ]'},
     {"lights": 'LightSource "point" "point3 from" [ 2 2 0 ]'}, None),
    ("LightSource spot to", {"lights": 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ]'},
     {"lights": 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 2 0 0 ]'}, None),
    ("LightSource spot coneangle", {"lights": 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ]'},
     {"lights": 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ] "float coneangle" 60'}, None),
    ("LightSource spot conedeltaangle", {"lights": 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ]'},
     {"lights": 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ] "float conedeltaangle" 20'}, None),
    ("LightSource distant L", {"lights": 'LightSource "distant" "point3 to" [ 0 -1 0 ] "rgb L" [ 1 1 1 ]'},
     {"lights": 'LightSource "distant" "point3 to" [ 0 -1 0 ] "rgb L" [ 2 2 2 ]'}, 2.0),
    ("LightSource distant from", {"lights": 'LightSource "distant" "point3 to" [ 0 -1 0 ]'},
     {"lights": 'LightSource "distant" "point3 from" [ 1 0 0 ] "point3 to" [ 0 -1 0 ]'}, None),
    ("LightSource distant illuminance", {"lights": 'LightSource "distant" "point3 to" [ 0 -1 0 ] "float illuminance" 2'},
     {"lights": 'LightSource "distant" "point3 to" [ 0 -1 0 ] "float illuminance" 5'}, 2.5),
    ("LightSource infinite L", {"lights": 'LightSource "infinite" "rgb L" [ 1 1 1 ]'},
     {"lights": 'LightSource "infinite" "rgb L" [ 0.5 0.5 0.5 ]'}, 0.5),
    ("LightSource infinite illuminance", {"lights": 'LightSource "infinite" "float illuminance" 3'},
     {"lights": 'LightSource "infinite" "float illuminance" 6'}, 2.0),
    ("Shape sphere radius", {}, {"radius": "0.4"}, None),
    ("Shape trianglemesh N", {}, {"mesh": '"normal N" [ 0.5 1 0  0.5 1 0  -0.5 1 0  -0.5 1 0 ]'}, None),
    ("diffuse reflectance", {}, {"material": 'Material "diffuse" "rgb reflectance" [ 0.25 0.25 0.25 ]'}, None),
    ("coateddiffuse reflectance", {"material": 'Material "coateddiffuse"'},
     {"material": 'Material "coateddiffuse" "rgb reflectance" [ 0.1 0.1 0.1 ]'}, None),
    ("coateddiffuse roughness", {"material": 'Material "coateddiffuse"'},
     {"material": 'Material "coateddiffuse" "float roughness" 0.5'}, None),
    ("coateddiffuse uroughness", {"material": 'Material "coateddiffuse"'},
     {"material": 'Material "coateddiffuse" "float uroughness" 0.5'}, None),
    ("coateddiffuse vroughness", {"material": 'Material "coateddiffuse"'},
     {"material": 'Material "coateddiffuse" "float vroughness" 0.5'}, None),
    ("coateddiffuse remaproughness", {"material": 'Material "coateddiffuse" "float roughness" 0.3'},
     {"material": 'Material "coateddiffuse" "float roughness" 0.3 "bool remaproughness" false'}, None),
    ("coateddiffuse thickness", {"material": 'Material "coateddiffuse" "float roughness" 0.3 "rgb reflectance" [ 0.9 0.9 0.9 ]'},
     {"material": 'Material "coateddiffuse" "float roughness" 0.3 "rgb reflectance" [ 0.9 0.9 0.9 ] "float thickness" 1e-6'},
     None),
    ("coateddiffuse eta", {"material": 'Material "coateddiffuse"'},
     {"material": 'Material "coateddiffuse" "float eta" 2.5'}, None),
    ("coateddiffuse maxdepth", {"material": 'Material "coateddiffuse" "rgb reflectance" [ 0.9 0.9 0.9 ]'},
     {"material": 'Material "coateddiffuse" "rgb reflectance" [ 0.9 0.9 0.9 ] "integer maxdepth" 1'}, None),
    ("conductor eta", {"material": 'Material "conductor" "float roughness" 0.3'},
     {"material": 'Material "conductor" "float roughness" 0.3 "spectrum eta" "metal-Ag-eta"'}, None),
    ("conductor k", {"material": 'Material "conductor" "float roughness" 0.3'},
     {"material": 'Material "conductor" "float roughness" 0.3 "spectrum k" "metal-Ag-k"'}, None),
    ("conductor roughness", {"material": SILVER}, {"material": SILVER + ' "float roughness" 0.4'}, None),
    ("conductor uroughness", {"material": SILVER + ' "float roughness" 0.1'},
     {"material": SILVER + ' "float uroughness" 0.5'}, None),
    ("conductor vroughness", {"material": SILVER + ' "float roughness" 0.1'},
     {"material": SILVER + ' "float vroughness" 0.5'}, None),
    ("conductor remaproughness", {"material": SILVER + ' "float roughness" 0.2'},
     {"material": SILVER + ' "float roughness" 0.2 "bool remaproughness" false'}, None),
    ("dielectric eta", {"material": 'Material "dielectric" "float roughness" 0.3'},
     {"material": 'Material "dielectric" "float roughness" 0.3 "float eta" 2.4'}, None),
    ("dielectric roughness", {"material": 'Material "dielectric"'},
     {"material": 'Material "dielectric" "float roughness" 0.4'}, None),
    ("dielectric uroughness", {"material": 'Material "dielectric" "float roughness" 0.05'},
     {"material": 'Material "dielectric" "float uroughness" 0.6'}, None),
    ("dielectric vroughness", {"material": 'Material "dielectric" "float roughness" 0.05'},
     {"material": 'Material "dielectric" "float vroughness" 0.6'}, None),
    ("dielectric remaproughness", {"material": 'Material "dielectric" "float roughness" 0.2'},
     {"material": 'Material "dielectric" "float roughness" 0.2 "bool remaproughness" false'}, None),
]


_RENDERED = {}  # the base scenes' images, rendered once for the parameters that share them


@pytest.mark.parametrize("name,base,changed,ratio", PARAMETERS, ids=[p[0] for p in PARAMETERS])
def test_each_parameter_changes_the_image(name, base, changed, ratio, tmp_path):
    # the same render with one parameter changed: a different image (or, where the image is linear in the
    # parameter, the ratio of the means exactly)
    def image(fields, tag):
        text = BASE.format(**{**DEFAULTS, **fields})
        if text not in _RENDERED:
            _RENDERED[text] = render(tmp_path, tag, text, "--spp", "16", "--seed", "3")[0]
        return _RENDERED[text]

    a, b = image(base, "a"), image({**base, **changed}, "b")
    if ratio is None:
        assert np.abs(a - b).mean() > 0.01 * a.mean(), (name, a.mean(), b.mean())
    else:
        assert abs(b.mean() / a.mean() - ratio) < 1e-4 * ratio, (name, b.mean() / a.mean())
