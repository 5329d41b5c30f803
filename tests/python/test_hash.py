"""The per-stream shifts and the cursor's padding follow the formula
documented in hash.h / udm1.h (reimplemented here), and look independent."""

import ctypes

import numpy as np

import reference as ref
import udm1
from udm1 import _native


def test_offsets_follow_the_documented_hash():
    rng = np.random.default_rng(1)
    for seed in [0, 1, 2**64 - 1, int(rng.integers(0, 2**63))]:
        s = udm1.Sequence("wr", 40, seed=seed)
        for stream in [0, 1, 2**32, 2**64 - 1, int(rng.integers(0, 2**63))]:
            for dim in [0, 1, 2, 39]:
                assert s.offset(dim, stream) == ref.shift(seed, stream, dim)


def test_base_offsets_add_to_the_shift():
    offs = np.array([2**63, 5], dtype=np.uint64)
    s = udm1.Sequence(alphas=[udm1.Sqrt(2), udm1.Sqrt(3)], seed=9, offsets=offs)
    assert s.offset(0, 4) == (2**63 + ref.shift(9, 4, 0)) % 2**64
    s = udm1.Sequence(alphas=[udm1.Sqrt(2), udm1.Sqrt(3)], seed=9, offsets=offs, randomize=False)
    assert s.offset(0, 4) == 2**63 and s.offset(1, 4) == 5


def test_padding_follows_the_documented_hash():
    s = udm1.Sequence("we", 2, seed=77)
    cur = _native.Cursor()
    for stream in [0, 3, 2**40]:
        for index in [0, 1, 1000, 2**64 - 1]:
            assert _native.lib.udm1_cursor_start(ctypes.byref(cur), s.handle, stream, index, 2) == 0
            for dim in range(2, 6):
                v = _native.lib.udm1_cursor_1d_f64(ctypes.byref(cur))
                assert v == ref.to_f64(ref.pad(77, stream, index, dim))
            assert _native.lib.udm1_cursor_padded(ctypes.byref(cur)) == 4


def test_shifts_are_uniform_and_uncorrelated():
    # 20000 (stream, dim) shifts: uniform in [0,1) and no correlation between neighbours
    s = udm1.Sequence("wr", 4, seed=3)
    u = np.array([[s.offset(d, st) for d in range(4)] for st in range(5000)], dtype=np.float64) / 2**64
    x = u.ravel()
    assert abs(x.mean() - 0.5) < 5 * np.sqrt(1 / 12 / x.size)
    for d in range(3):
        r = np.corrcoef(u[:, d], u[:, d + 1])[0, 1]
        assert abs(r) < 5 / np.sqrt(u.shape[0])
    r = np.corrcoef(u[:-1, 0], u[1:, 0])[0, 1]
    assert abs(r) < 5 / np.sqrt(u.shape[0])
