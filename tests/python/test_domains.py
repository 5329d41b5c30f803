"""Domains and streams (udm1/domain.h, udm1/stream.h) pinned by the independent reference: a domain is
defined by the values it gives. The library's udm1_stream_fill_raw and udm1_domain_fill_raw (which the
header's inline draws equal bit for bit: tests/c/test_stream.c) against reference.py's exact arithmetic,
the documented hash and an independent transcription of the index scramble, for the root, children,
chains, splits, indices below and above 2^32, and padding past the sequence's dimensions; Sobol and PMJ02
domains against their unrandomized values and the documented words, index permutation and scrambling."""

import ctypes

import numpy as np
import pytest

import reference as ref
import udm1
from stream_abi import M32, M64, Domain, Stream  # the ctypes mirror of udm1/stream.h and udm1/domain.h
from udm1._native import lib


# ---- the reference: the documented derivations, written out independently ----

def reverse32(x: int) -> int:
    return int(f"{x & M32:032b}"[::-1], 2)


def owen_hash32(x: int, seed: int) -> int:
    x ^= (x * 0x3D20ADEA) & M32
    x = (x + seed) & M32
    x = (x * ((seed >> 16) | 1)) & M32
    x ^= (x * 0x05526C56) & M32
    x ^= (x * 0x53A22864) & M32
    return x


def child_key(parent: int, key: int) -> int:
    k = ref.mix64(parent + (key + 1) * ref.GOLDEN_GAMMA)
    return k or ref.GOLDEN_GAMMA


def derive(path, key, index, dim, stream_key):
    """(key, index, dim) after path's steps: ("child", key), ("next", k), ("split", key, count, i) and
    ("chain", key, i), as udm1/domain.h defines them."""
    for step in path:
        base = ((key or stream_key) + dim) & M64
        if step[0] == "child":
            key, dim = child_key(base, step[1]), 0
        elif step[0] == "next":
            dim += 4 * step[1]
        elif step[0] == "split":
            key, dim, index = child_key(base, step[1]), 0, (index * step[2] + step[3]) & M64
        else:
            key, dim = child_key(child_key(base, step[1]), step[2]), 0
    return key, index, dim


def domain_values(alphas, seed, stream, path, index, n):
    """Raw values of the domain reached from (stream, index) by path (a root if empty)."""
    sk = ref.seed_key(seed)
    key, index, dim = derive(path, 0, index, 0, ref.stream_key(sk, stream))
    out = []
    for j in range(dim, dim + n):
        if key == 0:  # the root's chain: the stream's own shift and index
            off = ref.shift(seed, stream, j)
            m = index
        else:
            off = ref.mix64(key + ref.dim_key(sk, j))
            m = (index & ~M32) | reverse32(owen_hash32(reverse32(index & M32), key >> 32))
        if j < len(alphas):
            out.append(ref.raw_value(off, alphas[j], m & M64))
        else:  # padding past the sequence's dimensions: the cursor's rule with the domain's key
            out.append(ref.mix64(off + (index + 1) * ref.GOLDEN_GAMMA))
    return out


PATHS = [[], [("child", 0)], [("child", 3)], [("child", 3), ("child", 0)], [("split", 5, 4, 2)],
         [("chain", 2, 9)], [("child", 2**64 - 1), ("split", 1, 8, 7)], [("next", 1)], [("next", 2), ("child", 1)],
         [("child", 1), ("next", 1)]]


@pytest.mark.parametrize("preset,d", [("wr", 4), ("rd", 3), ("wr-ao", 2)])
def test_domains_equal_the_reference(preset, d):
    seed = 7
    seq = udm1.Sequence(preset, d, seed=seed)
    alphas = [ref.round128(f) for f in ref.preset_fracs(preset, d)]
    for stream in (0, (5 << 32) | 9, M64):
        st = Stream()
        assert lib.udm1_stream_init(ctypes.byref(st), seq.handle, stream, 0, 12) == 0
        assert st.struct_size == ctypes.sizeof(Stream)  # this mirror of udm1/stream.h is current
        for index in (0, 1, 1000, M32, 1 << 32, (1 << 40) + 17, M64 // 8):
            for path in PATHS:
                want = domain_values(alphas, seed, stream, path, index, 4)
                # derive as the header does (its inline functions are not callable from ctypes)
                key, idx, dim = derive(path, 0, index, 0, st.key)
                dom = Domain(ctypes.pointer(st), key, idx, dim, 0)
                raw = (ctypes.c_uint64 * 4)()
                assert lib.udm1_domain_fill_raw(ctypes.byref(dom), 4, raw) == 0
                assert list(raw) == want, (preset, stream, index, path)


def owen64(v: int, r: int) -> int:
    """Owen scrambling of a 0.64 value as udm1/stream.h documents it: the top 32 bits by the nested hash
    keyed by the word's low half, the low 32 a hash of the scrambled top and the word's high half."""
    top = reverse32(owen_hash32(reverse32(v >> 32), r & M32))
    return (top << 32) | (ref.mix64(((top << 32) | (r >> 32)) ^ 0x4F57454E00000000) & M32)


def permuted(index: int, K: int, seed: int) -> int:
    """A child's index: the low 32 bits Owen-scrambled; in a K-point set the scramble of ceil(log2 K) bits
    cycle-walked back into [0, K)."""
    if not K:
        return (index & ~M32) | reverse32(owen_hash32(reverse32(index & M32), seed))
    k = max(K - 1, 0).bit_length()
    v = index & M32
    while True:
        v = 0 if k == 0 else reverse32(owen_hash32(reverse32(v) >> (32 - k), seed) & ((1 << k) - 1)) >> (32 - k)
        if v < K:
            return v


@pytest.mark.parametrize("preset,d,K,mode", [("sobol-owen", 6, 0, "owen"), ("sobol", 5, 0, "xor"),
                                             ("pmj02", 6, 256, "xor"), ("pmj02", 4, 100, "xor")])
def test_base2_domains_equal_the_reference(preset, d, K, mode):
    """Sobol and PMJ02 domains (drawn inline by the header for these randomizations): the sequence's own
    unrandomized values at the domain's index (the root's own, a child's permuted one), randomized by the
    domain's words mix64(key + K_j) - the root's the stream's - with the preset's randomization, written
    out here from the documentation."""
    seed = 9
    seq = udm1.Sequence(preset, d, point_count=K, seed=seed)
    plain = udm1.Sequence(preset, d, point_count=K, seed=seed, randomize=False)
    sk = ref.seed_key(seed)

    def base(index):
        return [int(v) for v in plain.points(1, index, dtype=np.uint64)[0]]

    for stream in (0, (5 << 32) | 9):
        st = Stream()
        assert lib.udm1_stream_init(ctypes.byref(st), seq.handle, stream, 0, d) == 0
        for index in ((0, 1, 77, K - 1) if K else (0, 1, 1000, M32, (1 << 32) + 5)):
            for path in PATHS:
                key, idx, dim = derive(path, 0, index, 0, st.key)
                n = min(4, d - dim)
                if n <= 0 or (K and idx >= K):
                    continue
                if key == 0:
                    m, words = idx, [ref.shift(seed, stream, dim + j) for j in range(n)]
                else:
                    m, words = permuted(idx, K, key >> 32), [ref.mix64(key + ref.dim_key(sk, dim + j)) for j in range(n)]
                v = base(m)[dim:dim + n]
                want = [owen64(v[j], words[j]) if mode == "owen" else v[j] ^ words[j] for j in range(n)]
                dom = Domain(ctypes.pointer(st), key, idx, dim, 0)
                raw = (ctypes.c_uint64 * 4)()
                assert lib.udm1_domain_fill_raw(ctypes.byref(dom), n, raw) == 0
                assert list(raw)[:n] == want, (preset, stream, index, path)


def test_stream_values_and_padding_equal_the_reference():
    seed, d = 11, 3
    seq = udm1.Sequence("wr", d, seed=seed)
    alphas = [ref.round128(f) for f in ref.preset_fracs("wr", d)]
    st = Stream()
    assert lib.udm1_stream_init(ctypes.byref(st), seq.handle, 42, 1, 5) == 0
    # dimensions 1, 2 inline (UDM1_STREAM_INLINE); 3..5 padded; the children of keys 0 and 1 of its one
    # block held (UDM1_STREAM_CHILDREN: two keys per block), key 0's in slot 0
    assert st.held == 2 and st.flags == 1 | 2 * 8
    key = child_key(st.key, 0)
    assert st.dim_key[63] == key and list(st.a_hi[60:64]) == [ref.mix64(key + st.dim_key[j]) for j in range(4)]
    raw = (ctypes.c_uint64 * 5)()
    for index in (0, 3, 1 << 33):
        assert lib.udm1_stream_fill_raw(ctypes.byref(st), index, 0, 5, raw) == 0
        for j in range(5):
            dim = 1 + j
            want = (ref.raw_value(ref.shift(seed, 42, dim), alphas[dim], index) if dim < d
                    else ref.pad(seed, 42, index, dim))
            assert raw[j] == want


def morton(stream: int) -> int:
    x, y, m = stream & M32, stream >> 32, 0
    for b in range(32):
        m |= ((x >> b) & 1) << (2 * b) | ((y >> b) & 1) << (2 * b + 1)
    return m


def test_screen_domains_keep_the_pixels_segments():
    """Screen-space randomization: a child's key is the same in every pixel, and its index is the pixel's
    segment base m N plus the permuted sample index, so neighbouring pixels hold consecutive segments of
    one shifted sequence in every domain (the reference computes it independently)."""
    seed, d, N = 5, 4, 16
    seq = udm1.Sequence("wr", d, seed=seed, randomize="screen", screen_spp=N)
    alphas = [ref.round128(f) for f in ref.preset_fracs("wr", d)]
    sk = ref.seed_key(seed)
    root_key = ref.stream_key(sk, M64)  # the seed's, not the pixel's
    keys = set()
    for stream in (0, 1, (1 << 32) | 3, (7 << 32) | 6):
        st = Stream()
        assert lib.udm1_stream_init(ctypes.byref(st), seq.handle, stream, 0, 4) == 0
        assert st.key == root_key and st.index_base == morton(stream) * N
        for n in (0, 5, 15):
            key = child_key(root_key, 2)
            dom = Domain(ctypes.pointer(st), key, n)
            raw = (ctypes.c_uint64 * 4)()
            assert lib.udm1_domain_fill_raw(ctypes.byref(dom), 4, raw) == 0
            m = morton(stream) * N + reverse32(owen_hash32(reverse32(n), key >> 32))
            want = [ref.raw_value(ref.mix64(key + ref.dim_key(sk, j)), alphas[j], m % (1 << 64)) for j in range(4)]
            assert list(raw) == want
            keys.add(key)
    assert len(keys) == 1
