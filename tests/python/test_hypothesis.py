"""Property-based tests (Hypothesis) of the package and, through it, the C API: random descriptors,
index ranges, splits, dimension windows and dtypes, asserting the sequence contract (udm1/seq.h):

- every value is exact: for the Weyl presets without a transform, the raw 0.64 value of (n, j) is the top
  64 bits of (O_j 2^64 + n A_j) mod 2^128, with A_j and O_j read back from the library, and A_j of a
  square root equals round(frac(sqrt k) 2^128) computed here with math.isqrt;
- float64 and float32 are the documented conversions of the raw value, in [0, 1);
- bulk, per-sample and many-points calls, any split of a range and any window of dimensions agree bit
  for bit;
- every refusal is a udm1.UDM1Error or ValueError (TypeError for a non-number) with a one-line message.

Failing examples Hypothesis found stay below as @example regression cases.
"""

import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

import udm1

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
                     st.text(max_size=3), st.none())


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
