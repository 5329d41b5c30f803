"""Test integrands: exact integrals against numerical integration; the
metrics' Python wrappers against their definitions."""

import math

import numpy as np
import pytest
from scipy import integrate

import udm1

SMOOTH_2D = ["gaussian", "product-peak", "bilinear"]
DISCONTINUOUS_2D = ["disk", "triangle", "halfplane", "step"]
GENZ = ["genz-oscillatory", "genz-product-peak", "genz-corner-peak", "genz-gaussian", "genz-continuous",
        "genz-discontinuous"]


@pytest.mark.parametrize("name", SMOOTH_2D)
def test_smooth_2d_exact_against_quadrature(name):
    f = lambda y, x: udm1.integrand(name, np.array([[x, y]]))[0]
    val, err = integrate.dblquad(f, 0, 1, 0, 1, epsabs=1e-12, epsrel=1e-12)
    assert udm1.integrand_exact(name, 2) == pytest.approx(val, rel=1e-9)


@pytest.mark.parametrize("name", DISCONTINUOUS_2D)
def test_discontinuous_2d_exact_against_a_fine_grid(name):
    # midpoint rule on a 4000 x 4000 grid: error ~ perimeter / 4000 ~ 1e-4
    g = (np.arange(4000) + 0.5) / 4000
    x, y = np.meshgrid(g, g)
    pts = np.column_stack([x.ravel(), y.ravel()])
    assert udm1.integrand(name, pts).mean() == pytest.approx(udm1.integrand_exact(name, 2), abs=2e-4)


@pytest.mark.parametrize("name", GENZ)
@pytest.mark.parametrize("d", [2, 3, 6])
def test_genz_exact_against_qmc(name, d):
    # 2^18 Owen-scrambled Sobol points, 4 randomizations: far below the tolerance
    seq = udm1.Sequence("sobol-owen", d, seed=1)
    est = np.mean([udm1.integrand(name, seq.points(1 << 18, stream=r)).mean() for r in range(4)])
    exact = udm1.integrand_exact(name, d)
    tol = 1e-3 if "discontinuous" in name else 1e-4
    assert est == pytest.approx(exact, rel=tol, abs=tol * 1e-3)


def test_genz_1d_against_quadrature():
    for name in GENZ[:5]:
        f = lambda x: udm1.integrand(name, np.array([[x]]))[0]
        val, _ = integrate.quad(f, 0, 1, epsabs=1e-13, epsrel=1e-13, limit=200)
        assert udm1.integrand_exact(name, 1) == pytest.approx(val, rel=1e-10)


def test_integration_error_converges_faster_for_qmc():
    # the RMSE of Owen-scrambled Sobol on a smooth integrand falls much faster than N^-1/2
    seq = udm1.Sequence("sobol-owen", 2, seed=3)
    r1 = seq.integration_error("gaussian", 2, 256, 32)[0]
    r2 = seq.integration_error("gaussian", 2, 4096, 32)[0]
    slope = math.log(r2 / r1) / math.log(16)
    assert slope < -1.2
    rnd = udm1.Sequence("pcg32", 2, seed=3)
    s1 = rnd.integration_error("gaussian", 2, 256, 64)[0]
    s2 = rnd.integration_error("gaussian", 2, 4096, 64)[0]
    assert -0.8 < math.log(s2 / s1) / math.log(16) < -0.2


def test_wrappers():
    x = np.array([[0.1, 0.1], [0.9, 0.1], [0.5, 0.6]])
    assert udm1.min_distance(x) == pytest.approx(math.sqrt(0.41))
    assert udm1.min_distance(x, toroidal=True) == pytest.approx(0.2)
    assert udm1.star_discrepancy(np.array([[0.5, 0.5]])) == pytest.approx(0.75)
    with pytest.raises(ValueError):
        udm1.integrand("nope", x)
    with pytest.raises(udm1.UDM1Error):
        udm1.integrand("disk", np.zeros((2, 3)))
    sp = udm1.Sequence("pcg32", 2, seed=2).spectrum(128, size=16, randomizations=4)
    assert sp.shape == (16, 16) and sp[8, 8] == pytest.approx(128)
    zp = udm1.Sequence("wr-ao", 2, seed=2).zoneplate(32, 16, 4)
    assert zp.shape == (16, 32) and zp.dtype == np.float32 and 0 <= zp.min() and zp.max() <= 1
