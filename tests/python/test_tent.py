"""The tent transform "NAME+tent": every value x of sampler NAME becomes 1 - |2x - 1|, exactly in the
0.64 fixed point (2x below 1/2, 2 - 2x above), in every access path; and on a smooth non-periodic
integrand it lowers the error of the randomly shifted Kronecker sequences, as the periodization
argument says (their Fourier coefficients then decay as h^-2 instead of h^-1)."""

import math

import numpy as np
import pytest

import udm1


def tent_u64(a):
    a = a.astype(np.uint64)
    return np.where(a >> np.uint64(63), (np.uint64(0) - a) << np.uint64(1), a << np.uint64(1))


@pytest.mark.parametrize("name,kw", [("wr", {}), ("wopt", {}), ("rd", {}), ("sobol-owen", {}), ("halton", {}),
                                     ("pcg32", {}), ("pmj02", {"point_count": 64}), ("episwr", {"point_count": 64})])
def test_exact_in_every_path(name, kw):
    d = 2 if name == "episwr" else 4
    plain = udm1.Sequence(name, d, seed=3, **kw).points(64, stream=11, dtype=np.uint64)
    tent = udm1.Sequence(name + "+tent", d, seed=3, **kw)
    assert tent.name == name + "+tent"
    bulk = tent.points(64, stream=11, dtype=np.uint64)
    assert np.array_equal(bulk, tent_u64(plain))
    split = np.vstack([tent.points(20, stream=11, dtype=np.uint64), tent.points(44, first=20, stream=11, dtype=np.uint64)])
    assert np.array_equal(split, bulk)
    for n in (0, 31, 63):
        for j in range(d):
            assert tent.sample(n, j, stream=11, dtype=np.uint64) == bulk[n, j]
    f64 = tent.points(64, stream=11)
    assert np.all((f64 >= 0) & (f64 < 1)) and np.array_equal(f64, (bulk >> np.uint64(11)) * 2.0 ** -53)


def test_screen_mode_too():
    plain = udm1.Sequence("wr", 2, seed=1, randomize="screen", screen_spp=8).points(8, stream=(3 << 32) | 5, dtype=np.uint64)
    tent = udm1.Sequence("wr+tent", 2, seed=1, randomize="screen", screen_spp=8).points(8, stream=(3 << 32) | 5,
                                                                                          dtype=np.uint64)
    assert np.array_equal(tent, tent_u64(plain))


@pytest.mark.parametrize("bad", ["wr+foo", "wr+tent+tent", "+tent", "nothing+tent"])
def test_unknown_names(bad):
    with pytest.raises(udm1.UDM1Error, match="unknown preset"):
        udm1.Sequence(bad, 2)


@pytest.mark.parametrize("name", ["wr", "rd", "wopt"])
def test_lowers_the_error_on_a_smooth_integrand(name):
    exact = (math.e - 1) * 2 * (math.exp(0.5) - 1)  # integral of exp(x + y/2) over the unit square
    rmse = {}
    for variant in (name, name + "+tent"):
        errs = [np.mean(np.exp(p[:, 0] + 0.5 * p[:, 1])) - exact
                for p in (udm1.Sequence(variant, 2, seed=s).points(4096) for s in range(1, 33))]
        rmse[variant] = math.sqrt(np.mean(np.square(errs)))
    assert rmse[name + "+tent"] < rmse[name] / 1.5, rmse
