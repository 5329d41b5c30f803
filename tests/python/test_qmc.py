"""udm1's scipy.stats.qmc engines follow the QMCEngine conventions."""

import numpy as np
import pytest
from scipy import integrate
from scipy.stats import qmc

import udm1
import udm1.qmc as uq

ENGINES = [uq.WR, uq.WMMR, uq.HWMMR, uq.Rd]


@pytest.mark.parametrize("cls", ENGINES)
def test_is_a_qmc_engine(cls):
    e = cls(4, seed=1)
    assert isinstance(e, qmc.QMCEngine)
    x = e.random(100)
    assert x.shape == (100, 4) and x.dtype == np.float64
    assert np.all((x >= 0) & (x < 1))
    assert e.num_generated == 100


@pytest.mark.parametrize("cls", ENGINES)
def test_reset_and_fast_forward(cls):
    e = cls(3, seed=2)
    a = e.random(50)
    e.reset()
    assert e.num_generated == 0
    assert np.array_equal(e.random(50), a)
    e.reset()
    e.fast_forward(20)
    assert e.num_generated == 20
    assert np.array_equal(e.random(30), a[20:])
    assert e.fast_forward(2**62) is e  # O(1): no points generated


def test_same_seed_same_points_other_seed_differs():
    a = uq.WR(2, seed=11).random(64)
    assert np.array_equal(a, uq.WR(2, seed=11).random(64))
    assert np.array_equal(a, uq.WR(2, rng=np.random.default_rng(11)).random(64))
    assert not np.array_equal(a, uq.WR(2, seed=12).random(64))
    b = uq.WR(2, scramble=False).random(64)
    assert np.all(b[0] == 0) and np.array_equal(b, udm1.Sequence("wr", 2, randomize=False).points(64))


def test_discrepancy_and_scale_work():
    x = uq.WR(2, seed=3).random(256)
    assert qmc.discrepancy(x) < qmc.discrepancy(np.random.default_rng(3).random((256, 2)))
    y = qmc.scale(x, [-1, 0], [1, 10])
    assert y.min() >= -1 and y.max() < 10


def test_qmc_quad_integrates():
    # integral of prod cos(x_i) over [0,1]^3 = sin(1)^3
    f = lambda x: np.prod(np.cos(x), axis=0)
    res = integrate.qmc_quad(f, [0, 0, 0], [1, 1, 1], n_estimates=8, n_points=4096, qrng=uq.WR(3, seed=5))
    exact = np.sin(1.0) ** 3
    assert abs(res.integral - exact) < 1e-4
    assert res.standard_error < 1e-3
    # the randomized estimates differ (independent shifts per seed)
    assert res.standard_error > 0


def test_episwr_engine_is_a_point_set():
    e = uq.EPISWR(n=64, seed=1)
    x = e.random(64)
    xs = np.sort(x[:, 0])
    assert np.allclose(np.diff(xs), 1 / 64)
    with pytest.raises(udm1.UDM1Error):
        e.random(1)  # only 64 points


def test_generic_engine_and_errors():
    e = uq.Weyl(2, preset="wgr", seed=0)
    assert e.random(4).shape == (4, 2)
    with pytest.raises(udm1.UDM1Error):
        uq.Weyl(3, preset="wgr")
