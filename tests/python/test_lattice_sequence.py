"""The embedded rank-1 lattice "lattice-seq": x_n = {phi_2(n) z + shift}, phi_2 the base-2 radical inverse.
Pinned: its raw values are exactly reverse64(n) z_j mod 2^64 at every index (up to 2^64 - 1); its first
2^m points are, for every m, the lattice {k z / 2^m}; its generating vector is the one
tools/lattice_search.py finds (re-run here for the first dimensions); its 2D projections are far below
random points' wrap-around discrepancy at every power of two; the random shift is one word per dimension."""

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import qmc

import udm1

ROOT = Path(__file__).resolve().parents[2]
MAX_D = next(p.max_dimensions for p in udm1.presets() if p.name == "lattice-seq")


def reverse64(n: int) -> int:
    return int(f"{n:064b}"[::-1], 2)


def generating_vector(d):
    # reverse64(2^63) = 1: the unrandomized point 2^63 is z itself
    seq = udm1.Sequence("lattice-seq", d, randomize=False)
    return [int(seq.sample(1 << 63, j, dtype=np.uint64)) for j in range(d)]


def test_values_are_the_bit_reversal_times_z():
    z = generating_vector(MAX_D)
    assert z[0] == 1 and all(c % 2 == 1 and c < 1 << 20 for c in z) and len(set(z)) == MAX_D
    seq = udm1.Sequence("lattice-seq", MAX_D, randomize=False)
    for first in (0, 1, 1000, (1 << 40) - 5, (1 << 64) - 300):
        raw = seq.points(300, first, dtype=np.uint64)
        for i in range(0, 300, 7):
            phi = reverse64(first + i)
            assert [int(v) for v in raw[i]] == [phi * c % (1 << 64) for c in z], first + i


@pytest.mark.parametrize("m", [1, 4, 9, 13])
def test_every_power_of_two_is_a_lattice(m):
    n, z = 1 << m, np.array(generating_vector(12), dtype=np.int64)
    raw = udm1.Sequence("lattice-seq", 12, randomize=False).points(n, dtype=np.uint64)
    got = {tuple(int(v) >> (64 - m) for v in row) for row in raw}
    assert all(int(v) & ((1 << (64 - m)) - 1) == 0 for v in raw.ravel())  # on the grid 1/2^m
    assert got == {tuple(int(v) for v in (k * z) % n) for k in range(n)}


@pytest.mark.release_only("reruns the search (NumPy); the other tests of this file run the library's lattice under the sanitizers")
def test_generating_vector_is_the_search_tools():
    sys.path.insert(0, str(ROOT / "tools"))
    import lattice_search

    head = lattice_search.search(3, bits=20, count=256, m_min=6)
    assert head == generating_vector(3)
    assert "LATTICE_SEQ_Z[]" in lattice_search.header(head, 20, 256, 6)


@pytest.mark.parametrize("m", [6, 10, 14])
def test_projections_far_below_random(m):
    n = 1 << m
    pts = udm1.Sequence("lattice-seq", 8, seed=4).points(n)
    for a, b in ((0, 1), (2, 3), (1, 6), (4, 7)):
        assert qmc.discrepancy(pts[:, [a, b]], method="WD") < 0.2 * udm1.discrepancy_random(n, 2, "WD"), (m, a, b)


def test_the_shift_is_one_word_per_dimension():
    plain = udm1.Sequence("lattice-seq", 5, randomize=False).points(64, dtype=np.uint64)
    shifted = udm1.Sequence("lattice-seq", 5, seed=9)
    for stream in (0, 3):
        raw = shifted.points(64, stream=stream, dtype=np.uint64)
        word = raw[0] - plain[0]
        assert (raw - plain == word).all() and (word != 0).all()
    assert not (shifted.points(8, stream=0) == shifted.points(8, stream=1)).all()
