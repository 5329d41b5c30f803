"""The hardening matrices over every command-line tool:

- bad input: each documented bad input gives a one-line error that names it, a non-zero exit, and no
  output file (not even a temporary one) in the output folder; so do inputs and outputs that make a
  library fail (damaged images, unwritable outputs, broken meshes and tabulated BSDF files) and scene text with control characters;
- determinism: every tool's output is bit-identical across 1, 2 and 8 threads and across repeated runs."""

import gzip
import os
import resource
import signal
import stat
import struct
import subprocess
import zlib
from pathlib import Path

import pytest

TOOLS = {"seq": os.environ.get("UDM1_SEQ_TOOL", ""), "noise": os.environ.get("UDM1_NOISE_TOOL", ""),
         "ao": os.environ.get("UDM1_AO_TOOL", ""), "pt": os.environ.get("UDM1_PT_TOOL", "")}
pytestmark = pytest.mark.skipif(not all(TOOLS.values()), reason="the tools' paths (UDM1_*_TOOL) are not set: run "
                                "through CTest")

# (tool, arguments with {out} for the output file, a word the error must contain)
BAD = [
    ("seq", ["dump", "nope", "-n", "4", "-o", "{out}.npy"], "nope"),
    ("seq", ["dump", "wr", "-n", "-3", "-o", "{out}.npy"], "-3"),
    ("seq", ["dump", "wr", "-d", "0", "-o", "{out}.npy"], "0"),
    ("seq", ["plot", "wr", "-n", "16", "-o", "/nonexistent/dir/p.png"], "/nonexistent/dir/p.png"),
    ("seq", ["frobnicate"], "frobnicate"),
    ("noise", ["--size", "0x0", "-o", "{out}.png"], "0x0"),
    ("noise", ["--size", "100000x100000", "-o", "{out}.png"], "100000x100000"),
    ("noise", ["--pattern", "plaid", "-o", "{out}.png"], "plaid"),
    ("noise", ["--table", "nope", "-o", "{out}.png"], "nope"),
    ("noise", ["--octaves", "nan", "-o", "{out}.png"], "nan"),
    ("noise", ["-o", "{out}.bmp"], ".bmp"),
    ("ao", ["--sampler", "nope", "-o", "{out}.exr"], "nope"),
    ("ao", ["--spp", "0", "-o", "{out}.exr"], "0"),
    ("ao", ["--size", "12x", "-o", "{out}.exr"], "12x"),
    ("ao", ["--scene", "/nonexistent.pbrt", "-o", "{out}.exr"], "/nonexistent.pbrt"),
    ("ao", ["--scene", "/dev/zero", "-o", "{out}.exr"], "/dev/zero"),
    ("ao", ["--randomize", "blue", "-o", "{out}.exr"], "blue"),
    ("pt", ["--sampler", "wr+foo", "-o", "{out}.exr"], "wr+foo"),
    ("pt", ["--spp", "abc", "-o", "{out}.exr"], "abc"),
    ("pt", ["--threads", "0", "-o", "{out}.exr"], "0"),
    ("pt", ["--scene", "/dev/zero", "-o", "{out}.exr"], "/dev/zero"),
    ("pt", ["--sampler", "lattice", "--spp", "16777217", "-o", "{out}.exr"], "16777216"),
    ("pt", ["--sampler", "pmj02", "--randomize", "screen", "-o", "{out}.exr"], "Weyl"),
    ("pt", ["merge", "{out}.missing.exr", "-o", "{out}.exr"], "missing"),
    ("pt", ["compare", "/dev/zero", "/dev/zero"], "/dev/zero"),
]


@pytest.mark.parametrize("tool,args,word", BAD, ids=[f"{t}:{' '.join(a[:2])}" for t, a, _ in BAD])
def test_bad_input(tool, args, word, tmp_path):
    out = tmp_path / "out"
    argv = [TOOLS[tool]] + [a.replace("{out}", str(out)) for a in args]
    r = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path, timeout=120)
    lines = r.stderr.strip().splitlines()
    assert r.returncode != 0, (argv, r.stdout, r.stderr)
    assert len(lines) == 1 and word in lines[0], (argv, r.stderr)
    assert "Traceback" not in r.stderr and "terminate called" not in r.stderr
    assert list(tmp_path.iterdir()) == [], (argv, list(tmp_path.iterdir()))  # no output, no temporary file


# Errors that come from libraries or quote raw input: what OpenImageIO, libpng, libtiff, OpenEXR, the PLY and
# OBJ readers, the scene lexer and the C library say reaches the user as the tool's one line, naming the file
# (and line, for scene files); nothing of it is printed on its own line, no raw byte of the input reaches the
# terminal, and no output file is left. The inputs are made once (library_inputs); {in} is their folder,
# {out} a name in the run's own empty folder.
SCENE_HEAD = 'LookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective"\nWorldBegin\n'
SCENE_TRI = 'Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  0 1 0 ] "integer indices" [ 0 1 2 ]\n'


@pytest.fixture(scope="module")
def library_inputs(tmp_path_factory):
    d = tmp_path_factory.mktemp("inputs")
    for name in ("good.png", "good.exr", "good.tif"):
        subprocess.run([TOOLS["noise"], "--size", "32x32", "-o", str(d / name)], check=True, timeout=120)
    subprocess.run([TOOLS["seq"], "plot", "wr", "--size", "64", "-o", str(d / "good.jpg")], check=True, timeout=120)
    subprocess.run([TOOLS["ao"], "--size", "8x8", "--spp", "1", "-o", str(d / "part.exr")], check=True, timeout=120,
                   capture_output=True)
    side = 16  # a Radiance HDR by hand: header, then flat RGBE pixels
    (d / "good.hdr").write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (side, side)
                                 + bytes([128, 64, 32, 129]) * side * side)
    for ext in ("png", "exr", "tif", "jpg", "hdr"):  # each cut in the middle of its pixels
        data = (d / f"good.{ext}").read_bytes()
        (d / f"cut.{ext}").write_bytes(data[: len(data) // 2])
    png = bytearray((d / "good.png").read_bytes())
    png[29] ^= 0xFF  # IHDR's CRC
    (d / "crc.png").write_bytes(bytes(png))
    idat = png.find(b"IDAT")  # a whole file whose image data is not a deflate stream (its CRC right)
    body = bytes(range(50))
    (d / "deflate.png").write_bytes(bytes(png[: idat - 4]) + struct.pack(">I", len(body)) + b"IDAT" + body
                                    + struct.pack(">I", zlib.crc32(b"IDAT" + body)) + png[png.find(b"IEND") - 4:])
    (d / "text.png").write_text("not an image\n")
    (d / "adir.png").mkdir()
    (d / "adir.exr").mkdir()
    (d / "afile").write_text("a file, not a folder\n")
    os.mkfifo(d / "fifo.npy")
    (d / "badhead.ply").write_bytes(b"ply\nformat \x1b[2Jbinary\r\nend_header\n")
    (d / "noend.ply").write_bytes(b"ply\nformat ascii 1.0\nelement vertex 3\n")
    (d / "ctl.obj").write_bytes(b"v 0 0 0\nv 1 \x1b[0m 0\n")
    # a tabulated BSDF file (Material "measured") whose one field, named with control characters, lies outside it
    name = b"nd\x1b[2J\r\x85\xff\tf"
    (d / "ctl.bsdf").write_bytes(b"tensor_file\0\x01\x00" + struct.pack("<I", 1) + struct.pack("<H", len(name)) + name +
                                 struct.pack("<HBQQ", 1, 10, 1 << 40, 4))
    scenes = {
        "texture.pbrt": SCENE_HEAD + 'Texture "t" "spectrum" "imagemap" "string filename" "cut.png"\n'
                        'Material "diffuse" "texture reflectance" "t"\n' + SCENE_TRI,
        "envcut.pbrt": SCENE_HEAD + 'LightSource "infinite" "string filename" "cut.hdr"\n' + SCENE_TRI,
        "plymesh.pbrt": SCENE_HEAD + 'Shape "plymesh" "string filename" "noend.ply"\n',
        "cr.pbrt": SCENE_HEAD + 'Shape "sphere\r\t\x1b[31m"\n',
        "ctl.pbrt": SCENE_HEAD + 'Frob\x01\x7f\x85 3\n' + SCENE_TRI,
        "type.pbrt": SCENE_HEAD + 'Shape "trianglemesh" "poi\x1bnt3 P" [ 0 0 0 ]\n',
        "long.pbrt": SCENE_HEAD + "x" * 100000 + "\n",
        "nul.pbrt": SCENE_HEAD + "Frob\0nicate 1\n",
        "gz.pbrt": SCENE_HEAD + 'Include "inc.pbrt"\n',
        "badgz.pbrt": SCENE_HEAD + 'Include "bad.pbrt.gz"\n',
        "spd.pbrt": SCENE_HEAD + 'AreaLightSource "diffuse" "spectrum L" "spd.txt"\n' + SCENE_TRI,
        "measured.pbrt": SCENE_HEAD + 'Material "measured" "string filename" "ctl.bsdf"\n' + SCENE_TRI,
    }
    for name, text in scenes.items():
        (d / name).write_bytes(text.encode("latin-1"))
    (d / "inc.pbrt").write_bytes(gzip.compress((SCENE_HEAD + SCENE_TRI).encode()))  # gzip bytes, not named .gz
    (d / "bad.pbrt.gz").write_bytes(b"not \x1b[2J gzip\r\n")
    (d / "spd.txt").write_text("400 1\nabc\ndef\n")
    return d


# (tool, arguments, words the one line must hold, the output file size limit in bytes or None; negative:
# the limit with SIGXFSZ ignored, so that the write returns EFBIG to the writer)
LIBRARY_BAD = [
    # images read: cut short, a bad CRC, a bad deflate stream, not an image at all (libpng, OpenEXR, libtiff,
    # libjpeg, Radiance)
    ("pt", ["compare", "{in}/cut.png", "{in}/good.png"], ["cut.png"], None),
    ("pt", ["compare", "{in}/crc.png", "{in}/good.png"], ["crc.png"], None),
    ("ao", ["compare", "{in}/good.png", "{in}/cut.tif"], ["cut.tif"], None),
    ("pt", ["compare", "{in}/cut.jpg", "{in}/good.jpg"], ["cut.jpg"], None),
    ("pt", ["compare", "{in}/cut.hdr", "{in}/good.hdr"], ["cut.hdr"], None),
    ("ao", ["sweep", "--against", "{in}/deflate.png", "--size", "8x8", "--spp", "1"], ["deflate.png"], None),
    ("ao", ["merge", "{in}/cut.exr", "-o", "{out}.exr"], ["cut.exr"], None),
    ("pt", ["compare", "{in}/good.png", "{in}/text.png"], ["text.png"], None),
    ("pt", ["--scene", "{in}/texture.pbrt", "--size", "8x8", "-o", "{out}.exr"], ["texture.pbrt:4", "cut.png"], None),
    ("pt", ["--scene", "{in}/envcut.pbrt", "--size", "8x8", "-o", "{out}.exr"], ["envcut.pbrt:4", "cut.hdr"], None),
    # images written: a folder or a device named as the file, a folder that cannot be written
    ("noise", ["--size", "16x16", "-o", "{in}/adir.png"], ["adir.png"], None),
    ("seq", ["plot", "wr", "-o", "{in}/afile/p.png"], ["afile/p.png"], None),
    ("seq", ["dump", "wr", "-o", "{in}/fifo.npy"], ["fifo.npy"], None),
    ("noise", ["figures", "-o", "{in}/afile"], ["afile"], None),
    ("noise", ["--size", "16x16", "-o", "{out}.png", "--pov", "{in}/afile/tex"], ["afile/tex"], None),
    ("ao", ["--size", "8x8", "--spp", "1", "-o", "{in}/adir.exr"], ["adir.exr"], None),
    ("pt", ["--size", "8x8", "--spp", "1", "-o", "{out}.exr", "--png", "{in}/afile/p.png"], ["afile/p.png"], None),
    ("pt", ["compare", "{in}/good.png", "{in}/good.png", "--diff", "{in}/adir.png"], ["adir.png"], None),
    ("ao", ["sweep", "--against", "{in}/part.exr", "--size", "8x8", "--spp", "1", "--images", "{in}/afile"],
     ["afile"], None),
    # images written past the file size limit (a write fails in the middle of the file)
    ("noise", ["--size", "128x128", "--pattern", "granite", "-o", "{out}.png"], ["out.png"], 3000),
    ("noise", ["--size", "128x128", "--pattern", "granite", "-o", "{out}.png"], ["out.png"], -3000),
    ("seq", ["plot", "wr", "-o", "{out}.hdr"], ["out.hdr"], 3000),
    ("seq", ["dump", "wr", "-n", "4000", "-o", "{out}.npy"], ["out.npy"], 3000),
    ("ao", ["--size", "64x64", "--spp", "4", "-o", "{out}.png", "--png", "{out}.exr"], ["out.exr"], 3000),
    ("pt", ["--size", "32x32", "--spp", "2", "--checkpoints", "1,2", "-o", "{out}.exr"], ["out.1.exr"], 3000),
    # meshes: a PLY header with control characters, one without end_header, an OBJ with an escape sequence
    ("ao", ["--scene", "{in}/badhead.ply", "-o", "{out}.exr"], ["badhead.ply:2"], None),
    ("pt", ["--scene", "{in}/plymesh.pbrt", "-o", "{out}.exr"], ["plymesh.pbrt:4", "noend.ply"], None),
    ("ao", ["--scene", "{in}/ctl.obj", "-o", "{out}.exr"], ["ctl.obj:2"], None),
    # a tabulated BSDF file's field named with control characters (quoted in the message)
    ("pt", ["--scene", "{in}/measured.pbrt", "-o", "{out}.exr"], ["measured.pbrt:4", "ctl.bsdf", "lies outside"], None),
    # scene text quoted in the message: CR, tab, escape sequences, DEL, C1 controls, NUL, a line of 100000
    # bytes, a gzip file where text is expected, a file named .gz that is not gzip, a spectrum file's bad word
    ("pt", ["--scene", "{in}/cr.pbrt", "-o", "{out}.exr"], ["cr.pbrt:4"], None),
    ("ao", ["--scene", "{in}/ctl.pbrt", "-o", "{out}.exr"], ["ctl.pbrt:4"], None),
    ("pt", ["--scene", "{in}/type.pbrt", "-o", "{out}.exr"], ["type.pbrt:4"], None),
    ("pt", ["--scene", "{in}/long.pbrt", "-o", "{out}.exr"], ["long.pbrt:4"], None),
    ("ao", ["--scene", "{in}/nul.pbrt", "-o", "{out}.exr"], ["nul.pbrt:4"], None),
    ("pt", ["--scene", "{in}/gz.pbrt", "-o", "{out}.exr"], ["inc.pbrt:1"], None),
    ("pt", ["--scene", "{in}/badgz.pbrt", "-o", "{out}.exr"], ["badgz.pbrt:4", "bad.pbrt.gz", "not valid gzip data"], None),
    ("pt", ["--scene", "{in}/spd.pbrt", "-o", "{out}.exr"], ["spd.pbrt:4", "spd.txt"], None),
]


def file_size_limit(limit):
    """A preexec_fn: the child may write files of at most abs(limit) bytes (a larger write fails with EFBIG,
    or SIGXFSZ kills a tool that does not ignore it; a negative limit ignores SIGXFSZ for the tool)."""
    def apply():
        resource.setrlimit(resource.RLIMIT_FSIZE, (abs(limit), abs(limit)))
        if limit < 0:
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    return apply


@pytest.mark.parametrize("tool,args,words,fsize", LIBRARY_BAD,
                         ids=[f"{t}:{' '.join(Path(a).name for a in args)}{f':limit{f}' if f else ''}"
                              for t, args, _, f in LIBRARY_BAD])
def test_library_errors_are_one_line(tool, args, words, fsize, library_inputs, tmp_path):
    out = tmp_path / "out"
    argv = [TOOLS[tool]] + [a.replace("{in}", str(library_inputs)).replace("{out}", str(out)) for a in args]
    r = subprocess.run(argv, capture_output=True, cwd=tmp_path, timeout=300,
                       preexec_fn=file_size_limit(fsize) if fsize else None)
    err = r.stderr.decode("utf-8")  # strictly: a raw byte of a binary input would not decode
    lines = err.splitlines()  # splits at CR, VT, FF, the C1 NEL and U+2028 too
    assert r.returncode not in (0, -signal.SIGXFSZ), (argv, r.returncode, err)
    assert r.returncode > 0, (argv, r.returncode, err)  # an exit, not a signal
    assert len(lines) == 1 and lines[0].startswith(f"udm1-{tool}: ") and err.endswith("\n"), (argv, err)
    assert lines[0].isprintable() and len(lines[0]) < 1000, (argv, err)
    assert all(w in lines[0] for w in words), (argv, words, err)
    assert r.stdout == b"", (argv, r.stdout)  # no result printed before the error
    assert list(tmp_path.iterdir()) == [], (argv, list(tmp_path.iterdir()))  # no output, no temporary file
    if any("fifo.npy" in a for a in args):
        assert stat.S_ISFIFO(os.stat(library_inputs / "fifo.npy").st_mode)  # a device or FIFO is never replaced
    assert [p.name for p in (library_inputs / "adir.png").iterdir()] == []  # nor written into as a folder


# (tool, arguments writing {out}); each run with --threads 1, 2 and 8, and twice with the default
SAME = [
    ("noise", ["--size", "96x64", "--pattern", "marble", "--table", "wr", "-o", "{out}.png"]),
    ("noise", ["--size", "96x64", "--pattern", "granite", "-o", "{out}.exr"]),
    ("ao", ["--size", "48x32", "--spp", "8", "--sampler", "wopt", "-o", "{out}.exr"]),
    ("ao", ["--size", "48x32", "--spp", "8", "--sampler", "lattice", "--png", "{out}.png"]),
    ("pt", ["--size", "40x30", "--spp", "8", "--sampler", "wr", "--randomize", "screen", "-o", "{out}.exr"]),
    ("pt", ["--size", "40x30", "--spp", "8", "--sampler", "pmj02", "--png", "{out}.png"]),
]


@pytest.mark.parametrize("tool,args", SAME, ids=[f"{t}:{a[-1]}:{a[5] if len(a) > 5 else ''}" for t, a in SAME])
def test_bit_identical_across_threads_and_runs(tool, args, tmp_path):
    outputs = []
    for k, threads in enumerate(["1", "2", "8", None, None]):
        out = tmp_path / f"r{k}"
        argv = [TOOLS[tool]] + [a.replace("{out}", str(out)) for a in args] + (["--threads", threads] if threads else [])
        r = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path, timeout=300)
        assert r.returncode == 0, (argv, r.stderr)
        outputs.append(Path(str(out) + args[-1][len("{out}"):]).read_bytes())
    assert all(o == outputs[0] for o in outputs[1:])


def test_seq_dump_identical_across_runs(tmp_path):
    outs = []
    for k in range(3):
        r = subprocess.run([TOOLS["seq"], "dump", "wopt", "-n", "300", "-d", "16", "--seed", "5", "-o",
                            str(tmp_path / f"d{k}.npy")], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        outs.append((tmp_path / f"d{k}.npy").read_bytes())
    assert outs[0] == outs[1] == outs[2]


def test_point_sets_at_the_largest_point_count():
    """Found by fuzzing: CMJ with K = 2^32 - 1 hung (N + m - 1 wrapped in 32 bits, and the permutation of an
    empty range never ended). Every point set at its largest K gives values in [0, 1) at once."""
    import numpy as np

    import udm1

    for name, k in (("cmj", 2**32 - 1), ("grps", 2**26), ("lp", 2**32 - 1), ("hammersley", 2**32 - 1),
                    ("episwr", 2**32 - 1), ("lattice", 2**24), ("pmj02", 2**20)):
        seq = udm1.Sequence(name, 2, point_count=k, seed=3)
        v = np.array([seq.sample(i, j) for i in (0, 1, k // 3, k - 1) for j in (0, 1)])
        assert np.all((v >= 0) & (v < 1)), name


# What every tool does with no arguments: its built-in default, written to a default image in the
# current folder (udm1-seq plots WR's points; udm1-noise a noise texture; the renderers the Cornell box).
DEFAULT_IMAGES = {"seq": "seq.png", "noise": "noise.png", "ao": "ao.png", "pt": "pt.png"}


@pytest.mark.parametrize("tool", sorted(DEFAULT_IMAGES))
def test_no_arguments_write_the_default_image(tool, tmp_path):
    r = subprocess.run([TOOLS[tool]], capture_output=True, text=True, cwd=tmp_path, timeout=900)
    assert r.returncode == 0, r.stderr
    assert [p.name for p in tmp_path.iterdir()] == [DEFAULT_IMAGES[tool]]
    assert (tmp_path / DEFAULT_IMAGES[tool]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --help after every subcommand prints the usage and exits 0, writing nothing.
SUBCOMMANDS = {"seq": ["list", "dump", "metrics", "plot", "spectrum", "zoneplate", "check"],
               "noise": ["figures"],
               "ao": ["reference", "merge", "compare", "sweep"],
               "pt": ["reference", "merge", "compare", "sweep", "export"]}


@pytest.mark.parametrize("tool,command", [(t, c) for t in sorted(SUBCOMMANDS) for c in [None] + SUBCOMMANDS[t]])
def test_help_on_every_subcommand(tool, command, tmp_path):
    argv = [TOOLS[tool]] + ([command] if command else []) + ["--help"]
    r = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path, timeout=60)
    assert r.returncode == 0 and r.stdout.startswith("usage: "), (argv, r.stdout, r.stderr)
    if command:
        assert command in r.stdout, (argv, r.stdout)
    assert list(tmp_path.iterdir()) == []
