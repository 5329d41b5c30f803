"""The package as a user installs it: the wheel built from this checkout by pip (scikit-build-core,
pyproject.toml), installed into a fresh virtual environment outside the checkout, and used there with
nothing pointing back at the checkout (no PYTHONPATH, no UDM1_LIBRARY):

- it loads the copy of libudm1 inside the installed package;
- raw fixed-point values of two presets, randomized, at small and huge indices and several streams,
  equal those the independent reference (reference.py) computes here;
- a udm1 engine (a scipy.stats.qmc.QMCEngine) drives scipy.integrate.qmc_quad to the exact integral within its standard error;
- the wheel's metadata carries the library's version and the numpy and scipy requirements, and
  auditwheel finds it manylinux-compatible.

Needs pip to reach the package index (or its cache) for scikit-build-core, numpy and scipy."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

import reference as ref
import udm1

ROOT = Path(__file__).resolve().parents[2]
CASES = [("wr", 4, 12345), ("rd", 3, 99)]  # preset, dimensions, seed (random shifts on)
STREAMS = [0, 5, 2**64 - 1]
FIRSTS = [0, 2**40, 2**64 - 8]

SMOKE = r"""
import json, sys
import numpy as np
from scipy.integrate import qmc_quad
import udm1, udm1.qmc
cases, streams, firsts = json.loads(sys.argv[1])
raw = {}
for name, d, seed in cases:
    s = udm1.Sequence(name, d, seed=seed, randomize=True)
    for stream in streams:
        for first in firsts:
            raw[f"{name}/{stream}/{first}"] = [[str(int(v)) for v in row] for row in
                                               s.points(8, first=first, stream=stream, dtype=np.uint64)]
f = lambda x: np.prod(x, axis=0)  # over [0, 1]^3: 1/8
r = qmc_quad(f, [0, 0, 0], [1, 1, 1], n_points=4096, n_estimates=8, qrng=udm1.qmc.WR(3, rng=1))
print(json.dumps({"library": udm1.library_path, "package": udm1.__file__, "version": udm1.__version__,
                  "raw": raw, "integral": float(r.integral), "standard_error": float(r.standard_error)}))
"""


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert r.returncode == 0, f"{' '.join(map(str, cmd))} failed:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("wheel")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "UDM1_LIBRARY")}
    run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q", "-w", str(tmp / "dist")], env=env)
    wheels = sorted((tmp / "dist").glob("udm1-*.whl"))
    assert len(wheels) == 1, wheels
    venv = tmp / "venv"
    run([sys.executable, "-m", "venv", str(venv)], env=env)
    py = venv / "bin" / "python"
    run([str(py), "-m", "pip", "install", "-q", "--disable-pip-version-check", str(wheels[0])], env=env)
    out = run([str(py), "-c", SMOKE, json.dumps([CASES, STREAMS, FIRSTS])], cwd=tmp, env=env)
    return wheels[0], venv, json.loads(out.stdout)


def test_installed_package_loads_its_own_library(installed):
    _, venv, got = installed
    assert Path(got["package"]).resolve().is_relative_to(venv.resolve())
    assert Path(got["library"]).resolve() == (Path(got["package"]).parent / "libudm1.so.1").resolve()
    assert got["version"] == udm1.version()


def test_installed_values_equal_the_reference(installed):
    _, _, got = installed
    for name, d, seed in CASES:
        fr = ref.preset_fracs(name, d)
        for stream in STREAMS:
            for first in FIRSTS:
                rows = got["raw"][f"{name}/{stream}/{first}"]
                for i, row in enumerate(rows):
                    for j in range(d):
                        want = ref.raw_value(ref.shift(seed, stream, j), ref.round128(fr[j]), first + i)
                        assert int(row[j]) == want, f"{name} stream {stream} index {first + i} dim {j}"


def test_installed_engine_in_qmc_quad(installed):
    _, _, got = installed
    err = got["standard_error"]
    mc = ((1 / 27 - 1 / 64) / (4096 * 8)) ** 0.5  # plain Monte Carlo's standard error with as many points
    assert 0 < err < 0.5 * mc  # (measured: about mc / 6)
    assert abs(got["integral"] - 0.125) < 5 * err


def test_wheel_metadata_and_platform(installed):
    wheel, _, _ = installed
    assert wheel.name.startswith(f"udm1-{udm1.version()}-py3-none-linux_x86_64") or "py3-none" in wheel.name
    with zipfile.ZipFile(wheel) as z:
        meta = z.read(f"udm1-{udm1.version()}.dist-info/METADATA").decode()
        names = z.namelist()
    assert "udm1/libudm1.so.1" in names and "udm1/sequence.py" in names
    assert f"Version: {udm1.version()}" in meta
    assert any(line.startswith("Requires-Dist: numpy>=") for line in meta.splitlines())
    assert any(line.startswith("Requires-Dist: scipy>=") for line in meta.splitlines())
    aw = subprocess.run([sys.executable, "-m", "auditwheel", "show", str(wheel)], capture_output=True, text=True)
    if aw.returncode != 0 and "No module named auditwheel" in aw.stderr:
        pytest.skip("auditwheel is not installed (python/requirements.txt installs it)")
    assert "manylinux" in aw.stdout, aw.stdout + aw.stderr
