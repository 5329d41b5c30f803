"""udm1-pt's "nanovdb" medium through the whole tool, on NanoVDB files that NanoVDB's own builder writes into
the test's folder (udm1_test_nvdb_write, built beside udm1-pt from tests/cpp/nvdb_grids.h): it renders, its
parameters change the image, its temperature grid glows without any light, both path loops agree, and every
bad file or grid is refused with the scene's file and line (tests/cpp/test_pt_nanovdb.cpp checks the lookups,
the majorants and damaged files byte by byte). Where udm1-pt's build has no NanoVDB reader, a nanovdb medium
is refused naming the missing reader."""

import os
import subprocess
from pathlib import Path

import pytest
from cli_checks import fails_cleanly
from pt_tool import TOOL, render_text, run

pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")

WRITER = os.environ.get("UDM1_NVDB_WRITER") or str(Path(TOOL).parent / "udm1_test_nvdb_write")
HAVE_WRITER = bool(TOOL) and Path(WRITER).is_file()
needs_writer = pytest.mark.skipif(not HAVE_WRITER, reason="udm1_test_nvdb_write is not built (no NanoVDB in this build)")

# the builder's fog sphere (radius 1 about (2, 2, 2)) brought to (0, 1.1, 0) by the medium's transform
SCENE = """LookAt 0 1.5 -5  0 0.9 0  0 1 0
Camera "perspective" "float fov" [ 40 ]
Integrator "volpath" "integer maxdepth" [ 6 ]
WorldBegin
{light}
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "trianglemesh" "point3 P" [ -6 0 -6  6 0 -6  6 0 6  -6 0 6 ] "integer indices" [ 0 2 1 0 3 2 ]
AttributeBegin
{transform}
MakeNamedMedium "vdb" "string type" "nanovdb" "string filename" "{file}" {params}
AttributeEnd
AttributeBegin
Material "interface"
MediumInterface "vdb" ""
Translate 0 1.1 0
Shape "sphere" "float radius" [ 1.5 ]
AttributeEnd
"""
LIGHT = 'AttributeBegin AreaLightSource "diffuse" "rgb L" [ 6 6 6 ] Translate -2 3 -1 Shape "sphere" "float radius" [ 0.5 ] AttributeEnd'
BASE = dict(light=LIGHT, transform="Translate 0 1.1 0 Translate -2 -2 -2", file="sphere.nvdb",
            params='"rgb sigma_a" [ 0.4 0.4 0.4 ] "rgb sigma_s" [ 2 2 2 ]')
MEDIUM_LINE = 10  # the MakeNamedMedium's line in SCENE


def write(tmp_path, kind, name=None):
    r = subprocess.run([WRITER, str(tmp_path / (name or f"{kind}.nvdb")), kind], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def render(tmp_path, fields, *args, name="s"):
    return render_text(tmp_path, SCENE.format(**fields), *args, name=name)


@needs_writer
@pytest.mark.release_only("renders the paths test_fire_glows_without_lights_and_loops_agree runs under the sanitizers")
@pytest.mark.parametrize("change", [
    dict(params=BASE["params"] + ' "float scale" [ 3 ]'),
    dict(params=BASE["params"] + ' "float g" [ 0.8 ]'),
    dict(params='"rgb sigma_a" [ 2 0.4 0.4 ] "rgb sigma_s" [ 2 2 2 ]'),
    dict(transform="Translate 0.5 1.1 0 Translate -2 -2 -2"),
    dict(file="fire.nvdb"),
    dict(file="fire.nvdb", params=BASE["params"] + ' "float Lescale" [ 4 ]'),
    dict(file="fire.nvdb", params=BASE["params"] + ' "float temperatureoffset" [ 800 ]'),
    dict(file="fire.nvdb", params=BASE["params"] + ' "float temperaturescale" [ 0.7 ]'),
    dict(file="named.nvdb", params=BASE["params"] + ' "string gridname" "smoke"'),  # (the same sphere: no change)
])
def test_each_parameter_changes_the_image(change, tmp_path):
    for kind in ("sphere", "fire", "named"):
        write(tmp_path, kind)
    a, _ = render(tmp_path, BASE, name="a")
    b, _ = render(tmp_path, {**BASE, **change}, name="b")
    assert a.mean() > 0.005
    if "gridname" in change.get("params", ""):
        assert (a == b).all()
    else:
        assert abs(a - b).max() > 0.01 * a.max(), change
    # the fire's temperatures named otherwise: no glow (pbrt-v4 reads "temperature" unless told)
    if change.get("file") == "fire.nvdb" and "Lescale" in change.get("params", ""):
        c, _ = render(tmp_path, {**BASE, **change, "params": change["params"] + ' "string temperaturename" "heat"'}, name="c")
        assert (c == a).all()


@needs_writer
def test_fire_glows_without_lights_and_loops_agree(tmp_path):
    write(tmp_path, "fire")
    fields = {**BASE, "light": "", "file": "fire.nvdb"}
    a, _ = render(tmp_path, fields, "--loop", "scalar", name="a")
    b, _ = render(tmp_path, fields, "--loop", "wavefront", name="b")
    assert (a == b).all() and a.mean() > 0.001
    assert a[..., 0].mean() > a[..., 2].mean()  # (a blackbody below 3000 K: red above blue)
    cold, _ = render(tmp_path, {**fields, "params": BASE["params"] + ' "float Lescale" [ 0 ]'}, name="c")
    assert cold.max() == 0


@needs_writer
@pytest.mark.parametrize("kind,params,words", [
    ("named", "", 'no grid named "density" (pbrt-v4 needs its density grid)'),
    ("named", '"string gridname" "velocity"', 'no grid named "velocity"'),
    ("double", "", 'grid "density" of type double, not float'),
    ("temperature-double", "", 'grid "temperature" of type double, not float'),
    ("level-set", "", "not a fog volume (pbrt-v4 refuses it)"),
    ("negative", "", 'grid "density" holds a negative value ('),
    ("nan", "", 'grid "density" holds a non-finite value'),
    ("empty", "", "the box of its grids' active voxels is empty"),
    ("text", "", "not a NanoVDB file (it does not begin with NanoVDB's magic number)"),
    ("truncated", "", "truncated (its grids need more bytes than it has)"),
    ("absent", "", "cannot open the NanoVDB file"),
    ("sphere", '"rgb Le" [ 1 1 1 ]', "unsupported parameter 'Le'"),
])
def test_bad_files_refused_with_file_and_line(kind, params, words, tmp_path):
    if kind == "text":
        (tmp_path / "text.nvdb").write_text("not a grid\n")
    elif kind == "truncated":
        write(tmp_path, "fire", "whole.nvdb")
        data = (tmp_path / "whole.nvdb").read_bytes()
        (tmp_path / "truncated.nvdb").write_bytes(data[:len(data) // 2])
    elif kind != "absent":
        write(tmp_path, kind)
    scene = tmp_path / "bad.pbrt"
    scene.write_text(SCENE.format(**{**BASE, "file": f"{kind}.nvdb", "params": params}))
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr"],
                      f"{scene}:{MEDIUM_LINE}: ", tmp_path, code=1)
    assert words in r.stderr, (words, r.stderr)
    if kind not in ("sphere",):
        assert f"{kind}.nvdb" in r.stderr, r.stderr


def test_no_filename_refused(tmp_path):
    scene = tmp_path / "bad.pbrt"
    scene.write_text(SCENE.format(**BASE).replace('"string filename" "sphere.nvdb" ', ""))
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "bad.exr"],
                      f"{scene}:{MEDIUM_LINE}: ", tmp_path, code=1)
    assert 'no "string filename" (pbrt-v4 needs it)' in r.stderr, r.stderr


@pytest.mark.skipif(HAVE_WRITER, reason="this build reads NanoVDB files")
def test_without_a_reader_refused_naming_it(tmp_path):
    (tmp_path / "sphere.nvdb").write_bytes(b"\0" * 64)
    scene = tmp_path / "s.pbrt"
    scene.write_text(SCENE.format(**BASE))
    r = fails_cleanly(run, ["--scene", str(scene), "--spp", "1", "--size", "8x8", "-o", "s.exr"],
                      f"{scene}:{MEDIUM_LINE}: ", tmp_path, code=1)
    assert "needs a NanoVDB reader (Debian's libnanovdb-dev)" in r.stderr, r.stderr
