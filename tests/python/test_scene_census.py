"""The scene census (bench/bench_scene_census.py) on a small collection made here: which scenes it counts, the
stand-ins it makes (valid files that udm1-pt reads, placed by pbrt-v4's path rule, the collection left
untouched), what it reports (renders, the tool's own first refusal, an include whose text is absent, a file
no stand-in can replace, a scene read on condensed text), and the one skip line where the collection is absent."""

import gzip
import json
import os
import pathlib
import subprocess
import sys
import zlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT / "bench"))
import bench_scene_census  # noqa: E402
from pbrt_placeholders import stand_in  # noqa: E402
from pbrt_references import main_files, scan  # noqa: E402

TOOL = os.environ.get("UDM1_PT_TOOL", "")
TOOL = str(pathlib.Path(TOOL).resolve()) if TOOL else ""  # the renderer runs in each scene's folder
needs_tool = pytest.mark.skipif(not TOOL, reason="UDM1_PT_TOOL (the udm1-pt binary) is not set")
CENSUS = [sys.executable, str(ROOT / "bench" / "bench_scene_census.py")]

VIEW = ('LookAt 0 0 5  0 0 0  0 1 0\nCamera "perspective" "float fov" 40\n'
        'Film "rgb" "integer xresolution" 32 "integer yresolution" 32 "string filename" "out.exr"\nWorldBegin\n')
LIGHT = ('AttributeBegin\nAreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\nTranslate 0 3 3\n'
         'Shape "sphere" "float radius" 1\nAttributeEnd\n')
SCENES = {
    # renders as it stands: nothing it names is absent
    "plain/plain.pbrt": VIEW + LIGHT + 'Material "diffuse"\nShape "trianglemesh" "integer indices" [ 0 1 2 ]\n'
                                       '    "point3 P" [ -1 -1 0  1 -1 0  0 1 0 ]\n',
    # renders with stand-ins: a mesh, image textures of every format, an environment map, spectra, a tabulated BSDF
    "assets/assets.pbrt": VIEW + LIGHT + 'LightSource "infinite" "string filename" "textures/sky.exr"\n'
        + "".join(f'Texture "t{e}" "spectrum" "imagemap" "string filename" "textures/wood.{e}"\n'
                  for e in ("png", "exr", "pfm", "tga", "hdr"))
        + 'Material "diffuse" "texture reflectance" "tpng"\nShape "plymesh" "string filename" "geometry/part.ply"\n'
        + "".join(f'AttributeBegin\nTranslate {i - 2} -1 0\nMaterial "diffuse" "texture reflectance" "t{e}"\n'
                  f'Shape "sphere" "float radius" 0.3\nAttributeEnd\n'
                  for i, e in enumerate(("exr", "pfm", "tga", "hdr")))
        + 'Material "conductor" "spectrum eta" "spds/x.eta.spd" "spectrum k" "spds/x.k.spd"\n'
          'Shape "sphere" "float radius" 0.2\n'
        + 'Material "measured" "string filename" "bsdfs/x.bsdf"\nTranslate 0 1 0\nShape "sphere" "float radius" 0.2\n',
    # refused: curves are not modelled
    "unsupported/curve.pbrt": VIEW + LIGHT
    + 'Shape "curve" "point3 P" [ 0 0 0  1 0 0  1 1 0  0 1 0 ] "float width" 0.1\n',
    # not readable: its include's text is absent
    "partial/partial.pbrt": VIEW + LIGHT + 'Include "geometry/big.pbrt"\n',
    # the names of an include are the main file's (pbrt-v4), and a grid no stand-in can replace
    "rule/rule.pbrt": VIEW + LIGHT + 'Include "geometry/mat.pbrt"\n'
                                     'MakeNamedMedium "m" "string type" "nanovdb" "string filename" "grid.nvdb"\n',
    "rule/geometry/mat.pbrt": '# "string filename" "textures/commented.png" is a comment\n'
                              'Texture "inner" "spectrum" "imagemap"\n    "string filename" [ "textures/inner.png" ]\n'
                              'Material "diffuse" "texture reflectance" "inner"\nShape "sphere" "float radius" 0.5\n',
    # its include's full text is absent, a condensed transcription of it is in .condensed/
    "short/short.pbrt": VIEW + LIGHT + 'Include "geometry/mesh.pbrt"\n',
}
TRIANGLE = 'Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  0 1 0 ] "integer indices" [ 0 1 2 ]\n'
CONDENSED = {
    # names inside a condensed include follow pbrt-v4's rule too (relative to short/, the main file's folder)
    "short/geometry/mesh.pbrt": 'Texture "t" "spectrum" "imagemap" "string filename" "textures/c.png"\n'
                                'Material "diffuse" "texture reflectance" "t"\n' + TRIANGLE,
    # a main file whose full text is absent (the manifest lists it), read from its condensed transcription
    "bigmain/bigmain.pbrt": VIEW + LIGHT + 'Material "diffuse"\n' + TRIANGLE,
}


def make_collection(folder: pathlib.Path) -> pathlib.Path:
    col = folder / "collection"
    for rel, text in SCENES.items():
        (col / rel).parent.mkdir(parents=True, exist_ok=True)
        (col / rel).write_text(text)
    for rel, text in CONDENSED.items():
        (col / ".condensed" / rel).parent.mkdir(parents=True, exist_ok=True)
        (col / ".condensed" / rel).write_text(text)
    (col / "MANIFEST.txt").write_text("# test manifest\ngone/gone.pbrt\t0\t100\tno\tscene\ttoo large\n"
                                      "partial/geometry/big.pbrt\t0\t900000\tno\tinclude\ttoo large\n"
                                      "short/geometry/mesh.pbrt\t0\t800000\tno\tinclude\ttoo large\n"
                                      "bigmain/bigmain.pbrt\t0\t700000\tno\tscene\ttoo large\n")
    return col


def snapshot(folder: pathlib.Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def census(tmp_path_factory):
    if not TOOL:
        pytest.skip("UDM1_PT_TOOL (the udm1-pt binary) is not set")
    folder = tmp_path_factory.mktemp("census")
    col = make_collection(folder)
    before = snapshot(col)
    out = folder / "out"
    r = subprocess.run(CENSUS + ["--collection", str(col), "--tool", TOOL, "--out", str(out), "--timeout", "60",
                                 "--pbrt", ""], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    data = json.loads((out / "census.json").read_text())
    return {"col": col, "out": out, "stdout": r.stdout, "data": data, "before": before,
            "rows": {row["scene"]: row for row in data["rows"]}}


def test_scenes_are_main_files(tmp_path):
    col = make_collection(tmp_path)
    assert [p.relative_to(col).as_posix() for p in main_files(col)] == sorted(
        k for k in SCENES if "geometry/" not in k)


def test_references_follow_pbrt_v4s_path_rule(tmp_path):
    col = make_collection(tmp_path)
    refs = scan(col / "rule" / "rule.pbrt", col).references
    names = {(r.name, r.path.relative_to(col).as_posix(), r.source) for r in refs}
    # a name inside rule/geometry/mat.pbrt is relative to rule/ (the main file's folder), not to rule/geometry/
    assert ("textures/inner.png", "rule/textures/inner.png", "rule/geometry/mat.pbrt") in names
    assert not any(r.name == "textures/commented.png" for r in refs)  # comments name nothing
    assert not any(r.name == "out.exr" for r in refs)  # the Film's output is not read
    spectra = {r.name for r in scan(col / "assets" / "assets.pbrt", col).references if r.param in ("eta", "k")}
    assert spectra == {"spds/x.eta.spd", "spds/x.k.spd"}


def test_stand_ins_are_what_they_say():
    ply, what = stand_in("a/b.ply")
    assert what == "a PLY tetrahedron" and ply.startswith(b"ply\nformat binary_little_endian 1.0\n")
    assert b"property float nx" in ply and b"property float u" in ply  # normals and uv on every vertex
    assert len(ply.split(b"end_header\n", 1)[1]) == 12 * 8 * 4 + 4 * (1 + 3 * 4)
    gz, what = stand_in("m.ply.gz")
    assert gzip.decompress(gz) == ply and what.endswith("gzipped")
    png, _ = stand_in("t.PNG")
    idat = png[png.index(b"IDAT") + 4:png.index(b"IEND") - 8]
    assert zlib.decompress(idat) == (b"\x00" + bytes((188, 188, 188)) * 4) * 4  # 0.5 through the sRGB curve
    normal, what = stand_in("n.png", normal_map=True)
    assert what.endswith("(flat normal map)") and zlib.decompress(
        normal[normal.index(b"IDAT") + 4:normal.index(b"IEND") - 8]) == (b"\x00" + bytes((128, 128, 255)) * 4) * 4
    for name in ("g.nvdb", "p.jpg"):
        data, why = stand_in(name)
        assert data is None and why
    bsdf, what = stand_in("b.bsdf")
    assert what == "a grey tabulated BSDF" and bsdf.startswith(b"tensor_file\0\x01\x00")
    assert stand_in("x.spd")[0].split(b"\n")[1:3] == [b"300 1", b"900 1"]


@needs_tool
@pytest.mark.parametrize("ext", ["png", "exr", "pfm", "tga", "hdr"])
def test_udm1_pt_reads_each_image_stand_in_as_grey(tmp_path, ext):
    # the environment is the stand-in; the camera sees only it (a small sphere far behind the camera)
    (tmp_path / f"sky.{ext}").write_bytes(stand_in(f"sky.{ext}")[0])
    (tmp_path / "s.pbrt").write_text('LookAt 0 0 0  0 0 1  0 1 0\nCamera "perspective" "float fov" 40\n'
                                     'Film "rgb" "integer xresolution" 8 "integer yresolution" 8\nWorldBegin\n'
                                     f'LightSource "infinite" "string filename" "sky.{ext}"\n'
                                     'Translate 0 0 -50\nShape "sphere" "float radius" 1\n')
    r = subprocess.run([TOOL, "--scene", "s.pbrt", "--spp", "1", "--threads", "1", "-o", "o.exr"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert r.returncode == 0, r.stderr
    mean = [float(x) for x in r.stdout.split(" mean ")[1].split()[:3]]
    assert all(abs(m - 0.5) < 0.005 for m in mean), (ext, mean)  # 8-bit: 188 decodes to 0.5029


@needs_tool
def test_renders_with_stand_ins_udm1_pt_reads(census):
    rows = census["rows"]
    assert rows["plain/plain.pbrt"]["result"] == "renders" and rows["plain/plain.pbrt"]["stand_ins"] == {}
    assets = rows["assets/assets.pbrt"]
    # udm1-pt read every stand-in (a mesh, five image formats, an environment map, two spectra, a tabulated BSDF)
    # to render it
    assert assets["result"] == "renders", assets
    assert sorted(assets["stand_ins"]) == sorted(
        ["assets/geometry/part.ply", "assets/textures/sky.exr", "assets/spds/x.eta.spd", "assets/spds/x.k.spd",
         "assets/bsdfs/x.bsdf"]
        + [f"assets/textures/wood.{e}" for e in ("png", "exr", "pfm", "tga", "hdr")])
    overlay = census["out"] / "overlay"
    assert (overlay / "assets/geometry/part.ply").read_bytes() == stand_in("part.ply")[0]
    assert "| assets/assets.pbrt | renders |" in census["stdout"]
    # the collection itself is left as it was: stand-ins go to the overlay only
    assert snapshot(census["col"]) == census["before"]


@needs_tool
def test_first_refusal_is_the_tools_own(census):
    row = census["rows"]["unsupported/curve.pbrt"]
    direct = subprocess.run([TOOL, "--scene", "unsupported/curve.pbrt", "--size", "16x16", "--spp", "1", "-o",
                             str(census["out"] / "direct.exr")], capture_output=True, text=True,
                            cwd=census["col"], timeout=120)
    assert direct.returncode != 0
    line = direct.stderr.strip().splitlines()[0].removeprefix("udm1-pt: ")
    assert row["result"] == "refused" and row["refusal"] == line, (row, line)
    assert row["refusal"].startswith("unsupported/curve.pbrt:") and row["feature"]
    assert f"| unsupported/curve.pbrt | refused | {line} |" in census["stdout"]


@needs_tool
def test_absent_text_and_impossible_stand_ins_are_reported(census):
    rows = census["rows"]
    partial = rows["partial/partial.pbrt"]
    assert partial["result"] == "not readable"
    assert partial["refusal"].startswith("partial/geometry/big.pbrt: not fetched")
    assert not (census["out"] / "overlay/partial/geometry/big.pbrt").exists()  # no text is invented
    gone = rows["gone/gone.pbrt"]
    assert gone["result"] == "not readable" and "main file not fetched" in gone["refusal"]
    rule = rows["rule/rule.pbrt"]
    assert rule["stand_ins"] == {"rule/textures/inner.png": "a 4x4 PNG"}  # where pbrt-v4 reads it
    assert rule["blocked"] == {"rule/grid.nvdb": stand_in("grid.nvdb")[1]}
    tally = dict((f, n) for f, n, _ in bench_scene_census.tally(census["data"]["rows"]))
    assert tally["text not available (include not fetched)"] == 1
    assert tally["text not available (main file not fetched)"] == 1
    assert sum(tally.values()) == sum(r["result"] != "renders" for r in census["data"]["rows"])


@needs_tool
def test_condensed_text_is_used_and_labelled(census):
    rows = census["rows"]
    short, big = rows["short/short.pbrt"], rows["bigmain/bigmain.pbrt"]
    assert short["result"] == "renders" and short["condensed"] == ["short/geometry/mesh.pbrt"], short
    assert short["stand_ins"] == {"short/textures/c.png": "a 4x4 PNG"} and short["unreadable"] == {}
    assert big["result"] == "renders" and big["condensed"] == ["bigmain/bigmain.pbrt"], big
    overlay = census["out"] / "overlay"
    for rel, text in CONDENSED.items():  # read where the full text would be, from the overlay only
        assert (overlay / rel).read_text() == text and not (census["col"] / rel).exists()
    # never counted as read whole: labelled in its row and counted apart in the summary
    assert "| short/short.pbrt | renders |" in census["stdout"]
    assert "condensed geometry (short/geometry/mesh.pbrt) |" in census["stdout"]
    assert "condensed geometry (bigmain/bigmain.pbrt) |" in census["stdout"]
    renders = sum(r["result"] == "renders" for r in rows.values())
    assert f"Results: renders {renders} (of which 2 on condensed text)" in census["stdout"]
    assert rows["plain/plain.pbrt"]["condensed"] == [] and rows["partial/partial.pbrt"]["result"] == "not readable"
    assert snapshot(census["col"]) == census["before"]


FAKE_PBRT = """#!/bin/sh
# pbrt-v4's command line as the census gives it; the scene file is the last argument
for last; do :; done
case "$last" in
  plain.pbrt) exit 0 ;;
  curve.pbrt) echo 'pbrt version 4'
              printf '\\033[1m\\033[31mError\\033[0m: %s\\n' 'curve.pbrt:9:2: "width": unused parameter.' >&2
              exit 1 ;;
  *) echo '[ tid 1 @ 0.000s samplers.cpp:194 ] FATAL Check failed: x' >&2; kill -ABRT $$ ;;
esac
"""


@needs_tool
def test_pbrt_v4_column_is_its_result_on_the_same_overlay(tmp_path):
    col = make_collection(tmp_path)
    fake = tmp_path / "pbrt"
    fake.write_text(FAKE_PBRT)
    fake.chmod(0o755)
    out = tmp_path / "out"
    r = subprocess.run(CENSUS + ["--collection", str(col), "--tool", TOOL, "--out", str(out), "--pbrt", str(fake),
                                 "--only", "plain,curve,assets", "--readme-table"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    rows = {row["scene"]: row for row in json.loads((out / "census.json").read_text())["rows"]}
    assert rows["plain/plain.pbrt"]["pbrt"] == {"result": "renders", "message": ""}
    assert rows["unsupported/curve.pbrt"]["pbrt"] == {"result": "refused",
                                                      "message": 'curve.pbrt:9:2: "width": unused parameter.'}
    assert rows["assets/assets.pbrt"]["pbrt"] == {"result": "crash", "message": "FATAL Check failed: x"}
    assert "(pbrt-v4 renders 1 of the 3 with the same stand-ins)" in r.stdout
    assert "| first refusal | scenes | pbrt-v4 renders |" in r.stdout
    md = (out / "census.md").read_text()
    assert '| refused: curve.pbrt:9:2: "width": unused parameter. |' in md


def test_absent_collection_is_one_skip_line(tmp_path):
    r = subprocess.run(CENSUS + ["--collection", str(tmp_path / "absent"), "--out", str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and r.stderr == ""
    assert r.stdout.count("\n") == 1 and r.stdout.startswith("skipped: the pbrt-v4 scene collection's text is absent")
    env = dict(os.environ, UDM1_PBRT_SCENES=str(tmp_path / "also-absent"))
    r = subprocess.run(CENSUS + ["--out", str(tmp_path / "out")], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 0 and str(tmp_path / "also-absent") in r.stdout


@needs_tool
def test_absent_includes_empty_judges_the_rest_and_is_labelled(tmp_path):
    col = make_collection(tmp_path)
    # an absent include that defines a named material the main file uses: refused (named), never rendered
    (col / "named" / "named.pbrt").parent.mkdir(parents=True)
    (col / "named" / "named.pbrt").write_text(VIEW + LIGHT + 'Include "materials.pbrt"\nNamedMaterial "gone"\n' + TRIANGLE)
    # an absent include whose last directive the main file's parameters continue (pbrt-v4 reads on past an
    # included file's end): not judged on the empty stand-in, the include's text is needed
    (col / "continued" / "continued.pbrt").parent.mkdir(parents=True)
    (col / "continued" / "continued.pbrt").write_text(VIEW + LIGHT + 'AttributeBegin\nInclude "geometry/medium.pbrt"\n'
                                                      '  "spectrum sigma_a" [ 300 20 830 20 ]\nAttributeEnd\n' + TRIANGLE)
    before = snapshot(col)
    out = tmp_path / "out"
    r = subprocess.run(CENSUS + ["--collection", str(col), "--tool", TOOL, "--out", str(out), "--pbrt", "",
                                 "--only", "partial,named,plain,continued", "--absent-includes", "empty"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    rows = {row["scene"]: row for row in json.loads((out / "census.json").read_text())["rows"]}
    partial, named, plain = rows["partial/partial.pbrt"], rows["named/named.pbrt"], rows["plain/plain.pbrt"]
    assert partial["result"] == "renders" and partial["emptied"] == ["partial/geometry/big.pbrt"], partial
    assert partial["unreadable"] == {}
    assert named["result"] == "refused" and "gone" in named["refusal"] and named["emptied"] == ["named/materials.pbrt"]
    assert plain["result"] == "renders" and plain["emptied"] == []
    continued = rows["continued/continued.pbrt"]
    assert continued["result"] == "not readable" and continued["emptied"] == ["continued/geometry/medium.pbrt"], continued
    assert continued["refusal"].startswith("continued/continued.pbrt:") and "its text is needed" in continued["refusal"]
    assert "empty includes (partial/geometry/big.pbrt) |" in r.stdout
    assert "Results: renders 2 (of which 1 with absent includes empty), not readable 1 (of which 1 with absent includes " \
           "empty), refused 1 (of which 1 with absent includes empty)" \
        in r.stdout, r.stdout
    assert snapshot(col) == before  # the collection untouched: the empty files are in the overlay
    # without the option the same include is reported as not readable
    r = subprocess.run(CENSUS + ["--collection", str(col), "--tool", TOOL, "--out", str(tmp_path / "out2"), "--pbrt", "",
                                 "--only", "partial"], capture_output=True, text=True, timeout=300)
    row = json.loads((tmp_path / "out2" / "census.json").read_text())["rows"][0]
    assert row["result"] == "not readable" and "partial/geometry/big.pbrt" in row["unreadable"]


NVDB_WRITER = str(pathlib.Path(TOOL).parent / "udm1_test_nvdb_write") if TOOL else ""


@needs_tool
@pytest.mark.skipif(not NVDB_WRITER or not pathlib.Path(NVDB_WRITER).is_file(),
                    reason="udm1_test_nvdb_write is not built (no NanoVDB in this build)")
def test_nvdb_stand_ins_with_the_writer(tmp_path):
    # with --nvdb-writer an absent NanoVDB grid gets a stand-in NanoVDB's builder wrote, where pbrt-v4 reads it,
    # and a scene whose medium renders it (in a sphere) renders; without it, it is reported as impossible
    col = tmp_path / "col"
    scene = ('Integrator "volpath"\n' + VIEW + LIGHT + 'AttributeBegin\nTranslate -2 -2 -2\n'
             'MakeNamedMedium "m" "string type" "nanovdb" "string filename" "grids/smoke.nvdb"\nAttributeEnd\n'
             'AttributeBegin\nMaterial "interface"\nMediumInterface "m" ""\nShape "sphere" "float radius" 1.5\nAttributeEnd\n')
    (col / "vdb").mkdir(parents=True)
    (col / "vdb" / "vdb.pbrt").write_text(scene)
    rows = {}
    for flag in ([], ["--nvdb-writer", NVDB_WRITER]):
        out = tmp_path / f"out{len(flag)}"
        r = subprocess.run(CENSUS + ["--collection", str(col), "--tool", TOOL, "--out", str(out), "--pbrt", "", *flag],
                           capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr
        rows[bool(flag)] = json.loads((out / "census.json").read_text())["rows"][0]
        assert not (col / "vdb" / "grids").exists()  # (the collection untouched)
    assert rows[False]["result"] == "blocked" and rows[False]["blocked"] == {"vdb/grids/smoke.nvdb": stand_in("x.nvdb")[1]}
    assert rows[False]["feature"] == "no stand-in (a NanoVDB grid)", rows[False]
    assert rows[True]["result"] == "renders", rows[True]
    assert rows[True]["stand_ins"] == {"vdb/grids/smoke.nvdb": bench_scene_census.NVDB_STAND_IN}
    assert (tmp_path / "out2" / "overlay" / "vdb" / "grids" / "smoke.nvdb").read_bytes()[:8] == b"NanoVDB0"
