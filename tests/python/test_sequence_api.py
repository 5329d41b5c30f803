"""The Python Sequence class: arrays, dtypes, ranges, determinism and errors."""

import numpy as np
import pytest

import udm1


def test_points_match_samples_all_dtypes():
    s = udm1.Sequence("hwmmr", 22, seed=4)
    for dt in (np.float64, np.float32, np.uint64):
        pts = s.points(300, first=2**40, stream=12, dtype=dt)
        assert pts.dtype == dt and pts.shape == (300, 22)
        for n in (0, 1, 150, 299):
            for j in (0, 7, 21):
                assert pts[n, j] == s.sample(2**40 + n, j, stream=12, dtype=dt)


def test_dims_subrange_and_out():
    s = udm1.Sequence("wr", 10, seed=1)
    whole = s.points(64)
    assert np.array_equal(s.points(64, dims=slice(3, 7)), whole[:, 3:7])
    assert np.array_equal(s.points(64, dims=range(9, 10)), whole[:, 9:])
    out = np.empty((64, 10))
    assert s.points(64, out=out) is out
    assert np.array_equal(out, whole)
    with pytest.raises(ValueError):
        s.points(64, out=np.empty((64, 9)))
    with pytest.raises(ValueError):
        s.points(4, dims=range(0, 10, 2))


def test_split_equals_whole_and_runs_repeat():
    s = udm1.Sequence("rd", 5, seed=8)
    whole = s.points(10000, first=123)
    parts = np.vstack([s.points(3333, first=123), s.points(6667, first=123 + 3333)])
    assert np.array_equal(whole, parts)
    assert np.array_equal(whole, udm1.Sequence("rd", 5, seed=8).points(10000, first=123))
    assert not np.array_equal(whole, udm1.Sequence("rd", 5, seed=9).points(10000, first=123))


def test_float32_never_one():
    # the largest raw value, through a custom offset: float32 must stay below 1
    s = udm1.Sequence(alphas=[udm1.Fixed(1)], offsets=[2**64 - 1], randomize=False)
    x = s.points(100, dtype=np.float32)
    assert x.max() < np.float32(1.0) and x.max() == np.float32(1 - 2**-24)
    y = s.points(100, dtype=np.float64)
    assert y.max() < 1.0 and y.max() == 1 - 2**-53


def test_properties_and_repr():
    s = udm1.Sequence("episwr", 2, point_count=64, seed=3)
    assert (s.d, s.name, s.point_count, s.seed, s.randomized) == (2, "episwr", 64, 3, True)
    assert "episwr" in repr(s)
    c = udm1.Sequence(alphas=[udm1.Sqrt(2), 0.5 ** 0.5 + 0.1], randomize=False)
    assert c.name == "custom" and c.d == 2 and not c.randomized
    s.close()
    with pytest.raises(ValueError):
        s.points(1)


def test_presets_listed():
    names = [p.name for p in udm1.presets()]
    for n in ["wr", "wr-ao", "we", "wgr", "wmmr", "hwmmr", "rd", "golden", "epis", "episwr"]:
        assert n in names
    assert [p for p in udm1.presets() if p.name == "wmmr"][0].max_dimensions == 22


@pytest.mark.parametrize(
    "kwargs,status,words",
    [
        (dict(preset="nope", d=2), "UDM1_ERROR_UNKNOWN_PRESET", "'nope'"),
        (dict(preset="wr", d=0), "UDM1_ERROR_DIMENSION", "dimensions is 0"),
        (dict(preset="wr", d=65537), "UDM1_ERROR_DIMENSION", "65537"),
        (dict(preset="we", d=3), "UDM1_ERROR_DIMENSION", "'we'"),
        (dict(preset="epis", d=1), "UDM1_ERROR_POINT_COUNT", "'epis'"),
        (dict(preset="episwr", d=2, point_count=2**32), "UDM1_ERROR_POINT_COUNT", "4294967296"),
        (dict(alphas=[udm1.Sqrt(2), udm1.Sqrt(49)]), "UDM1_ERROR_RATIONAL_ALPHA", "sqrt(49)"),
        (dict(alphas=[float("nan")]), "UDM1_ERROR_INVALID_ARGUMENT", "alphas[0]"),
        (dict(alphas=[2.0]), "UDM1_ERROR_RATIONAL_ALPHA", "alphas[0]"),
    ],
)
def test_bad_input_raises_with_status_and_message(kwargs, status, words):
    with pytest.raises(udm1.UDM1Error) as err:
        udm1.Sequence(**kwargs)
    assert err.value.status_name == status
    assert words in str(err.value) and "\n" not in str(err.value)


def test_bad_access_raises():
    s = udm1.Sequence("episwr", 2, point_count=16, seed=1)
    with pytest.raises(udm1.UDM1Error) as err:
        s.sample(16, 0)
    assert err.value.status_name == "UDM1_ERROR_INDEX_RANGE"
    with pytest.raises(udm1.UDM1Error) as err:
        s.sample(0, 2)
    assert err.value.status_name == "UDM1_ERROR_DIMENSION"
    with pytest.raises(udm1.UDM1Error):
        s.points(17)
    with pytest.raises(udm1.UDM1Error):
        s.sample(-1, 0)
    with pytest.raises(udm1.UDM1Error):
        s.sample(2**64, 0)
    w = udm1.Sequence("wr", 2)
    with pytest.raises(udm1.UDM1Error) as err:
        w.points(2, first=2**64 - 1)
    assert err.value.status_name == "UDM1_ERROR_INDEX_RANGE"
    assert w.points(0).shape == (0, 2)
    with pytest.raises(ValueError):
        w.points(-1)
    with pytest.raises(TypeError):
        udm1.Sequence(alphas=["sqrt2"])
    with pytest.raises(ValueError):
        udm1.Sequence("wr")  # no d


def test_check_reports():
    r = udm1.Sequence("wmmr", 22, randomize=False).check(256)
    assert not r["dependent"] and not r["rational"]
    assert r["worst_l2_star"] > 3 * r["random_l2_star"]
    r = udm1.check_alphas([udm1.Sqrt(487), udm1.Sqrt(237173)], 256)
    assert r["worst_l2_star"] > 0.7 * r["random_l2_star"]  # "no better than random"
    r = udm1.check_alphas([udm1.Sqrt(3), udm1.Sqrt(12)], 64)
    assert r["dependent"] and r["dependent_exact"] and r["dependent_dims"] == (0, 1)
    r = udm1.check_alphas([udm1.Sqrt(3), udm1.Sqrt(4)], 64)
    assert r["rational"] and r["rational_dim"] == 1


@pytest.mark.parametrize("name,kw", [("wr", {}), ("sobol-owen", {}), ("pmj02", {"point_count": 64}), ("halton", {})])
def test_points_at_equals_samples(name, kw):
    """points_at (udm1_seq_fill_points_f64): point indices[k] of stream streams[k], equal to per-point samples,
    with runs of one stream and dimensions past the sequence's own (padding, as the cursor pads)."""
    s = udm1.Sequence(name, 6, seed=5, **kw)
    streams = np.array([7, 7, 7, (3 << 32) | 2, 9, 9, 7], dtype=np.uint64)
    indices = np.array([0, 5, 63, 1, 2, 2, 40], dtype=np.uint64)
    got = s.points_at(streams, indices, dims=range(2, 9))
    assert got.shape == (7, 7)
    for k in range(7):
        for j in range(4):  # dims 2..5: the sequence's own
            assert got[k, j] == s.sample(int(indices[k]), 2 + j, stream=int(streams[k]))
    c = udm1.Sequence(name, 6, seed=5, **kw)
    assert np.array_equal(got, c.points_at(streams, indices, dims=range(2, 9)))  # padding is a function of its inputs
    assert np.all((got >= 0) & (got < 1))
    with pytest.raises(ValueError):
        s.points_at(streams, indices[:3])
    if kw:
        with pytest.raises(udm1.UDM1Error, match="indices\\[0\\] = 64"):
            s.points_at(np.array([1]), np.array([64]))
