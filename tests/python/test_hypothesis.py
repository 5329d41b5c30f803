"""Property-based tests (Hypothesis) of the package and, through it, the C API: random descriptors,
index ranges, splits, dimension windows and dtypes, asserting the sequence contract (udm1/seq.h):

- every value is exact: for the Weyl presets without a transform, the raw 0.64 value of (n, j) is the top
  64 bits of (O_j 2^64 + n A_j) mod 2^128, with A_j and O_j read back from the library, and A_j of a
  square root equals round(frac(sqrt k) 2^128) computed here with math.isqrt;
- float64 and float32 are the documented conversions of the raw value, in [0, 1);
- bulk, per-sample and many-points calls, any split of a range and any window of dimensions agree bit
  for bit;
- every refusal is a udm1.UDM1Error or ValueError (TypeError for a non-number) with a one-line message;
- streams and domains (through ctypes, stream_abi.py): stream fills equal Sequence.points_at, nothing is
  written on any refused fill or init, a child domain's aligned blocks of samples (a split's sub-samples,
  merged over aligned parents) are shifted copies of the sequence's first points;
- Noise: batches equal per-point calls, gradients equal central differences within a derived bound,
  finite coordinates of any size give finite values (or a one-line refusal of a pattern whose octaves
  overflow), and what is not real numbers is refused by the converter;
- udm1.integrate: the exact sums do not depend on the chunk or the split, every bad argument is refused
  before f runs, and any magnitude up to 1e300 gives a finite estimate, stderr and bound.

Failing examples Hypothesis found stay below as @example regression cases.
"""

import ctypes
import math
import os
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

import udm1
from stream_abi import DIMENSION_INDEX_LIMIT, Domain, Stream, child_key  # the ctypes mirror of the headers
from udm1._native import lib

PRESETS = {p.name: p for p in udm1.presets()}
WEYL = {"wr", "wr-ao", "we", "wgr", "wmmr", "hwmmr", "rd", "golden", "wopt"}
POINT_SET_MAX = {"pmj02": 1 << 20, "lattice": 1 << 24}
RANDOMIZE = [True, False, "shift", "permute", "owen", "screen"]
U64 = (1 << 64) - 1

# the test command's profile; UDM1_HYPOTHESIS=long explores 50x as many examples
_checks = [HealthCheck.too_slow, HealthCheck.data_too_large]
settings.register_profile("udm1", max_examples=300, deadline=None, suppress_health_check=_checks)
settings.register_profile("long", max_examples=15000, deadline=None, suppress_health_check=_checks)
settings.load_profile(os.environ.get("UDM1_HYPOTHESIS", "udm1"))


@st.composite
def descriptors(draw, names=tuple(sorted(PRESETS))):
    """(kwargs for udm1.Sequence) of a valid descriptor: preset, dimensions, point count, seed and a
    randomization the preset has."""
    name = draw(st.sampled_from(names))
    info = PRESETS[name]
    d = draw(st.integers(1, min(info.max_dimensions, 12)))
    k = draw(st.integers(1, min(POINT_SET_MAX.get(name, 1 << 32), 5000))) if info.point_set else 0
    randomize = draw(st.sampled_from(RANDOMIZE))
    kw = dict(preset=name, d=d, point_count=k, seed=draw(st.integers(0, U64)), randomize=randomize)
    if randomize == "screen":
        kw["screen_spp"] = draw(st.integers(1, 64))
    return kw


def make(kw):
    """The sequence, or None where the library refuses the randomization for that preset (checked to be
    a UDM1Error with a one-line message)."""
    try:
        return udm1.Sequence(**kw)
    except udm1.UDM1Error as e:
        assert str(e) and "\n" not in str(e), repr(e)
        assert kw["randomize"] in ("permute", "owen", "screen", "shift"), f"{kw}: {e}"
        return None


def indices(seq, draw, count):
    """A first index with count points after it inside the sequence (or point set)."""
    top = (seq.point_count or (1 << 64)) - count
    return draw(st.one_of(st.integers(0, min(top, 1000)), st.integers(0, top), st.just(top)))


@given(kw=descriptors(), data=st.data())
def test_bulk_samples_splits_and_windows_agree(kw, data):
    s = make(kw)
    assume(s is not None)
    n = data.draw(st.integers(1, min(40, s.point_count or 40)))
    first = indices(s, data.draw, n)
    stream = data.draw(st.one_of(st.integers(0, 8), st.integers(0, U64)))
    raw = s.points(n, first, stream=stream, dtype=np.uint64)
    f64 = s.points(n, first, stream=stream)
    f32 = s.points(n, first, stream=stream, dtype=np.float32)
    # the documented conversions, in [0, 1)
    assert np.array_equal(f64, (raw >> np.uint64(11)).astype(np.float64) * 2.0**-53)
    assert np.array_equal(f32, ((raw >> np.uint64(40)).astype(np.float64) * 2.0**-24).astype(np.float32))
    assert f64.min() >= 0 and f64.max() < 1 and f32.max() < np.float32(1)
    # any split of the range
    k = data.draw(st.integers(1, n))  # (a first part of at least one point: first + k is then below 2^64)
    split = np.vstack([s.points(k, first, stream=stream, dtype=np.uint64),
                       s.points(n - k, first + k if k < n else first, stream=stream, dtype=np.uint64)])
    assert np.array_equal(raw, split)
    # a window of dimensions
    j0 = data.draw(st.integers(0, s.d - 1))
    j1 = data.draw(st.integers(j0 + 1, s.d))
    assert np.array_equal(s.points(n, first, stream=stream, dims=range(j0, j1), dtype=np.uint64), raw[:, j0:j1])
    # per sample, at drawn places
    for _ in range(3):
        i, j = data.draw(st.integers(0, n - 1)), data.draw(st.integers(0, s.d - 1))
        assert s.sample(first + i, j, stream=stream, dtype=np.uint64) == raw[i, j]
        assert s.sample(first + i, j, stream=stream) == f64[i, j]
    # many points at once (points of several streams, in any order)
    m = data.draw(st.integers(1, n))
    pick = np.array(data.draw(st.lists(st.integers(0, n - 1), min_size=m, max_size=m)))
    streams = np.full(m, stream, dtype=np.uint64)
    assert np.array_equal(s.points_at(streams, first + pick.astype(np.uint64)), f64[pick])


def weyl_exact(s, first, stream, n):
    raw = s.points(n, first, stream=stream, dtype=np.uint64)
    for j in range(s.d):
        a, o = s.alpha(j), s.offset(j, stream=stream)
        for i in range(n):
            want = (((o << 64) + (first + i) * a) % (1 << 128)) >> 64
            assert int(raw[i, j]) == want, (j, first + i)


@given(kw=descriptors(names=tuple(sorted(WEYL))), data=st.data())
def test_weyl_values_are_exact(kw, data):
    kw = dict(kw, randomize=kw["randomize"] if kw["randomize"] in (True, False, "shift") else "shift")
    kw.pop("screen_spp", None)
    s = udm1.Sequence(**kw)
    n = data.draw(st.integers(1, 16))
    weyl_exact(s, indices(s, data.draw, n), data.draw(st.integers(0, U64)), n)


def test_weyl_values_are_exact_at_the_top_of_every_range():
    weyl_exact(udm1.Sequence("wr", 3, seed=U64), U64 - 4, U64, 5)


@given(k=st.integers(2, U64).filter(lambda k: math.isqrt(k) ** 2 != k), seed=st.integers(0, U64))
@example(k=2, seed=0).via("sqrt2")
@example(k=U64, seed=1).via("the largest k")
def test_square_root_generators_are_exact(k, seed):
    s = udm1.Sequence(alphas=[udm1.Sqrt(k)], seed=seed)
    r = (math.isqrt(k << 258) + 1) // 2  # round(sqrt(k) 2^128): floor(2 sqrt(k) 2^128), halved up
    assert s.alpha(0) == r % (1 << 128)


BAD_INTS = st.one_of(st.integers(max_value=-1), st.integers(min_value=1 << 64), st.floats(allow_nan=True),
                     st.text(max_size=3), st.none(), st.booleans(), st.complex_numbers())


@given(arg=st.sampled_from(["d", "point_count", "seed", "screen_spp", "n", "first", "stream", "index", "dim"]),
       value=BAD_INTS)
@example(arg="n", value=1579782403.0).via("found: 23.5 GiB allocated before the library refused the range")
def test_refusals_are_errors_with_a_message(arg, value):
    def call():
        if arg in ("d", "point_count", "seed", "screen_spp"):
            kw = dict(preset="episwr", d=2, point_count=64, seed=1, randomize="screen" if arg == "screen_spp" else True)
            kw[arg] = value
            return udm1.Sequence(**kw).points(2)
        s = udm1.Sequence("episwr", 2, point_count=64, seed=1)
        if arg in ("n", "first", "stream"):
            return s.points(**{"n": 2, arg: value})
        return s.sample(**{"index": 0, "dim": 0, arg: value})

    try:
        call()
    except (udm1.UDM1Error, ValueError, TypeError) as e:
        assert str(e) and "\n" not in str(e)
        return
    # accepted: only an integral float inside the range may be
    assert isinstance(value, float) and value.is_integer() and 0 <= value < 1 << 64, (arg, value)


@given(dtype=st.sampled_from(["float16", "int32", "int64", "complex128", "bool", "uint32", "float128"]))
def test_unsupported_dtypes_are_refused(dtype):
    with pytest.raises(ValueError) as e:
        udm1.Sequence("wr", 2).points(4, dtype=dtype)
    assert "float64" in str(e.value) or "not a dtype" in str(e.value)


# ---------------------------------------------------------------------------------------------------------
# Streams and domains (udm1/stream.h, udm1/domain.h) through ctypes, Noise, and udm1.integrate. Fewer
# examples each (a tenth of the profile's, at least 25): the file must stay fast.

FEW = settings(max_examples=max(25, settings.default.max_examples // 10))
SEQUENCES = tuple(sorted(PRESETS))
WEYL_SEQUENCES = tuple(sorted(n for n in WEYL if not PRESETS[n].point_set))


def stream_of(seq, stream, first, count):
    """A udm1_stream of seq (which the caller keeps alive: the stream refers to it)."""
    st_ = Stream()
    status = lib.udm1_stream_init(ctypes.byref(st_), seq.handle, stream, first, count)
    assert status == 0, lib.udm1_last_error()
    return st_


def raw_to_f64(raw):
    return (np.asarray(raw, dtype=np.uint64) >> np.uint64(11)).astype(np.float64) * 2.0**-53


def raw_to_f32(raw):
    return ((np.asarray(raw, dtype=np.uint64) >> np.uint64(40)).astype(np.float64) * 2.0**-24).astype(np.float32)


@FEW
@given(kw=descriptors(), data=st.data())
def test_stream_fills_equal_points_at(kw, data):
    """udm1_stream_fill_raw / _f32 of any stream, dimension window (held, padded, or outside the stream's
    own) and index equal Sequence.points_at (udm1_seq_fill_points_f64) at the same (stream, index,
    dimension), and the float draw is the documented conversion of the raw one."""
    s = make(kw)
    assume(s is not None)
    stream = data.draw(st.one_of(st.integers(0, 8), st.integers(0, U64)))
    count = data.draw(st.integers(1, 64))
    first = data.draw(st.one_of(st.integers(0, s.d + 4), st.integers(0, (1 << 32) - 1 - 200)))
    index = data.draw(st.integers(0, s.point_count - 1) if s.point_count else st.one_of(st.integers(0, 5000),
                                                                                        st.integers(0, U64)))
    dim = data.draw(st.integers(0, count + 8))
    n = data.draw(st.integers(1, 70))
    st_ = stream_of(s, stream, first, count)
    raw = (ctypes.c_uint64 * n)()
    assert lib.udm1_stream_fill_raw(ctypes.byref(st_), index, dim, n, raw) == 0
    f32 = (ctypes.c_float * n)()
    assert lib.udm1_stream_fill_f32(ctypes.byref(st_), index, dim, n, f32) == 0
    want = s.points_at([stream], [index], dims=range(first + dim, first + dim + n))[0]
    assert np.array_equal(raw_to_f64(list(raw)), want)
    assert np.array_equal(np.array(list(f32), dtype=np.float32), raw_to_f32(list(raw)))


def _unchanged(buffer_type, n, call):
    """call(buffer) on a buffer of n sentinel words fails with a one-line message and leaves it unchanged."""
    buf = (buffer_type * max(n, 1))()
    ctypes.memset(buf, 0xA5, ctypes.sizeof(buf))
    before = bytes(buf)
    status = call(buf)
    message = lib.udm1_last_error().decode()
    assert status != 0 and message and "\n" not in message
    assert bytes(buf) == before, f"written on error: {message}"
    return message


@FEW
@given(kw=descriptors(), data=st.data())
def test_nothing_is_written_on_error(kw, data):
    """Every stream and domain fill the library refuses (an index outside a point set, dimensions past
    the dimension index limit, a domain draw of 0 or more than 4 values) leaves the output untouched;
    so does a refused udm1_stream_init for the stream struct."""
    s = make(kw)
    assume(s is not None)
    st_ = stream_of(s, data.draw(st.integers(0, U64)), 0, data.draw(st.integers(1, 64)))
    K = s.point_count
    far = DIMENSION_INDEX_LIMIT - data.draw(st.integers(0, 63))  # a window that passes the limit
    n = data.draw(st.integers(1, 64))
    bad_index = data.draw(st.integers(K, U64)) if K else 0
    cases = [lambda b: lib.udm1_stream_fill_raw(ctypes.byref(st_), 0, far, max(n, DIMENSION_INDEX_LIMIT - far + 1), b)]
    if K:
        cases.append(lambda b: lib.udm1_stream_fill_raw(ctypes.byref(st_), bad_index, 0, n, b))
    for call in cases:
        _unchanged(ctypes.c_uint64, 64 + 1, call)
    # float draws of up to 64 values (more: see test_stream_fill_f32_writes_nothing_on_error below)
    m = max(n, DIMENSION_INDEX_LIMIT - far + 1)
    if m <= 64:
        _unchanged(ctypes.c_float, m, lambda b: lib.udm1_stream_fill_f32(ctypes.byref(st_), 0, far, m, b))
    if K:
        _unchanged(ctypes.c_float, n, lambda b: lib.udm1_stream_fill_f32(ctypes.byref(st_), bad_index, 0, n, b))
    # domains: a child (key != 0) or the root, at a bad count, dimension or index
    key = data.draw(st.one_of(st.just(0), st.integers(1, U64)))
    for count, dim, index in ((0, 0, 0), (data.draw(st.integers(5, 1000)), 0, 0),
                              (4, DIMENSION_INDEX_LIMIT - data.draw(st.integers(0, 3)), 0)) + \
            (((data.draw(st.integers(1, 4)), 0, bad_index),) if K else ()):
        dom = Domain(ctypes.pointer(st_), key, index, dim, 0)
        _unchanged(ctypes.c_uint64, max(count, 4), lambda b: lib.udm1_domain_fill_raw(ctypes.byref(dom), count, b))
        _unchanged(ctypes.c_float, max(count, 4), lambda b: lib.udm1_domain_fill_f32(ctypes.byref(dom), count, b))
    # a refused stream: the struct as it was
    bad = data.draw(st.sampled_from([(0, 0), (0, 65), (DIMENSION_INDEX_LIMIT - 3, 8)]))
    target = Stream()
    ctypes.memset(ctypes.byref(target), 0x5A, ctypes.sizeof(target))
    before = bytes(target)
    assert lib.udm1_stream_init(ctypes.byref(target), s.handle, 1, bad[0], bad[1]) != 0
    assert bytes(target) == before


def test_stream_fill_f32_writes_nothing_on_error():
    seq = udm1.Sequence("wr", 4, seed=1)  # kept alive: a stream refers to its sequence
    st_ = stream_of(seq, 0, 0, 4)
    first = DIMENSION_INDEX_LIMIT - 100  # the first 64 values are inside the limit, the rest pass it
    _unchanged(ctypes.c_float, 200, lambda b: lib.udm1_stream_fill_f32(ctypes.byref(st_), 0, first, 200, b))


@FEW
@given(name=st.sampled_from(WEYL_SEQUENCES), data=st.data())
def test_domain_children_and_splits_are_shifted_copies(name, data):
    """A child domain's samples over an aligned block of 2^k indices are 2^k consecutive points of the
    sequence, shifted (udm1/domain.h): so a child's first 2^k samples, one parent sample's 2^a sub-samples
    (a split), and the merged sub-samples of 2^b consecutive parents, all have the wrap-around discrepancy
    of the sequence's own first points (a translation of the torus does not change it)."""
    d = 2 if PRESETS[name].max_dimensions >= 2 else 1
    s = udm1.Sequence(name, d, seed=data.draw(st.integers(0, U64)), randomize=data.draw(st.sampled_from([True,
                                                                                                         "shift"])))
    st_ = stream_of(s, data.draw(st.integers(0, U64)), 0, d)
    key = 0
    for _ in range(data.draw(st.integers(1, 3))):  # a chain of children
        key = child_key(key, 0, st_.key, data.draw(st.integers(0, U64)))
    a, b = data.draw(st.integers(0, 4)), data.draw(st.integers(0, 3))
    n = 1 << (a + b)  # the merged block: 2^b parents of 2^a sub-samples each
    parent0 = data.draw(st.integers(0, 1000)) << b
    first = parent0 << a
    raw = (ctypes.c_uint64 * d)()
    pts = []
    for index in range(first, first + n):
        assert lib.udm1_domain_fill_raw(ctypes.byref(Domain(ctypes.pointer(st_), key, index, 0, 0)), d, raw) == 0
        pts.append(list(raw))
    got = raw_to_f64(pts)
    own = udm1.Sequence(name, d, randomize=False).points(n)
    if n > 1:
        assert udm1.discrepancy(got, "WD") == pytest.approx(udm1.discrepancy(own, "WD"), rel=1e-9, abs=1e-12)
    # and the first coordinates are the own points' shifted by one constant (mod 1): their circular gaps agree
    def circular_gaps(v):
        v = np.sort(v)
        return np.sort(np.diff(np.append(v, v[0] + 1)))

    assert np.allclose(circular_gaps(got[:, 0]), circular_gaps(own[:, 0]), atol=1e-12)


COORD = st.floats(min_value=-1e4, max_value=1e4, allow_nan=False, allow_infinity=False)
ANY_COORD = st.floats(allow_nan=False, allow_infinity=False)
F32_COORD = st.floats(allow_nan=False, allow_infinity=False, width=32)


def noises():
    return st.builds(udm1.Noise, table=st.sampled_from([None, "wr", "rd", "sobol-owen", "drand48", "halton"]),
                     seed=st.integers(0, U64), period=st.sampled_from([0, 3, 256, (4, 7, 0, 5)]))


@FEW
@given(noise=noises(), d=st.integers(1, 4), data=st.data())
def test_noise_batches_equal_per_point_calls(noise, d, data):
    """A batch of points gives each point's value and gradient bit for bit (float64 and float32), in
    rows or as coordinate arrays, and gradient=True does not change the values."""
    m = data.draw(st.integers(1, 12))
    pts = np.array(data.draw(st.lists(st.lists(ANY_COORD | COORD, min_size=d, max_size=d), min_size=m, max_size=m)))
    for x in (pts, pts.astype(np.float32) if np.all(np.abs(pts) < 3e38) else None):
        if x is None:
            continue
        values, grads = noise.noise(x, gradient=True)
        assert np.array_equal(values, noise.noise(x), equal_nan=False)
        assert np.array_equal(noise.noise(tuple(x.T)), values)
        for k in range(m):
            v1, g1 = noise.noise(x[k:k + 1], gradient=True)
            assert v1[0] == values[k] and np.array_equal(g1[0], grads[k])
        if 2 <= d <= 3:
            cells = noise.cellular(x)
            assert all(noise.cellular(x[k:k + 1])[0] == cells[k] for k in range(m))


@FEW
@given(noise=noises(), d=st.integers(1, 4), data=st.data())
def test_noise_gradients_match_central_differences(noise, d, data):
    """Improved noise is C2 (the quintic fade has zero first and second derivatives at the cell ends), and
    along one axis its third derivative is bounded: each of the 2^d corner terms is fade products times a
    linear function with |value| <= 2 and |slope| <= 1, and |fade'''| <= 60, |fade''| <= 5.8, so
    |d^3 n / dx^3| <= 2^d (60 2 + 3 5.8) < 16 138 = 2208. A central difference over the steps actually
    taken (h = 1e-5, |x| <= 1e4 so the steps are exact to 2e-12) is then within h^2 / 6 2208 = 3.7e-8
    (Taylor, with f'' Lipschitz), plus rounding of about 2 eps / h = 4.4e-11 (|n| <= 1): 1e-6 bounds it
    with a margin of 25."""
    m = data.draw(st.integers(1, 8))
    pts = np.array(data.draw(st.lists(st.lists(COORD, min_size=d, max_size=d), min_size=m, max_size=m)))
    _, grads = noise.noise(pts, gradient=True)
    for k in range(d):
        up, down = pts.copy(), pts.copy()
        up[:, k] += 1e-5
        down[:, k] -= 1e-5
        step = up[:, k] - down[:, k]
        central = (noise.noise(up) - noise.noise(down)) / step
        assert np.max(np.abs(central - grads[:, k])) < 1e-6


@FEW
@given(noise=noises(), data=st.data())
def test_noise_is_finite_at_any_magnitude(noise, data):
    """Finite coordinates of any size give finite noise, gradients and cellular values (float64 and
    float32); a pattern whose octaves overflow the double range is refused in one line naming the point,
    never a NaN or an infinity."""
    for d in (1, 2, 3, 4):
        for coord in (ANY_COORD, F32_COORD):
            x = np.array(data.draw(st.lists(st.lists(coord, min_size=d, max_size=d), min_size=1, max_size=6)),
                         dtype=np.float32 if coord is F32_COORD else np.float64)
            v, g = noise.noise(x, gradient=True)
            assert np.all(np.isfinite(v)) and np.all(np.isfinite(g))
            if 2 <= d <= 3:
                for output in ("f1", "f2-f1", "cell"):
                    assert np.all(np.isfinite(noise.cellular(x, output=output)))
    x = np.array(data.draw(st.lists(st.lists(ANY_COORD, min_size=3, max_size=3), min_size=1, max_size=4)))
    name = data.draw(st.sampled_from(udm1.patterns()))
    try:
        out = noise.pattern(name, x)
    except udm1.UDM1Error as e:
        assert "at point" in str(e) and "\n" not in str(e)
    else:
        assert np.all(np.isfinite(out))


BAD_ELEMENTS = st.one_of(st.booleans(), st.complex_numbers(allow_nan=False).filter(lambda z: z.imag != 0),
                         st.text(max_size=3), st.none(), st.just(b"1"))


@FEW
@given(data=st.data(), bad=BAD_ELEMENTS)
def test_noise_refuses_what_is_not_real_numbers(data, bad):
    """A bool, complex number, string, bytes or None anywhere in the points (rows, coordinate arrays, a
    whole array of such) is refused by the converter with one line naming the points, with no warning."""
    d = data.draw(st.integers(2, 3))
    rows = [[0.5] * d for _ in range(data.draw(st.integers(1, 4)))]
    i, j = data.draw(st.integers(0, len(rows) - 1)), data.draw(st.integers(0, d - 1))
    rows[i][j] = bad
    shape = data.draw(st.sampled_from(["rows", "columns", "array"]))
    if shape == "columns":
        points = tuple([row[k] for row in rows] for k in range(d))
    elif shape == "array":
        points = np.array(rows, dtype=object) if not isinstance(bad, bool) else np.array(rows) > 0
    else:
        points = rows
    n = udm1.Noise()
    for call in (lambda: n.noise(points), lambda: n.cellular(points)):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises((TypeError, udm1.UDM1Error)) as e:
                call()
        assert "points" in str(e.value) and "\n" not in str(e.value)


def smooth(x):
    """cos(w . x), elementwise (a matrix product's rounding can depend on how many rows it is given)."""
    w = np.linspace(0.5, 1.5, x.shape[1])
    return np.cos(sum(w[j] * x[:, j] for j in range(x.shape[1])))


@FEW
@given(name=st.sampled_from(["wr", "sobol-owen", "rd", "halton", "pcg32", "lattice-seq"]), data=st.data())
def test_integrals_do_not_depend_on_chunk_or_split(name, data):
    """The exact sums of f and f^2 over [0, n), hence the estimate and its standard error, are the same
    bit for bit for any chunk and any split of the range into two parts, joined in either order."""
    from udm1.integrate import IntegralSpec, integrate_range

    d, n = data.draw(st.integers(1, 4)), data.draw(st.integers(2, 3000))
    seed = data.draw(st.integers(0, U64))
    whole = udm1.integrate(smooth, name, d, n, seed=seed, chunk=data.draw(st.integers(1, 5000)))
    k = data.draw(st.integers(1, n - 1))
    spec = IntegralSpec(name, d, n, seed)
    chunk = data.draw(st.integers(1, 5000))
    left, right = integrate_range(smooth, spec, 0, k, chunk), integrate_range(smooth, spec, k, n - k, chunk)
    joined = right + left
    assert (joined.sum, joined.sum_sq) == (whole.sum, whole.sum_sq)
    assert (joined.value, joined.stderr) == (whole.value, whole.stderr)


# an integrate argument and a value of it the converter refuses, with the exception it must raise
BAD_ARGUMENTS = st.one_of(
    st.tuples(st.sampled_from(["chunk", "n"]), st.one_of(st.integers(max_value=0), st.integers(min_value=1 << 64)),
              st.just(ValueError)),
    st.tuples(st.sampled_from(["chunk", "n", "seed", "stream", "d", "n_max", "n_init", "replications"]),
              st.floats(allow_nan=True).filter(lambda v: not (v == v and v.is_integer())), st.just(ValueError)),
    st.tuples(st.sampled_from(["seed", "stream"]), st.one_of(st.integers(max_value=-1),
                                                           st.integers(min_value=1 << 64)), st.just(ValueError)),
    st.tuples(st.sampled_from(["chunk", "n", "seed", "stream", "d", "n_max", "n_init", "replications", "confidence",
                               "abs_tol", "rel_tol"]), st.one_of(st.booleans(), st.text(max_size=2),
                                                                 st.complex_numbers(), st.just([1])),
              st.just(TypeError)),
    st.tuples(st.sampled_from(["abs_tol", "rel_tol"]), st.one_of(st.floats(max_value=0), st.just(float("inf")),
                                                                 st.just(float("nan"))), st.just(ValueError)),
    st.tuples(st.just("confidence"), st.one_of(st.floats(max_value=0.4999), st.floats(min_value=1.0),
                                               st.just(float("nan"))), st.just(ValueError)),
    st.tuples(st.sampled_from(["transform", "criterion"]), st.text(max_size=4).filter(
        lambda t: t not in udm1.TRANSFORMS and t not in ("lattice", "replications")), st.just(ValueError)),
)


@FEW
@given(bad=BAD_ARGUMENTS, tolerance=st.booleans())
def test_integrate_refuses_every_bad_argument_before_f_runs(bad, tolerance):
    name, value, error = bad
    calls = []

    def f(x):
        calls.append(1)
        return smooth(x)

    kw = {"abs_tol": 1e-3} if tolerance or name in ("abs_tol", "rel_tol") else {"n": 100}
    if name in ("abs_tol", "rel_tol") and name in kw:
        del kw[name]
    if name == "n":
        kw = {}
    kw[name] = value
    with pytest.raises(error) as e:
        udm1.integrate(f, "wr", kw.pop("d", 2), **kw)
    assert name in str(e.value) and "\n" not in str(e.value), (name, value, str(e.value))
    assert not calls


@FEW
@given(scale=st.one_of(st.floats(min_value=1e-300, max_value=1e300), st.floats(min_value=-1e300, max_value=-1e-300),
                       st.integers(-1000, 1000).map(lambda k: 2.0 ** k)),
       name=st.sampled_from(["wr", "sobol-owen", "lattice-seq"]))
def test_integrals_at_any_magnitude(scale, name):
    """f of any finite magnitude up to 1e300 (and powers of two from 2^-1000 to 2^1000): a finite estimate
    and standard error (positive for a non-constant f), and a tolerance rule with a finite bound."""
    r = udm1.integrate(lambda x: scale * smooth(x), name, 2, 256, seed=3)
    assert math.isfinite(r.value) and math.isfinite(r.stderr) and r.stderr > 0
    t = udm1.integrate(lambda x: scale * smooth(x), name, 2, rel_tol=0.05, n_init=64, replications=4,
                       transform="baker" if name == "lattice-seq" else None, strict=False)
    assert math.isfinite(t.estimate) and all(math.isfinite(b) and b >= 0 for _, _, b in t.history)
