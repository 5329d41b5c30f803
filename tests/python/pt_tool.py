"""udm1-pt as the tool tests run it: the binary from UDM1_PT_TOOL, a run, a run that must succeed, an
EXR read as linear RGB (through Mitsuba's Bitmap), and a small render of a scene's text."""

import os
import subprocess

import numpy as np

TOOL = os.environ.get("UDM1_PT_TOOL", "")


def run(*args, cwd=None):
    return subprocess.run([TOOL, *args], capture_output=True, text=True, cwd=cwd, timeout=600)


def ok(*args, cwd=None):
    r = run(*args, cwd=cwd)
    assert r.returncode == 0, r.stderr
    return r


def read_exr(path):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return np.array(mi.Bitmap(str(path)), dtype=np.float64)[..., :3]


def render_text(tmp_path, text, *args, name="s"):
    """The scene `text` written to tmp_path/NAME.pbrt and rendered at 16 x 12, 8 spp: (its image, the run)."""
    scene = tmp_path / f"{name}.pbrt"
    scene.write_text(text)
    out = tmp_path / f"{name}.exr"
    r = ok("--scene", str(scene), "-o", str(out), "--size", "16x12", "--spp", "8", *args, cwd=tmp_path)
    return read_exr(out), r
