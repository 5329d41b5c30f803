"""The edges of the Python package: every integer that crosses into C is range-checked (ctypes would
wrap it silently), non-integral numbers are refused where an integer is expected, unsupported dtypes
name the supported ones, Python-side arithmetic never fails before the library's own check speaks,
and the qmc engines take a legacy RandomState seed as scipy's engines do."""

import numpy as np
import pytest
from scipy.stats import qmc

import udm1
import udm1.qmc

# (what, call, the argument's name that the error must contain)
OUT_OF_RANGE = [
    ("Sqrt past 2^64", lambda: udm1.Sequence(alphas=[udm1.Sqrt(2**64 + 2)]), "k"),
    ("negative Sqrt", lambda: udm1.Sequence(alphas=[udm1.Sqrt(-5)]), "k"),
    ("Fixed past 2^128", lambda: udm1.Sequence(alphas=[udm1.Fixed(2**128 + 5)]), "Fixed"),
    ("negative Fixed", lambda: udm1.Sequence(alphas=[udm1.Fixed(-1)]), "Fixed"),
    ("point count past 2^64", lambda: udm1.Sequence("episwr", 2, point_count=2**64 + 16), "point_count"),
    ("negative point count", lambda: udm1.Sequence("episwr", 2, point_count=-16), "point_count"),
    ("dimensions past 2^32", lambda: udm1.Sequence("wr", 2**32 + 2), "d"),
    ("seed past 2^64", lambda: udm1.Sequence("wr", 2, seed=2**64 + 1), "seed"),
    ("negative seed", lambda: udm1.Sequence("wr", 2, seed=-1), "seed"),
    ("screen_spp past 2^32", lambda: udm1.Sequence("wr", 2, randomize="screen", screen_spp=2**32 + 16), "screen_spp"),
    ("n past 2^64", lambda: udm1.Sequence("wr", 2).points(2**64 + 2), "n"),
    ("first past 2^64", lambda: udm1.Sequence("wr", 2).points(2, first=2**64), "first"),
    ("negative first", lambda: udm1.Sequence("wr", 2).points(2, first=-1), "first"),
    ("stream past 2^64", lambda: udm1.Sequence("wr", 2).points(2, stream=2**64), "stream"),
    ("sample index past 2^64", lambda: udm1.Sequence("wr", 2).sample(2**64, 0), "index"),
    ("sample dim past 2^32", lambda: udm1.Sequence("wr", 2).sample(0, 2**32 + 1), "dim"),
    ("randomizations past 2^32",
     lambda: udm1.Sequence("wr", 2).integration_error("disk", 2, 64, 2**32 + 3), "randomizations"),
    ("integration n past 2^64", lambda: udm1.Sequence("wr", 2).integration_error("disk", 2, 2**64 + 64), "n"),
    ("integrand d past 2^32", lambda: udm1.Sequence("wr", 2).integration_error("disk", 2**32 + 2, 64), "d"),
    ("integrand code past 2^32", lambda: udm1.integrand(2**32 + 4, np.zeros((2, 2))), "integrand"),
    ("spectrum size past 2^32", lambda: udm1.Sequence("wr", 2).spectrum(64, size=2**32 + 2), "size"),
    ("spectrum n past 2^64", lambda: udm1.Sequence("wr", 2).spectrum(2**64 + 64, size=2), "n"),
    ("zoneplate spp past 2^32", lambda: udm1.Sequence("wr", 2).zoneplate(2, 2, 2**32 + 1), "spp"),
    ("zoneplate width past 2^32", lambda: udm1.Sequence("wr", 2).zoneplate(2**32 + 2, 2, 1), "width"),
    ("check n past 2^64", lambda: udm1.Sequence("wr", 2).check(2**64 + 256), "n"),
    ("check_alphas n past 2^64", lambda: udm1.check_alphas([udm1.Sqrt(2)], 2**64 + 256), "n"),
    ("discrepancy_random n past 2^64", lambda: udm1.discrepancy_random(2**64 + 1, 2), "n"),
    ("discrepancy_random d past 2^32", lambda: udm1.discrepancy_random(16, 2**32 + 2), "d"),
    ("integrand_exact d past 2^32", lambda: udm1.integrand_exact("genz-gaussian", 2**32 + 2), "d"),
    ("noise seed past 2^64", lambda: udm1.Noise("wr", seed=2**64 + 3), "seed"),
    ("negative noise seed", lambda: udm1.Noise("wr", seed=-3), "seed"),
    ("noise period past 2^32", lambda: udm1.Noise(period=2**32 + 4), "period"),
    ("pattern octaves past 2^32", lambda: udm1.Noise().pattern_grid("fbm", 4, 4, octaves=2**32 + 6), "octaves"),
    ("grid width past 2^32", lambda: udm1.Noise().pattern_grid("fbm", 2**32 + 4, 4), "width"),
    ("points_at dims past 2^32", lambda: udm1.Sequence("wr", 2).points_at([0], [0], dims=range(2**32, 2**32 + 2)),
     "dims"),
]

NOT_INTEGRAL = [
    ("d = 2.5", lambda: udm1.Sequence("wr", 2.5), "d"),
    ("n = 2.7", lambda: udm1.Sequence("wr", 2).points(2.7), "n"),
    ("first = 1.5", lambda: udm1.Sequence("wr", 2).points(2, first=1.5), "first"),
    ("seed = 0.5", lambda: udm1.Sequence("wr", 2, seed=0.5), "seed"),
    ("Sqrt(2.5)", lambda: udm1.Sequence(alphas=[udm1.Sqrt(2.5)]), "k"),
    ("point_count = 64.5", lambda: udm1.Sequence("episwr", 2, point_count=64.5), "point_count"),
    ("randomizations = 3.5", lambda: udm1.Sequence("wr", 2).integration_error("disk", 2, 64, 3.5), "randomizations"),
    ("spectrum size = 64.5", lambda: udm1.Sequence("wr", 2).spectrum(64, size=64.5), "size"),
    ("noise period = 4.5", lambda: udm1.Noise(period=4.5), "period"),
    ("grid width = 16.5", lambda: udm1.Noise().pattern_grid("fbm", 16.5, 4), "width"),
    ("engine fast_forward(2.5)", lambda: udm1.qmc.WR(2, seed=1).fast_forward(2.5), "n"),
    ("Sequence.sample(index=0.5)", lambda: udm1.Sequence("wr", 2).sample(0.5, 0), "index"),
]


@pytest.mark.parametrize("what,call,name", OUT_OF_RANGE, ids=[c[0] for c in OUT_OF_RANGE])
def test_out_of_range_integers_are_refused(what, call, name):
    with pytest.raises(ValueError) as e:
        call()
    assert name in str(e.value), f"{what}: the error does not name '{name}': {e.value}"


@pytest.mark.parametrize("what,call,name", NOT_INTEGRAL, ids=[c[0] for c in NOT_INTEGRAL])
def test_non_integral_numbers_are_refused(what, call, name):
    with pytest.raises((ValueError, TypeError)) as e:
        call()
    assert name in str(e.value), f"{what}: the error does not name '{name}': {e.value}"


def test_integral_values_of_other_types_are_accepted():
    s = udm1.Sequence("wr", np.int64(3), seed=np.uint64(7))
    a = s.points(np.int32(5), first=np.uint16(2), stream=np.int8(1))
    b = udm1.Sequence("wr", 3, seed=7).points(5, first=2, stream=1)
    assert np.array_equal(a, b)
    assert np.array_equal(udm1.Sequence("wr", 3, seed=7).points(5.0), udm1.Sequence("wr", 3, seed=7).points(5))
    # the largest values that fit are taken as they are
    top = udm1.Sequence("wr", 1, seed=2**64 - 1).points(1, first=2**64 - 1, stream=2**64 - 1, dtype=np.uint64)
    assert top.shape == (1, 1)


def test_unsupported_dtype_names_the_supported_ones():
    s = udm1.Sequence("wr", 2)
    for call in (lambda: s.points(4, dtype=np.int32), lambda: s.sample(0, 0, dtype="float16")):
        with pytest.raises(ValueError) as e:
            call()
        for name in ("float64", "float32", "uint64"):
            assert name in str(e.value)


def test_library_checks_speak_before_python_arithmetic():
    # a zero-size grid: the library's one-line error, not ZeroDivisionError
    with pytest.raises(udm1.UDM1Error) as e:
        udm1.Noise().pattern_grid("marble", 0, 4)
    assert "width" in str(e.value)
    with pytest.raises(udm1.UDM1Error):
        udm1.Noise().pattern_grid("marble", 4, 0)
    with pytest.raises(udm1.UDM1Error):
        udm1.Sequence("wr", 2).zoneplate(0, 4, 1)


def test_engines_take_a_legacy_random_state_as_scipy_does():
    for engine in (udm1.qmc.WR, udm1.qmc.Rd):
        a = engine(2, seed=np.random.RandomState(3)).random(8)
        b = engine(2, seed=np.random.RandomState(3)).random(8)
        c = engine(2, seed=np.random.RandomState(4)).random(8)
        assert np.array_equal(a, b) and not np.array_equal(a, c)
    # scipy's own engines accept the same argument (seed=, not rng=): the convention followed
    qmc.Sobol(2, seed=np.random.RandomState(3)).random(8)
    # (scipy's qmc_quad itself needs an engine seeded by a Generator: it spawns from it)
