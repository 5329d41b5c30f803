"""udm1-seq: outputs equal the library's points, and every bad input gives a
one-line error naming it, the documented exit code, and no output file."""

import os
import subprocess

import numpy as np
import pytest

import udm1

TOOL = os.environ.get("UDM1_SEQ_TOOL", "")
pytestmark = pytest.mark.skipif(not TOOL, reason="UDM1_SEQ_TOOL (the udm1-seq binary) is not set")


def run(*args, cwd=None):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, cwd=cwd, timeout=120)


def test_list_names_every_preset():
    r = run("list")
    assert r.returncode == 0
    for p in udm1.presets():
        assert p.name in r.stdout


def test_dump_csv_and_npy_equal_the_library(tmp_path):
    r = run("dump", "sobol-owen", "-n", "100", "-d", "3", "--seed", "7", "--stream", "5")
    assert r.returncode == 0, r.stderr
    csv = np.loadtxt(r.stdout.splitlines(), delimiter=",")
    ref = udm1.Sequence("sobol-owen", 3, seed=7).points(100, stream=5)
    assert np.array_equal(csv, ref)  # %.17g round-trips doubles
    out = tmp_path / "p.npy"
    assert run("dump", "cmj", "-n", "64", "-d", "4", "-o", str(out)).returncode == 0
    assert np.array_equal(np.load(out), udm1.Sequence("cmj", 4, point_count=64, seed=1).points(64))


def test_images_and_metrics(tmp_path):
    import matplotlib.image as mpimg

    for cmd, extra in [("plot", ["-n", "256"]), ("spectrum", ["-n", "256", "--reps", "2", "--size", "32"]),
                       ("zoneplate", ["--spp", "2", "--width", "40", "--height", "30"])]:
        out = tmp_path / f"{cmd}.png"
        r = run(cmd, "pmj02", *extra, "-o", str(out))
        assert r.returncode == 0, r.stderr
        img = mpimg.imread(out)
        assert img.shape[0] > 0
    assert mpimg.imread(tmp_path / "zoneplate.png").shape[:2] == (30, 40)
    r = run("metrics", "halton", "-n", "512", "-d", "3", "--reps", "4")
    assert r.returncode == 0 and "star discrepancy" in r.stdout and "genz-gaussian" in r.stdout
    r = run("check", "wmmr", "-d", "22", "-n", "256")
    assert r.returncode == 0 and "worst 2D projection (17, 19)" in r.stdout


@pytest.mark.parametrize(
    "args,code,words",
    [
        (["dump", "nope"], 2, "'nope'"),
        (["dump", "wr", "-n", "abc"], 2, "-n 'abc'"),
        (["dump", "wr", "-n", "0"], 2, "-n '0'"),
        (["dump", "wr", "-n", "-5"], 2, "-n '-5'"),
        (["dump", "wr", "-d", "99999999"], 2, "-d '99999999'"),
        (["dump", "wr", "--seed", "1.5"], 2, "--seed '1.5'"),
        (["dump", "wr", "--frobnicate"], 2, "'--frobnicate'"),
        (["dump", "wr", "-n"], 2, "-n needs a value"),
        (["dump", "we", "-d", "3"], 2, "'we'"),
        (["dump", "wr", "--randomize", "wild"], 2, "'wild'"),
        (["dump", "wr", "--randomize", "screen-fixed"], 2, "screen-fixed"),
        (["dump", "sobol", "--randomize", "screen"], 2, "Weyl"),
        (["plot", "wr", "-n", "10"], 2, "-o FILE"),
        (["spectrum", "wr", "--size", "33", "-o", "x.png"], 2, "--size 33"),
        (["spectrum", "golden", "-o", "x.png"], 2, "'golden'"),
        (["frob"], 2, "'frob'"),
        (["check", "sobol", "-d", "2"], 2, "not a Weyl"),
    ],
)
def test_bad_input(args, code, words, tmp_path):
    r = run(*args, cwd=tmp_path)
    assert r.returncode == code, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("udm1-seq: ") and words in lines[0], r.stderr
    assert list(tmp_path.iterdir()) == []  # no output, no temporary file


def test_unwritable_output_leaves_nothing(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        for cmd, name in [("plot", "p.png"), ("dump", "p.npy"), ("dump", "p.csv")]:
            r = run(cmd, "wr", "-n", "16", "-o", str(ro / name))
            if os.geteuid() == 0:  # root may write anyway: then the file must be complete
                assert r.returncode == 0
                continue
            assert r.returncode == 1 and str(ro / name) in r.stderr and len(r.stderr.strip().splitlines()) == 1
            assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o700)
    r = run("plot", "wr", "-n", "16", "-o", str(tmp_path / "missing" / "p.png"))
    assert r.returncode == 1 and "missing" in r.stderr
    r = run("plot", "wr", "-n", "16", "-o", str(tmp_path / "p.unknownext"))
    assert r.returncode == 2 and "p.unknownext" in r.stderr
    assert [p.name for p in tmp_path.iterdir()] == ["ro"]
