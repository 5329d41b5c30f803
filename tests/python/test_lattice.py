"""The rank-1 lattice point set "lattice": x_n = {n z / K + shift} with z built component by component.
Pinned: its values are exactly floor(2^64 {n z_j / K}); z_j are distinct units mod K while units last;
its 2D wrap-around discrepancy is far below random points'; edge cases (K = 1, 2, more dimensions than
units); and the reason it exists: with the tent transform a lattice integrates a smooth non-periodic
function with error ~ N^-2, far below Owen-scrambled Sobol's."""

import math

import numpy as np
import pytest
from scipy.stats import qmc

import udm1


def generating_vector(k, d):
    seq = udm1.Sequence("lattice", d, point_count=k, randomize=False)
    return [(int(seq.sample(1, j, dtype=np.uint64)) * k + (1 << 64) - 1) >> 64 for j in range(d)]


@pytest.mark.parametrize("k", [3, 16, 48, 1000, 4096])
def test_values_exact_and_z_distinct_units(k):
    d = 6
    z = generating_vector(k, d)
    assert z[0] == 1 and all(math.gcd(c, k) == 1 for c in z)
    units = sum(math.gcd(c, k) == 1 for c in range(1, k))
    assert len(set(z)) == min(d, units)
    raw = udm1.Sequence("lattice", d, point_count=k, randomize=False).points(k, dtype=np.uint64)
    for n in range(0, k, max(1, k // 97)):
        for j in range(d):
            assert int(raw[n, j]) == ((n * z[j]) % k << 64) // k, (n, j)


@pytest.mark.parametrize("k", [64, 1024])
def test_far_below_random_discrepancy(k):
    pts = udm1.Sequence("lattice", 4, point_count=k, seed=2).points(k)
    for a, b in ((0, 1), (1, 2), (2, 3), (0, 3)):
        assert qmc.discrepancy(pts[:, [a, b]], method="WD") < 0.1 * udm1.discrepancy_random(k, 2, "WD")


def test_edge_cases():
    assert np.array_equal(udm1.Sequence("lattice", 3, point_count=1, randomize=False).points(1), np.zeros((1, 3)))
    two = udm1.Sequence("lattice", 3, point_count=2, randomize=False).points(2)
    assert np.array_equal(two, [[0, 0, 0], [0.5, 0.5, 0.5]])
    many = udm1.Sequence("lattice", 64, point_count=16, seed=1).points(16)  # 8 units for 64 dimensions
    assert many.shape == (16, 64) and np.all((many >= 0) & (many < 1))
    with pytest.raises(udm1.UDM1Error):
        udm1.Sequence("lattice", 65, point_count=16)
    with pytest.raises(udm1.UDM1Error):
        udm1.Sequence("lattice", 2)  # a point set needs K
    with pytest.raises(udm1.UDM1Error, match="at most 16777216 points"):  # found by fuzzing: 2^32 points hung
        udm1.Sequence("lattice", 2, point_count=2**24 + 1)


def test_tent_lattice_converges_like_n_minus_2():
    exact = (math.e - 1) * 2 * (math.exp(0.5) - 1)  # integral of exp(x + y/2) over the unit square
    ns, rmse = [256, 1024, 4096], {}
    for name in ("lattice+tent", "sobol-owen"):
        rmse[name] = []
        for n in ns:
            kw = {"point_count": n} if name.startswith("lattice") else {}
            errs = [np.mean(np.exp(p[:, 0] + 0.5 * p[:, 1])) - exact
                    for p in (udm1.Sequence(name, 2, seed=s, **kw).points(n) for s in range(1, 17))]
            rmse[name].append(math.sqrt(np.mean(np.square(errs))))
    slope = np.polyfit(np.log(ns), np.log(rmse["lattice+tent"]), 1)[0]
    assert slope < -1.7, rmse
    assert rmse["lattice+tent"][-1] < rmse["sobol-owen"][-1] / 10, rmse
