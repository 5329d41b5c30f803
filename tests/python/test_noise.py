"""udm1's noise against an independent transcription of Perlin's reference
Improved Noise (2002), and the Python wrappers."""

import math

import numpy as np
import pytest

import udm1

PERLIN = [151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99, 37,
          240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, 57, 177,
          33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146,
          158, 231, 83, 111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25,
          63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100,
          109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
          59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153,
          101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218,
          246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107,
          49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205,
          93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180]


def perlin_reference(x, y, z):
    """ImprovedNoise.java, transcribed."""
    p = PERLIN + PERLIN
    fade = lambda t: t * t * t * (t * (t * 6 - 15) + 10)
    lerp = lambda t, a, b: a + t * (b - a)

    def grad(h, x, y, z):
        h &= 15
        u = x if h < 8 else y
        v = y if h < 4 else (x if h in (12, 14) else z)
        return (u if h & 1 == 0 else -u) + (v if h & 2 == 0 else -v)

    X, Y, Z = math.floor(x) & 255, math.floor(y) & 255, math.floor(z) & 255
    x, y, z = x - math.floor(x), y - math.floor(y), z - math.floor(z)
    u, v, w = fade(x), fade(y), fade(z)
    A = p[X] + Y; AA = p[A] + Z; AB = p[A + 1] + Z
    B = p[X + 1] + Y; BA = p[B] + Z; BB = p[B + 1] + Z
    return lerp(w, lerp(v, lerp(u, grad(p[AA], x, y, z), grad(p[BA], x - 1, y, z)),
                        lerp(u, grad(p[AB], x, y - 1, z), grad(p[BB], x - 1, y - 1, z))),
                lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1), grad(p[BA + 1], x - 1, y, z - 1)),
                     lerp(u, grad(p[AB + 1], x, y - 1, z - 1), grad(p[BB + 1], x - 1, y - 1, z - 1))))


def test_equals_perlin_reference_bit_for_bit():
    assert sorted(PERLIN) == list(range(256))
    rng = np.random.default_rng(1)
    pts = np.vstack([rng.uniform(-300, 300, (3000, 3)), [[3.14, 42, 7], [0.5, 0.5, 0.5], [-4.2, 10, 6]]])
    ours = udm1.Noise().noise(pts)
    ref = np.array([perlin_reference(*p) for p in pts])
    assert np.array_equal(ours, ref)
    assert ours[-3] == 0.13691995878400012 and ours[-2] == -0.25 and abs(ours[-1] - 0.14208) < 1e-12
    perm, grad = udm1.Noise().tables()
    assert list(perm) == PERLIN


def test_tileable_textures_have_equal_edges():
    for P in (3, 8, 17, 256, 300):
        n = udm1.Noise("wr", seed=2, period=P)
        img = n.pattern_grid("fbm", 2 * P, P, size=(P, P), octaves=4)  # lambda 2: octaves keep the period
        # the column of x = 0 and the one of x = P are the same values: compare the noise there directly
        ys = (np.arange(P) + 0.5)
        left = n.pattern("fbm", np.column_stack([np.zeros(P), ys, np.zeros(P)]), octaves=4)
        right = n.pattern("fbm", np.column_stack([np.full(P, float(P)), ys, np.zeros(P)]), octaves=4)
        assert np.max(np.abs(left - right)) <= 1e-12
        assert img.shape == (P, 2 * P)


def test_wrappers_and_errors():
    n = udm1.Noise("sobol-owen", seed=1, kind="classic")
    assert n.noise(np.array([0.3, 1.7])).shape == (2,)
    assert n.noise(np.zeros((4, 2))).shape == (4,)
    with pytest.raises(udm1.UDM1Error):
        n.noise(np.array([[np.nan, 0, 0]]))
    with pytest.raises(udm1.UDM1Error):
        udm1.Noise("nope")
    with pytest.raises(ValueError):
        udm1.Noise(kind="smooth")
    with pytest.raises(ValueError):
        n.pattern_grid("plaid", 4, 4)
    with pytest.raises(udm1.UDM1Error):
        n.pattern_grid("marble", 4, 4, octaves=0)
    img = n.pattern_grid("granite", 32, 16)
    assert img.shape == (16, 32) and img.dtype == np.float32 and 0 <= img.min() and img.max() <= 1
    assert "marble" in udm1.patterns() and "waves" in udm1.patterns()


@pytest.mark.parametrize("kind", ["improved", "classic"])
@pytest.mark.parametrize("d", [1, 2, 3, 4])
def test_eval_values_gradients_and_layouts(kind, d):
    if kind == "classic" and d == 4:
        with pytest.raises(udm1.UDM1Error, match="4D"):
            udm1.Noise(kind=kind).noise(np.zeros((3, 4)))
        return
    n = udm1.Noise("rd", seed=3, kind=kind)
    rng = np.random.default_rng(d)
    pts = rng.uniform(-50, 50, (2000, d))
    values = n.noise(pts)
    v2, grads = n.noise(pts, gradient=True)
    assert grads.shape == (2000, d) and np.array_equal(values, v2)  # the value part bit for bit
    assert np.array_equal(n.noise(tuple(pts.T)), values)  # one array per axis = packed rows
    h = 1e-6
    for k in range(d):
        e = np.zeros(d)
        e[k] = h
        central = (n.noise(pts + e) - n.noise(pts - e)) / (2 * h)
        # central differences are O(h^2) off except where a point straddles a cell edge
        inside = np.all(np.abs(pts - np.round(pts)) > 2 * h, axis=1)
        assert np.max(np.abs(central - grads[:, k])[inside]) < 1e-5
    # float: every kernel gives the bits of the scalar float code; here, close to double
    p32 = pts.astype(np.float32)
    f32, g32 = n.noise(p32, gradient=True)
    assert f32.dtype == np.float32 and g32.dtype == np.float32
    ref = n.noise(p32.astype(np.float64))
    assert np.max(np.abs(f32 - ref)) < 1e-5
    assert np.array_equal(n.noise(p32), f32)
    assert np.array_equal(n.noise(pts, dtype="float32"), f32)


def test_4d_noise_loops_over_its_period():
    n = udm1.Noise("wr", seed=5, period=(0, 0, 0, 7))
    rng = np.random.default_rng(9)
    pts = rng.uniform(-20, 20, (500, 4))
    shifted = pts + np.array([0, 0, 0, 7.0])
    assert np.array_equal(n.noise(pts), n.noise(shifted))
    free = udm1.Noise("wr", seed=5)
    assert not np.array_equal(free.noise(pts), free.noise(shifted))


def test_eval_refuses_bad_input_plainly():
    n = udm1.Noise()
    with pytest.raises(ValueError, match="1 to 4"):
        n.noise(np.zeros((3, 5)))
    with pytest.raises(ValueError, match="one shape"):
        n.noise((np.zeros(3), np.zeros(4)))
    with pytest.raises(udm1.UDM1Error, match="point 1"):
        n.noise(np.array([[0.0, 0, 0], [0, np.inf, 0]], dtype=np.float32))


def _cellular_brute(noise, pts, jitter, metric):
    """The documented definition by brute force over the cells within 4 (numpy, no fused multiply-add:
    equal to udm1's values within a few ulps; the C tests compare bit for bit)."""
    perm, _ = noise.tables()
    off = noise.cellular_offsets().astype(np.float64)
    c1 = jitter / 256
    c0 = 0.5 - 127.5 * c1
    f = np.floor(pts)
    t = pts - f
    base = f.astype(np.int64)
    d = pts.shape[1]
    rng = range(-4, 5)
    dist = []
    for dz in (rng if d == 3 else [0]):
        for dy in rng:
            for dx in rng:
                dv = np.array([dx, dy, dz][:d])
                ix = (base + dv) & 255
                h = perm[(perm[ix[:, 0]].astype(np.int64) + ix[:, 1]) & 255]
                if d == 3:
                    h = perm[(h.astype(np.int64) + ix[:, 2]) & 255]
                v = c1 * off[h, :d] + (c0 - (t - dv))
                dist.append({"euclidean": np.sqrt((v * v).sum(1)), "manhattan": np.abs(v).sum(1),
                             "chebyshev": np.abs(v).max(1)}[metric])
    return np.sort(np.array(dist), axis=0)[:3]


@pytest.mark.parametrize("d", [2, 3])
@pytest.mark.parametrize("metric", ["euclidean", "manhattan", "chebyshev"])
def test_cellular_against_brute_force(d, metric):
    n = udm1.Noise("halton", seed=4)
    pts = np.random.default_rng(d).uniform(-40, 40, (700, d))
    for jitter in (1.0, 0.45):
        F = _cellular_brute(n, pts, jitter, metric)
        for k, out in enumerate(("f1", "f2", "f3")):
            got = n.cellular(pts, output=out, metric=metric, jitter=jitter)
            assert np.allclose(got, F[k], rtol=1e-14, atol=1e-14)
        assert np.allclose(n.cellular(pts, output="f2-f1", metric=metric, jitter=jitter), F[1] - F[0], atol=1e-13)
        got32 = n.cellular(pts.astype(np.float32), metric=metric, jitter=jitter)
        assert got32.dtype == np.float32 and np.max(np.abs(got32 - F[0])) < 1e-4
    cell = n.cellular(pts, output="cell")
    assert cell.min() >= 0 and cell.max() <= 1 and len(np.unique(cell)) > 100


def test_cellular_is_periodic_and_refuses_bad_input():
    n = udm1.Noise("rd", seed=1, period=(4, 6, 0))
    pts = np.floor(np.random.default_rng(2).uniform(-10, 10, (300, 3)) * 1024) / 1024
    for axis, P in ((0, 4), (1, 6)):
        moved = pts.copy()
        moved[:, axis] += 5 * P
        assert np.array_equal(n.cellular(pts, output="f2"), n.cellular(moved, output="f2"))
    with pytest.raises(ValueError, match="output"):
        n.cellular(pts, output="f4")
    with pytest.raises(ValueError, match="metric"):
        n.cellular(pts, metric="hamming")
    with pytest.raises(udm1.UDM1Error, match="jitter"):
        n.cellular(pts, jitter=2)
    with pytest.raises(udm1.UDM1Error, match="exponent"):
        n.cellular(pts, metric="minkowski", exponent=0.5)
    with pytest.raises(ValueError, match="2 to 3"):
        n.cellular(np.zeros((3, 4)))
    with pytest.raises(udm1.UDM1Error, match="point 1"):
        n.cellular(np.array([[0.0, 0], [np.nan, 0]]))


def test_crackle_pattern():
    n = udm1.Noise("rd", seed=1)
    pts = np.random.default_rng(3).uniform(-20, 20, (500, 3))
    default = n.pattern("crackle", pts)
    F = [n.cellular(pts, output=o) for o in ("f1", "f2")]
    assert np.array_equal(default, np.clip(F[1] - F[0], 0, 1))  # form <-1, 1, 0>: F2 - F1
    f1 = n.pattern("crackle", pts, form=(1, 0, 0), metric=1)
    assert np.array_equal(f1, np.clip(n.cellular(pts, metric="manhattan"), 0, 1))
    solid = n.pattern("crackle", pts, solid=True)
    assert 0 <= solid.min() and solid.max() <= 1 and len(np.unique(solid)) > 20
    with pytest.raises(udm1.UDM1Error, match="crackle_metric"):
        n.pattern("crackle", pts, metric=0.5)
    with pytest.raises(ValueError, match="form"):
        n.pattern("crackle", pts, form=(1, 0))


@pytest.mark.parametrize("name", ["noise", "fbm", "turbulence", "ridged"])
@pytest.mark.parametrize("kind", ["improved", "classic"])
def test_pattern_gradients(name, kind):
    n = udm1.Noise("wr", seed=6, kind=kind)
    pts = np.random.default_rng(4).uniform(-30, 30, (1500, 3))
    kw = dict(octaves=5, omega=0.6, lacunarity=2.1)
    values = n.pattern(name, pts, **kw)
    v, g = n.pattern(name, pts, gradient=True, **kw)
    assert np.array_equal(v, values) and g.shape == (1500, 3)
    h = 1e-7
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        central = (n.pattern(name, pts + e, **kw) - n.pattern(name, pts - e, **kw)) / (2 * h)
        err = np.abs(central - g[:, k])
        # kinks (cell edges of every octave, |n| = 0, the clamps) are crossed by a few points
        assert np.mean(err < 1e-4 * (1 + np.abs(g[:, k]))) > 0.97
        assert np.median(err) < 1e-6


def test_pattern_gradients_only_for_raw_sums():
    with pytest.raises(udm1.UDM1Error, match="marble has no gradient"):
        udm1.Noise().pattern("marble", np.zeros((2, 3)), gradient=True)
