"""udm1-noise: images equal the library's patterns, in every format and on any
number of threads; textures tile; POV-Ray renders the include it writes with
the right gamma; the figures command; and every bad input fails cleanly."""

import os
import shutil
import subprocess

import numpy as np
import pytest

import udm1

TOOL = os.environ.get("UDM1_NOISE_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_NOISE_TOOL (the udm1-noise binary) is not set")


def run(*args, cwd=None):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, cwd=cwd, timeout=300)


def read(path):
    import matplotlib.image as mpimg

    img = mpimg.imread(path)
    return img if img.ndim == 2 else img[..., 0]


def test_png_equals_the_library(tmp_path):
    out = tmp_path / "t.png"
    r = run("--pattern", "granite", "--table", "wmmr", "--seed", "4", "--size", "64x32", "--scale", "3", "-o", str(out))
    assert r.returncode == 0, r.stderr
    ref = udm1.Noise("wmmr", seed=4).pattern_grid("granite", 64, 32, size=(3, 1.5))
    img = read(out)
    assert img.shape == (32, 64)
    assert np.max(np.abs(img - np.clip(ref, 0, 1))) <= 0.5 / 255 + 1e-6  # 8-bit rounding
    data = out.read_bytes()
    gama = data.find(b"gAMA")
    assert gama > 0 and int.from_bytes(data[gama + 4:gama + 8], "big") == 100000  # linear: gamma 1.0


def test_formats_and_threads_are_deterministic(tmp_path):
    outs = {}
    for threads in ("1", "2", "8"):
        for ext, extra in (("png", ["--bits", "16"]), ("exr", []), ("tif", [])):
            out = tmp_path / f"t{threads}.{ext}"
            r = run("--pattern", "marble", "--turbulence", "0.7", "--colors", "pov", "--size", "96x64", "--threads",
                    threads, *extra, "-o", str(out))
            assert r.returncode == 0, r.stderr
            outs.setdefault(ext, []).append(out.read_bytes())
    for ext, blobs in outs.items():
        assert blobs[0] == blobs[1] == blobs[2], ext


def test_period_gives_a_seamless_texture(tmp_path):
    # a texture with period 5 over 200 pixels, and the same texture rendered from x = 2.5 (100 pixels on):
    # the second is the first rolled by half its width, wrapping around: the texture tiles
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    common = ["--pattern", "fbm", "--period", "5", "--size", "200x200", "--octaves", "4", "--bits", "16"]
    assert run(*common, "-o", str(a)).returncode == 0
    assert run(*common, "--origin", "2.5,0,0", "-o", str(b)).returncode == 0
    img, shifted = read(a).astype(np.float64), read(b).astype(np.float64)
    assert np.max(np.abs(shifted - np.roll(img, -100, axis=1))) <= 2 / 65535
    assert img.std() > 0.05


@pytest.mark.skipif(shutil.which("povray") is None, reason="povray is not installed (Debian package povray)")
def test_povray_renders_the_include(tmp_path):
    r = run("--pattern", "bozo", "--table", "rd", "--scale", "6", "--size", "256x256", "-o", str(tmp_path / "bozo.png"),
            "--pov", str(tmp_path / "bozo"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "bozo.inc").exists() and (tmp_path / "bozo_demo.pov").exists()
    p = subprocess.run(["povray", "+Ibozo_demo.pov", "+Orender.png", "+FN", "+W128", "+H128", "-D", "-J",
                        "File_Gamma=1.0"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-2000:]
    render = read(tmp_path / "render.png")
    tex = read(tmp_path / "bozo.png").reshape(128, 2, 128, 2).mean(axis=(1, 3))
    assert abs(render.mean() - tex.mean()) < 0.02  # decoded as sRGB it would be far darker
    assert np.corrcoef(render.ravel(), tex.ravel())[0, 1] > 0.95


@pytest.mark.parametrize("pattern", ["noise", "fbm", "turbulence", "ridged"])
def test_frames_loop(pattern, tmp_path):
    # 8 frames over the loop [0, 2): the frame after the last (time 2) is the first, bit for bit, and the
    # step from the last frame to the first is as small as any other step: the animation loops
    common = ["--pattern", pattern, "--loop", "2", "--size", "96x64", "--bits", "16", "--table", "rd"]
    r = run(*common, "--frames", "8", "-o", str(tmp_path / "a.png"))
    assert r.returncode == 0, r.stderr
    frames = [tmp_path / f"a_{k:04d}.png" for k in range(8)]
    assert all(f.exists() for f in frames) and not (tmp_path / "a.png").exists()
    assert run(*common, "--time", "2", "-o", str(tmp_path / "next.png")).returncode == 0
    assert (tmp_path / "next.png").read_bytes() == frames[0].read_bytes()
    assert run(*common, "--time", "1.75", "-o", str(tmp_path / "last.png")).returncode == 0
    assert (tmp_path / "last.png").read_bytes() == frames[7].read_bytes()
    imgs = [read(f).astype(np.float64) for f in frames]
    steps = [np.abs(imgs[(k + 1) % 8] - imgs[k]).mean() for k in range(8)]
    assert min(steps) > 0 and steps[7] < 1.5 * np.median(steps[:7])


CRACKLE_CASES = [("", []), ("form <1,0,0>", ["--form", "1,0,0"]), ("form <0,0.5,0> metric 1", ["--form", "0,0.5,0", "--metric", "1"]),
                 ("metric 3 form <0,0.7,0>", ["--metric", "3", "--form", "0,0.7,0"]), ("offset 0.5", ["--offset", "0.5"]),
                 ("solid", ["--solid"])]


@pytest.mark.skipif(shutil.which("povray") is None, reason="povray is not installed (Debian package povray)")
@pytest.mark.parametrize("pov,args", CRACKLE_CASES, ids=[c[0] or "default" for c in CRACKLE_CASES])
def test_crackle_as_povray_renders_it(pov, args, tmp_path):
    # POV-Ray's own crackle (its hash places the feature points) and udm1's (a sequence places them) over
    # the same 32 x 32 units: different cells, the same pattern: the same distribution of values
    (tmp_path / "c.pov").write_text(
        "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
        "camera { orthographic location <16, 16, -1> look_at <16, 16, 0> right 32*x up 32*y }\n"
        "plane { z, 0 texture { pigment { crackle %s color_map { [0 rgb 0] [1 rgb 1] } }"
        " finish { ambient 1 diffuse 0 emission 0 } } }\n" % pov)
    p = subprocess.run(["povray", "+Ic.pov", "+Opov.png", "+FN", "+W256", "+H256", "-D", "-J", "File_Gamma=1.0"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr[-2000:]
    r = run("--pattern", "crackle", *args, "--table", "rd", "--scale", "32", "--size", "256x256", "--bits", "16",
            "-o", str(tmp_path / "udm1.png"))
    assert r.returncode == 0, r.stderr
    theirs, ours = read(tmp_path / "pov.png"), read(tmp_path / "udm1.png")
    assert abs(theirs.mean() - ours.mean()) < 0.02 and abs(theirs.std() - ours.std()) < 0.02
    h = [np.histogram(x, bins=10, range=(0, 1))[0] / x.size for x in (theirs, ours)]
    assert np.abs(h[0] - h[1]).sum() < (0.2 if pov == "solid" else 0.1)  # solid: POV's noise against udm1's


def test_figures(tmp_path):
    r = run("figures", "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    for f in ("figure2.png", "figure3.png", "figures.md"):
        assert (tmp_path / f).exists()
    fig = read(tmp_path / "figure2.png")
    top, bottom = fig[:256], fig[-256:]
    assert top.std() > 0.05 and bottom.std() > 0.05 and not np.array_equal(top, bottom)


@pytest.mark.parametrize(
    "args,code,words",
    [
        (["--size", "0x10"], 2, "--size '0x10'"),
        (["--size", "100000x10"], 2, "--size '100000x10'"),
        (["--size", "12"], 2, "--size '12'"),
        (["--pattern", "plaid"], 2, "'plaid'"),
        (["--table", "nope"], 2, "'nope'"),
        (["--origin", "nan,0,0"], 2, "--origin 'nan'"),
        (["--turbulence", "inf"], 2, "--turbulence 'inf'"),
        (["--scale", "0"], 2, "--scale '0'"),
        (["--octaves", "11"], 2, "--octaves '11'"),
        (["--bits", "12"], 2, "--bits"),
        (["--wave", "square"], 2, "'square'"),
        (["--frobnicate"], 2, "'--frobnicate'"),
        (["--frames", "0"], 2, "--frames '0'"),
        (["--pattern", "marble", "--frames", "4"], 2, "'marble'"),
        (["--kind", "classic", "--time", "1"], 2, "--kind improved"),
        (["--loop", "1.5", "--frames", "2"], 2, "--loop '1.5'"),
        (["--metric", "0.5", "--pattern", "crackle"], 2, "--metric '0.5'"),
    ],
)
def test_bad_input(args, code, words, tmp_path):
    r = run(*args, "-o", "x.png", cwd=tmp_path)
    assert r.returncode == code, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("udm1-noise: ") and words in lines[0], r.stderr
    assert list(tmp_path.iterdir()) == []


def test_unwritable_output(tmp_path):
    r = run("-o", str(tmp_path / "missing" / "x.png"))
    assert r.returncode == 1 and "missing" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    r = run("-o", "")
    assert r.returncode == 2
    r = run("-o", str(tmp_path / "x.unknownext"))
    assert r.returncode == 2 and "x.unknownext" in r.stderr
    r = run("figures", "-o", str(tmp_path / "nodir"))
    assert r.returncode == 1 and "nodir" in r.stderr
    assert list(tmp_path.iterdir()) == []
