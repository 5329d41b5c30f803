"""The package's one input converter (udm1/_convert.py) and every public function that takes numbers:

- what numpy or ctypes would coerce is refused before any cast, naming the argument: complex values
  (numpy would keep their real part with a warning), strings (numpy parses them), bools (numpy takes
  them as 0 and 1), None and other objects, in scalars, arrays, lists and tuples of arrays;
- integer arrays are range-checked without wrapping (a negative stream cast to uint64 would wrap) and
  float arrays of indices follow the scalar rule: integral values taken, others refused;
- numpy scalars (np.float32, np.int8, np.uint64, ...) and 0-d arrays are taken wherever Python numbers
  are, with the same result;
- every refusal is a TypeError or udm1.UDM1Error (a ValueError) with a one-line message naming the
  argument, and no warning is emitted on the way.
"""

import warnings

import numpy as np
import pytest

import udm1
import udm1.qmc
from udm1 import _convert

P3 = np.array([[0.25, 1.5, -2.0], [3.0, 0.5, 7.25]])  # points for the noise calls
S2 = np.array([[0.1, 0.2], [0.6, 0.7], [0.3, 0.9]])   # a sample for the metrics


def seq():
    return udm1.Sequence("wr", 3, seed=5)


def prod(x):
    return np.prod(x, axis=1)


def read_only(a):
    a.setflags(write=False)
    return a


# (what, call, the exception types allowed, the argument's name the message must contain)
REFUSED = [
    # Sequence
    ("points_at negative stream", lambda: seq().points_at(np.array([-1]), np.array([0])), ValueError, "streams[0]"),
    ("points_at negative index", lambda: seq().points_at([0, 0], np.array([3, -2])), ValueError, "indices[1]"),
    ("points_at fractional index", lambda: seq().points_at([0], [1.5]), ValueError, "indices[0]"),
    ("points_at fractional stream array", lambda: seq().points_at(np.array([0.5]), [0]), ValueError, "streams[0]"),
    ("points_at index past 2^64", lambda: seq().points_at([0], [2**64]), ValueError, "indices[0]"),
    ("points_at float index past 2^64", lambda: seq().points_at([0], np.array([2.0**64])), ValueError, "indices[0]"),
    ("points_at nan index", lambda: seq().points_at([0], np.array([np.nan])), ValueError, "indices[0]"),
    ("points_at bool streams", lambda: seq().points_at(np.array([True]), [0]), TypeError, "streams"),
    ("points_at string indices", lambda: seq().points_at([0], ["1"]), TypeError, "indices"),
    ("points_at complex indices", lambda: seq().points_at([0], np.array([1 + 0j])), TypeError, "indices"),
    ("points_at bool in a list", lambda: seq().points_at([0, 1], [2, True]), TypeError, "indices[1]"),
    ("points_at 2-D streams", lambda: seq().points_at(np.zeros((2, 2), dtype=np.uint64), np.zeros((2, 2))),
     ValueError, "streams"),
    ("points bool n", lambda: seq().points(True), TypeError, "n"),
    ("points complex first", lambda: seq().points(2, first=1 + 0j), TypeError, "first"),
    ("points string stream", lambda: seq().points(2, stream="1"), TypeError, "stream"),
    ("points read-only out", lambda: seq().points(2, out=read_only(np.zeros((2, 3)))), ValueError, "out"),
    ("points list out", lambda: seq().points(2, out=[[0.0] * 3] * 2), ValueError, "out"),
    ("sample bool index", lambda: seq().sample(np.True_, 0), TypeError, "index"),
    ("Sequence bool seed", lambda: udm1.Sequence("wr", 2, seed=True), TypeError, "seed"),
    ("Sequence bytes preset", lambda: udm1.Sequence(b"wr", 2), TypeError, "preset"),
    ("Sequence complex alpha", lambda: udm1.Sequence(alphas=[1j]), TypeError, "alphas[0]"),
    ("Sequence bool alpha", lambda: udm1.Sequence(alphas=[0.5, True]), TypeError, "alphas[1]"),
    ("Sequence negative offsets", lambda: udm1.Sequence("wr", 2, offsets=np.array([1, -1])), ValueError, "offsets[1]"),
    ("Sequence string offsets", lambda: udm1.Sequence("wr", 2, offsets=["1", "2"]), TypeError, "offsets[0]"),
    ("Sequence bool randomize code", lambda: udm1.Sequence("wr", 2, randomize=1), ValueError, "randomize"),
    # scipy.stats.qmc engines
    ("engine random(2.5)", lambda: udm1.qmc.WR(2, seed=1).random(2.5), ValueError, "n"),
    ("engine random(-1)", lambda: udm1.qmc.WR(2, seed=1).random(-1), ValueError, "n"),
    ("engine random(True)", lambda: udm1.qmc.WR(2, seed=1).random(True), TypeError, "n"),
    ("engine fast_forward(-3)", lambda: udm1.qmc.Rd(2, seed=1).fast_forward(-3), ValueError, "n"),
    ("engine fast_forward past the set", lambda: udm1.qmc.EPISWR(n=16, seed=1).fast_forward(17), ValueError,
     "fast_forward"),
    ("engine string d", lambda: udm1.qmc.WR("2"), TypeError, "d"),
    ("engine scramble='yes'", lambda: udm1.qmc.WR(2, scramble="yes"), TypeError, "scramble"),
    ("engine EPISWR n=-8", lambda: udm1.qmc.EPISWR(n=-8), ValueError, "n"),
    ("engine optimization", lambda: udm1.qmc.WR(2, seed=1, optimization="random-cd"), ValueError, "optimization"),
    # metrics
    ("discrepancy complex sample", lambda: udm1.discrepancy(S2 + 0j), TypeError, "sample"),
    ("discrepancy string sample", lambda: udm1.discrepancy([["0.1", "0.2"]]), TypeError, "sample"),
    ("discrepancy bool sample", lambda: udm1.discrepancy(S2 > 0.5), TypeError, "sample"),
    ("discrepancy method 3", lambda: udm1.discrepancy(S2, 3), TypeError, "method"),
    ("discrepancy_random bool n", lambda: udm1.discrepancy_random(True, 2), TypeError, "n"),
    ("star_discrepancy tuple of bools", lambda: udm1.star_discrepancy(((True, False), (False, True))), TypeError,
     "sample"),
    ("min_distance object sample", lambda: udm1.min_distance(np.array([[0.1, None]], dtype=object)), TypeError,
     "sample"),
    ("min_distance toroidal='no'", lambda: udm1.min_distance(S2, toroidal="no"), TypeError, "toroidal"),
    ("integrand complex sample", lambda: udm1.integrand("disk", S2.astype(complex)), TypeError, "sample"),
    ("integrand_exact float d", lambda: udm1.integrand_exact("disk", 2.5), ValueError, "d"),
    # Noise
    ("noise complex points", lambda: udm1.Noise().noise(P3 + 1j), TypeError, "points"),
    ("noise complex coordinate array", lambda: udm1.Noise().noise((np.zeros(2), np.ones(2) * 1j)), TypeError,
     "points[1]"),
    ("noise tuple of strings", lambda: udm1.Noise().noise((["1", "2"], ["3", "4"])), TypeError, "points[0]"),
    ("noise tuple of bools", lambda: udm1.Noise().noise(([True, False], [False, True])), TypeError, "points[0]"),
    ("noise bool coordinate arrays", lambda: udm1.Noise().noise((np.array([True]), np.array([0.5]))), TypeError,
     "points[0]"),
    ("noise string rows", lambda: udm1.Noise().noise(np.array([["0.5", "1", "2"]])), TypeError, "points"),
    ("noise long double past the double range",
     lambda: udm1.Noise().noise(np.array([[np.longdouble("1e4000"), 0, 0]])), ValueError, "points[0, 0]"),
    ("noise dtype int32", lambda: udm1.Noise().noise(P3, dtype="int32"), ValueError, "dtype"),
    ("noise gradient='yes'", lambda: udm1.Noise().noise(P3, gradient="yes"), TypeError, "gradient"),
    ("cellular bool points", lambda: udm1.Noise().cellular(P3 > 0), TypeError, "points"),
    ("cellular complex jitter", lambda: udm1.Noise().cellular(P3, jitter=0.5j), TypeError, "jitter"),
    ("cellular nan exponent", lambda: udm1.Noise().cellular(P3, exponent=float("nan")), ValueError, "exponent"),
    ("cellular bool jitter", lambda: udm1.Noise().cellular(P3, jitter=True), TypeError, "jitter"),
    ("pattern complex points", lambda: udm1.Noise().pattern("fbm", P3 * 1j), TypeError, "points"),
    ("pattern string omega", lambda: udm1.Noise().pattern("fbm", P3, omega="0.5"), TypeError, "omega"),
    ("pattern inf lacunarity", lambda: udm1.Noise().pattern("fbm", P3, lacunarity=np.inf), ValueError, "lacunarity"),
    ("pattern two turbulences", lambda: udm1.Noise().pattern("marble", P3, turbulence=(0.5, 0.5)), ValueError,
     "turbulence"),
    ("pattern bool form", lambda: udm1.Noise().pattern("crackle", P3, form=(True, 0, 0)), TypeError, "form"),
    ("pattern solid='no'", lambda: udm1.Noise().pattern("crackle", P3, solid="no"), TypeError, "solid"),
    ("pattern_grid short origin", lambda: udm1.Noise().pattern_grid("fbm", 4, 4, origin=(0, 0)), ValueError,
     "origin"),
    ("pattern_grid nan size", lambda: udm1.Noise().pattern_grid("fbm", 4, 4, size=(1, np.nan)), ValueError, "size"),
    ("pattern_grid bool width", lambda: udm1.Noise().pattern_grid("fbm", True, 4), TypeError, "width"),
    ("Noise bool period", lambda: udm1.Noise(period=(4, True, 0)), TypeError, "period[1]"),
    ("Noise bytes table", lambda: udm1.Noise(b"wr"), TypeError, "table"),
    ("Noise kind 1", lambda: udm1.Noise(kind=1), TypeError, "kind"),
    # exact sums
    ("ExactSum complex values", lambda: udm1.ExactSum().add([1.0, 2j]), TypeError, "values"),
    ("ExactSum bool values", lambda: udm1.ExactSum().add(np.array([True, False])), TypeError, "values"),
    ("ExactSum string values", lambda: udm1.ExactSum().add(["1.5"]), TypeError, "values"),
    ("ExactSum int64 not a double", lambda: udm1.ExactSum().add(np.array([2**53 + 1])), ValueError, "values[0]"),
    ("ExactSum long double not a double",
     lambda: udm1.ExactSum().add(np.array([1, 1 + np.finfo(np.longdouble).eps], dtype=np.longdouble)), ValueError,
     "values[1]"),
    ("ExactSum.mean(n=1.5)", lambda: udm1.ExactSum().add([1.0]).mean(1.5), ValueError, "n"),
    # integrate
    ("integrate complex values", lambda: udm1.integrate(lambda x: prod(x) + 0j, "wr", 2, n=8), TypeError, "f(x)"),
    ("integrate bool values", lambda: udm1.integrate(lambda x: x[:, 0] < 0.5, "wr", 2, n=8), TypeError, "f(x)"),
    ("integrate string values", lambda: udm1.integrate(lambda x: ["1"] * len(x), "wr", 2, n=8), TypeError, "f(x)"),
    ("integrate complex abs_tol", lambda: udm1.integrate(prod, "wr", 2, abs_tol=1e-3 + 0j), TypeError, "abs_tol"),
    ("integrate string rel_tol", lambda: udm1.integrate(prod, "wr", 2, rel_tol="0.1"), TypeError, "rel_tol"),
    ("integrate bool n", lambda: udm1.integrate(prod, "wr", 2, n=True), TypeError, "n"),
]


@pytest.mark.parametrize("what,call,errors,name", REFUSED, ids=[c[0] for c in REFUSED])
def test_refused_naming_the_argument(what, call, errors, name):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a ComplexWarning or DeprecationWarning on the way is a coercion
        with pytest.raises(errors) as e:
            call()
    message = str(e.value)
    assert name in message, f"{what}: the error does not name {name!r}: {message}"
    assert message and "\n" not in message, f"{what}: {message!r}"


def _same(a, b):
    if isinstance(a, tuple):
        return all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, udm1.Integral):
        return a.sum == b.sum and a.sum_sq == b.sum_sq
    if isinstance(a, udm1.ToleranceResult):
        return (a.estimate, a.error_bound, a.n) == (b.estimate, b.error_bound, b.n)
    return np.array_equal(np.asarray(a), np.asarray(b))


# (what, the call with numpy scalars (or 0-d arrays), the same call with Python numbers)
ACCEPTED = [
    ("points int8/uint64", lambda: udm1.Sequence("wr", np.int8(3), seed=np.uint64(5)).points(np.uint16(4),
                                                                                           first=np.int64(2)),
     lambda: udm1.Sequence("wr", 3, seed=5).points(4, first=2)),
    ("points 0-d arrays", lambda: seq().points(np.array(4), stream=np.array(7)), lambda: seq().points(4, stream=7)),
    ("points integral float32", lambda: seq().points(np.float32(4.0)), lambda: seq().points(4)),
    ("points_at int8 and float arrays",
     lambda: seq().points_at(np.array([1, 2], dtype=np.int8), np.array([3.0, 2.0**60])),
     lambda: seq().points_at(np.array([1, 2], dtype=np.uint64), np.array([3, 2**60], dtype=np.uint64))),
    ("points_at lists up to 2^64 - 1", lambda: seq().points_at([0, 2**64 - 1], [2**64 - 2, 0]),
     lambda: seq().points_at(np.array([0, 2**64 - 1], dtype=np.uint64), np.array([2**64 - 2, 0], dtype=np.uint64))),
    ("sample numpy index", lambda: seq().sample(np.uint64(2**63), np.int16(1)), lambda: seq().sample(2**63, 1)),
    ("Sequence float32 alpha", lambda: udm1.Sequence(alphas=[np.float32(0.3)], seed=1).points(4),
     lambda: udm1.Sequence(alphas=[float(np.float32(0.3))], seed=1).points(4)),
    ("Sequence numpy bool randomize", lambda: udm1.Sequence("wr", 2, randomize=np.False_).points(3),
     lambda: udm1.Sequence("wr", 2, randomize=False).points(3)),
    ("engine numpy n", lambda: udm1.qmc.WR(np.int32(2), seed=3).random(np.uint8(5)),
     lambda: udm1.qmc.WR(2, seed=3).random(5)),
    ("engine numpy fast_forward", lambda: udm1.qmc.WR(2, seed=3).fast_forward(np.int64(7)).random(2),
     lambda: udm1.qmc.WR(2, seed=3).fast_forward(7).random(2)),
    ("discrepancy float32 sample", lambda: udm1.discrepancy(S2.astype(np.float32)),
     lambda: udm1.discrepancy(S2.astype(np.float32).astype(np.float64))),
    ("discrepancy int sample", lambda: udm1.discrepancy(np.array([[0, 1], [1, 0]])),
     lambda: udm1.discrepancy(np.array([[0.0, 1.0], [1.0, 0.0]]))),
    ("min_distance numpy bool", lambda: udm1.min_distance(S2, toroidal=np.True_),
     lambda: udm1.min_distance(S2, toroidal=True)),
    ("noise int16 points", lambda: udm1.Noise().noise(np.array([[1, 2, 3]], dtype=np.int16)),
     lambda: udm1.Noise().noise(np.array([[1.0, 2.0, 3.0]]))),
    ("noise lists", lambda: udm1.Noise().noise([[0.25, 1.5], [-2.0, 3.0]]),
     lambda: udm1.Noise().noise((np.array([0.25, 1.5]), np.array([-2.0, 3.0])))),
    ("cellular float32 jitter", lambda: udm1.Noise("rd").cellular(P3, jitter=np.float32(0.5), exponent=np.int8(3),
                                                                  metric="minkowski"),
     lambda: udm1.Noise("rd").cellular(P3, jitter=0.5, exponent=3.0, metric="minkowski")),
    ("pattern numpy params", lambda: udm1.Noise().pattern("fbm", P3, octaves=np.uint8(3), omega=np.float32(0.5),
                                                          turbulence=np.array([0.25, 0.5, 1.0])),
     lambda: udm1.Noise().pattern("fbm", P3, octaves=3, omega=0.5, turbulence=[0.25, 0.5, 1.0])),
    ("pattern_grid numpy sizes", lambda: udm1.Noise().pattern_grid("marble", np.int64(8), np.uint32(4),
                                                                   origin=np.zeros(3), size=np.array([2.0, 1.0])),
     lambda: udm1.Noise().pattern_grid("marble", 8, 4, origin=(0, 0, 0), size=(2, 1))),
    ("Noise numpy period and seed", lambda: udm1.Noise("wr", seed=np.uint64(3), period=np.array([4, 4, 0])).noise(P3),
     lambda: udm1.Noise("wr", seed=3, period=(4, 4, 0)).noise(P3)),
    ("ExactSum int and float32 values", lambda: udm1.ExactSum().add(np.array([3, -7], dtype=np.int8)).value(),
     lambda: udm1.ExactSum().add([3.0, -7.0]).value()),
    ("integrate numpy arguments", lambda: udm1.integrate(prod, "wr", np.int64(2), np.uint32(100), seed=np.uint8(3),
                                                        chunk=np.int16(7), stream=np.uint64(2)),
     lambda: udm1.integrate(prod, "wr", 2, 100, seed=3, chunk=7, stream=2)),
    ("integrate float32 tolerance", lambda: udm1.integrate(prod, "wr", 2, abs_tol=np.float32(1e-3),
                                                          confidence=np.float32(0.9), n_init=np.int32(64)),
     lambda: udm1.integrate(prod, "wr", 2, abs_tol=float(np.float32(1e-3)), confidence=float(np.float32(0.9)),
                            n_init=64)),
    ("integrate float32 values", lambda: udm1.integrate(lambda x: prod(x).astype(np.float32), "wr", 2, n=64),
     lambda: udm1.integrate(lambda x: prod(x).astype(np.float32).astype(np.float64), "wr", 2, n=64)),
]


@pytest.mark.parametrize("what,numpy_call,python_call", ACCEPTED, ids=[c[0] for c in ACCEPTED])
def test_numpy_scalars_are_taken_as_python_numbers(what, numpy_call, python_call):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _same(numpy_call(), python_call()), what


def test_scalar_and_array_rules_agree():
    """An integer argument takes the same values as a scalar and inside an array: integral floats yes,
    fractional, non-finite, negative or too large no, bools never."""
    for value in (0, 7, 2**53, 2**64 - 1, 3.0, np.float32(5.0), np.int8(4), np.uint64(2**64 - 1)):
        assert _convert.u64(value, "v") == int(_convert.index_array(np.array([value]), "v")[0]) == int(value)
    for value in (-1, 2**64, 2.5, float("nan"), float("inf"), -0.5):
        with pytest.raises(ValueError):
            _convert.u64(value, "v")
        with pytest.raises(ValueError):
            _convert.index_array(np.array([value], dtype=object if isinstance(value, int) else float), "v")
        with pytest.raises(ValueError):
            _convert.index_array([value], "v")
    for value in (True, np.True_, 1j, "1", None, b"1"):
        with pytest.raises(TypeError):
            _convert.u64(value, "v")
        with pytest.raises(TypeError):
            _convert.index_array([value], "v")
    # wrapping: numpy casts these silently; the converter does not
    for array in (np.array([-1], dtype=np.int64), np.array([-(2**63)]), np.array([2.0**64]), np.array([-1.0])):
        with pytest.raises(ValueError):
            _convert.index_array(array, "v")
    assert _convert.index_array(np.array([2**64 - 1], dtype=np.uint64), "v")[0] == 2**64 - 1
    assert _convert.index_array(np.array([2.0**63]), "v")[0] == 2**63


def test_real_scalars():
    assert _convert.real(np.float32(0.5), "x") == 0.5 and _convert.real(np.int8(-3), "x") == -3.0
    assert _convert.real(np.array(2.5), "x") == 2.5
    for bad in (True, 1j, "1", None, np.array([1.0])):
        with pytest.raises(TypeError, match="x"):
            _convert.real(bad, "x")
    for bad in (float("nan"), float("inf"), 10**400):
        with pytest.raises(ValueError, match="x"):
            _convert.real(bad, "x")
    assert _convert.real(float("inf"), "x", finite=False) == float("inf")
    with pytest.raises(ValueError, match=r"x = 0.0 is outside \(0"):
        _convert.real(0.0, "x", lo=0.0, lo_open=True)


def test_no_array_is_read_before_it_is_written(monkeypatch):
    """Every np.empty of the package is written whole before it is read: with np.empty poisoned (NaN, or
    all ones for integers) the results are the same bit for bit."""
    def run():
        s = udm1.Sequence("sobol-owen", 4, seed=3)
        n = udm1.Noise("rd", seed=2)
        q = udm1.qmc.WR(2, seed=1)
        return [
            s.points(33, 5, stream=2), s.points(9, dtype=np.uint64),
            s.points_at([1, 2, 3], [4, 5, 6], dims=range(2, 7)),
            s.spectrum(64, size=8, randomizations=2), s.zoneplate(6, 5, 2),
            n.noise(P3), n.noise(P3, gradient=True), n.cellular(P3, output="f2"), n.pattern("fbm", P3, gradient=True),
            n.pattern_grid("marble", 7, 3), n.tables(), n.cellular_offsets(),
            udm1.integrand("disk", S2), q.random(5), q.random(3),
            udm1.integrate(prod, "wr", 3, n=1000, chunk=77, seed=1),
            udm1.integrate(prod, "sobol-owen", 2, abs_tol=1e-4, n_init=64, replications=4, chunk=50),
            udm1.integrate(prod, "lattice-seq", 2, abs_tol=1e-6, transform="baker", chunk=100),
        ]

    clean = run()
    real_empty = np.empty

    def poisoned(shape, dtype=float, *args, **kwargs):
        a = real_empty(shape, dtype, *args, **kwargs)
        a.fill(np.nan if np.dtype(dtype).kind in "fc" else 1)
        return a

    monkeypatch.setattr(np, "empty", poisoned)  # the package's modules call it as np.empty
    assert all(_same(a, b) for a, b in zip(run(), clean))
