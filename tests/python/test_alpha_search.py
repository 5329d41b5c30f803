"""tools/alpha_search.py and the preset it made (wopt): the figure of merit is the exact wrap-around L2
discrepancy of the Kronecker set, the preset holds exactly the generators the search chooses, and its worst
2D projection is better than the paper's WR and Roberts' R_d in many dimensions (measured by the library's
L2-star check, a criterion the search did not optimize)."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import qmc

import udm1

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import alpha_search  # noqa: E402

WOPT_ARGS = dict(dims=64, max_prime=16384, n_min=32, n_max=4096)  # as in libudm1/src/seq/presets.c


@pytest.mark.parametrize("ks,n", [((2, 13), 300), ((6761, 1999), 1000), ((3, 5), 37)])
def test_figure_of_merit_is_the_wrap_around_discrepancy(ks, n):
    a = np.mod(np.sqrt(np.array(ks, dtype=float)), 1.0)
    g = alpha_search.g_table(a, n)
    ratio = alpha_search.ratios(g[0] * g[1], np.array([n]), 2)[0]
    pts = np.mod(np.outer(np.arange(n), a), 1.0)
    expected = (1.5 ** 2 - (4 / 3) ** 2) / n
    assert ratio * expected == pytest.approx(qmc.discrepancy(pts, method="WD"), rel=1e-9)
    shifted = np.mod(pts + [0.31, 0.77], 1.0)  # the random shift does not change it
    assert ratio * expected == pytest.approx(qmc.discrepancy(shifted, method="WD"), rel=1e-9)
    assert expected == pytest.approx(udm1.discrepancy_random(n, 2, "WD"), rel=1e-12)


@pytest.mark.release_only("reruns the whole search (NumPy); the other tests of this file run its library calls under the sanitizers")
def test_preset_is_the_search_result():
    ns = np.unique(np.round(np.geomspace(WOPT_ARGS["n_min"], WOPT_ARGS["n_max"], 48)).astype(int))
    ks = alpha_search.search(alpha_search.primes_upto(WOPT_ARGS["max_prime"]), WOPT_ARGS["dims"], ns)
    mine = udm1.Sequence(alphas=[udm1.Sqrt(k) for k in ks], randomize=False).points(64, dtype=np.uint64)
    preset = udm1.Sequence("wopt", 64, randomize=False).points(64, dtype=np.uint64)
    assert np.array_equal(mine, preset)


@pytest.mark.parametrize("d", [32, 64])
def test_worst_projection_better_than_wr_and_rd(d):
    wopt = udm1.Sequence("wopt", d, randomize=False).check(256)
    for other in ("wr", "rd"):
        theirs = udm1.Sequence(other, d, randomize=False).check(256)
        assert wopt["worst_l2_star"] < 0.75 * theirs["worst_l2_star"], (other, wopt["message"], theirs["message"])
    assert not wopt["dependent"] and not wopt["rational"]


def test_tool_runs_and_rejects_bad_arguments(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    tool = [sys.executable, str(ROOT / "tools" / "alpha_search.py")]
    r = subprocess.run(tool + ["--dims", "4", "--max-prime", "200", "--check-n", "128", "--out", str(tmp_path)],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "preset.inc").read_text().count("SQRT(") == 4 and "search" in r.stdout
    for bad in (["--dims", "0"], ["--dims", "100", "--max-prime", "100"], ["--n-min", "50", "--n-max", "40"]):
        r = subprocess.run(tool + bad, capture_output=True, text=True, env=env)
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, (bad, r.stderr)


def test_wider_candidate_pool(tmp_path):
    """Cube roots and R_d's generators as candidates: the exact values written for the library are the numbers
    named, to 2^-120."""
    import json

    import mpmath

    mpmath.mp.dps = 60
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "alpha_search.py"), "--dims", "6", "--candidates",
                        "cbrt,rd", "--max-cube", "40", "--max-rd", "4", "--check-n", "64", "--no-compare", "--out",
                        str(tmp_path)], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    names = json.loads((tmp_path / "search.json").read_text())["generators"]
    lines = (tmp_path / "preset.inc").read_text().strip().splitlines()[1:]
    assert len(names) == len(lines) == 6
    for name, line in zip(names, lines):
        hi, lo = (int(x.rstrip("ul,"), 16) for x in line.split("(")[1].split(")")[0].split(", "))
        if name.startswith("cbrt"):
            x = mpmath.cbrt(int(name[5:-1]))
        else:
            d, k = name[4:].split("^-")
            x = mpmath.findroot(lambda t, d=int(d): t ** (d + 1) - t - 1, 1.1) ** -int(k)
        assert abs(mpmath.mpf((hi << 64) | lo) / mpmath.mpf(2) ** 128 - mpmath.frac(x)) < mpmath.mpf(2) ** -120, name
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "alpha_search.py"), "--candidates", "sqrt,quartic"],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 2 and "quartic" in r.stderr and len(r.stderr.strip().splitlines()) == 1
