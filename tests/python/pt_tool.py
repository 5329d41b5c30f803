"""udm1-pt as the tool tests run it: the binary from UDM1_PT_TOOL, a run, a run that must succeed, and an
EXR read as linear RGB (through Mitsuba's Bitmap)."""

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
