"""The hardening matrices over every command-line tool:

- bad input: each documented bad input gives a one-line error that names it, a non-zero exit, and no
  output file (not even a temporary one) in the output folder;
- determinism: every tool's output is bit-identical across 1, 2 and 8 threads and across repeated runs."""

import os
import subprocess
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
